// The fly camera of `run --scene FILE` (app/fly_camera.h) without a window: its first camera is
// the file's, keys move it by speed * dt along the view, right and world up, mouse drags turn
// it, the wheel scales the speed within its clamp, Home goes back.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/glm.hpp>

#include "app/fly_camera.h"

namespace rp::app {
namespace {

constexpr float kEps = 1e-5f;

void expect_near(glm::vec3 a, glm::vec3 b, float eps, const char* what) {
  EXPECT_NEAR(a.x, b.x, eps) << what;
  EXPECT_NEAR(a.y, b.y, eps) << what;
  EXPECT_NEAR(a.z, b.z, eps) << what;
}

glm::vec3 view_direction(const scene::Camera& c) { return glm::normalize(c.target - c.position); }

// A file camera somewhere off the axes, looking down and to the side, with its own lens.
scene::Camera file_camera() {
  scene::Camera c;
  c.position = {3.0f, 2.0f, 5.0f};
  c.target = c.position + glm::normalize(glm::vec3(-0.4f, -0.3f, -1.0f));
  c.up = {0.0f, 1.0f, 0.0f};
  c.fov_y_deg = 45.0f;
  c.near_plane = 0.05f;
  c.far_plane = 80.0f;
  return c;
}

TEST(FlyCamera, StartsAsTheFileCamera) {
  const scene::Camera home = file_camera();
  const FlyCamera fly(home, 2.0f);
  const scene::Camera c = fly.camera();
  expect_near(c.position, home.position, kEps, "position");
  expect_near(view_direction(c), view_direction(home), kEps, "view direction");
  expect_near(c.up, home.up, kEps, "up");
  EXPECT_EQ(c.fov_y_deg, home.fov_y_deg);
  EXPECT_EQ(c.near_plane, home.near_plane);
  EXPECT_EQ(c.far_plane, home.far_plane);
  expect_near(fly.forward(), view_direction(home), kEps, "forward()");
  EXPECT_FLOAT_EQ(fly.speed(), 2.0f);
}

TEST(FlyCamera, KeepsARolledOrVerticalFileCameraUntilTheFirstLook) {
  scene::Camera rolled = file_camera();
  rolled.up = glm::normalize(glm::vec3(0.5f, 1.0f, 0.1f));
  expect_near(FlyCamera(rolled, 1.0f).camera().up, rolled.up, kEps, "rolled up");

  scene::Camera down;  // straight down, the top of the picture towards -Z
  down.position = {0.0f, 10.0f, 0.0f};
  down.target = {0.0f, 0.0f, 0.0f};
  down.up = {0.0f, 0.0f, -1.0f};
  FlyCamera fly(down, 1.0f);
  expect_near(view_direction(fly.camera()), {0.0f, -1.0f, 0.0f}, kEps, "straight down");
  // Moving does not touch the view; the first look continues from heading -Z, pitch -89.
  FlyInput ahead;
  ahead.forward = 1.0f;
  fly.update(ahead, 0.5f);
  expect_near(fly.camera().position, {0.0f, 9.5f, 0.0f}, kEps, "down is forward");
  FlyInput look;
  look.look = {0.0f, -1e-3f};
  fly.update(look, 0.0f);
  EXPECT_NEAR(fly.yaw_degrees(), 0.0f, 1e-3f);
  EXPECT_NEAR(fly.pitch_degrees(), -FlyCamera::kMaxPitchDegrees, 1e-3f);
  expect_near(fly.camera().up, {0.0f, 1.0f, 0.0f}, 0.0f, "level after looking");
}

TEST(FlyCamera, ForwardMovesAlongTheViewBySpeedTimesDt) {
  FlyCamera fly(file_camera(), 3.0f);
  const glm::vec3 start = fly.position(), view = fly.forward();
  FlyInput input;
  input.forward = 1.0f;
  fly.update(input, 0.1f);
  expect_near(fly.position(), start + view * (3.0f * 0.1f), kEps, "forward");
  input = {};
  input.back = 1.0f;
  fly.update(input, 0.1f);
  expect_near(fly.position(), start, kEps, "back again");
  // The view is not changed by moving.
  expect_near(view_direction(fly.camera()), view, kEps, "view kept");
}

TEST(FlyCamera, StrafingIsPerpendicularToTheViewAndHorizontal) {
  FlyCamera fly(file_camera(), 1.0f);
  const glm::vec3 start = fly.position();
  FlyInput input;
  input.right = 1.0f;
  fly.update(input, 0.25f);
  const glm::vec3 moved = fly.position() - start;
  EXPECT_NEAR(glm::length(moved), 0.25f, kEps);
  EXPECT_NEAR(glm::dot(moved, fly.forward()), 0.0f, kEps);
  EXPECT_NEAR(moved.y, 0.0f, kEps);
  // Right is to the right: looking down -Z (roughly), +X.
  EXPECT_GT(moved.x, 0.0f);
  // Also after turning.
  FlyInput look;
  look.look = {300.0f, -120.0f};
  fly.update(look, 0.0f);
  const glm::vec3 before = fly.position();
  input = {};
  input.left = 1.0f;
  fly.update(input, 0.5f);
  const glm::vec3 left = fly.position() - before;
  EXPECT_NEAR(glm::length(left), 0.5f, kEps);
  EXPECT_NEAR(glm::dot(left, fly.forward()), 0.0f, kEps);
  EXPECT_NEAR(left.y, 0.0f, kEps);
}

TEST(FlyCamera, UpAndDownFollowWorldY) {
  FlyCamera fly(file_camera(), 2.0f);
  const glm::vec3 start = fly.position();
  FlyInput input;
  input.up = 1.0f;
  fly.update(input, 0.5f);
  expect_near(fly.position(), start + glm::vec3(0.0f, 1.0f, 0.0f), kEps, "E");
  input = {};
  input.down = 1.0f;
  fly.update(input, 0.25f);
  expect_near(fly.position(), start + glm::vec3(0.0f, 0.5f, 0.0f), kEps, "Q");
}

TEST(FlyCamera, TwoKeysMoveAtTheSpeedAndOppositeKeysCancel) {
  FlyCamera fly(file_camera(), 1.0f);
  const glm::vec3 start = fly.position();
  FlyInput input;
  input.forward = input.right = 1.0f;
  fly.update(input, 1.0f / 8.0f);
  EXPECT_NEAR(glm::length(fly.position() - start), 1.0f / 8.0f, kEps);
  const glm::vec3 mid = fly.position();
  input = {};
  input.forward = input.back = input.up = input.down = 1.0f;
  fly.update(input, 0.25f);
  expect_near(fly.position(), mid, 0.0f, "cancelled");
}

TEST(FlyCamera, MouseDeltaTurnsYawAndPitch) {
  scene::Camera home;  // level, looking down -Z: yaw 0, pitch 0
  home.position = {0.0f, 1.0f, 0.0f};
  home.target = {0.0f, 1.0f, -1.0f};
  FlyCamera fly(home, 1.0f);
  EXPECT_NEAR(fly.yaw_degrees(), 0.0f, 1e-4f);
  EXPECT_NEAR(fly.pitch_degrees(), 0.0f, 1e-4f);
  // Right by 90 degrees' worth of pixels: yaw -90 (turned right), looking down +X.
  FlyInput input;
  input.look = {90.0f / FlyCamera::kDegreesPerPixel, 0.0f};
  fly.update(input, 0.0f);
  EXPECT_NEAR(fly.yaw_degrees(), -90.0f, 1e-3f);
  expect_near(view_direction(fly.camera()), {1.0f, 0.0f, 0.0f}, kEps, "turned right");
  // Up by 30 degrees (the mouse moves up: negative y).
  input.look = {0.0f, -30.0f / FlyCamera::kDegreesPerPixel};
  fly.update(input, 0.0f);
  EXPECT_NEAR(fly.pitch_degrees(), 30.0f, 1e-3f);
  const glm::vec3 expected(std::cos(glm::radians(30.0f)), std::sin(glm::radians(30.0f)), 0.0f);
  expect_near(view_direction(fly.camera()), expected, kEps, "looking up");
  expect_near(fly.camera().position, home.position, 0.0f, "turning does not move");
}

TEST(FlyCamera, PitchClampsAt89Degrees) {
  FlyCamera fly(file_camera(), 1.0f);
  FlyInput input;
  input.look = {0.0f, -1e5f};  // far past straight up
  fly.update(input, 0.0f);
  EXPECT_FLOAT_EQ(fly.pitch_degrees(), FlyCamera::kMaxPitchDegrees);
  EXPECT_LT(view_direction(fly.camera()).y, 1.0f);
  input.look = {0.0f, 2e5f};
  fly.update(input, 0.0f);
  EXPECT_FLOAT_EQ(fly.pitch_degrees(), -FlyCamera::kMaxPitchDegrees);
  // Spinning round many times keeps the yaw in [-180, 180].
  input.look = {1e7f, 0.0f};
  fly.update(input, 0.0f);
  EXPECT_LE(std::abs(fly.yaw_degrees()), 180.0f);
}

TEST(FlyCamera, ScrollScalesTheSpeedWithinItsClamp) {
  FlyCamera fly(file_camera(), 4.0f);
  FlyInput input;
  input.scroll = 1.0f;
  fly.update(input, 0.0f);
  EXPECT_NEAR(fly.speed(), 4.0f * 1.25f, 1e-5f);
  input.scroll = -2.0f;
  fly.update(input, 0.0f);
  EXPECT_NEAR(fly.speed(), 4.0f / 1.25f, 1e-5f);
  input.scroll = 1000.0f;
  fly.update(input, 0.0f);
  const float max_speed = 4.0f * std::pow(FlyCamera::kSpeedStep, FlyCamera::kMaxSpeedSteps);
  EXPECT_NEAR(fly.speed(), max_speed, max_speed * 1e-5f);
  input.scroll = -5000.0f;
  fly.update(input, 0.0f);
  const float min_speed = 4.0f / std::pow(FlyCamera::kSpeedStep, FlyCamera::kMaxSpeedSteps);
  EXPECT_NEAR(fly.speed(), min_speed, min_speed * 1e-5f);
  // The new speed moves this very frame.
  input = {};
  input.scroll = 20.0f;  // back to the base speed
  input.forward = 1.0f;
  const glm::vec3 start = fly.position();
  fly.update(input, 0.1f);
  EXPECT_NEAR(fly.speed(), 4.0f, 1e-4f);
  EXPECT_NEAR(glm::length(fly.position() - start), 0.4f, 1e-5f);
}

TEST(FlyCamera, HomeResetsPositionAndViewButKeepsTheSpeed) {
  const scene::Camera home = file_camera();
  FlyCamera fly(home, 1.0f);
  FlyInput input;
  input.forward = input.up = 1.0f;
  input.look = {123.0f, 45.0f};
  input.scroll = 3.0f;
  fly.update(input, 0.3f);
  ASSERT_GT(glm::length(fly.position() - home.position), 0.1f);
  const float speed = fly.speed();
  FlyInput reset;
  reset.home = true;
  fly.update(reset, 0.1f);
  const scene::Camera c = fly.camera();
  expect_near(c.position, home.position, kEps, "position");
  expect_near(view_direction(c), view_direction(home), kEps, "view");
  expect_near(c.up, home.up, kEps, "up");
  EXPECT_FLOAT_EQ(fly.speed(), speed);
}

TEST(FlyCamera, LongFramesAndBadInputDoNotThrowTheCameraAway) {
  FlyCamera fly(file_camera(), 1.0f);
  const glm::vec3 start = fly.position();
  FlyInput input;
  input.forward = 1.0f;
  fly.update(input, 30.0f);  // a hitch: moves for kMaxStepSeconds only
  EXPECT_NEAR(glm::length(fly.position() - start), FlyCamera::kMaxStepSeconds, kEps);
  const glm::vec3 here = fly.position();
  fly.update(input, -1.0f);
  fly.update(input, std::nanf(""));
  input.look = {std::nanf(""), 1.0f};
  input.scroll = std::nanf("");
  fly.update(input, 0.0f);
  EXPECT_EQ(fly.position(), here);
  EXPECT_TRUE(std::isfinite(fly.yaw_degrees()) && std::isfinite(fly.pitch_degrees()));
  EXPECT_FLOAT_EQ(fly.speed(), 1.0f);
}

TEST(FlyCamera, BaseSpeedIsAQuarterOfTheBoundsDiagonalPerSecond) {
  EXPECT_NEAR(FlyCamera::base_speed_for({glm::vec3(0.0f), glm::vec3(3.0f, 4.0f, 0.0f)}), 1.25f,
              1e-6f);
  EXPECT_NEAR(FlyCamera::base_speed_for({glm::vec3(-50.0f), glm::vec3(50.0f)}),
              0.25f * std::sqrt(3.0f) * 100.0f, 1e-3f);
  EXPECT_EQ(FlyCamera::base_speed_for(scene::Bounds{glm::vec3(1.0f), glm::vec3(-1.0f)}), 1.0f);
  EXPECT_EQ(FlyCamera::base_speed_for({glm::vec3(2.0f), glm::vec3(2.0f)}), 1.0f);
  EXPECT_EQ(FlyCamera(file_camera(), 0.0f).base_speed(), 1.0f);
}

}  // namespace
}  // namespace rp::app
