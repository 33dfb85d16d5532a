// Light pass: direct light from the lamp (Lambert, directional falloff, Poisson-disk shadow
// lookup rotated per pixel) + ambient + emission -> HDR float4 per pixel. Pass name "light".
#pragma once

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"

namespace rp::passes {

class LightPass {
 public:
  LightPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs);
  // hdr: float4 per pixel (rgb linear radiance, a unused), gbuffer.width x gbuffer.height.
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
           const render::GBuffer& gbuffer, const render::ShadowMap& shadow, ::cl::Buffer& hdr);

 private:
  ::cl::Kernel kernel_;
};

}  // namespace rp::passes
