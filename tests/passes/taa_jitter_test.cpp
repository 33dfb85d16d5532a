// TAA sub-pixel jitter in GpuScene::update (SPEC 6.7): Halton(2,3) values by hand, offsets in
// (-0.5, 0.5) pixels, the jittered view_proj moves projected points by exactly the jitter
// (pixel y down), and the unjittered matrices stay unjittered.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <set>
#include <utility>

#include <glm/glm.hpp>

#include "render/gpu_scene.h"
#include "support/cl_fixture.h"

namespace {

using rp::render::halton;
using rp::render::taa_jitter_px;

TEST(TaaJitter, HaltonValuesByHand) {
  const float base2[] = {1.f / 2, 1.f / 4, 3.f / 4, 1.f / 8, 5.f / 8, 3.f / 8, 7.f / 8, 1.f / 16};
  const float base3[] = {1.f / 3, 2.f / 3, 1.f / 9, 4.f / 9, 7.f / 9, 2.f / 9, 5.f / 9, 8.f / 9};
  for (uint32_t i = 0; i < 8; ++i) {
    EXPECT_FLOAT_EQ(halton(i + 1, 2), base2[i]) << "index " << i + 1;
    EXPECT_FLOAT_EQ(halton(i + 1, 3), base3[i]) << "index " << i + 1;
  }
  EXPECT_FLOAT_EQ(halton(16, 2), 1.0f / 32);
  EXPECT_FLOAT_EQ(halton(9, 3), 1.0f / 27);
  EXPECT_EQ(halton(0, 2), 0.0f);
}

TEST(TaaJitter, SixteenDistinctOffsetsInsideThePixelThenRepeat) {
  // Frame 0 uses Halton point 1: (1/2, 1/3) - 0.5; frame 1 point 2: (1/4, 2/3) - 0.5.
  EXPECT_FLOAT_EQ(taa_jitter_px(0, 16).x, 0.0f);
  EXPECT_FLOAT_EQ(taa_jitter_px(0, 16).y, 1.0f / 3 - 0.5f);
  EXPECT_FLOAT_EQ(taa_jitter_px(1, 16).x, -0.25f);
  EXPECT_FLOAT_EQ(taa_jitter_px(1, 16).y, 2.0f / 3 - 0.5f);
  std::set<std::pair<float, float>> seen;
  glm::vec2 sum(0.0f);
  for (uint32_t k = 0; k < 16; ++k) {
    const glm::vec2 j = taa_jitter_px(k, 16);
    EXPECT_GT(j.x, -0.5f);
    EXPECT_LT(j.x, 0.5f);
    EXPECT_GT(j.y, -0.5f);
    EXPECT_LT(j.y, 0.5f);
    seen.insert({j.x, j.y});
    sum += j;
    EXPECT_EQ(taa_jitter_px(k + 16, 16), j) << "cycle of 16";
    EXPECT_EQ(taa_jitter_px(k, 0), glm::vec2(0.0f)) << "0 frames = off";
  }
  EXPECT_EQ(seen.size(), 16u);
  // Well spread: the mean offset is small (Halton is low-discrepancy).
  EXPECT_LT(std::abs(sum.x / 16), 0.05f);
  EXPECT_LT(std::abs(sum.y / 16), 0.05f);
}

// Pixel position of world point p under clip matrix m (types.h: y down).
glm::vec2 to_pixels(const glm::mat4& m, glm::vec3 p, float w, float h) {
  const glm::vec4 c = m * glm::vec4(p, 1.0f);
  return {(c.x / c.w * 0.5f + 0.5f) * w, (0.5f - c.y / c.w * 0.5f) * h};
}

glm::mat4 from_gpu(const rp::gpu::rp_mat4& m) {
  glm::mat4 out(1.0f);
  for (int i = 0; i < 4; ++i) out[i] = glm::vec4(m.c[i].x, m.c[i].y, m.c[i].z, m.c[i].w);
  return out;
}

class GpuSceneJitter : public ::testing::Test {
 protected:
  GpuSceneJitter()
      : scene_(rp::test::context().context, rp::test::context().queue, rp::scene::SceneAssets{}) {
    frame_.camera.position = {0.3f, 0.2f, 2.7f};
    frame_.prev_camera.position = {0.25f, 0.2f, 2.7f};
  }
  rp::render::GpuScene scene_;
  rp::scene::FrameScene frame_;
  static constexpr uint32_t kW = 160, kH = 90;
};

TEST_F(GpuSceneJitter, JitteredViewProjMovesPointsByTheJitterInPixels) {
  const float aspect = float(kW) / float(kH);
  const glm::mat4 expected_vp = frame_.camera.projection(aspect) * frame_.camera.view();
  const glm::mat4 expected_prev = frame_.prev_camera.projection(aspect) * frame_.prev_camera.view();
  const glm::vec3 points[] = {{0, 0, 0}, {-0.8f, 0.7f, -0.9f}, {0.9f, -0.95f, 0.5f}};
  glm::vec2 previous_jitter(0.0f);
  for (uint32_t k = 0; k < 20; ++k) {
    frame_.frame_index = k;
    scene_.update(frame_, kW, kH, 64, 64, 16);
    const auto& c = scene_.constants;
    const glm::vec2 jitter = taa_jitter_px(k, 16);
    EXPECT_EQ(glm::vec2(c.jitter.x, c.jitter.y), jitter) << "frame " << k;
    EXPECT_EQ(glm::vec2(c.jitter.z, c.jitter.w), previous_jitter) << "frame " << k;
    previous_jitter = jitter;
    EXPECT_EQ(std::memcmp(&c.view_proj_unjittered, &expected_vp, 64), 0) << "frame " << k;
    EXPECT_EQ(std::memcmp(&c.prev_view_proj_unjittered, &expected_prev, 64), 0) << "frame " << k;
    const glm::mat4 vp = from_gpu(c.view_proj), inv = from_gpu(c.inv_view_proj);
    for (const glm::vec3& p : points) {
      const glm::vec2 moved = to_pixels(vp, p, kW, kH) - to_pixels(expected_vp, p, kW, kH);
      EXPECT_NEAR(moved.x, jitter.x, 1e-4f) << "frame " << k;
      EXPECT_NEAR(moved.y, jitter.y, 1e-4f) << "frame " << k;
    }
    const glm::mat4 id = vp * inv;
    for (int i = 0; i < 4; ++i)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(id[i][r], i == r ? 1.0f : 0.0f, 1e-4f);
  }
}

TEST_F(GpuSceneJitter, NoJitterByDefault) {
  frame_.frame_index = 5;
  scene_.update(frame_, kW, kH, 64);
  const auto& c = scene_.constants;
  EXPECT_EQ(std::memcmp(&c.view_proj, &c.view_proj_unjittered, 64), 0);
  EXPECT_EQ(c.jitter.x, 0.0f);
  EXPECT_EQ(c.jitter.y, 0.0f);
  EXPECT_EQ(c.jitter.z, 0.0f);
  EXPECT_EQ(c.jitter.w, 0.0f);
}

}  // namespace
