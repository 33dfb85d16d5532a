#include "passes/gbuffer.h"

#include <string>

#include "cl/error.h"

namespace rp::passes {
namespace {

// 16x16 work-groups: dimension 0 spans 16 pixels of a row, the vector width PoCL's work-item
// loops use on AVX-512 (and a common warp multiple on GPUs).
constexpr size_t kGroup = 16;

}  // namespace

GBufferPass::GBufferPass(const rp::cl::Context& /*context*/, rp::cl::ProgramCache& programs)
    : kernel_(programs.kernel("gbuffer.cl", "gbuffer_resolve")) {}

void GBufferPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                      const render::VisibilityBuffer& vis, render::GBuffer& out) {
  const uint32_t w = scene.constants.width, h = scene.constants.height;
  if (vis.width != w || vis.height != h || out.width != w || out.height != h)
    throw rp::cl::Error("gbuffer pass: frame size " + std::to_string(w) + "x" + std::to_string(h) +
                        " does not match the visibility buffer (" + std::to_string(vis.width) +
                        "x" + std::to_string(vis.height) + ") or the GBuffer (" +
                        std::to_string(out.width) + "x" + std::to_string(out.height) + ")");
  if (w == 0 || h == 0) return;
  cl_uint arg = 0;
  kernel_.setArg(arg++, scene.frame);
  kernel_.setArg(arg++, vis.ids);
  kernel_.setArg(arg++, vis.bary);
  kernel_.setArg(arg++, scene.instances);
  kernel_.setArg(arg++, scene.spheres);
  kernel_.setArg(arg++, scene.vertices);
  kernel_.setArg(arg++, scene.triangles);
  kernel_.setArg(arg++, scene.materials);
  kernel_.setArg(arg++, scene.textures);
  kernel_.setArg(arg++, scene.texels);
  kernel_.setArg(arg++, out.albedo);
  kernel_.setArg(arg++, out.normal_depth);
  kernel_.setArg(arg++, out.position);
  kernel_.setArg(arg++, out.emission);
  kernel_.setArg(arg++, out.velocity);
  profiler.enqueue("gbuffer", kernel_,
                   ::cl::NDRange(rp::cl::round_up(w, kGroup), rp::cl::round_up(h, kGroup)),
                   ::cl::NDRange(kGroup, kGroup));
}

}  // namespace rp::passes
