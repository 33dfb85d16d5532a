// The render scale that holds a frame time (--target-ms): fed each frame's measured time, it
// moves the scale (render pixels per output pixel, per axis) so that the time settles inside a
// band below the target, smoothly and with hysteresis:
// - the times are smoothed (exponential, a quarter of each new frame), and the scale changes at
//   most every kSettleFrames frames, after which the smoothing restarts (the frames before a
//   change say nothing about the new size);
// - the first frame at a size, the renderer's first included, is left out: it allocates and
//   first touches the size's buffers and is slower than the size's usual frame (it also traced
//   every indirect cone once, about 25 ms more on the static demo at 720x720, before the
//   indirect pass kept its history across sizes); counted, such frames had made the scale
//   cycle, each step's slow first frame pushing it back down;
// - inside [kLow, kHigh] x target nothing changes; outside, the scale moves toward the size the
//   smoothed time predicts for kAim x target, taking the time as proportional to the pixels
//   (scale^2), by at most kMaxStep down or up per change, in steps of kQuantum (so that noise
//   does not reallocate the render-size buffers every few frames).
#pragma once

#include <cstdint>

namespace rp::app {

class FrameTimeScale {
 public:
  static constexpr double kLow = 0.85, kHigh = 1.03, kAim = 0.94;
  static constexpr uint32_t kSettleFrames = 4;
  static constexpr float kMaxStep = 0.15f;  // relative change of the scale per step
  static constexpr float kQuantum = 1.0f / 40.0f;
  static constexpr float kMinScale = 0.5f, kMaxScale = 1.0f;

  // target_ms > 0; start: the first frames' scale (clamped to [kMinScale, kMaxScale]).
  FrameTimeScale(double target_ms, float start);

  // Feeds the time of a frame rendered at scale(); returns the scale for the next frame.
  float update(double frame_ms);
  float scale() const { return scale_; }
  double target_ms() const { return target_ms_; }
  double smoothed_ms() const { return smoothed_ms_; }

 private:
  double target_ms_;
  float scale_;
  double smoothed_ms_ = 0.0;
  uint32_t frames_ = 0;  // frames fed since the last change
  bool first_at_size_ = true;  // the next frame is the first at scale_
};

}  // namespace rp::app
