#include "passes/light.h"

#include <string>

#include "cl/error.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 16;  // 16x16 work-groups (see gbuffer.cpp)

}  // namespace

LightPass::LightPass(const rp::cl::Context& /*context*/, rp::cl::ProgramCache& programs,
                     ShadowFilter filter)
    : kernel_(programs.kernel("light.cl", "light_direct",
                              filter == ShadowFilter::kPcf5x5 ? "-DRP_SHADOW_PCF5=1" : "")) {}

void LightPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                    const render::GBuffer& gbuffer, const render::ShadowMap& shadow,
                    ::cl::Buffer& hdr) {
  const uint32_t w = scene.constants.width, h = scene.constants.height;
  if (gbuffer.width != w || gbuffer.height != h)
    throw rp::cl::Error("light pass: frame size " + std::to_string(w) + "x" + std::to_string(h) +
                        " does not match the GBuffer (" + std::to_string(gbuffer.width) + "x" +
                        std::to_string(gbuffer.height) + ")");
  if (shadow.size != scene.constants.shadow_size)
    throw rp::cl::Error("light pass: shadow map is " + std::to_string(shadow.size) +
                        " texels wide but the frame constants say " +
                        std::to_string(scene.constants.shadow_size));
  if (w == 0 || h == 0) return;
  cl_uint arg = 0;
  kernel_.setArg(arg++, scene.frame);
  kernel_.setArg(arg++, gbuffer.albedo);
  kernel_.setArg(arg++, gbuffer.normal_depth);
  kernel_.setArg(arg++, gbuffer.position);
  kernel_.setArg(arg++, gbuffer.emission);
  kernel_.setArg(arg++, shadow.depth);
  kernel_.setArg(arg++, hdr);
  profiler.enqueue("light", kernel_,
                   ::cl::NDRange(rp::cl::round_up(w, kGroup), rp::cl::round_up(h, kGroup)),
                   ::cl::NDRange(kGroup, kGroup));
}

}  // namespace rp::passes
