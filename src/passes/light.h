// Light pass: direct light from the lamp (Lambert, directional falloff, Poisson-disk shadow
// lookup rotated per pixel) + indirect diffuse light cone traced through the voxel radiance chain
// (kernels/common/cone_trace.h) + emission -> HDR float4 per pixel. Pass name "light".
#pragma once

#include <cstdint>
#include <optional>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"

namespace rp::passes {

// How the shadow map is filtered: one Poisson-disk tap rotated per pixel and frame (the default,
// SPEC 6.5: enough under GI + TAA), or the 5x5 PCF reference (25 taps, -DRP_SHADOW_PCF5=1).
enum class ShadowFilter { kPoissonOneTap, kPcf5x5 };

// Extra outputs for the direct / indirect debug views, width x height float4 each (16 bytes per
// pixel): direct = albedo * lamp light (shadowed), indirect = albedo * cone-traced irradiance/pi;
// rgb linear radiance, a = 1 covered / 0 background; emission is in neither.
struct LightComponents {
  ::cl::Buffer direct;
  ::cl::Buffer indirect;
};

class LightPass {
 public:
  // Builds the default (hdr only) kernel; the split variant builds on first use.
  LightPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
            ShadowFilter filter = ShadowFilter::kPoissonOneTap);

  // hdr: float4 per pixel (rgb linear radiance, a = 1 covered / 0 background), gbuffer.width x
  // gbuffer.height. voxels: the radiance chain of kernels/shared/voxel_layout.h,
  // voxel_resolution^3 voxels at level 0 (a power of two, 2..1024) and voxel_levels levels
  // (1..log2(voxel_resolution) + 1; the buffer must hold rp_voxel_total of them).
  // The kernel reads the chain's size from these arguments, not from FrameConstants.voxel_*.
  // components: when given, the direct and indirect terms are also written there (a separate
  // kernel variant; the default path writes hdr only).
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
           const render::GBuffer& gbuffer, const render::ShadowMap& shadow,
           const ::cl::Buffer& voxels, uint32_t voxel_resolution, uint32_t voxel_levels,
           ::cl::Buffer& hdr, LightComponents* components = nullptr);

 private:
  void check_sizes(const render::GpuScene& scene, const render::GBuffer& gbuffer,
                   const render::ShadowMap& shadow) const;

  rp::cl::ProgramCache* programs_;
  std::string filter_options_;
  ::cl::Kernel kernel_;                        // cone traced, hdr only
  std::optional<::cl::Kernel> split_kernel_;  // cone traced, + direct / indirect
};

}  // namespace rp::passes
