#include "passes/tone_map.h"

namespace rp::passes {
namespace {

// 1D over the flat pixel index: 64 work-items per group (720 * 720 is a multiple of 64).
constexpr size_t kGroup = 64;

}  // namespace

ToneMapPass::ToneMapPass(const rp::cl::Context& /*context*/, rp::cl::ProgramCache& programs)
    : kernel_(programs.kernel("tone_map.cl", "tone_map_output")) {}

void ToneMapPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                      const ::cl::Buffer& hdr, ::cl::Buffer& rgba8) {
  const cl_uint pixels = scene.constants.width * scene.constants.height;
  if (pixels == 0) return;
  kernel_.setArg(0, hdr);
  kernel_.setArg(1, rgba8);
  kernel_.setArg(2, pixels);
  profiler.enqueue("tone_map", kernel_, ::cl::NDRange(rp::cl::round_up(pixels, kGroup)),
                   ::cl::NDRange(kGroup));
}

}  // namespace rp::passes
