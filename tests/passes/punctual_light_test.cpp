// The punctual light pass (kernels/punctual_light.cl, common/punctual_light.h) against the host's
// light model (scene/punctual_light.h, the path tracer's) on a hand-written GBuffer: matte
// points at random positions and normals under a directional, a spot and a point light (range
// window included), with every shadow view empty (all lit) and fully occluded (all dark: also
// near the point light's cube edges, where the receiver's push along its normal crosses faces).
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "passes/punctual_light.h"
#include "render/gpu_scene.h"
#include "scene/punctual_light.h"
#include "support/cl_fixture.h"

namespace {

struct Point {
  glm::vec3 p, n, albedo;
};

std::vector<rp::scene::PunctualLight> test_lights() {
  std::vector<rp::scene::PunctualLight> lights(3);
  lights[0].type = rp::scene::LightType::kDirectional;
  lights[0].direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.2f));
  lights[0].intensity = {0.8f, 0.7f, 0.6f};
  lights[1].type = rp::scene::LightType::kSpot;
  lights[1].position = {0.2f, 0.9f, 0.1f};
  lights[1].direction = glm::normalize(glm::vec3(-0.1f, -1.0f, 0.05f));
  lights[1].inner_cone = 0.4f;
  lights[1].outer_cone = 0.9f;
  lights[1].intensity = {0.5f, 0.6f, 0.9f};
  lights[2].type = rp::scene::LightType::kPoint;
  lights[2].position = {-0.5f, 0.4f, 0.3f};
  lights[2].range = 1.5f;
  lights[2].intensity = {0.9f, 0.5f, 0.2f};
  return lights;
}

// Runs the pass over `points` (one pixel each, 8 wide) with every shadow texel set to `depth`
// and returns rgba per pixel.
std::vector<float> run(const std::vector<Point>& points, float depth) {
  auto& ctx = rp::test::context();
  const uint32_t width = 8, height = uint32_t((points.size() + width) / width);
  const uint32_t shadow_size = 32;
  rp::render::GpuScene scene(ctx.context, ctx.queue, rp::scene::SceneAssets{});
  rp::scene::FrameScene frame;
  frame.lamp = false;
  frame.light.intensity = glm::vec3(0.0f);
  frame.lights = test_lights();
  scene.update(frame, width, height, shadow_size);
  const size_t n = size_t(width) * height;
  std::vector<float> albedo(n * 4, 0.0f), normal(n * 4, 0.0f), position(n * 4, 0.0f),
      emission(n * 4, 0.0f), hdr(n * 4, 0.0f);
  for (size_t i = 0; i < points.size(); ++i) {
    std::memcpy(&albedo[i * 4], &points[i].albedo, 12);
    std::memcpy(&normal[i * 4], &points[i].n, 12);
    std::memcpy(&position[i * 4], &points[i].p, 12);
    albedo[i * 4 + 3] = position[i * 4 + 3] = 1.0f;
  }
  rp::render::GBuffer gb;
  gb.resize(ctx.context, width, height);
  ctx.queue.enqueueWriteBuffer(gb.albedo, CL_TRUE, 0, n * 16, albedo.data());
  ctx.queue.enqueueWriteBuffer(gb.normal_depth, CL_TRUE, 0, n * 16, normal.data());
  ctx.queue.enqueueWriteBuffer(gb.position, CL_TRUE, 0, n * 16, position.data());
  ctx.queue.enqueueWriteBuffer(gb.emission, CL_TRUE, 0, n * 16, emission.data());
  rp::render::ShadowMap sm;
  sm.resize(ctx.context, shadow_size);
  sm.ensure_floats(ctx.context, 2 * uint64_t(shadow_size) * shadow_size + scene.punctual.floats);
  std::vector<float> depths(size_t(sm.depth_floats), depth);
  ctx.queue.enqueueWriteBuffer(sm.depth, CL_TRUE, 0, depths.size() * 4, depths.data());
  ::cl::Buffer out(ctx.context, CL_MEM_READ_WRITE, n * 16);
  ctx.queue.enqueueWriteBuffer(out, CL_TRUE, 0, n * 16, hdr.data());
  rp::cl::Profiler profiler(ctx.queue);
  rp::passes::PunctualLightPass pass(rp::test::programs());
  pass.run(profiler, scene, gb, sm, out, nullptr);
  ctx.queue.enqueueReadBuffer(out, CL_TRUE, 0, n * 16, hdr.data());
  return hdr;
}

std::vector<Point> random_points(int count) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-0.8f, 0.8f), a(0.1f, 0.9f);
  std::vector<Point> points;
  for (int i = 0; i < count; ++i) {
    Point pt;
    pt.p = {u(rng), u(rng) * 0.5f - 0.3f, u(rng)};
    pt.n = glm::normalize(glm::vec3(u(rng), u(rng) + 1.2f, u(rng)));  // mostly upwards
    pt.albedo = {a(rng), a(rng), a(rng)};
    points.push_back(pt);
  }
  return points;
}

TEST(PunctualLight, UnshadowedMatchesTheHostLightModel) {
  const std::vector<Point> points = random_points(61);
  const std::vector<float> hdr = run(points, 1.0f);  // every shadow view empty
  const auto lights = test_lights();
  for (size_t i = 0; i < points.size(); ++i) {
    glm::dvec3 expected(0.0);
    for (const auto& light : lights) {
      const rp::scene::LightSample s = rp::scene::sample_light(light, points[i].p);
      const double c = glm::dot(points[i].n, s.l);
      if (c > 0.0)
        expected += glm::dvec3(points[i].albedo) * glm::dvec3(light.intensity) * c *
                    double(s.attenuation);
    }
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(hdr[4 * i + size_t(k)], expected[k], 1e-4 + 1e-4 * expected[k])
          << "point " << i << " channel " << k;
  }
}

TEST(PunctualLight, FullyOccludedViewsLeaveNoLight) {
  const std::vector<Point> points = random_points(29);
  const std::vector<float> hdr = run(points, 0.0f);  // an occluder at every view's near plane
  for (size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(hdr[4 * i + size_t(k)], 0.0f) << "point " << i;
}

}  // namespace
