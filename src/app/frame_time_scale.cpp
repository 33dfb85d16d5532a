#include "app/frame_time_scale.h"

#include <algorithm>
#include <cmath>

namespace rp::app {

FrameTimeScale::FrameTimeScale(double target_ms, float start)
    : target_ms_(target_ms), scale_(std::clamp(start, kMinScale, kMaxScale)) {}

float FrameTimeScale::update(double frame_ms) {
  if (!(frame_ms >= 0.0) || !std::isfinite(frame_ms)) return scale_;  // a bogus time says nothing
  if (first_at_size_) {  // the size's first frame restarts the histories: not its usual time
    first_at_size_ = false;
    return scale_;
  }
  smoothed_ms_ = frames_ == 0 ? frame_ms : 0.75 * smoothed_ms_ + 0.25 * frame_ms;
  if (++frames_ < kSettleFrames) return scale_;
  const double ratio = smoothed_ms_ / target_ms_;
  if (ratio >= kLow && ratio <= kHigh) return scale_;
  if (ratio < kLow && scale_ >= kMaxScale) return scale_;  // fast enough at full size
  if (ratio > kHigh && scale_ <= kMinScale) return scale_;  // as small as it goes
  // time ~ pixels ~ scale^2: the scale that would take kAim x target
  const double wanted = scale_ * std::sqrt(kAim / std::max(ratio, 1e-6));
  const double limited =
      std::clamp(wanted, double(scale_) * (1.0 - kMaxStep), double(scale_) * (1.0 + kMaxStep));
  // round toward the current scale, so that a step never overshoots the prediction
  const double steps = limited / kQuantum;
  const double q = (limited < scale_ ? std::ceil(steps) : std::floor(steps)) * kQuantum;
  float next = static_cast<float>(q);
  if (next == scale_) next += ratio > kHigh ? -kQuantum : kQuantum;  // out of band: move
  next = std::clamp(next, kMinScale, kMaxScale);
  if (next != scale_) {
    scale_ = next;
    frames_ = 0;
    first_at_size_ = true;
  }
  return scale_;
}

}  // namespace rp::app
