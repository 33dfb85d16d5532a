#include "passes/sky_background.h"

#include "cl/kernel_args.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"

namespace rp::passes {
namespace {
// eight pixels of a row per work-item (kernels/sky.cl)
constexpr size_t kGroupX = 8, kGroupY = 4;
}  // namespace

void SkyBackgroundPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                            const render::GBuffer& gbuffer, ::cl::Buffer& hdr) {
  const gpu::FrameConstants& c = scene.constants;
  if (c.sky.levels == 0 || c.width == 0 || c.height == 0) return;
  if (!kernel_()) kernel_ = programs_->kernel("sky.cl", "sky_background");
  rp::cl::bind_args(kernel_, scene.frame, scene.sky_seen, gbuffer.position, hdr);
  profiler.enqueue(pass_name::kSky, kernel_,
                   ::cl::NDRange(rp::cl::round_up((c.width + 7) / 8, kGroupX),
                                 rp::cl::round_up(c.height, kGroupY)),
                   ::cl::NDRange(kGroupX, kGroupY));
}

}  // namespace rp::passes
