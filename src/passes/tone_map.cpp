#include "passes/tone_map.h"

#include "cl/error.h"

namespace rp::passes {
namespace {

// 1D over the flat byte index (4 per pixel, see kernels/tone_map.cl): 256 work-items per group.
constexpr size_t kGroup = 256;

}  // namespace

ToneMapPass::ToneMapPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                         bool dither)
    : kernel_(programs.kernel("tone_map.cl", "tone_map_output")), dither_(dither) {
  // The kernel writes bytes and relies on R being the low byte of each packed uint.
  if (!context.info.device.getInfo<CL_DEVICE_ENDIAN_LITTLE>())
    throw rp::cl::Error("tone map: device '" + context.info.name +
                        "' is big-endian; the RGBA8 output assumes a little-endian device");
}

void ToneMapPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                      const ::cl::Buffer& hdr, ::cl::Buffer& rgba8) {
  const cl_uint bytes = scene.constants.width * scene.constants.height * 4u;
  if (bytes == 0) return;
  kernel_.setArg(0, hdr);
  kernel_.setArg(1, rgba8);
  kernel_.setArg(2, bytes);
  kernel_.setArg(3, cl_uint(dither_ ? 1u : 0u));
  kernel_.setArg(4, cl_uint(scene.constants.frame_index));
  profiler.enqueue("tone_map", kernel_, ::cl::NDRange(rp::cl::round_up(bytes, kGroup)),
                   ::cl::NDRange(kGroup));
}

}  // namespace rp::passes
