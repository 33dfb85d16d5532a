#include "app/fly_camera.h"

#include <algorithm>
#include <cmath>

namespace rp::app {
namespace {

const glm::vec3 kWorldUp(0.0f, 1.0f, 0.0f);
constexpr float kPi = 3.14159265358979f;

// A unit vector, or `fallback` when `v` has no usable length.
glm::vec3 unit_or(glm::vec3 v, glm::vec3 fallback) {
  const float length = glm::length(v);
  return length > 1e-12f && std::isfinite(length) ? v / length : fallback;
}

float finite_or_zero(float v) { return std::isfinite(v) ? v : 0.0f; }

// The view direction for a yaw around +Y and a pitch (radians): yaw 0, pitch 0 looks down -Z.
glm::vec3 direction(float yaw, float pitch) {
  return {-std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
}

}  // namespace

FlyCamera::FlyCamera(const scene::Camera& home, float base_speed)
    : home_(home),
      base_speed_(base_speed > 0.0f && std::isfinite(base_speed) ? base_speed : 1.0f),
      position_(home.position) {
  home_forward_ = unit_or(home.target - home.position, glm::vec3(0.0f, 0.0f, -1.0f));
  // The heading a look continues from: the view's horizontal part; looking straight down
  // (up), the top (bottom) of the picture is ahead.
  glm::vec3 heading(home_forward_.x, 0.0f, home_forward_.z);
  if (glm::length(heading) < 1e-6f)
    heading = home_forward_.y < 0.0f ? glm::vec3(home.up.x, 0.0f, home.up.z)
                                     : glm::vec3(-home.up.x, 0.0f, -home.up.z);
  heading = unit_or(heading, glm::vec3(0.0f, 0.0f, -1.0f));
  yaw_ = std::atan2(-heading.x, -heading.z);
  const float max_pitch = glm::radians(kMaxPitchDegrees);
  pitch_ = std::clamp(std::asin(std::clamp(home_forward_.y, -1.0f, 1.0f)), -max_pitch, max_pitch);
  home_right_ = unit_or(glm::cross(home_forward_, home.up),
                        glm::vec3(std::cos(yaw_), 0.0f, -std::sin(yaw_)));
}

float FlyCamera::base_speed_for(const scene::Bounds& bounds) {
  if (bounds.empty()) return 1.0f;
  const float diagonal = glm::length(bounds.size());
  return diagonal > 0.0f && std::isfinite(diagonal) ? 0.25f * diagonal : 1.0f;
}

void FlyCamera::reset() {
  // Everything the constructor derives from the home camera, with the chosen speed kept.
  const float steps = speed_steps_;
  *this = FlyCamera(home_, base_speed_);
  speed_steps_ = steps;
}

float FlyCamera::speed() const { return base_speed_ * std::pow(kSpeedStep, speed_steps_); }

glm::vec3 FlyCamera::forward() const {
  return home_orientation_ ? home_forward_ : direction(yaw_, pitch_);
}

glm::vec3 FlyCamera::right() const {
  return home_orientation_ ? home_right_ : glm::vec3(std::cos(yaw_), 0.0f, -std::sin(yaw_));
}

void FlyCamera::update(const FlyInput& input, float dt_seconds) {
  if (input.home) reset();
  speed_steps_ =
      std::clamp(speed_steps_ + finite_or_zero(input.scroll), -kMaxSpeedSteps, kMaxSpeedSteps);

  const glm::vec2 look(finite_or_zero(input.look.x), finite_or_zero(input.look.y));
  if (look.x != 0.0f || look.y != 0.0f) {
    home_orientation_ = false;
    // Dragging right turns right (negative yaw), dragging down looks down.
    yaw_ -= glm::radians(look.x * kDegreesPerPixel);
    yaw_ = std::remainder(yaw_, 2.0f * kPi);  // stays in [-pi, pi]: no precision lost spinning
    const float max_pitch = glm::radians(kMaxPitchDegrees);
    pitch_ = std::clamp(pitch_ - glm::radians(look.y * kDegreesPerPixel), -max_pitch, max_pitch);
  }

  const float dt = std::clamp(finite_or_zero(dt_seconds), 0.0f, kMaxStepSeconds);
  glm::vec3 move = finite_or_zero(input.forward - input.back) * forward() +
                   finite_or_zero(input.right - input.left) * right() +
                   finite_or_zero(input.up - input.down) * kWorldUp;
  // Two keys at once (forward and right) move at the speed, not faster.
  if (const float length = glm::length(move); length > 1.0f) move /= length;
  position_ += move * (speed() * dt);
}

scene::Camera FlyCamera::camera() const {
  scene::Camera c = home_;
  c.position = position_;
  const glm::vec3 offset = home_.target - home_.position;
  if (home_orientation_) {
    c.target = position_ + offset;
  } else {
    // The target only gives a direction; keeping the file's distance keeps its precision.
    c.target = position_ + forward() * std::max(glm::length(offset), 1e-3f);
    c.up = kWorldUp;
  }
  return c;
}

}  // namespace rp::app
