// Light pass: direct light from the lamp (Lambert, directional falloff, Poisson-disk shadow
// lookup rotated per pixel) + ambient + emission -> HDR float4 per pixel. Pass name "light".
#pragma once

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"

namespace rp::passes {

// How the shadow map is filtered: one Poisson-disk tap rotated per pixel and frame (the default,
// SPEC 6.5: enough under GI + TAA), or the 5x5 PCF reference (25 taps, -DRP_SHADOW_PCF5=1).
enum class ShadowFilter { kPoissonOneTap, kPcf5x5 };

class LightPass {
 public:
  LightPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
            ShadowFilter filter = ShadowFilter::kPoissonOneTap);
  // hdr: float4 per pixel (rgb linear radiance, a unused), gbuffer.width x gbuffer.height.
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
           const render::GBuffer& gbuffer, const render::ShadowMap& shadow, ::cl::Buffer& hdr);

 private:
  ::cl::Kernel kernel_;
};

}  // namespace rp::passes
