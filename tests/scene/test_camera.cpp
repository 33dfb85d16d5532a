// Camera and shadow-map matrices against values worked out by hand from the definitions of a
// look-at view and an OpenGL perspective projection.
#include <cmath>

#include <gtest/gtest.h>

#include "scene/frame_scene.h"

namespace {

using rp::scene::Camera;
using rp::scene::PointLight;

glm::vec3 to_ndc(const glm::mat4& m, glm::vec3 p) {
  const glm::vec4 c = m * glm::vec4(p, 1.0f);
  return glm::vec3(c) / c.w;
}

TEST(Camera, DefaultViewIsATranslationAlongZ) {
  const Camera camera;  // at (0, 0, 2.7) looking at the origin, y up
  const glm::mat4 v = camera.view();
  const glm::vec4 p = v * glm::vec4(0.3f, -0.2f, 1.0f, 1.0f);
  EXPECT_NEAR(p.x, 0.3f, 1e-6f);
  EXPECT_NEAR(p.y, -0.2f, 1e-6f);
  EXPECT_NEAR(p.z, 1.0f - 2.7f, 1e-6f);
  EXPECT_NEAR(p.w, 1.0f, 1e-6f);
}

TEST(Camera, ViewFromTheSideLooksDownMinusZ) {
  Camera camera;
  camera.position = {2.0f, 0.0f, 0.0f};  // on +x, looking at the origin: view -z is world -x
  const glm::mat4 v = camera.view();
  const glm::vec4 origin = v * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  EXPECT_NEAR(origin.z, -2.0f, 1e-6f);
  // World -z lies to the camera's right: right = forward x up = (-1,0,0) x (0,1,0) = (0,0,-1).
  const glm::vec4 right = v * glm::vec4(0.0f, 0.0f, -1.0f, 1.0f);
  EXPECT_NEAR(right.x, 1.0f, 1e-6f);
  EXPECT_NEAR(right.y, 0.0f, 1e-6f);
}

TEST(Camera, ProjectionMatchesOpenGLPerspective) {
  const Camera camera;  // 60 deg, near 0.1, far 4
  const float f = 1.0f / std::tan(30.0f * 3.14159265f / 180.0f);  // 1.7320508
  const glm::mat4 p = camera.projection(2.0f);
  EXPECT_NEAR(p[0][0], f / 2.0f, 1e-6f);
  EXPECT_NEAR(p[1][1], f, 1e-6f);
  EXPECT_NEAR(p[2][2], -(4.0f + 0.1f) / (4.0f - 0.1f), 1e-6f);
  EXPECT_NEAR(p[3][2], -2.0f * 4.0f * 0.1f / (4.0f - 0.1f), 1e-6f);
  EXPECT_NEAR(p[2][3], -1.0f, 0.0f);
  EXPECT_NEAR(p[3][3], 0.0f, 0.0f);
  // Near and far planes map to z_ndc = -1 and +1; x scales with f / aspect / depth.
  EXPECT_NEAR(to_ndc(p, {0.0f, 0.0f, -0.1f}).z, -1.0f, 1e-5f);
  EXPECT_NEAR(to_ndc(p, {0.0f, 0.0f, -4.0f}).z, 1.0f, 1e-5f);
  const glm::vec3 q = to_ndc(p, {0.5f, -0.25f, -2.0f});
  EXPECT_NEAR(q.x, f / 2.0f * 0.5f / 2.0f, 1e-6f);
  EXPECT_NEAR(q.y, f * -0.25f / 2.0f, 1e-6f);
}

TEST(PointLight, ShadowMapLooksStraightDownWithMinusZUp) {
  const PointLight light;  // (0, 1.1, 0), 120 deg, near 0.05, far 2.5
  const glm::mat4 m = light.view_proj();
  const float f = 1.0f / std::tan(60.0f * 3.14159265f / 180.0f);  // 0.5773503
  // Straight below the lamp: centre of the map; depth follows the distance below the lamp.
  const glm::vec3 below = to_ndc(m, {0.0f, 1.1f - 1.0f, 0.0f});
  EXPECT_NEAR(below.x, 0.0f, 1e-6f);
  EXPECT_NEAR(below.y, 0.0f, 1e-6f);
  EXPECT_NEAR(to_ndc(m, {0.0f, 1.1f - 0.05f, 0.0f}).z, -1.0f, 1e-5f);
  EXPECT_NEAR(to_ndc(m, {0.0f, 1.1f - 2.5f, 0.0f}).z, 1.0f, 1e-5f);
  // +x is image right, -z is image up.
  const glm::vec3 right = to_ndc(m, {0.2f, 0.1f, 0.0f});
  EXPECT_NEAR(right.x, f * 0.2f / 1.0f, 1e-6f);
  EXPECT_NEAR(right.y, 0.0f, 1e-6f);
  const glm::vec3 up = to_ndc(m, {0.0f, 0.1f, -0.3f});
  EXPECT_NEAR(up.x, 0.0f, 1e-6f);
  EXPECT_NEAR(up.y, f * 0.3f / 1.0f, 1e-6f);
}

TEST(PointLight, ShadowFrustumCoversTheBoxFloor) {
  const PointLight light;
  const glm::mat4 m = light.view_proj();
  for (const float x : {-1.0f, 1.0f}) {
    for (const float z : {-1.0f, 1.0f}) {
      const glm::vec3 q = to_ndc(m, {x, -1.0f, z});
      EXPECT_LT(std::fabs(q.x), 1.0f);
      EXPECT_LT(std::fabs(q.y), 1.0f);
      EXPECT_LT(std::fabs(q.z), 1.0f);
    }
  }
}

}  // namespace
