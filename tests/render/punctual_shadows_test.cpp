// The punctual lights' shadow views (render/punctual_shadows.h): a directional light's view
// covers the frame's geometry (ShadowBounds) and nothing more, so its texels are as fine as
// the scene allows; the bounds are snapped so that small motions keep the views; without
// bounds, or beyond the volume, the view covers the whole volume. GpuScene::frame_bounds
// gathers the instances' and spheres' bounds.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "render/gpu_scene.h"
#include "render/punctual_shadows.h"
#include "support/cl_fixture.h"

namespace {

using rp::render::ShadowBounds;

constexpr uint32_t kSize = 1024;

glm::mat4 to_glm(const rp::gpu::rp_mat4& m) {
  glm::mat4 out;
  for (int c = 0; c < 4; ++c) out[c] = {m.c[c].x, m.c[c].y, m.c[c].z, m.c[c].w};
  return out;
}

rp::gpu::ShadowViewGpu sun_view(glm::vec3 dir, const ShadowBounds& bounds) {
  rp::scene::PunctualLight sun;
  sun.type = rp::scene::LightType::kDirectional;
  sun.direction = glm::normalize(dir);
  const rp::render::PunctualSetup setup =
      rp::render::setup_punctual_lights({sun}, kSize, 0, bounds);
  EXPECT_EQ(setup.views.size(), 1u);
  return setup.views.at(0);
}

// Every corner of [lo, hi] lies inside the view's clip volume.
void expect_covers(const rp::gpu::ShadowViewGpu& v, glm::vec3 lo, glm::vec3 hi) {
  const glm::mat4 vp = to_glm(v.view_proj);
  for (int k = 0; k < 8; ++k) {
    const glm::vec3 corner(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
    const glm::vec4 clip = vp * glm::vec4(corner, 1.0f);
    ASSERT_NEAR(clip.w, 1.0f, 1e-6f) << "orthographic";
    EXPECT_LE(std::abs(clip.x), 1.0f) << "corner " << k;
    EXPECT_LE(std::abs(clip.y), 1.0f) << "corner " << k;
    EXPECT_LE(std::abs(clip.z), 1.0f) << "corner " << k;
  }
}

const glm::vec3 kSuns[] = {{0.35f, -0.85f, 0.4f}, {0.0f, -1.0f, 0.0f}, {-0.9f, -0.1f, 0.2f},
                           {0.3f, -1.0f, -0.2f}};

TEST(PunctualShadows, WithoutBoundsTheSunSeesTheWholeVolume) {
  for (const glm::vec3& dir : kSuns) expect_covers(sun_view(dir, {}), glm::vec3(-1), glm::vec3(1));
}

TEST(PunctualShadows, TheSunsViewCoversTheFramesGeometry) {
  const ShadowBounds b{{-0.8f, -0.31f, -0.5f}, {0.9f, 0.2f, 0.43f}};
  for (const glm::vec3& dir : kSuns) expect_covers(sun_view(dir, b), b.lo, b.hi);
}

TEST(PunctualShadows, AFlatSceneGetsFinerTexels) {
  // The atrium's extent in render space (30 x 15 x 13 m, its longest side across the volume)
  // under its sun. By hand: the view's axes are right = (-0.753, 0, 0.659) and up = (0.559,
  // 0.530, 0.638); the bounds snapped to sixteenths are +-(1, 0.5, 0.4375), so the half-extents
  // are 0.753 + 0.659 * 0.4375 = 1.041 and 0.559 + 0.530 * 0.5 + 0.638 * 0.4375 = 1.103; the
  // whole volume's are 1.412 and 1.727. Texels (1.01 margins alike) 1.727 / 1.103 = 1.566 x
  // finer.
  const ShadowBounds atrium{{-1.0f, -0.5f, -0.43f}, {1.0f, 0.5f, 0.43f}};
  const glm::vec3 sun(0.35f, -0.85f, 0.4f);
  const float whole = sun_view(sun, {}).depth.w, fitted = sun_view(sun, atrium).depth.w;
  EXPECT_NEAR(whole / fitted, 1.566f, 0.01f);
  // texel size = the view's width over its texels
  const glm::mat4 vp = to_glm(sun_view(sun, atrium).view_proj);
  const float width = 2.0f / glm::length(glm::vec3(vp[0][0], vp[1][0], vp[2][0]));
  EXPECT_NEAR(fitted, width / float(kSize), 1e-6f);
}

TEST(PunctualShadows, SmallMotionsKeepTheViews) {
  const ShadowBounds a{{-0.52f, -0.3f, -0.4f}, {0.51f, 0.27f, 0.33f}};
  ShadowBounds b = a;
  b.lo += glm::vec3(0.004f, -0.003f, 0.002f);  // within the same sixteenths
  b.hi += glm::vec3(0.005f, 0.004f, -0.003f);
  for (const glm::vec3& dir : kSuns) {
    const auto va = sun_view(dir, a), vb = sun_view(dir, b);
    EXPECT_EQ(std::memcmp(&va, &vb, sizeof va), 0);
  }
  ShadowBounds c = a;
  c.hi.x = 0.6f;  // past the next sixteenth: a new view
  const auto va = sun_view(kSuns[0], a), vc = sun_view(kSuns[0], c);
  EXPECT_NE(std::memcmp(&va, &vc, sizeof va), 0);
}

TEST(PunctualShadows, BoundsBeyondTheVolumeAreClippedToIt) {
  const ShadowBounds huge{glm::vec3(-5.0f), glm::vec3(4.0f)};
  const ShadowBounds outside{glm::vec3(2.0f), glm::vec3(3.0f)};  // nothing inside: whole volume
  for (const glm::vec3& dir : kSuns) {
    const auto whole = sun_view(dir, {});
    const auto a = sun_view(dir, huge), b = sun_view(dir, outside);
    EXPECT_EQ(std::memcmp(&whole, &a, sizeof whole), 0);
    EXPECT_EQ(std::memcmp(&whole, &b, sizeof whole), 0);
  }
}

TEST(PunctualShadows, FrameBoundsHoldTheInstancesAndSpheres) {
  rp::scene::SceneAssets assets;
  rp::scene::Mesh tri;
  tri.vertices.resize(3);
  tri.vertices[0].position = {0.0f, 0.0f, 0.0f};
  tri.vertices[1].position = {1.0f, 0.0f, 0.0f};
  tri.vertices[2].position = {0.0f, 2.0f, 0.5f};
  tri.triangles = {{0, 1, 2}};
  tri.materials = {0};
  assets.meshes.push_back(tri);
  assets.materials.resize(1);
  auto& ctx = rp::test::context();
  rp::render::GpuScene scene(ctx.context, ctx.queue, assets);
  rp::scene::FrameScene frame;
  EXPECT_TRUE(scene.frame_bounds(frame).empty());
  rp::scene::MeshInstance inst;
  inst.mesh = 0;
  inst.model = glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f, 0.1f, 0.2f)) *
               glm::scale(glm::mat4(1.0f), glm::vec3(0.25f));
  frame.instances.push_back(inst);
  ShadowBounds b = scene.frame_bounds(frame);
  EXPECT_EQ(b.lo, glm::vec3(-0.5f, 0.1f, 0.2f));
  EXPECT_EQ(b.hi, glm::vec3(-0.25f, 0.6f, 0.325f));
  rp::scene::Sphere s;
  s.center = {0.7f, -0.2f, 0.0f};
  s.radius = 0.1f;
  frame.spheres.push_back(s);
  b = scene.frame_bounds(frame);
  EXPECT_NEAR(b.lo.x, -0.5f, 1e-6f);
  EXPECT_NEAR(b.lo.y, -0.3f, 1e-6f);
  EXPECT_NEAR(b.lo.z, -0.1f, 1e-6f);
  EXPECT_NEAR(b.hi.x, 0.8f, 1e-6f);
  EXPECT_NEAR(b.hi.y, 0.6f, 1e-6f);
  EXPECT_NEAR(b.hi.z, 0.325f, 1e-6f);
}

}  // namespace
