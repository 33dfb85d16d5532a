// Temporal anti-aliasing (SPEC 6.7): resolves the jittered HDR frame against the reprojected,
// neighbourhood-clipped history (kernels/taa.cl). Pass name "taa".
//
// Use: enable the 16-frame Halton jitter in GpuScene::update (jitter_frames = 16) while TAA is
// on, run() after the light pass every frame, and reset_history() on camera cuts. The pass
// owns its history (tone-mapped rgb as three float planes per buffer, two buffers ping-pong,
// 24 bytes per pixel in all), allocated on first use and on resize; a resize also resets it.
// The first frame after a reset outputs the current frame.
#pragma once

#include <cstdint>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "passes/frame_memory.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"

namespace rp::passes {

struct TaaSettings {
  float history_weight = 0.9f;  // f in out = hist * f + current * (1 - f), in [0, 1)
  float gamma = 1.0f;           // clip box = mean +- gamma * stddev (YCoCg, 5-tap cross)
  // false: the current colour is the jittered sample at the pixel (the accumulation then
  // integrates the pixel footprint: sharpest). true: hdr_in is resampled bilinearly at the
  // unjittered pixel centre (steadier, softer). See kernels/taa.cl.
  bool unjitter_current = false;
};

class TaaPass {
 public:
  TaaPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
          TaaSettings settings = {});

  // hdr_in: float4 linear HDR of this (jittered) frame, width x height of scene.constants.
  // gbuffer: velocity (float2 px, current - previous), same size. depth: a float per pixel
  // ordered as the view depth (render::VisibilityBuffer::depth: z_ndc * 0.5 + 0.5, 1 where
  // nothing); only its order matters (the nearest surface's velocity). hdr_out: float4, the
  // resolved frame in linear HDR (must not alias hdr_in).
  // The jitter comes from scene.constants.jitter.xy (used only with unjitter_current).
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene, const ::cl::Buffer& hdr_in,
           const render::GBuffer& gbuffer, const ::cl::Buffer& depth, ::cl::Buffer& hdr_out);

  // Forget the history: the next run() outputs its current frame (camera cuts).
  void reset_history() { history_valid_ = false; }
  // The next run() blends a history (false on the first frame and after reset_history()).
  bool history_valid() const { return history_valid_; }

  // Device memory for a width x height frame (passes/frame_memory.h): the two histories of
  // three float planes; what the pass holds now.
  static uint64_t frame_bytes(uint32_t width, uint32_t height) {
    return 2 * pixel_count(width, height) * 3 * sizeof(float);
  }
  uint64_t frame_device_bytes() const { return buffer_bytes({&history_[0], &history_[1]}); }

  const TaaSettings& settings() const { return settings_; }
  void set_settings(const TaaSettings& settings);

 private:
  ::cl::Context context_;
  rp::cl::ProgramCache* programs_;
  ::cl::Kernel kernel_;
  ::cl::Kernel border_kernel_;  // RP_TAA_BORDER build (width % 8 != 0), built on first use
  TaaSettings settings_;
  uint32_t width_ = 0, height_ = 0;
  ::cl::Buffer history_[2];  // tone-mapped R, G, B planes; history_[current_] is the latest
  int current_ = 0;
  bool history_valid_ = false;
};

}  // namespace rp::passes
