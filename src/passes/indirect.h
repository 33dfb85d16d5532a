// Indirect light at reduced resolution (the fast quality mode; kernels/indirect.cl):
// one cone of the 16-cone set per 4x4 pixel block per frame (directions interleaved over the
// blocks, rotated per frame), a geometry-aware spatial filter, and temporal accumulation; on
// coated surfaces also one reflection cone per block (not accumulated). The
// light pass upsamples the result (LightPass::run with a LowResIndirect). Pass names
// "indirect_trace" and "indirect_filter".
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "passes/frame_memory.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"

namespace rp::passes {

// What the light pass upsamples: the accumulated irradiance / pi per low-resolution sample and
// the samples' geometry, planar float planes of width x height samples, padded (row stride
// `stride`, planes `plane` floats apart; kernels/common/indirect.h), and the world size of one
// full-resolution pixel per unit of view depth.
struct LowResIndirect {
  uint32_t width = 0, height = 0;
  uint32_t stride = 0, plane = 0;
  const ::cl::Buffer* irradiance = nullptr;  // 5 planes: irradiance / pi r, g, b; age in frames;
                                             // luminance second moment
  const ::cl::Buffer* geometry = nullptr;    // 4 planes: unit normal x, y, z; dot(normal, position)
  const ::cl::Buffer* specular = nullptr;    // 3 planes: this frame's reflection cone radiance
                                             // r, g, b (coated samples; 0 elsewhere)
  float pixel_scale = 0.0f;
};

// What screen-space reflections read (kernels/common/ssr.h): this frame's visibility depth
// (z_ndc * 0.5 + 0.5), the previous frame's light pass output (hdr, float4) and this frame's
// GBuffer velocity (float2, pixels). prev_hdr must hold the previous frame of the same size
// whenever the pass has history.
struct SsrInputs {
  const ::cl::Buffer* depth = nullptr;
  const ::cl::Buffer* prev_hdr = nullptr;
  const ::cl::Buffer* velocity = nullptr;
};

class IndirectPass {
 public:
  static constexpr uint32_t kScale = 4;  // full-resolution pixels per sample, per side
  // Weight of this frame's spatial estimate once a sample has history (after the first
  // 1 / kAlphaMin frames, which are averaged evenly) while its light does not change; a changed
  // estimate gets up to RP_INDIRECT_ALPHA_FAST (kernels/indirect.cl).
  static constexpr float kAlphaMin = 0.04f;

  // gi_options: "-DRP_GI_SVO" when the voxels given to run are the sparse voxel octree
  // (kernels/shared/svo_layout.h) instead of the dense chain; "" otherwise.
  IndirectPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
               const std::string& gi_options = "");

  // Traces, filters and accumulates this frame's indirect light; the result stays valid until
  // the next run. voxels: the radiance chain (kernels/shared/voxel_layout.h), checked by the
  // light pass's rules. Reallocates its planes when the frame size changes; the history
  // carries over (the previous frame's planes resampled to the new blocks; no SSR history and
  // no still-camera reflection history on that frame).
  // ssr: screen-space reflections for the sharp coats (null: reflection cones only). Pass
  // "ssr_min_z" builds the min-Z pyramid when ssr is given.
  LowResIndirect run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                     const render::GBuffer& gbuffer, const ::cl::Buffer& voxels,
                     uint32_t voxel_resolution, uint32_t voxel_levels,
                     const SsrInputs* ssr = nullptr);
  // Coarsest level of the min-Z pyramid for a frame w x h (kernels/common/ssr.h): at most 6
  // (64-pixel cells), no level smaller than 2 x 2.
  static uint32_t ssr_top_level(uint32_t w, uint32_t h);
  // Floats of the min-Z pyramid for a frame w x h: one, then levels 1 .. ssr_top_level.
  static uint64_t hiz_floats(uint32_t w, uint32_t h);

  // Device memory for a frame w x h (passes/frame_memory.h): the low-resolution planes, the
  // min-Z pyramid and the 16-byte stand-in; and what the pass holds now.
  static uint64_t frame_bytes(uint32_t w, uint32_t h);
  uint64_t frame_device_bytes() const;

  // The next run starts a fresh history (world reset, camera cut).
  void reset_history() { history_valid_ = false; }

  // The last run's other planes (tests, debugging; layout as LowResIndirect): this frame's cone
  // radiance (3 planes: r, g, b) and sample positions (4 planes: x, y, z, view depth).
  const ::cl::Buffer& radiance_planes() const { return radiance_; }
  const ::cl::Buffer& position_planes() const { return position_; }
  // This frame's reflection cones (3 planes r, g, b; -1 marks a checkerboard hole) and the
  // same with the holes filled (what the light pass upsamples).
  const ::cl::Buffer& specular_planes() const { return specular_; }
  // The last run's filled reflections (after the still-camera history blend).
  const ::cl::Buffer& specular_filled_planes() const { return specular_filled_[1 - current_]; }

  // Samples per side for a frame of `pixels` pixels: ceil(pixels / kScale).
  static uint32_t low_res(uint32_t pixels) { return (pixels + kScale - 1) / kScale; }
  // Padded plane layout (kernels/common/indirect.h): two rows and columns of zeros around the
  // samples, rows round_up(width, 8) + 8 floats apart.
  static uint32_t plane_stride(uint32_t lr_width) { return (lr_width + 7) / 8 * 8 + 8; }
  static uint32_t plane_size(uint32_t lr_width, uint32_t lr_height) {
    return plane_stride(lr_width) * (lr_height + 4);
  }

 private:
  void resize(uint32_t width, uint32_t height);
  // geometry_[slot] and history_[slot] anew at width_ x height_, zeroed.
  void reallocate_slot(int slot);

  // The trace kernel: all 16 cones per block (warm: no history yet) or one; with the diffuse
  // cones' sky code (sky) or without (render/sky_texture.h: kNoDiffuseSkyOption). Built on
  // first use; the constructor builds the two without a sky.
  ::cl::Kernel& trace_kernel(bool warm, bool sky);

  const rp::cl::Context* context_;
  rp::cl::ProgramCache* programs_;
  std::string gi_options_;
  bool octree_ = false;  // built with RP_GI_SVO
  std::optional<::cl::Kernel> traces_[2][2];  // [warm][sky]
  ::cl::Kernel filter_;
  ::cl::Kernel min_z_;               // kernels/ssr.cl
  ::cl::Buffer hiz_;                 // the min-Z pyramid's levels 1 .. top (kernels/common/ssr.h)
  ::cl::Buffer dummy_;               // bound where SSR is off
  uint32_t width_ = 0, height_ = 0;  // full-resolution size the planes were made for
  ::cl::Buffer radiance_;            // 3 planes: this frame's cone radiance r, g, b
  ::cl::Buffer position_;            // 4 planes: this frame's sample positions and view depths
  ::cl::Buffer specular_;            // 3 planes: this frame's reflection cone radiance r, g, b
                                     // (-1: a hole of the rough coats' checkerboard)
  ::cl::Buffer specular_filled_[2];  // 3 planes each: the same with the holes filled and the
                                     // still-camera history blended in, [cur] / [prev]
  ::cl::Buffer geometry_[2];         // 4 planes each; [current_]: this frame's, the other: the
                                     // previous frame's
  ::cl::Buffer history_[2];          // 5 planes each, likewise
  int current_ = 0;
  bool history_valid_ = false;
  // The full-resolution size the previous frame's planes (geometry_ and history_ of the slot
  // that is not current_) were made for: width_ x height_ except on the first frame after a
  // change of size, which resamples them (indirect_filter) instead of starting over.
  uint32_t prev_width_ = 0, prev_height_ = 0;
  // The current_ slot still has the old size's layout (the frame after a change of size).
  bool stale_slot_ = false;
};

// World size of one pixel per unit of view depth for a frame `height` pixels tall: 2 / (height *
// P[1][1]), P = the projection part of view_proj (view_proj * inverse(view)).
float pixel_scale(const render::GpuScene& scene);

}  // namespace rp::passes
