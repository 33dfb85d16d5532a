// Light pass: direct light from the lamp (the surface model of kernels/common/brdf.h: GGX coat
// over Lambert; directional falloff, the shadow filtered as render::ShadowMode says) + indirect
// diffuse light + emission -> HDR float4 per pixel. Two kernels: the lamp's visibility per
// pixel (kernels/shadow_visibility.cl, in the shadow mode's filter), then the light itself. The
// indirect light is either the 16-cone set traced per pixel through the voxel radiance chain
// (kernels/common/cone_trace.h; the reference quality mode) or the indirect pass's accumulated
// low-resolution result upsampled with depth- and normal-aware weights (passes/indirect.h; the
// fast mode). Pass name "light" (both kernels).
#pragma once

#include <cstdint>
#include <optional>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "passes/indirect.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"
#include "render/render_settings.h"

namespace rp::passes {

// Extra outputs for the direct / indirect / specular debug views and the accuracy report,
// width x height float4 each (16 bytes per pixel): direct = the lamp's light (shadowed; diffuse
// + specular), indirect = the gathered light (diffuse + the coat's share), specular = the
// specular part of both (kernels/light.cl); rgb linear radiance, a = 1 covered / 0
// background; emission is in none.
struct LightComponents {
  ::cl::Buffer direct;
  ::cl::Buffer indirect;
  ::cl::Buffer specular;
};

class LightPass {
 public:
  // Kernel variants (hdr only or split; per-pixel cones or upsampling) build on first use.
  // Kernel options: see gi_options below.
  // gi_options: "-DRP_GI_SVO" when the voxels given to run are the sparse voxel octree
  // (kernels/shared/svo_layout.h) instead of the dense chain; "" otherwise.
  LightPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
            render::ShadowMode filter = render::ShadowMode::kPcss, std::string gi_options = "");

  // Switches the shadow filter for the next run (its kernels build on first use).
  void set_filter(render::ShadowMode filter) { filter_ = filter; }
  render::ShadowMode filter() const { return filter_; }

  // The pcss visibility's chunk checkerboard (kernels/shadow_visibility.cl): half the 4x2
  // chunks computed, the others filled where all their neighbours agree on lit or umbra (on by
  // default; off computes every chunk).
  void set_shadow_checkerboard(bool on) { checkerboard_ = on; }
  // Frames that no temporal history will average (TAA off, the first frame, after a cut): pcss
  // filters each pixel with kPcssTapsWithoutHistory taps instead of the default 6, so a single
  // frame's penumbrae are not a stipple that only TAA smooths (the blocker search stays).
  void set_without_history(bool on) { without_history_ = on; }
  static constexpr int kPcssTapsWithoutHistory = 16;
  // Device memory for a frame w x h under `filter` (passes/frame_memory.h): the lamp's
  // visibility and, for pcss with the checkerboard, its chunks' verdicts; and what the pass
  // holds now (both only grow: a smaller frame keeps them).
  static uint64_t frame_bytes(uint32_t w, uint32_t h, render::ShadowMode filter);
  uint64_t frame_device_bytes() const { return buffer_bytes({&visibility_, &consensus_}); }
  // The last run's lamp visibility: width x height floats in [0, 1], row-major (for tests); not
  // written for a frame without the lamp (light_intensity 0).
  const ::cl::Buffer& visibility() const { return visibility_; }

  // hdr: float4 per pixel (rgb linear radiance, a = 1 covered / 0 background), gbuffer.width x
  // gbuffer.height. voxels: the radiance chain of kernels/shared/voxel_layout.h,
  // voxel_resolution^3 voxels at level 0 (a power of two, 2..1024) and voxel_levels levels
  // (1..log2(voxel_resolution) + 1; the buffer must hold rp_voxel_total of them).
  // The kernel reads the chain's size from these arguments, not from FrameConstants.voxel_*.
  // components: when given, the direct and indirect terms are also written there (a separate
  // kernel variant; the default path writes hdr only).
  // indirect: when given, the indirect light is upsampled from it (the fast mode; the voxel
  // chain is then only checked, not read); else the 16 cones are traced per pixel.
  // ssr (the reference mode, without `indirect`): the screen-space reflections' inputs;
  // ssr->prev_hdr must not be `hdr` (the previous frame's output, copied). nullptr: no previous
  // frame, the reflection cone alone.
  // prt: the PRT pass's sky light (PrtSkyPass::output(), float4 E / pi per pixel), added to
  // the diffuse indirect light (a separate kernel variant); the cones must then carry no
  // diffuse sky (SkyGpu.diffuse_cones 0). nullptr: the cones' sky alone.
  // shadow.mips must hold at least shadow_mip_planes(filter()) planes (the shadow filter pass).
  // Builds the hdr-only kernel of one variant now (the renderer builds its kernels up front).
  void prepare(bool upsample) {
    variant(upsample, false);
    shadow_kernel();
  }

  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
           const render::GBuffer& gbuffer, const render::ShadowMap& shadow,
           const ::cl::Buffer& voxels, uint32_t voxel_resolution, uint32_t voxel_levels,
           ::cl::Buffer& hdr, LightComponents* components = nullptr,
           const LowResIndirect* indirect = nullptr, const SsrInputs* ssr = nullptr,
           const ::cl::Buffer* prt = nullptr);

 private:
  void check_sizes(const render::GpuScene& scene, const render::GBuffer& gbuffer,
                   const render::ShadowMap& shadow) const;

  // Light kernel variant [upsample][split][prt] and the visibility kernel of filter_, built on
  // first use.
  ::cl::Kernel& variant(bool upsample, bool split, bool prt = false);
  ::cl::Kernel& shadow_kernel();
  // The lamp's visibility per pixel (kernels/shadow_visibility.cl) into visibility_; nothing
  // when the lamp is off.
  void run_visibility(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                      const render::GBuffer& gbuffer, const render::ShadowMap& shadow);

  const rp::cl::Context* context_;
  rp::cl::ProgramCache* programs_;
  render::ShadowMode filter_;
  std::string gi_options_;  // -DRP_GI_SVO... for the light kernels ("" = the dense chain)
  std::optional<::cl::Kernel> kernels_[2][2][2];
  std::optional<::cl::Kernel> shadow_kernels_[4][2];  // [filter][without history]
  // width x height floats in [0, 1] (one per pixel, row-major), grown on demand
  ::cl::Buffer visibility_;
  size_t visibility_bytes_ = 0;
  bool checkerboard_ = true;
  bool without_history_ = false;
  ::cl::Buffer consensus_;  // uchar per 4x2 chunk (the checkerboard's black chunks' verdicts)
  size_t consensus_bytes_ = 0;
};

// Throws rp::cl::Error (naming `pass`) unless `voxels` holds a chain of voxel_resolution^3 at
// level 0 (a power of two, 2..1024) with voxel_levels levels (1..log2(resolution) + 1). An
// octree (octree = true) is only checked to hold its header.
void check_voxel_chain(const char* pass, const ::cl::Buffer& voxels, uint32_t voxel_resolution,
                       uint32_t voxel_levels, bool octree = false);

}  // namespace rp::passes
