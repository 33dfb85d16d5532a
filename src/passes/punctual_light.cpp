#include "passes/punctual_light.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 16;  // 16x16 work-groups, as the light pass

}  // namespace

void PunctualLightPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                            const render::GBuffer& gbuffer, const render::ShadowMap& shadow,
                            ::cl::Buffer& hdr, LightComponents* components) {
  if (scene.constants.punctual_count == 0) return;
  ::cl::Kernel& kernel = components ? split_ : hdr_only_;
  if (!kernel())
    kernel = programs_.kernel("punctual_light.cl", "punctual_light_add",
                              components ? "-DRP_LIGHT_SPLIT=1" : "");
  cl_uint arg = 0;
  kernel.setArg(arg++, scene.frame);
  kernel.setArg(arg++, gbuffer.albedo);
  kernel.setArg(arg++, gbuffer.normal_depth);
  kernel.setArg(arg++, gbuffer.position);
  kernel.setArg(arg++, gbuffer.emission);
  kernel.setArg(arg++, shadow.depth);
  kernel.setArg(arg++, scene.brdf_table);
  if (components) {
    kernel.setArg(arg++, components->direct);
    kernel.setArg(arg++, components->specular);
  }
  kernel.setArg(arg++, hdr);
  const uint32_t w = gbuffer.width, h = gbuffer.height;
  profiler.enqueue("punctual_light", kernel,
                   ::cl::NDRange(rp::cl::round_up(w, kGroup), rp::cl::round_up(h, kGroup)),
                   ::cl::NDRange(kGroup, kGroup));
}

}  // namespace rp::passes
