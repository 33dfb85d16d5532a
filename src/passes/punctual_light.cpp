#include "passes/punctual_light.h"

#include "passes/pass_names.h"

namespace rp::passes {
namespace {

// 8 pixels of a row per work-item (kernels/punctual_light.cl); work-groups of 16 x 4 such
// chunks, as the light pass's light_compose.
constexpr size_t kGroupX = 16, kGroupY = 4;

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
  profiler.enqueue(pass_name::kPunctualLight, kernel,
                   ::cl::NDRange(rp::cl::round_up((w + 7) / 8, kGroupX),
                                 rp::cl::round_up(h, kGroupY)),
                   ::cl::NDRange(kGroupX, kGroupY));
}

}  // namespace rp::passes
