#include "passes/punctual_light.h"

#include "cl/kernel_args.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"

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
  // Without the components the variant reads neither: any buffer will do.
  rp::cl::bind_args(kernel, scene.frame, gbuffer.albedo, gbuffer.normal_depth, gbuffer.position,
                    gbuffer.emission, shadow.depth, scene.brdf_table,
                    components ? components->direct : hdr,
                    components ? components->specular : hdr, hdr);
  const uint32_t w = gbuffer.width, h = gbuffer.height;
  profiler.enqueue(pass_name::kPunctualLight, kernel,
                   ::cl::NDRange(rp::cl::round_up((w + 7) / 8, kGroupX),
                                 rp::cl::round_up(h, kGroupY)),
                   ::cl::NDRange(kGroupX, kGroupY));
}

}  // namespace rp::passes
