// Temporal upsampling (the render scale): resolves a jittered frame rendered at a smaller size
// into the output size, accumulating the jittered samples of many frames into a history at the
// output size (kernels/taa_upsample.cl has the algorithm). Pass name "taa", like the same-size
// resolve (passes/taa.h) it replaces while the render size is below the output size.
//
// Use: jitter the camera with GpuScene::update's jitter_frames = upsample_jitter_frames(scale),
// run() after the light pass every frame, reset_history() on camera cuts. The pass owns its
// history (three float planes at the output size, two buffers ping-pong: 24 bytes per output
// pixel), what motion blur reads at the output size (motion(): velocity in output pixels and
// the motion blur's depth/speed plane, 12 bytes), allocated on first use and when the output
// size changes, and its first kernel's per-render-pixel colour and neighbourhood box (three
// float4: 48 bytes per render pixel), allocated when the render size changes.
#pragma once

#include <cstdint>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "passes/frame_memory.h"
#include "passes/motion_blur.h"
#include "passes/taa.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"

namespace rp::passes {

// Jitter phases for a render scale (render pixels per output pixel, per axis): at least 16 (the
// same-size TAA's), and about 8 samples per output pixel at lower scales (32 at 0.5).
uint32_t upsample_jitter_frames(float scale);

class TaaUpsamplePass {
 public:
  TaaUpsamplePass(const rp::cl::Context& context, rp::cl::ProgramCache& programs);

  // hdr_in: float4 linear HDR of this jittered frame and gbuffer (velocity, normal_depth) at
  // the render size, scene.constants.width x height. hdr_out: float4 at out_width x out_height
  // (must not alias hdr_in). The jitter comes from scene.constants.jitter.xy.
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene, const ::cl::Buffer& hdr_in,
           const render::GBuffer& gbuffer, uint32_t out_width, uint32_t out_height,
           ::cl::Buffer& hdr_out);

  // Forget the history: the next run() outputs the current frame's reconstruction alone.
  void reset_history() { history_valid_ = false; }
  // The next run() blends a history (false on the first frame and after reset_history()).
  bool history_valid() const { return history_valid_; }

  // The shutter of the motion blur that reads motion() from the next run() on: run() then
  // writes the depth/speed plane for it (kernels/common/depth_speed.h) beside the velocity;
  // 0 (the default): no motion blur, no plane.
  void set_motion_blur_shutter(float shutter) { blur_shutter_ = shutter; }

  // What the last run() wrote at the output size for motion blur: the velocity (float2, output
  // pixels) and, with a shutter set, the depth/speed plane made for it.
  MotionInputs motion() const {
    MotionInputs m;
    m.width = width_;
    m.height = height_;
    m.velocity = &velocity_;
    if (blur_shutter_ > 0.0f) {
      m.depth_speed = &depth_speed_;
      m.plane_shutter = blur_shutter_;
    }
    return m;
  }

  // Device memory for an out_width x out_height output from a render_width x render_height
  // frame (passes/frame_memory.h): the two histories of three float planes, motion()'s velocity
  // and depth/speed plane, and the per-render-pixel colour and box; what the pass holds now.
  static uint64_t frame_bytes(uint32_t out_width, uint32_t out_height, uint32_t render_width,
                              uint32_t render_height) {
    return pixel_count(out_width, out_height) * (2 * 3 * sizeof(float) + 8 + 4) +
           pixel_count(render_width, render_height) * 3 * 16;
  }
  uint64_t frame_device_bytes() const {
    return buffer_bytes({&history_[0], &history_[1], &velocity_, &depth_speed_, &colour_,
                         &box_centre_, &box_extent_});
  }

  const TaaSettings& settings() const { return settings_; }
  void set_settings(const TaaSettings& settings) { settings_ = settings; }

 private:
  ::cl::Context context_;
  rp::cl::ProgramCache* programs_;
  ::cl::Kernel box_kernel_, kernel_;  // built by the first run()
  TaaSettings settings_;
  uint32_t width_ = 0, height_ = 0;  // the output size the buffers have
  ::cl::Buffer history_[2];          // tone-mapped R, G, B planes; history_[current_] the latest
  int current_ = 0;
  bool history_valid_ = false;
  ::cl::Buffer velocity_;     // float2 per output pixel: motion in output pixels
  ::cl::Buffer depth_speed_;  // uint per output pixel: motion blur's plane for blur_shutter_
  float blur_shutter_ = 0.0f;
  uint32_t render_width_ = 0, render_height_ = 0;  // the render size the next three have
  ::cl::Buffer colour_, box_centre_, box_extent_;   // float4 per render pixel (the kernel's step 0)
};

}  // namespace rp::passes
