// GBuffer resolve: visibility buffer -> albedo, normal + linear depth, position, emission,
// velocity. Pass name "gbuffer".
#pragma once

#include <array>
#include <string>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"

namespace rp::passes {

class GBufferPass {
 public:
  // extra_options: further -D options for the kernels (tests: -DRP_GBUFFER_LOD_OUT).
  GBufferPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
              const std::string& extra_options = "");
  // texture_filter: RP_TEXTURE_FILTER_BILINEAR, _TRILINEAR or _ANISOTROPIC
  // (kernels/shared/types.h; render::TextureFilter). lod_bias: levels added to every filtered
  // level of detail (0 = the standard rule; the renderer passes kTaaTextureLodBias under TAA).
  // stochastic_levels: trilinear reads one of the two levels per tap, chosen at random per
  // pixel and frame with the blend's weight (the same mean at half the taps; under TAA only).
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
           const render::VisibilityBuffer& vis, render::GBuffer& out,
           uint32_t texture_filter, float lod_bias = 0.0f, bool stochastic_levels = false);
  // Texture level-of-detail bias while TAA jitters the camera (kernels/gbuffer.cl: why -1).
  static constexpr float kTaaTextureLodBias = -1.0f;

 private:
  const rp::cl::Context* context_;
  int span_ = 1;  // pixels per work-item along x (kernels/common/span.h)
  // resolve_[filter]: gbuffer_resolve built with -DRP_TEXTURE_FILTER_FIXED=filter on first use
  // (a constant filter lets the compiler drop the other paths: kernels/gbuffer.cl).
  std::array<::cl::Kernel, 3> resolve_;
  // gbuffer_material (kernels/gbuffer_material.cl): a file's normal, metallic-roughness and
  // emission maps, when the scene has any (GpuScene::has_material_maps); built on first use.
  ::cl::Kernel material_;
  void run_material(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                    const render::VisibilityBuffer& vis, render::GBuffer& out);
  rp::cl::ProgramCache* programs_;
  std::string options_;
  ::cl::Buffer no_texels_;  // one texel, bound when the scene has no texel buffer
};

}  // namespace rp::passes
