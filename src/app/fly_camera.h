// The window's fly camera for scene files (`rolypoly run --scene FILE`): a free camera moved by
// held keys and turned by mouse drags, in the file's world units (glTF: metres). Pure state and
// arithmetic, no window: run_command.cpp maps the window's input onto FlyInput each frame and
// hands camera() to FileFrameSource::set_camera.
//
// Orientation: yaw turns around world +Y (right-handed: positive yaw turns left; yaw 0 looks
// down -Z, glTF's camera default), pitch tilts up (positive) and down, clamped to +-89 degrees
// so the view never flips over the pole. Until the first look, the camera keeps the file
// camera's exact view direction and up vector (even a rolled one, or one looking straight
// down); the first look continues from the same yaw and pitch with +Y up.
#pragma once

#include <glm/glm.hpp>

#include "scene/frame_scene.h"

namespace rp::app {

// One frame's input. Movement axes are 1 while their key is held (fractions are allowed);
// opposite keys cancel.
struct FlyInput {
  float forward = 0.0f, back = 0.0f;  // W / S: along the view direction (pitch included)
  float right = 0.0f, left = 0.0f;    // D / A: horizontal, perpendicular to the view
  float up = 0.0f, down = 0.0f;       // E / Q: along world +Y
  // Mouse movement while looking (right button held), in screen pixels: x to the right, y
  // down. A distance, so not scaled by the frame time.
  glm::vec2 look{0.0f};
  float scroll = 0.0f;  // wheel notches, positive = away from the user (faster)
  bool home = false;    // back to the file's camera (the speed stays)
};

class FlyCamera {
 public:
  static constexpr float kDegreesPerPixel = 0.2f;  // a 450-pixel drag turns 90 degrees
  static constexpr float kMaxPitchDegrees = 89.0f;
  static constexpr float kSpeedStep = 1.25f;       // speed factor per scroll notch
  static constexpr float kMaxSpeedSteps = 20.0f;   // notches either way: 1.25^20, about x87
  // Longest frame time one update moves for: a hitch (a kernel build when a view or shadow
  // mode is first shown) must not throw the camera across the scene.
  static constexpr float kMaxStepSeconds = 0.5f;

  // `home`: the file's camera (world units); its fov and clip planes are kept. `base_speed`:
  // world units per second at notch 0 (base_speed_for).
  FlyCamera(const scene::Camera& home, float base_speed);

  // The base speed for a scene of these world bounds: a quarter of their diagonal per second,
  // so crossing a room and crossing a city both take a few seconds. 1 for empty or degenerate
  // bounds.
  static float base_speed_for(const scene::Bounds& bounds);

  // Applies one frame: scroll and look first, then moves for `dt_seconds` (clamped to
  // [0, kMaxStepSeconds]) at the new speed; `home` first of all.
  void update(const FlyInput& input, float dt_seconds);
  // Back to the file's camera: position and view; the speed stays.
  void reset();

  // Where the next frame is seen from: the home camera with this position and orientation.
  scene::Camera camera() const;

  const glm::vec3& position() const { return position_; }
  float yaw_degrees() const { return glm::degrees(yaw_); }
  float pitch_degrees() const { return glm::degrees(pitch_); }
  float speed() const;  // world units per second
  float base_speed() const { return base_speed_; }
  glm::vec3 forward() const;  // unit view direction
  glm::vec3 right() const;    // unit, horizontal once looked around, perpendicular to forward

 private:
  scene::Camera home_;
  float base_speed_;
  glm::vec3 position_;
  float yaw_ = 0.0f, pitch_ = 0.0f;  // radians
  float speed_steps_ = 0.0f;         // scroll notches, within +-kMaxSpeedSteps
  // Until the first look: the home camera's own orientation (exact, any roll or pitch).
  bool home_orientation_ = true;
  glm::vec3 home_forward_, home_right_;
};

}  // namespace rp::app
