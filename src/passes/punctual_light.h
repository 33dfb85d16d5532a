// Punctual light pass: a loaded scene's directional, point and spot lights, each with its own
// shadow map, added to the light pass's HDR output (kernels/punctual_light.cl). Runs only for
// frames with such lights; the demo has none. Pass name "punctual_light".
#pragma once

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "passes/light.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"

namespace rp::passes {

class PunctualLightPass {
 public:
  explicit PunctualLightPass(rp::cl::ProgramCache& programs) : programs_(programs) {}

  // hdr: the light pass's output (float4 per pixel), added to; components (optional): its
  // split outputs, the direct light and its specular part added to them as well. shadow: the
  // lamp's map with the lights' views after it (VisibilityPass::render_light_shadows).
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
           const render::GBuffer& gbuffer, const render::ShadowMap& shadow, ::cl::Buffer& hdr,
           LightComponents* components);

 private:
  rp::cl::ProgramCache& programs_;
  ::cl::Kernel hdr_only_, split_;  // built on first use
};

}  // namespace rp::passes
