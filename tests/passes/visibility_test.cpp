// The compute rasterizer (passes/visibility + kernels/visibility.cl) against the C++ reference
// (reference_raster.cpp, which mirrors the kernels' float operations) and against analytic
// ray-sphere intersection in double precision.
//
// Tolerances: ids and coverage must match exactly (same float edge functions); depth within
// 1e-5 relative and barycentrics within 1e-4 (they only differ by rounding of divisions).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "passes/reference_raster.h"
#include "passes/visibility.h"
#include "render/gpu_scene.h"
#include "render/gpu_types.h"
#include "support/cl_fixture.h"

namespace rp::test {
namespace {

glm::mat4 to_glm(const gpu::rp_mat4& m) {
  glm::mat4 out;
  for (int c = 0; c < 4; ++c) out[c] = glm::vec4(m.c[c].x, m.c[c].y, m.c[c].z, m.c[c].w);
  return out;
}

struct GpuImage {
  uint32_t width = 0, height = 0;
  std::vector<float> depth;
  std::vector<glm::uvec2> ids;
  std::vector<glm::vec2> bary;
  size_t index(uint32_t x, uint32_t y) const { return size_t(y) * width + x; }
  bool operator==(const GpuImage& o) const {  // bitwise
    return width == o.width && height == o.height &&
           std::equal(depth.begin(), depth.end(), o.depth.begin(), o.depth.end(),
                      [](float a, float b) { return std::memcmp(&a, &b, 4) == 0; }) &&
           ids == o.ids &&
           std::equal(bary.begin(), bary.end(), o.bary.begin(), o.bary.end(),
                      [](glm::vec2 a, glm::vec2 b) { return std::memcmp(&a, &b, 8) == 0; });
  }
};

GpuImage read_back(const render::VisibilityBuffer& vb) {
  GpuImage img;
  img.width = vb.width;
  img.height = vb.height;
  size_t n = size_t(vb.width) * vb.height;
  img.depth.resize(n);
  img.ids.resize(n);
  img.bary.resize(n);
  ::cl::CommandQueue& q = context().queue;
  q.enqueueReadBuffer(vb.depth, CL_TRUE, 0, n * sizeof(float), img.depth.data());
  q.enqueueReadBuffer(vb.ids, CL_TRUE, 0, n * sizeof(glm::uvec2), img.ids.data());
  q.enqueueReadBuffer(vb.bary, CL_TRUE, 0, n * sizeof(glm::vec2), img.bary.data());
  return img;
}

// Renders frames of one scene with one pass object, as the renderer does.
class Harness {
 public:
  explicit Harness(const scene::SceneAssets& assets)
      : scene_(context().context, context().queue, assets),
        pass_(context(), programs()),
        profiler_(context().queue) {}

  // Camera view. `replace`: render with this view_proj / inv_view_proj instead of the camera's.
  GpuImage render(const scene::FrameScene& frame, uint32_t w, uint32_t h,
                  const std::optional<RefView>& replace = std::nullopt) {
    scene_.update(frame, w, h, 64);
    if (replace) {
      scene_.constants.view_proj = gpu::to_gpu(replace->view_proj);
      scene_.constants.view_proj_unjittered = scene_.constants.view_proj;  // what culls
      scene_.constants.inv_view_proj = gpu::to_gpu(replace->inv_view_proj);
    }
    if (vb_.width != w || vb_.height != h) vb_.resize(context().context, w, h);
    pass_.render(profiler_, scene_, vb_);
    times_ = profiler_.collect();
    return read_back(vb_);
  }

  // The view the last render() used, for the reference.
  RefView view() const {
    RefView v;
    v.view_proj = to_glm(scene_.constants.view_proj);
    v.inv_view_proj = to_glm(scene_.constants.inv_view_proj);
    v.width = vb_.width;
    v.height = vb_.height;
    return v;
  }

  std::vector<float> render_shadow(const scene::FrameScene& frame, uint32_t size) {
    scene_.update(frame, 16, 16, size);
    if (sm_.size != size) sm_.resize(context().context, size);
    pass_.render_shadow(profiler_, scene_, sm_);
    times_ = profiler_.collect();
    std::vector<float> depth(2 * size_t(size) * size);  // nearest, then farthest plane
    context().queue.enqueueReadBuffer(sm_.depth, CL_TRUE, 0, depth.size() * sizeof(float),
                                      depth.data());
    return depth;
  }

  RefView shadow_view() const {
    RefView v;
    v.view_proj = to_glm(scene_.constants.light_view_proj);
    v.inv_view_proj = glm::inverse(v.view_proj);
    v.width = v.height = sm_.size;
    v.depth_only = true;
    return v;
  }

  const rp::cl::PassTimes& times() const { return times_; }
  uint32_t camera_triangles() const { return pass_.camera_triangles(); }

 private:
  render::GpuScene scene_;
  passes::VisibilityPass pass_;
  rp::cl::Profiler profiler_;
  render::VisibilityBuffer vb_;
  render::ShadowMap sm_;
  rp::cl::PassTimes times_;
};

// Same ids everywhere; depth within 1e-5 relative, barycentrics within 1e-4 where ids agree.
void expect_matches_reference(const GpuImage& g, const RefImage& r) {
  ASSERT_EQ(g.width, r.width);
  ASSERT_EQ(g.height, r.height);
  int id_errors = 0, depth_errors = 0, bary_errors = 0;
  for (uint32_t y = 0; y < g.height; ++y)
    for (uint32_t x = 0; x < g.width; ++x) {
      const size_t i = g.index(x, y);
      if (!r.alpha_edge.empty() && r.alpha_edge[i]) continue;  // either answer is right
      if (g.ids[i] != r.ids[i]) {
        if (++id_errors <= 5)
          ADD_FAILURE() << "ids at " << x << "," << y << ": kernel (" << g.ids[i].x << ","
                        << g.ids[i].y << ") reference (" << r.ids[i].x << "," << r.ids[i].y << ")";
        continue;
      }
      if (!(std::abs(g.depth[i] - r.depth[i]) <= 1e-5f * std::abs(r.depth[i])) &&
          ++depth_errors <= 5)
        ADD_FAILURE() << "depth at " << x << "," << y << ": " << g.depth[i] << " vs "
                      << r.depth[i];
      glm::vec2 d = glm::abs(g.bary[i] - r.bary[i]);
      if (!(d.x <= 1e-4f && d.y <= 1e-4f) && ++bary_errors <= 5)
        ADD_FAILURE() << "bary at " << x << "," << y << ": (" << g.bary[i].x << ","
                      << g.bary[i].y << ") vs (" << r.bary[i].x << "," << r.bary[i].y << ")";
    }
  EXPECT_EQ(id_errors, 0);
  EXPECT_EQ(depth_errors, 0);
  EXPECT_EQ(bary_errors, 0);
}

// Deterministic pseudo-random numbers in [0, 1).
struct Rng {
  uint32_t state;
  float next() {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) * (1.0f / 16777216.0f);
  }
  float range(float lo, float hi) { return lo + (hi - lo) * next(); }
};

scene::Mesh random_triangles(uint32_t seed, int count) {
  Rng rng{seed};
  std::vector<glm::vec3> pos;
  std::vector<glm::uvec3> tris;
  for (int t = 0; t < count; ++t) {
    glm::vec3 c(rng.range(-1.2f, 1.2f), rng.range(-0.9f, 0.9f), rng.range(-0.8f, 0.8f));
    for (int k = 0; k < 3; ++k)
      pos.push_back(c + glm::vec3(rng.range(-0.6f, 0.6f), rng.range(-0.6f, 0.6f),
                                  rng.range(-0.4f, 0.4f)));
    tris.push_back({uint32_t(3 * t), uint32_t(3 * t + 1), uint32_t(3 * t + 2)});
  }
  return make_test_mesh(pos, tris);
}

// Triangles that cross the near plane (camera at z = 2.75, near 0.1) or the eye plane, and one
// far behind everything that covers the whole view (touching every screen edge).
scene::Mesh special_triangles() {
  return make_test_mesh({{-0.3f, -0.2f, 2.9f}, {0.4f, 0.1f, 1.0f}, {-0.2f, 0.5f, 0.5f},
                         {0.1f, -0.3f, 2.70f}, {0.6f, -0.2f, 1.5f}, {0.2f, 0.4f, 1.2f},
                         {-20.0f, -20.0f, -0.95f}, {20.0f, -20.0f, -0.95f}, {0.0f, 30.0f, -0.95f},
                         {-3.0f, -0.4f, 2.70f}, {3.0f, -0.4f, 2.70f}, {0.0f, -0.8f, 0.0f}},
                        {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {9, 10, 11}});
}

glm::mat4 rotation_z(float angle, glm::vec3 translation) {
  float c = std::cos(angle), s = std::sin(angle);
  return glm::mat4(glm::vec4(c, s, 0, 0), glm::vec4(-s, c, 0, 0), glm::vec4(0, 0, 1, 0),
                   glm::vec4(translation, 1));
}

struct TestScene {
  scene::SceneAssets assets;
  scene::FrameScene frame = make_test_frame();
};

TestScene random_scene() {
  TestScene s;
  s.assets = make_test_assets({random_triangles(7u, 12), special_triangles()});
  scene::MeshInstance a, b, c;
  a.mesh = 0;
  b.mesh = 0;
  b.model = rotation_z(0.7f, glm::vec3(0.2f, -0.1f, -0.3f));
  c.mesh = 1;
  s.frame.instances = {a, b, c};
  return s;
}

TEST(Visibility, RandomTrianglesMatchReference) {
  TestScene s = random_scene();
  Harness h(s.assets);
  GpuImage g = h.render(s.frame, 64, 48);
  RefImage r = reference_raster(s.assets, s.frame, h.view());
  expect_matches_reference(g, r);
  // The scene exercises what it should: all three instances and the background-free view.
  std::vector<int> seen(3, 0);
  for (const glm::uvec2& id : g.ids)
    if (id.x < 3) ++seen[id.x];
  EXPECT_GT(seen[0], 0);
  EXPECT_GT(seen[1], 0);
  EXPECT_GT(seen[2], 0);
}

TEST(Visibility, OddSizeMatchesReference) {
  // Partial tiles on the right and bottom edges.
  TestScene s = random_scene();
  Harness h(s.assets);
  GpuImage g = h.render(s.frame, 37, 21);
  expect_matches_reference(g, reference_raster(s.assets, s.frame, h.view()));
}

TEST(Visibility, IcosphereMatchesReference) {
  scene::SceneAssets assets = make_test_assets({make_icosphere(2, 0.8f)});
  scene::FrameScene frame = make_test_frame();
  scene::MeshInstance inst;
  inst.model = rotation_z(0.3f, glm::vec3(0.05f, -0.1f, 0.3f));
  frame.instances.push_back(inst);
  Harness h(assets);
  GpuImage g = h.render(frame, 64, 64);
  expect_matches_reference(g, reference_raster(assets, frame, h.view()));

  // From inside the sphere every pixel sees it (no backface culling, no cracks).
  frame.camera.position = glm::vec3(0.1f, 0.0f, 0.3f);
  frame.camera.target = glm::vec3(0.0f, -0.5f, -1.0f);
  g = h.render(frame, 48, 48);
  expect_matches_reference(g, reference_raster(assets, frame, h.view()));
  for (const glm::uvec2& id : g.ids) ASSERT_EQ(id.x, 0u);
}

TEST(Visibility, PixelAlignedGridMatchesReference) {
  // Orthographic view with vertices on pixel centres and power-of-two sizes (all float steps
  // exact): many edge and vertex ties, all settled by the top-left rule, identically in the
  // kernel and the reference, each pixel covered at most once.
  std::vector<glm::vec3> pos;
  std::vector<glm::uvec3> tris;
  const int n = 5;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      pos.emplace_back(4.5f + 11.0f * float(i) + float((i * j) % 3),
                       3.5f + 8.0f * float(j) + float((i + 2 * j) % 3), 0.25f);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      if ((i + j) % 2) {
        tris.push_back({a, b, c});
        tris.push_back({a, c, d});
      } else {
        tris.push_back({a, b, d});
        tris.push_back({d, b, c});  // reversed winding: the fill rule must not care
      }
    }
  scene::SceneAssets assets = make_test_assets({make_test_mesh(pos, tris)});
  scene::FrameScene frame = make_test_frame();
  frame.instances.push_back({});
  RefView ortho;
  ortho.width = 64;
  ortho.height = 64;
  ortho.view_proj = glm::mat4(1.0f);
  ortho.view_proj[0][0] = 2.0f / 64.0f;
  ortho.view_proj[1][1] = -2.0f / 64.0f;
  ortho.view_proj[3][0] = -1.0f;
  ortho.view_proj[3][1] = 1.0f;
  ortho.inv_view_proj = glm::inverse(ortho.view_proj);
  Harness h(assets);
  GpuImage g = h.render(frame, 64, 64, ortho);
  RefImage r = reference_raster(assets, frame, h.view());
  expect_matches_reference(g, r);
  int covered = 0;
  for (size_t i = 0; i < r.ids.size(); ++i) {
    EXPECT_LE(r.hits_positive[i] + r.hits_negative[i], 1u);
    covered += g.ids[i].x == 0u;
  }
  EXPECT_GT(covered, 1500);
}

// Spheres only, against ray-sphere intersection in double precision. Pixels whose ray passes
// within 0.1 % of the radius of a silhouette are skipped (float rays may fall either side).
TEST(Visibility, SpheresMatchAnalyticIntersection) {
  scene::SceneAssets assets = make_test_assets({});
  scene::FrameScene frame = make_test_frame();
  auto sphere = [](glm::vec3 c, float r) {
    scene::Sphere s;
    s.center = c;
    s.prev_center = c;
    s.radius = r;
    return s;
  };
  frame.spheres = {sphere({0.2f, 0.1f, 0.3f}, 0.25f), sphere({0.0f, 0.0f, 0.0f}, 0.4f),
                   sphere({1.8f, 0.6f, 0.2f}, 0.3f),   // partly off the right edge
                   sphere({0.0f, 0.0f, 3.3f}, 0.2f),   // behind the camera
                   sphere({-0.5f, -0.3f, 0.6f}, 0.05f), sphere({-0.6f, 0.5f, -0.5f}, 0.0f)};
  Harness h(assets);
  GpuImage g = h.render(frame, 64, 48);
  RefView view = h.view();
  expect_matches_reference(g, reference_raster(assets, frame, view));

  const glm::dmat4 vp(view.view_proj);
  const glm::dmat4 inv = glm::inverse(vp);
  const glm::dvec3 eye(frame.camera.position);
  int checked = 0, hits = 0;
  for (uint32_t y = 0; y < 48; ++y)
    for (uint32_t x = 0; x < 64; ++x) {
      glm::dvec4 far = inv * glm::dvec4((x + 0.5) / 32.0 - 1.0, 1.0 - (y + 0.5) / 24.0, 1.0, 1.0);
      glm::dvec3 dir = glm::normalize(glm::dvec3(far) / far.w - eye);
      double best_t = 1e30, margin = 1e30;
      uint32_t best = RP_ID_NONE;
      for (uint32_t s = 0; s < frame.spheres.size(); ++s) {
        const scene::Sphere& sp = frame.spheres[s];
        glm::dvec3 oc = eye - glm::dvec3(sp.center);
        double b = glm::dot(oc, dir);
        double dist = glm::length(oc - b * dir);
        margin = std::min(margin, std::abs(dist - sp.radius) / std::max(1e-9, double(sp.radius)));
        double disc = double(sp.radius) * sp.radius - dist * dist;
        if (sp.radius <= 0.0f || disc < 0.0) continue;
        double t = -b - std::sqrt(disc);
        if (t > 0.0 && t < best_t) {
          best_t = t;
          best = RP_ID_SPHERE_BIT | s;
        }
      }
      if (margin < 1e-3) continue;
      ++checked;
      const size_t i = g.index(x, y);
      ASSERT_EQ(g.ids[i].x, best) << "pixel " << x << "," << y;
      if (best == RP_ID_NONE) {
        EXPECT_EQ(g.depth[i], 1.0f);
        continue;
      }
      ++hits;
      EXPECT_EQ(g.ids[i].y, 0u);
      EXPECT_EQ(g.bary[i], glm::vec2(0.0f));
      glm::dvec4 clip = vp * glm::dvec4(eye + best_t * dir, 1.0);
      double depth = clip.z / clip.w * 0.5 + 0.5;
      EXPECT_NEAR(g.depth[i], depth, 1e-5 * depth) << "pixel " << x << "," << y;
    }
  EXPECT_GT(checked, 2800);
  EXPECT_GT(hits, 150);
}

TEST(Visibility, SpheresAgainstTriangles) {
  // A quad at z = 0; sphere 0 in front of it, sphere 1 behind it, sphere 2 cutting through it
  // (its cap in front of the quad, the rest of its silhouette behind).
  scene::SceneAssets assets = make_test_assets({make_test_mesh(
      {{-0.8f, -0.8f, 0.0f}, {0.8f, -0.8f, 0.0f}, {0.8f, 0.8f, 0.0f}, {-0.8f, 0.8f, 0.0f}},
      {{0, 1, 2}, {0, 2, 3}})});
  scene::FrameScene frame = make_test_frame();
  frame.instances.push_back({});
  auto sphere = [](glm::vec3 c, float r) {
    scene::Sphere s;
    s.center = c;
    s.radius = r;
    return s;
  };
  frame.spheres = {sphere({0.3f, 0.35f, 0.3f}, 0.2f), sphere({-0.35f, -0.3f, -0.4f}, 0.3f),
                   sphere({0.35f, -0.35f, -0.1f}, 0.25f)};
  Harness h(assets);
  GpuImage g = h.render(frame, 64, 64);
  RefView view = h.view();
  expect_matches_reference(g, reference_raster(assets, frame, view));

  auto pixel_of = [&](glm::vec3 p) {
    glm::vec4 c = view.view_proj * glm::vec4(p, 1.0f);
    return g.index(uint32_t((c.x / c.w + 1.0f) * 32.0f), uint32_t((1.0f - c.y / c.w) * 32.0f));
  };
  EXPECT_EQ(g.ids[pixel_of({0.3f, 0.35f, 0.3f})].x, RP_ID_SPHERE_BIT | 0u);
  EXPECT_EQ(g.ids[pixel_of({-0.35f, -0.3f, -0.4f})].x, 0u);  // hidden behind the quad
  EXPECT_EQ(g.ids[pixel_of({0.35f, -0.35f, 0.0f})].x, RP_ID_SPHERE_BIT | 2u);
  int sphere1 = 0;
  for (const glm::uvec2& id : g.ids) sphere1 += id.x == (RP_ID_SPHERE_BIT | 1u);
  EXPECT_EQ(sphere1, 0);

  // Where sphere 2 cuts the quad, the nearer of plane and sphere (in double) must win; both
  // must win somewhere. Pixels within 0.1 % of the silhouette or of the cut are skipped.
  const glm::dmat4 inv = glm::inverse(glm::dmat4(view.view_proj));
  const glm::dvec3 eye(frame.camera.position), centre(0.35, -0.35, -0.1);
  int quad_wins = 0, sphere_wins = 0;
  for (uint32_t y = 0; y < 64; ++y)
    for (uint32_t x = 0; x < 64; ++x) {
      glm::dvec4 far = inv * glm::dvec4((x + 0.5) / 32.0 - 1.0, 1.0 - (y + 0.5) / 32.0, 1.0, 1.0);
      glm::dvec3 dir = glm::normalize(glm::dvec3(far) / far.w - eye);
      glm::dvec3 oc = eye - centre;
      double b = glm::dot(oc, dir), dist = glm::length(oc - b * dir);
      if (dist > 0.25 * 0.999) continue;
      double t_sphere = -b - std::sqrt(0.0625 - dist * dist);
      double t_plane = -eye.z / dir.z;
      if (std::abs(t_sphere - t_plane) < 1e-3) continue;
      uint32_t expected = t_plane < t_sphere ? 0u : (RP_ID_SPHERE_BIT | 2u);
      EXPECT_EQ(g.ids[g.index(x, y)].x, expected) << "pixel " << x << "," << y;
      (expected == 0u ? quad_wins : sphere_wins) += 1;
    }
  EXPECT_GT(quad_wins, 5);
  EXPECT_GT(sphere_wins, 50);
}

TEST(Visibility, ShadowMapMatchesReference) {
  scene::SceneAssets assets = make_test_assets(
      {make_test_mesh({{-1, -1, -1}, {1, -1, -1}, {1, -1, 1}, {-1, -1, 1}}, {{0, 1, 2}, {0, 2, 3}}),
       make_icosphere(1, 0.3f),
       make_test_mesh({{0.2f, 0.5f, 0.2f}, {0.7f, 0.5f, 0.2f}, {0.7f, 0.5f, 0.7f}}, {{0, 1, 2}})});
  scene::FrameScene frame = make_test_frame();
  scene::MeshInstance floor, ball, blocker;
  floor.mesh = 0;
  ball.mesh = 1;
  ball.model = rotation_z(0.0f, glm::vec3(0.0f, -0.5f, 0.0f));
  blocker.mesh = 2;
  blocker.casts_shadow = false;  // must not appear in the shadow map
  frame.instances = {floor, ball, blocker};
  scene::Sphere marble, fireball;
  marble.center = marble.prev_center = glm::vec3(-0.5f, -0.7f, 0.3f);
  marble.radius = 0.15f;
  fireball.center = fireball.prev_center = glm::vec3(0.4f, -0.6f, -0.4f);
  fireball.radius = 0.2f;
  fireball.casts_shadow = false;
  frame.spheres = {marble, fireball};

  Harness h(assets);
  std::vector<float> depth = h.render_shadow(frame, 64);
  RefView view = h.shadow_view();
  RefImage r = reference_raster(assets, frame, view);
  // Had the blocker and fireball cast shadows, the map would differ: the test sees them.
  scene::FrameScene all_cast = frame;
  all_cast.instances[2].casts_shadow = true;
  all_cast.spheres[1].casts_shadow = true;
  RefImage r_all = reference_raster(assets, all_cast, view);
  int errors = 0, differs = 0, on_ball = 0, thick = 0;
  const size_t plane = r.depth.size();
  ASSERT_EQ(depth.size(), 2 * plane);
  for (size_t i = 0; i < plane; ++i) {
    if (!(std::abs(depth[i] - r.depth[i]) <= 1e-5f * r.depth[i]) && ++errors <= 5)
      ADD_FAILURE() << "texel " << i << ": " << depth[i] << " vs " << r.depth[i];
    // the farthest plane: the ball's and marble's far sides, the floor's own depth below them
    const float back = depth[plane + i];
    if (!(std::abs(back - r.back[i]) <= 1e-5f * std::max(r.back[i], 1e-3f)) && ++errors <= 5)
      ADD_FAILURE() << "texel " << i << " (farthest): " << back << " vs " << r.back[i];
    if (depth[i] < 1.0f) {
      EXPECT_GE(back, depth[i]) << "texel " << i;
    }
    differs += depth[i] != r_all.depth[i];
    on_ball += depth[i] < 0.99f;
    thick += back > depth[i];
  }
  EXPECT_EQ(errors, 0);
  EXPECT_GT(differs, 20);
  EXPECT_GT(on_ball, 25);
  EXPECT_GT(thick, 25);
}

TEST(Visibility, EqualDepthsResolveByIds) {
  // Mesh 0: triangle A, a different triangle B, and A again (identical vertices: equal depths).
  // Two identical instances of it: instance 0 and primitive 0 must win every tie.
  std::vector<glm::vec3> pos = {{-0.6f, -0.5f, 0.0f}, {0.6f, -0.5f, 0.0f}, {0.0f, 0.6f, 0.0f},
                                {-0.2f, -0.7f, 0.0f}, {0.7f, 0.2f, 0.0f}, {-0.4f, 0.4f, 0.0f},
                                {-0.6f, -0.5f, 0.0f}, {0.6f, -0.5f, 0.0f}, {0.0f, 0.6f, 0.0f}};
  scene::SceneAssets assets =
      make_test_assets({make_test_mesh(pos, {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}})});
  scene::FrameScene frame = make_test_frame();
  frame.instances = {scene::MeshInstance{}, scene::MeshInstance{}};
  Harness h(assets);
  GpuImage g = h.render(frame, 64, 64);
  RefImage r = reference_raster(assets, frame, h.view());
  // A and B lie in one plane but are different triangles: their interpolated depths agree
  // only to rounding, which a device that fuses a * b + c rounds differently. Where they
  // overlap either may win; A's duplicate and the second instance are computed from the same
  // numbers, so those ties are exact and must go to the lower ids.
  int covered = 0, on_a = 0, a_or_b = 0;
  for (size_t i = 0; i < g.ids.size(); ++i) {
    ASSERT_EQ(g.ids[i].x == RP_ID_NONE, r.ids[i].x == RP_ID_NONE) << "coverage at " << i;
    if (g.ids[i] != r.ids[i]) {
      ++a_or_b;
      EXPECT_TRUE(g.ids[i].y + r.ids[i].y == 1u) << "kernel " << g.ids[i].y << " reference "
                                                 << r.ids[i].y << " at " << i;
      EXPECT_NEAR(g.depth[i], r.depth[i], 1e-5f * std::abs(r.depth[i])) << "at " << i;
    }
    if (g.ids[i].x == RP_ID_NONE) continue;
    ++covered;
    EXPECT_EQ(g.ids[i].x, 0u);
    EXPECT_NE(g.ids[i].y, 2u);  // A's duplicate never beats A
    on_a += g.ids[i].y == 0u;
  }
  EXPECT_GT(covered, 250);
  EXPECT_GT(on_a, 100);
  EXPECT_LE(a_or_b, covered / 50);
}

TEST(Visibility, SameFrameTwiceAndEverySpanAreBitIdentical) {
  TestScene s = random_scene();
  scene::Sphere ball;
  ball.center = glm::vec3(0.1f, 0.2f, 0.5f);
  ball.radius = 0.3f;
  s.frame.spheres = {ball};
  GpuImage first, second, other_span;
  {
    Harness h(s.assets);
    first = h.render(s.frame, 64, 48);
    second = h.render(s.frame, 64, 48);
  }
  EXPECT_TRUE(first == second);
  // The other work-item layout (1 pixel per work-item vs SIMD-wide spans).
  const bool gpu_default = context().info.is_gpu;
  setenv("ROLYPOLY_RASTER_SPAN", gpu_default ? "16" : "1", 1);
  try {
    Harness h(s.assets);
    other_span = h.render(s.frame, 64, 48);
  } catch (...) {
    unsetenv("ROLYPOLY_RASTER_SPAN");
    throw;
  }
  unsetenv("ROLYPOLY_RASTER_SPAN");
  EXPECT_TRUE(first == other_span);
}

TEST(Visibility, TileListGrowsAndInstanceSetChanges) {
  // Many large overlapping triangles: the list total exceeds the first guess. The first frame
  // with them overflows the list (the raster kernel then tests every item in the cut tiles),
  // the next ones use the list grown from the total read back; all match the reference.
  std::vector<glm::vec3> pos;
  std::vector<glm::uvec3> tris;
  for (int t = 0; t < 24; ++t) {
    float z = -0.9f + 0.07f * float(t);
    float a = 0.4f * float(t);
    for (int k = 0; k < 3; ++k) {
      float ang = a + 2.0944f * float(k);
      pos.emplace_back(3.0f * std::cos(ang), 3.0f * std::sin(ang), z);
    }
    tris.push_back({uint32_t(3 * t), uint32_t(3 * t + 1), uint32_t(3 * t + 2)});
  }
  scene::SceneAssets assets = make_test_assets({make_test_mesh(pos, tris), random_triangles(3u, 8)});
  scene::FrameScene frame = make_test_frame();
  scene::MeshInstance big, small;
  big.mesh = 0;
  small.mesh = 1;
  frame.instances = {small};
  Harness h(assets);
  GpuImage g = h.render(frame, 64, 48);
  expect_matches_reference(g, reference_raster(assets, frame, h.view()));
  frame.instances = {small, big};
  for (int i = 0; i < 2; ++i) {
    g = h.render(frame, 64, 48);
    expect_matches_reference(g, reference_raster(assets, frame, h.view()));
  }
  frame.instances = {big};
  g = h.render(frame, 80, 32);  // and a resize
  expect_matches_reference(g, reference_raster(assets, frame, h.view()));
}

// The camera leaves out instances wholly outside its frustum (not set up at all), and keeps
// one that straddles its edge: the picture is the reference's, which draws every instance.
TEST(Visibility, InstancesOutsideTheFrustumAreNotSetUp) {
  scene::SceneAssets assets = make_test_assets({random_triangles(11u, 12)});
  scene::FrameScene frame = make_test_frame();
  scene::MeshInstance inside, right, behind, edge;
  right.model = glm::translate(glm::mat4(1.0f), glm::vec3(40.0f, 0.0f, 0.0f));
  behind.model = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 12.0f));
  edge.model = glm::translate(glm::mat4(1.0f), glm::vec3(2.2f, 0.0f, 0.0f));
  frame.instances = {inside, right, behind, edge};
  Harness h(assets);
  GpuImage g = h.render(frame, 64, 48);
  expect_matches_reference(g, reference_raster(assets, frame, h.view()));
  EXPECT_EQ(h.camera_triangles(), 2u * 12u) << "the inside and the edge instance";
  bool edge_seen = false;
  for (const glm::uvec2& id : g.ids) edge_seen = edge_seen || id.x == 3u;
  EXPECT_TRUE(edge_seen) << "the edge instance should show (the test's set-up)";

  frame.instances[1].model = glm::mat4(1.0f);  // moved into view: set up again
  g = h.render(frame, 64, 48);
  expect_matches_reference(g, reference_raster(assets, frame, h.view()));
  EXPECT_EQ(h.camera_triangles(), 3u * 12u);
}

// ---- alpha masks (scene/frame_scene.h AlphaMode::kMask, kernels/common/alpha_mask.h) ----

// An 8x8 texture whose alpha makes holes: 0 or 255 in 2x2 blocks, a few blocks at 128
// (bilinear ramps cross the 0.5 cutoff between texel centres).
scene::Texture hole_texture(scene::TextureWrap wrap_u, scene::TextureWrap wrap_v) {
  scene::Texture t;
  t.name = "holes";
  t.width = t.height = 8;
  t.wrap_u = wrap_u;
  t.wrap_v = wrap_v;
  t.rgba.resize(8 * 8 * 4, 200);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const int block = (x / 2) + 4 * (y / 2);
      t.rgba[4 * (8 * y + x) + 3] = block % 3 == 0 ? 0 : block % 5 == 1 ? 128 : 255;
    }
  return t;
}

// A quad from `lo` to `hi` in the plane z = const (or, with `horizontal`, y = const), uv from
// uv_lo to uv_hi, every triangle of material `material`.
scene::Mesh card(glm::vec3 lo, glm::vec3 hi, glm::vec2 uv_lo, glm::vec2 uv_hi, uint32_t material,
                 bool horizontal = false) {
  std::vector<glm::vec3> p;
  if (horizontal)
    p = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z}};
  else
    p = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z}};
  scene::Mesh m = make_test_mesh(p, {{0, 1, 2}, {0, 2, 3}});
  const glm::vec2 uv[4] = {uv_lo, {uv_hi.x, uv_lo.y}, uv_hi, {uv_lo.x, uv_hi.y}};
  for (int k = 0; k < 4; ++k) m.vertices[size_t(k)].uv = uv[k];
  m.materials.assign(2, material);
  return m;
}

// Materials: 0 grey (opaque), 1 cut by the hole texture, 2 masked with no texture and an
// opacity below its cutoff (invisible).
void add_masked_materials(scene::SceneAssets& assets, scene::TextureWrap wrap_u,
                          scene::TextureWrap wrap_v) {
  assets.textures.push_back(hole_texture(wrap_u, wrap_v));
  scene::Material cut, gone;
  cut.name = "cut";
  cut.texture = 0;
  cut.alpha_mode = scene::AlphaMode::kMask;
  cut.alpha_cutoff = 0.5f;
  gone.name = "gone";
  gone.alpha_mode = scene::AlphaMode::kMask;
  gone.opacity = 0.3f;
  gone.alpha_cutoff = 0.4f;
  assets.materials = {assets.materials.at(0), cut, gone};
}

TEST(Visibility, AlphaMaskedCardsMatchReferenceWithEveryWrapMode) {
  using scene::TextureWrap;
  const TextureWrap modes[][2] = {{TextureWrap::kRepeat, TextureWrap::kMirroredRepeat},
                                  {TextureWrap::kClampToEdge, TextureWrap::kRepeat},
                                  {TextureWrap::kMirroredRepeat, TextureWrap::kClampToEdge}};
  for (const auto& wrap : modes) {
    scene::Mesh tris = random_triangles(11u, 10);
    for (size_t t = 0; t < tris.triangles.size(); ++t) tris.materials[t] = uint32_t(t % 3);
    for (size_t v = 0; v < tris.vertices.size(); ++v)
      tris.vertices[v].uv = glm::vec2(float(v % 5) * 0.45f - 0.7f, float(v % 7) * 0.3f - 0.4f);
    scene::SceneAssets assets = make_test_assets(
        {card({-1.1f, -0.8f, 0.2f}, {1.1f, 0.8f, 0.2f}, {-0.6f, -0.3f}, {2.1f, 1.8f}, 1),
         card({-3.0f, -3.0f, -0.7f}, {3.0f, 3.0f, -0.7f}, {0.0f, 0.0f}, {1.0f, 1.0f}, 0), tris});
    add_masked_materials(assets, wrap[0], wrap[1]);
    scene::FrameScene frame = make_test_frame();
    scene::MeshInstance front, back, scattered;
    front.mesh = 0;
    back.mesh = 1;
    scattered.mesh = 2;
    scattered.model = rotation_z(0.4f, glm::vec3(0.1f, 0.0f, 0.5f));
    frame.instances = {front, back, scattered};
    Harness h(assets);
    const GpuImage g = h.render(frame, 96, 64);
    const RefImage r = reference_raster(assets, frame, h.view());
    expect_matches_reference(g, r);
    // The card shows both: itself and the background through its holes; the invisible
    // material never appears.
    int card_pixels = 0, holes = 0, edges = 0;
    for (uint32_t y = 16; y < 48; ++y)
      for (uint32_t x = 24; x < 72; ++x) {
        const size_t i = g.index(x, y);
        card_pixels += g.ids[i].x == 0;
        holes += g.ids[i].x == 1;
      }
    for (size_t i = 0; i < g.ids.size(); ++i) {
      edges += r.alpha_edge[i];
      if (g.ids[i].x == 2) {
        ASSERT_NE(assets.meshes[2].materials[g.ids[i].y], 2u);
      }
    }
    EXPECT_GT(card_pixels, 200);
    EXPECT_GT(holes, 200);
    EXPECT_LT(edges, int(g.ids.size() / 50)) << "too few pixels compared";
  }
}

TEST(Visibility, AlphaMaskedCardCastsShadowsThroughItsHolesOnly) {
  scene::SceneAssets assets = make_test_assets(
      {card({-1.0f, -1.0f, -1.0f}, {1.0f, -1.0f, 1.0f}, {0, 0}, {1, 1}, 0, true),
       card({-0.8f, 0.0f, -0.8f}, {0.8f, 0.0f, 0.8f}, {-0.2f, -0.2f}, {1.3f, 1.3f}, 1, true)});
  add_masked_materials(assets, scene::TextureWrap::kRepeat, scene::TextureWrap::kRepeat);
  scene::FrameScene frame = make_test_frame();
  scene::MeshInstance floor, canopy;
  floor.mesh = 0;
  canopy.mesh = 1;
  frame.instances = {floor, canopy};
  Harness h(assets);
  const std::vector<float> depth = h.render_shadow(frame, 64);
  const RefImage r = reference_raster(assets, frame, h.shadow_view());
  const size_t plane = r.depth.size();
  int errors = 0, lit_through = 0, blocked = 0;
  for (size_t i = 0; i < plane; ++i) {
    if (r.alpha_edge[i]) continue;
    if (!(std::abs(depth[i] - r.depth[i]) <= 1e-5f * r.depth[i]) && ++errors <= 5)
      ADD_FAILURE() << "texel " << i << ": " << depth[i] << " vs " << r.depth[i];
    const float back = depth[plane + i];
    if (!(std::abs(back - r.back[i]) <= 1e-5f * std::max(r.back[i], 1e-3f)) && ++errors <= 5)
      ADD_FAILURE() << "texel " << i << " (farthest): " << back << " vs " << r.back[i];
  }
  // Under the canopy's extent (the map's middle) the floor is seen through the holes.
  for (uint32_t y = 20; y < 44; ++y)
    for (uint32_t x = 20; x < 44; ++x) {
      const size_t i = size_t(y) * 64 + x;
      if (r.alpha_edge[i] || depth[i] >= 1.0f) continue;
      (depth[plane + i] > depth[i] ? blocked : lit_through) += 1;
    }
  EXPECT_EQ(errors, 0);
  EXPECT_GT(blocked, 50);
  EXPECT_GT(lit_through, 50);
}

// The camera does not draw the back of a single-sided material (glTF doubleSided false):
// counter-clockwise in the mesh's space is the front, and a mirroring model matrix keeps the
// front on the same side of the surface while turning its winding on screen. Double-sided
// materials show both sides; the shadow map draws both sides of either.
TEST(Visibility, SingleSidedBackFacesAreCulledForTheCameraOnly) {
  const std::vector<glm::vec3> quad = {
      {-0.5f, -0.5f, 0.0f}, {0.5f, -0.5f, 0.0f}, {0.5f, 0.5f, 0.0f}, {-0.5f, 0.5f, 0.0f}};
  // mesh 0 faces +z (the camera), mesh 1 the other way
  scene::SceneAssets assets = make_test_assets(
      {make_test_mesh(quad, {{0, 1, 2}, {0, 2, 3}}), make_test_mesh(quad, {{0, 2, 1}, {0, 3, 2}})});
  scene::Material single;
  single.name = "single";
  single.double_sided = false;
  assets.materials.push_back(single);
  int cases = 0;
  for (const bool single_sided : {false, true})
    for (const uint32_t mesh : {0u, 1u})
      for (const bool mirrored : {false, true}) {
        for (scene::Mesh& m : assets.meshes)
          m.materials.assign(m.triangles.size(), single_sided ? 1u : 0u);
        Harness hm(assets);
        scene::FrameScene frame = make_test_frame();
        scene::MeshInstance inst;
        inst.mesh = mesh;
        inst.model = glm::scale(glm::mat4(1.0f), glm::vec3(mirrored ? -1.0f : 1.0f, 1.0f, 1.0f));
        inst.prev_model = inst.model;
        frame.instances.push_back(inst);
        const GpuImage g = hm.render(frame, 32, 32);
        expect_matches_reference(g, reference_raster(assets, frame, hm.view()));
        int covered = 0;
        for (const glm::uvec2& id : g.ids) covered += id.x == 0u;
        const bool seen = !single_sided || mesh == 0u;  // the mirror keeps the side facing +z
        SCOPED_TRACE(::testing::Message() << "single-sided " << single_sided << " mesh " << mesh
                                          << " mirrored " << mirrored);
        if (seen) {
          EXPECT_GE(covered, 80);  // about 10 x 10 pixels
        } else {
          EXPECT_EQ(covered, 0);
        }
        ++cases;
      }
  EXPECT_EQ(cases, 8);

  // A single-sided floor facing down still casts the lamp's shadow (from above).
  const std::vector<glm::vec3> floor = {
      {-0.6f, -0.2f, -0.6f}, {0.6f, -0.2f, -0.6f}, {0.6f, -0.2f, 0.6f}, {-0.6f, -0.2f, 0.6f}};
  scene::SceneAssets shadow_assets = make_test_assets({make_test_mesh(floor, {{0, 1, 2}, {0, 2, 3}})});
  shadow_assets.materials.push_back(single);
  shadow_assets.meshes[0].materials.assign(2, 1u);
  scene::FrameScene frame = make_test_frame();
  frame.instances.push_back(scene::MeshInstance{});
  Harness hs(shadow_assets);
  const std::vector<float> depth = hs.render_shadow(frame, 32);
  int casting = 0;
  for (size_t i = 0; i < size_t(32) * 32; ++i) casting += depth[i] < 1.0f;
  EXPECT_GT(casting, 20);
}

}  // namespace
}  // namespace rp::test
