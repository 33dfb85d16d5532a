// Motion blur pass (SPEC 6.8): 20x20 velocity tiles (max by a work-group reduction), their 3x3
// neighbourhood max, a depth/speed half2 plane, and McGuire et al. 2012's reconstruction filter
// along the neighbourhood max velocity in both directions (kernels/motion_blur.cl). Tiles whose
// neighbourhood max blur radius is at most half a pixel are copied unchanged. Pass name
// "motion_blur" (tile max, neighbourhood max, the depth/speed prepass unless the inputs bring
// the plane, block max, the still tiles' copy or bloom composite, reconstruct).
//
// Shutter: the blur vector is velocity * shutter (velocity in pixels per frame, shutter = the
// fraction of the frame interval the shutter is open, centred on the frame time), so an object
// smears velocity * shutter / 2 to each side. That half vector is clamped to 20 px (the tile
// size: a streak is at most 40 px), which keeps every blur inside the 3x3 tile neighbourhood.
#pragma once

#include <cstdint>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "passes/bloom.h"
#include "passes/frame_memory.h"
#include "render/frame_buffers.h"

namespace rp::passes {

// What motion blur reads at the image size: the velocity (float2, pixels per frame, current -
// previous) and either the linear depth (normal_depth.w of a float4 plane), from which the pass
// makes its depth/speed plane, or that plane made already for the shutter `plane_shutter`
// (kernels/common/depth_speed.h: the temporal upsampling writes it beside its velocity).
struct MotionInputs {
  uint32_t width = 0, height = 0;
  const ::cl::Buffer* velocity = nullptr;
  const ::cl::Buffer* normal_depth = nullptr;
  const ::cl::Buffer* depth_speed = nullptr;
  float plane_shutter = 0.0f;

  MotionInputs() = default;
  // A GBuffer's velocity and depth (implicit: a GBuffer is what motion blur reads at scale 1).
  MotionInputs(const render::GBuffer& g)  // NOLINT(google-explicit-constructor)
      : width(g.width), height(g.height), velocity(&g.velocity), normal_depth(&g.normal_depth) {}
};

class MotionBlurPass {
 public:
  static constexpr uint32_t kTileSize = 20;        // pixels per tile side
  static constexpr float kMaxBlurRadius = 20.0f;   // pixels, clamp of |velocity * shutter / 2|
  // Reconstruction samples per pixel (odd, the middle one is the pixel itself): for a tile
  // neighbourhood whose max blur radius is r pixels, min(2 * ceil(r) + 1, kSamples).
  static constexpr int kSamples = 15;
  static constexpr float kSoftDepth = 0.02f;       // scene units of the soft depth comparison

  MotionBlurPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs);

  // hdr_in, hdr_out: float4 per pixel (linear HDR), width x height, distinct buffers.
  // motion: width x height (a GBuffer will do). shutter in [0, 1] (0 copies the input); a
  // depth/speed plane in `motion` must have been made for this shutter. Enqueues only; the
  // intermediate buffers are (re)allocated on a size change. Throws rp::cl::Error on a size
  // mismatch, a bad shutter or missing inputs.
  void run(rp::cl::Profiler& profiler, const ::cl::Buffer& hdr_in, const MotionInputs& motion,
           uint32_t width, uint32_t height, float shutter, ::cl::Buffer& hdr_out);

  // The same with the bloom composited onto the output (bloom: from BloomPass::run_chain on
  // hdr_in and BloomPass::composite; its level 1 must be that of a width x height image):
  // hdr_out.rgb = blur(hdr_in).rgb * bloom.keep + up(U1) * bloom.scale, alpha blurred. With
  // shutter 0 it is BloomPass::run's mix exactly.
  void run(rp::cl::Profiler& profiler, const ::cl::Buffer& hdr_in, const MotionInputs& motion,
           uint32_t width, uint32_t height, float shutter, const BloomPass::Composite& bloom,
           ::cl::Buffer& hdr_out);

  // Intermediates of the last run (tests, debug views). tile_max and neighbour_max: float2 per
  // tile (the clamped half blur vector in pixels), tiles_x() x tiles_y() row-major;
  // depth_speed: 2 halves per pixel (linear depth, clamped blur radius in pixels), written only
  // in tiles within two tiles of one whose blur radius exceeds half a pixel (elsewhere stale),
  // or the plane the inputs brought.
  uint32_t tiles_x() const { return tiles_x_; }
  uint32_t tiles_y() const { return tiles_y_; }
  const ::cl::Buffer& tile_max() const { return tile_max_; }
  const ::cl::Buffer& neighbour_max() const { return neighbour_max_; }
  const ::cl::Buffer& depth_speed() const { return last_depth_speed_; }

  // Device memory for a width x height image (passes/frame_memory.h): the tile and block
  // maxima, and the depth/speed plane where the pass makes it (makes_plane: its inputs bring
  // none); what the pass holds now.
  static uint64_t frame_bytes(uint32_t width, uint32_t height, bool makes_plane = true);
  uint64_t frame_device_bytes() const {
    return buffer_bytes({&tile_max_, &neighbour_max_, &plane_needed_, &depth_speed_,
                         &block_speed_});
  }

 private:
  const rp::cl::Context* context_;
  void enqueue(rp::cl::Profiler& profiler, const ::cl::Buffer& hdr_in,
               const MotionInputs& motion, uint32_t width, uint32_t height, float shutter,
               const BloomPass::Composite* bloom, ::cl::Buffer& hdr_out);

  ::cl::Kernel tile_kernel_, neighbour_kernel_, depth_speed_kernel_, block_max_kernel_,
      composite_kernel_, reconstruct_kernel_;
  uint32_t width_ = 0, height_ = 0, tiles_x_ = 0, tiles_y_ = 0;
  ::cl::Buffer tile_max_, neighbour_max_, plane_needed_;
  ::cl::Buffer depth_speed_;       // the plane the pass makes (allocated when first made)
  ::cl::Buffer last_depth_speed_;  // the plane the last run read (depth_speed_ or the inputs')
  ::cl::Buffer block_speed_;  // float per 4x4 pixel block: its largest blur radius (flagged tiles)
};

}  // namespace rp::passes
