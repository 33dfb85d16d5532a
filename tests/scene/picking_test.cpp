// Mouse picking (SPEC.md section 4): cursor rays, sphere tracing against the tumblers, drag mode.
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "scene/frame_scene.h"
#include "scene/picking.h"
#include "scene/random.h"
#include "scene/tumbler_shape.h"

namespace {

using rp::scene::Camera;
using rp::scene::DragMode;
using rp::scene::Ray;
using rp::scene::Rng;
using rp::scene::TumblerShape;

constexpr float kPi = std::numbers::pi_v<float>;

const TumblerShape kShape;
const float kRestY = -1.0f + kShape.b;  // bottom sphere centre (centre of mass) on the floor

glm::mat4 upright_at(float x, float z) { return glm::translate(glm::mat4(1.0f), glm::vec3(x, kRestY, z)); }

// Reference world-space SDF through a general matrix inverse (not the rigid shortcut).
float sdf_world(const std::vector<glm::mat4>& models, size_t i, const glm::vec3& p) {
  return kShape.sdf(glm::vec3(glm::inverse(models[i]) * glm::vec4(p, 1.0f)));
}

float min_sdf_world(const std::vector<glm::mat4>& models, const glm::vec3& p) {
  float d = std::numeric_limits<float>::max();
  for (size_t i = 0; i < models.size(); ++i) d = std::min(d, sdf_world(models, i, p));
  return d;
}

TEST(Picking, RayDownOntoTheTopPole) {
  const std::vector<glm::mat4> models = {upright_at(-0.5f, 0.0f), upright_at(0.5f, 0.0f)};
  const auto hit = rp::scene::pick_tumbler(models, kShape, {0.5f, 0.9f, 0.0f}, {0.0f, -1.0f, 0.0f});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->index, 1u);
  // Top pole: y = -0.8 + y_t + t = -0.8 + 0.39238044.
  const float pole_y = -0.8f + 0.39238044f;
  EXPECT_NEAR(hit->point.x, 0.5f, 1e-6f);
  EXPECT_NEAR(hit->point.y, pole_y, 1e-4f);
  EXPECT_NEAR(hit->point.z, 0.0f, 1e-6f);
  EXPECT_NEAR(hit->distance, 0.9f - pole_y, 1e-4f);
  EXPECT_EQ(rp::scene::drag_mode_for(hit->point, kRestY), DragMode::Rotate);
}

TEST(Picking, TheNearerOfTwoInLineWins) {
  // Two tumblers on the x axis; a horizontal ray through both bottom-sphere centres hits the
  // equator of the nearer one at x = centre -+ b.
  for (bool swap : {false, true}) {
    std::vector<glm::mat4> models = {upright_at(-0.5f, 0.0f), upright_at(0.5f, 0.0f)};
    if (swap) std::swap(models[0], models[1]);
    const size_t left = swap ? 1 : 0, right = swap ? 0 : 1;

    const auto from_left = rp::scene::pick_tumbler(models, kShape, {-0.99f, kRestY, 0.0f}, {1.0f, 0.0f, 0.0f});
    ASSERT_TRUE(from_left);
    EXPECT_EQ(from_left->index, left);
    EXPECT_NEAR(from_left->point.x, -0.7f, 1e-4f);
    EXPECT_NEAR(from_left->distance, 0.29f, 1e-4f);

    // The direction need not be normalised; distance is along the unit direction.
    const auto from_right = rp::scene::pick_tumbler(models, kShape, {0.99f, kRestY, 0.0f}, {-3.0f, 0.0f, 0.0f});
    ASSERT_TRUE(from_right);
    EXPECT_EQ(from_right->index, right);
    EXPECT_NEAR(from_right->point.x, 0.7f, 1e-4f);
    EXPECT_NEAR(from_right->distance, 0.29f, 1e-4f);
  }
}

TEST(Picking, ModeBelowAndAboveTheCentreOfMass) {
  const std::vector<glm::mat4> models = {upright_at(0.0f, 0.0f)};
  // 0.1 below the centre of mass: the bottom sphere, x = -sqrt(b^2 - 0.1^2) = -0.173205.
  const auto low = rp::scene::pick_tumbler(models, kShape, {-0.99f, kRestY - 0.1f, 0.0f}, {1.0f, 0.0f, 0.0f});
  ASSERT_TRUE(low);
  EXPECT_NEAR(low->point.x, -0.17320508f, 1e-4f);
  EXPECT_EQ(rp::scene::drag_mode_for(low->point, kRestY), DragMode::Translate);
  // 0.2 above: on the cone, R(0.2) = -0.2 tan(pi/9) + 0.2 / cos(pi/9) = 0.140040.
  const auto high = rp::scene::pick_tumbler(models, kShape, {-0.99f, kRestY + 0.2f, 0.0f}, {1.0f, 0.0f, 0.0f});
  ASSERT_TRUE(high);
  EXPECT_NEAR(high->point.x, -0.14004f, 1e-4f);
  EXPECT_EQ(rp::scene::drag_mode_for(high->point, kRestY), DragMode::Rotate);
  // The boundary itself rotates; just below translates.
  EXPECT_EQ(rp::scene::drag_mode_for({0.0f, kRestY, 0.0f}, kRestY), DragMode::Rotate);
  EXPECT_EQ(rp::scene::drag_mode_for({0.0f, kRestY - 1e-4f, 0.0f}, kRestY), DragMode::Translate);
}

TEST(Picking, MissesSelectNothing) {
  const std::vector<glm::mat4> models = {upright_at(-0.5f, 0.0f), upright_at(0.5f, 0.0f)};
  // Straight down between the two (each is at most b = 0.2 wide).
  EXPECT_FALSE(rp::scene::pick_tumbler(models, kShape, {0.0f, 0.9f, 0.0f}, {0.0f, -1.0f, 0.0f}));
  // Pointing away from both.
  EXPECT_FALSE(rp::scene::pick_tumbler(models, kShape, {0.0f, kRestY, 0.0f}, {0.0f, 0.0f, 1.0f}));
  // Passing just above the top pole of one of them.
  EXPECT_FALSE(rp::scene::pick_tumbler(models, kShape, {-0.99f, -0.8f + 0.3924f + 0.002f, 0.0f},
                                       {1.0f, 0.0f, 0.0f}));
  // Behind the origin only.
  EXPECT_FALSE(rp::scene::pick_tumbler(models, kShape, {0.99f, kRestY, 0.0f}, {1.0f, 0.0f, 0.0f}));
  // No tumblers, no direction.
  EXPECT_FALSE(rp::scene::pick_tumbler({}, kShape, {0.0f, 0.0f, 0.9f}, {0.0f, 0.0f, -1.0f}));
  EXPECT_FALSE(rp::scene::pick_tumbler(models, kShape, {-0.99f, kRestY, 0.0f}, glm::vec3(0.0f)));
}

TEST(Picking, RotatedTumblerIsTracedInItsLocalSpace) {
  // Lying on its side: rotated +90 degrees about z, the axis (local +y) points to world -x, so
  // the top sphere centre is at p + (-y_t, 0, 0). A ray straight down over it meets the cone
  // there (the cone touches the top sphere only beyond y_t), whose line lies at distance t from
  // the top centre: the hit is t / cos(alpha) = 0.1064178 above the axis.
  const glm::vec3 p(0.3f, kRestY, -0.2f);
  const std::vector<glm::mat4> models = {
      glm::rotate(glm::translate(glm::mat4(1.0f), p), kPi / 2.0f, glm::vec3(0.0f, 0.0f, 1.0f))};
  const float top_x = p.x - kShape.y_t;
  const auto hit = rp::scene::pick_tumbler(models, kShape, {top_x, 0.9f, p.z}, {0.0f, -1.0f, 0.0f});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->point.y, p.y + 0.1064178f, 1e-4f);
  // 0.08 beyond the top centre along the axis (towards the top pole): the top sphere, whose
  // height there is sqrt(t^2 - 0.08^2) = 0.06.
  const auto pole = rp::scene::pick_tumbler(models, kShape, {top_x - 0.08f, 0.9f, p.z}, {0.0f, -1.0f, 0.0f});
  ASSERT_TRUE(pole);
  EXPECT_NEAR(pole->point.y, p.y + 0.06f, 1e-4f);
  // Over the bottom sphere instead: y = p_y + b.
  const auto bottom = rp::scene::pick_tumbler(models, kShape, {p.x, 0.9f, p.z}, {0.0f, -1.0f, 0.0f});
  ASSERT_TRUE(bottom);
  EXPECT_NEAR(bottom->point.y, p.y + kShape.b, 1e-4f);
  // Where an upright tumbler's top would be there is nothing now.
  EXPECT_FALSE(rp::scene::pick_tumbler(models, kShape, {p.x, 0.9f, p.z}, {1.0f, 0.0f, 0.0f}));
}

// Random rays from the camera side towards five randomly rotated tumblers. Every hit lies on the
// surface of the tumbler it names (|SDF| < 1e-4) with no tumbler crossed before it (fine sampling
// along the ray); every miss never passes through a tumbler.
TEST(Picking, HitsLieOnTheSurfaceAndAreTheFirstCrossing) {
  Rng rng(2024);
  std::vector<glm::mat4> models;
  for (int i = 0; i < 5; ++i) {
    const glm::vec3 pos(-0.7f + 0.35f * static_cast<float>(i), kRestY, rng.uniform(-0.5f, 0.5f));
    const glm::vec3 axis = rng.unit_vector();
    const float angle = rng.uniform(0.0f, 0.8f);
    models.push_back(glm::rotate(glm::translate(glm::mat4(1.0f), pos), angle, axis));
  }
  int hits = 0, misses = 0;
  for (int r = 0; r < 200; ++r) {
    const glm::vec3 origin(rng.uniform(-0.9f, 0.9f), rng.uniform(-0.5f, 0.9f), 0.99f);
    const glm::vec3 target(rng.uniform(-0.9f, 0.9f), rng.uniform(-1.0f, -0.4f), rng.uniform(-0.7f, 0.7f));
    const glm::vec3 dir = glm::normalize(target - origin);
    const auto hit = rp::scene::pick_tumbler(models, kShape, origin, dir);
    const float t_end = hit ? hit->distance : 4.0f;
    for (float t = 0.0f; t < t_end - 2e-3f; t += 1e-3f) {
      ASSERT_GT(min_sdf_world(models, origin + t * dir), -1e-3f) << "ray " << r << " t " << t;
    }
    if (hit) {
      ++hits;
      ASSERT_LT(hit->index, models.size());
      EXPECT_LT(std::abs(sdf_world(models, hit->index, hit->point)), 1e-4f) << "ray " << r;
      EXPECT_LT(glm::length(hit->point - (origin + hit->distance * dir)), 1e-5f);
    } else {
      ++misses;
    }
  }
  EXPECT_GT(hits, 20);  // both outcomes were exercised
  EXPECT_GT(misses, 20);
}

TEST(CameraRay, CentrePixelPointsAtTheTarget) {
  const Camera camera;  // at (0, 0, 2.7) looking at the origin, 60 degree vertical field of view
  for (glm::vec2 size : {glm::vec2(720.0f, 720.0f), glm::vec2(721.0f, 541.0f)}) {
    const glm::mat4 inv = glm::inverse(camera.projection(size.x / size.y) * camera.view());
    // The centre of the viewport (for 721 x 541 that is the centre of pixel (360, 270)).
    const Ray ray = rp::scene::camera_ray(inv, size * 0.5f, size);
    EXPECT_NEAR(glm::length(ray.direction), 1.0f, 1e-6f);
    EXPECT_NEAR(ray.direction.x, 0.0f, 1e-5f);
    EXPECT_NEAR(ray.direction.y, 0.0f, 1e-5f);
    EXPECT_NEAR(ray.direction.z, -1.0f, 1e-6f);
    // Starts on the near plane (0.1 in front of the camera), on the axis.
    EXPECT_NEAR(ray.origin.x, 0.0f, 1e-5f);
    EXPECT_NEAR(ray.origin.y, 0.0f, 1e-5f);
    EXPECT_NEAR(ray.origin.z, 2.6f, 1e-4f);
  }
}

TEST(CameraRay, TopEdgeIsHalfTheFieldOfViewUpAndPixelYGrowsDown) {
  const Camera camera;
  const glm::vec2 size(720.0f, 720.0f);
  const glm::mat4 inv = glm::inverse(camera.projection(1.0f) * camera.view());
  const Ray top = rp::scene::camera_ray(inv, {360.0f, 0.0f}, size);
  EXPECT_NEAR(top.direction.y / -top.direction.z, std::tan(kPi / 6.0f), 1e-5f);
  EXPECT_NEAR(top.direction.x, 0.0f, 1e-5f);
  const Ray bottom_left = rp::scene::camera_ray(inv, {0.0f, 720.0f}, size);
  EXPECT_NEAR(bottom_left.direction.x / -bottom_left.direction.z, -std::tan(kPi / 6.0f), 1e-5f);
  EXPECT_NEAR(bottom_left.direction.y / -bottom_left.direction.z, -std::tan(kPi / 6.0f), 1e-5f);
}

TEST(CameraRay, PicksTheTumblerUnderTheCursor) {
  // Project a tumbler's cone point to pixels with the forward matrices, then pick from there.
  const Camera camera;
  const glm::vec2 size(720.0f, 720.0f);
  const glm::mat4 view_proj = camera.projection(1.0f) * camera.view();
  const std::vector<glm::mat4> models = {upright_at(-0.5f, 0.0f), upright_at(0.5f, 0.3f)};
  const glm::vec3 target(0.5f, kRestY + 0.2f, 0.3f + 0.14f);  // front of the cone of tumbler 1
  const glm::vec4 clip = view_proj * glm::vec4(target, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  const glm::vec2 cursor((ndc.x + 1.0f) * 0.5f * size.x, (1.0f - ndc.y) * 0.5f * size.y);
  const Ray ray = rp::scene::camera_ray(glm::inverse(view_proj), cursor, size);
  const auto hit = rp::scene::pick_tumbler(models, kShape, ray.origin, ray.direction);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->index, 1u);
  EXPECT_LT(glm::length(hit->point - target), 2e-3f);
  EXPECT_EQ(rp::scene::drag_mode_for(hit->point, kRestY), DragMode::Rotate);
}

TEST(Picking, HorizontalPlaneIntersection) {
  const Ray ray{{0.0f, 1.0f, 2.0f}, glm::normalize(glm::vec3(0.0f, -1.0f, -1.0f))};
  const auto p = rp::scene::intersect_horizontal_plane(ray, -0.5f);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->x, 0.0f, 1e-6f);
  EXPECT_EQ(p->y, -0.5f);
  EXPECT_NEAR(p->z, 0.5f, 1e-5f);
  EXPECT_FALSE(rp::scene::intersect_horizontal_plane(ray, 1.5f));  // behind the origin
  EXPECT_FALSE(rp::scene::intersect_horizontal_plane({{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}}, -0.5f));
}

}  // namespace
