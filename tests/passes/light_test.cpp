// Light pass against a C++ reference on a hand-written GBuffer (points of a Cornell box with the
// lamp at (0, 1.1, 0)) and hand-made shadow maps: empty (1.0), fully occluded (0.0), the true
// depth of the floor (no acne allowed) and the floor with a square occluder above its centre.
// These direct-light tests give the pass an empty voxel chain (no indirect light); the cone
// traced indirect term is checked against the cone reference in light_cone_test below.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cl/error.h"
#include "cone_reference.h"
#include "kernels/shared/voxel_layout.h"
#include "passes/light.h"
#include "passes/pass_names.h"
#include "passes/shadow_filter.h"
#include "render/gpu_scene.h"
#include "scene/demo_scene.h"
#include "shading/brdf.h"
#include "shading/brdf_tables.h"
#include "support/cl_fixture.h"
#include "support/direct_light_ref.h"

namespace {

using rp::render::ShadowMode;

constexpr ShadowMode kAllFilters[] = {ShadowMode::kHard, ShadowMode::kPcf, ShadowMode::kPcss,
                                      ShadowMode::kVssm};

struct Point {
  glm::vec3 p, n, albedo, emission{0.0f};
  float gloss{0.0f};  // GBuffer emission.w: the gloss code (kernels/shared/brdf_layout.h)
};

const glm::vec3 kIntensity(6.0f, 5.0f, 4.0f);

// cos / (d^2 + a^2) * falloff: the unshadowed direct factor (support/direct_light_ref.h).
double direct_ref(const Point& pt, const rp::scene::PointLight& light) {
  return rp::test::direct_factor_ref(pt.p, pt.n, light);
}

// Expected radiance for a given shadow visibility, without indirect light (empty voxel chain).
glm::dvec3 radiance_ref(const Point& pt, const rp::scene::PointLight& light, double visibility) {
  return glm::dvec3(pt.albedo) * glm::dvec3(kIntensity) * direct_ref(pt, light) * visibility +
         glm::dvec3(pt.emission);
}

// An empty voxel chain: no indirect light.
const rp::test::cone::Chain& empty_chain() {
  static const rp::test::cone::Chain chain(16, 5);
  return chain;
}

class LightFixture {
 public:
  explicit LightFixture(uint32_t shadow_size) : shadow_size_(shadow_size) {
    auto& ctx = rp::test::context();
    scene_ = std::make_unique<rp::render::GpuScene>(ctx.context, ctx.queue,
                                                    rp::scene::SceneAssets{});
    frame_.light.intensity = kIntensity;
  }

  const rp::scene::PointLight& light() const { return frame_.light; }

  // Shadow map whose texel (tx, ty) holds the depth of the first surface hit by the lamp ray
  // through its centre; `hit(origin, dir)` returns the distance or a negative value for none.
  std::vector<float> shadow_map(const std::function<double(glm::dvec3, glm::dvec3)>& hit) const {
    return rp::test::shadow_map_ref(frame_.light, shadow_size_, hit);
  }

  // Runs the pass over `points` (one pixel each, in a row-major frame `width` wide; pixels past
  // the points are background) and returns rgba per pixel. `chain`: the voxel chain (default
  // empty); `mode`: hdr only or with the components, which `direct` / `indirect` receive.
  enum class Mode { kCones, kConesSplit };
  std::vector<float> run(const std::vector<Point>& points, const std::vector<float>& shadow,
                         ShadowMode filter, uint32_t frame_index = 0, uint32_t width = 8,
                         const rp::test::cone::Chain& chain = empty_chain(),
                         Mode mode = Mode::kCones, std::vector<float>* direct = nullptr,
                         std::vector<float>* indirect = nullptr,
                         std::vector<float>* specular = nullptr) {
    auto& ctx = rp::test::context();
    const uint32_t height = uint32_t((points.size() + width) / width);  // >= 1 background pixel
    frame_.frame_index = frame_index;
    scene_->update(frame_, width, height, shadow_size_);
    const size_t n = size_t(width) * height;
    std::vector<float> albedo(n * 4, 0.0f), normal_depth(n * 4, 0.0f), position(n * 4, 0.0f),
        emission(n * 4, 0.0f);
    for (size_t i = 0; i < points.size(); ++i) {
      const Point& pt = points[i];
      std::memcpy(&albedo[i * 4], &pt.albedo, 12);
      albedo[i * 4 + 3] = 1.0f;
      std::memcpy(&normal_depth[i * 4], &pt.n, 12);
      normal_depth[i * 4 + 3] = 1.0f;
      std::memcpy(&position[i * 4], &pt.p, 12);
      position[i * 4 + 3] = 1.0f;
      std::memcpy(&emission[i * 4], &pt.emission, 12);
      emission[i * 4 + 3] = pt.gloss;
    }
    rp::render::GBuffer gb;
    gb.resize(ctx.context, width, height);
    ctx.queue.enqueueWriteBuffer(gb.albedo, CL_TRUE, 0, n * 16, albedo.data());
    ctx.queue.enqueueWriteBuffer(gb.normal_depth, CL_TRUE, 0, n * 16, normal_depth.data());
    ctx.queue.enqueueWriteBuffer(gb.position, CL_TRUE, 0, n * 16, position.data());
    ctx.queue.enqueueWriteBuffer(gb.emission, CL_TRUE, 0, n * 16, emission.data());
    rp::render::ShadowMap sm;
    sm.resize(ctx.context, shadow_size_);
    // hand-made maps hold the nearest plane only: their occluders are sheets
    const std::vector<float> both =
        shadow.size() == size_t(shadow_size_) * shadow_size_
            ? rp::test::with_sheet_back_plane(shadow)
            : shadow;
    ctx.queue.enqueueWriteBuffer(sm.depth, CL_TRUE, 0, both.size() * 4, both.data());
    ::cl::Buffer voxels(ctx.context, CL_MEM_READ_ONLY, chain.voxels.size() * 16);
    ctx.queue.enqueueWriteBuffer(voxels, CL_TRUE, 0, chain.voxels.size() * 16,
                                 chain.voxels.data());
    ::cl::Buffer hdr(ctx.context, CL_MEM_READ_WRITE, n * 16);
    rp::cl::Profiler profiler(ctx.queue);
    if (const uint32_t planes = rp::render::shadow_mip_planes(filter); planes > 0)
      rp::passes::ShadowFilterPass(ctx, rp::test::programs()).run(profiler, *scene_, sm,
                                                                  planes > 1);
    rp::passes::LightPass pass(ctx, rp::test::programs(), filter);
    rp::passes::LightComponents components{::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16),
                                           ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16),
                                           ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16)};
    switch (mode) {
      case Mode::kCones:
        pass.run(profiler, *scene_, gb, sm, voxels, chain.resolution, chain.levels, hdr);
        break;
      case Mode::kConesSplit:
        pass.run(profiler, *scene_, gb, sm, voxels, chain.resolution, chain.levels, hdr,
                 &components);
        break;
    }
    EXPECT_EQ(profiler.collect().count(rp::passes::pass_name::kLight), 1u);
    std::vector<float> out(n * 4);
    ctx.queue.enqueueReadBuffer(hdr, CL_TRUE, 0, n * 16, out.data());
    if (direct) {
      direct->resize(n * 4);
      ctx.queue.enqueueReadBuffer(components.direct, CL_TRUE, 0, n * 16, direct->data());
    }
    if (indirect) {
      indirect->resize(n * 4);
      ctx.queue.enqueueReadBuffer(components.indirect, CL_TRUE, 0, n * 16, indirect->data());
    }
    if (specular) {
      specular->resize(n * 4);
      ctx.queue.enqueueReadBuffer(components.specular, CL_TRUE, 0, n * 16, specular->data());
    }
    return out;
  }

  rp::render::GpuScene& scene() { return *scene_; }

  uint32_t shadow_size() const { return shadow_size_; }

 private:
  uint32_t shadow_size_;
  rp::scene::FrameScene frame_;
  std::unique_ptr<rp::render::GpuScene> scene_;
};

// Points of the box: floor, walls high and low, ceiling (faces away from the lamp), an emitter,
// and one point outside the shadow frustum (beside the lamp, facing it).
std::vector<Point> box_points(const glm::vec3& light) {
  const glm::vec3 wood(0.6f, 0.5f, 0.4f), orange(0.9f, 0.5f, 0.1f), white(0.8f);
  std::vector<Point> pts = {
      {{0.0f, -1.0f, 0.0f}, {0, 1, 0}, wood},
      {{0.7f, -1.0f, -0.4f}, {0, 1, 0}, wood},
      {{0.95f, -1.0f, 0.95f}, {0, 1, 0}, wood},
      {{-1.0f, 0.0f, 0.0f}, {1, 0, 0}, orange},
      {{-1.0f, 0.9f, 0.3f}, {1, 0, 0}, orange},
      {{0.2f, 0.5f, -1.0f}, {0, 0, 1}, white},
      {{0.5f, 1.0f, 0.0f}, {0, -1, 0}, white},
      {{0.3f, -0.5f, 0.2f}, {0, -1, 0}, {0.2f, 0.2f, 0.2f}, {3.0f, 1.5f, 0.5f}},
      {{1.0f, -0.9f, 0.0f}, {-1, 0, 0}, white},
  };
  Point outside{{2.5f, 1.0f, 0.0f}, {}, white};
  outside.n = glm::normalize(light - outside.p);
  pts.push_back(outside);
  return pts;
}

constexpr size_t kOutside = 9;  // index of a point far outside the shadow frustum

// Independent frustum test: the point projects outside the shadow map's [-1,1]^2 (the 120 degree
// frustum misses the top of the side walls, e.g. point 4).
bool outside_shadow_frustum(const rp::scene::PointLight& light, const glm::vec3& p) {
  glm::dvec4 c = glm::dmat4(light.view_proj()) * glm::dvec4(glm::dvec3(p), 1.0);
  return c.w <= 0 || std::abs(c.x / c.w) > 1 || std::abs(c.y / c.w) > 1;
}

void expect_radiance(const std::vector<float>& hdr, size_t i, const glm::dvec3& want,
                     const char* what) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(hdr[i * 4 + c], want[c], 1e-5 * std::abs(want[c]) + 1e-7)
        << what << ": point " << i << " channel " << c;
}

double floor_hit(glm::dvec3 o, glm::dvec3 d) { return d.y < 0 ? (-1.0 - o.y) / d.y : -1.0; }

// The inside of the box: floor and the four walls (the lamp looks down, never at the ceiling).
double box_hit(glm::dvec3 o, glm::dvec3 d) {
  double t = floor_hit(o, d);
  for (int axis : {0, 2})
    for (double wall : {-1.0, 1.0})
      if (d[axis] * wall > 0) t = std::min(t, (wall - o[axis]) / d[axis]);
  return t;
}

// Floor plus a rectangular occluder at height 0, x in (-0.2, 0.3), z in (-0.6, 0): deliberately
// asymmetric so a mirrored shadow-map lookup shows. Its shadow on the floor spans
// x in (-0.38, 0.573), z in (-1.145, 0).
double floor_and_occluder_hit(glm::dvec3 o, glm::dvec3 d) {
  if (d.y < 0) {
    double t = (0.0 - o.y) / d.y;
    glm::dvec3 q = o + d * t;
    if (q.x > -0.2 && q.x < 0.3 && q.z > -0.6 && q.z < 0.0) return t;
  }
  return floor_hit(o, d);
}

TEST(Light, UnshadowedMatchesReference) {
  LightFixture fx(32);
  auto pts = box_points(fx.light().position);
  for (ShadowMode filter : kAllFilters) {
    auto hdr = fx.run(pts, std::vector<float>(32 * 32, 1.0f), filter);
    for (size_t i = 0; i < pts.size(); ++i)
      expect_radiance(hdr, i, radiance_ref(pts[i], fx.light(), 1.0), "lit");
    for (size_t i = pts.size(); i < hdr.size() / 4; ++i)
      for (int c = 0; c < 4; ++c) EXPECT_EQ(hdr[i * 4 + c], 0.0f) << "background pixel " << i;
  }
}

TEST(Light, FullyOccludedMapShadowsOnlyInsideTheFrustum) {
  LightFixture fx(32);
  auto pts = box_points(fx.light().position);
  for (ShadowMode filter : kAllFilters) {
    auto hdr = fx.run(pts, std::vector<float>(32 * 32, 0.0f), filter);
    ASSERT_TRUE(outside_shadow_frustum(fx.light(), pts[kOutside].p));
    int inside = 0;
    for (size_t i = 0; i < pts.size(); ++i) {
      double vis = outside_shadow_frustum(fx.light(), pts[i].p) ? 1.0 : 0.0;
      inside += vis == 0.0 && direct_ref(pts[i], fx.light()) > 0.0;
      expect_radiance(hdr, i, radiance_ref(pts[i], fx.light(), vis), "occluded map");
    }
    EXPECT_GT(direct_ref(pts[kOutside], fx.light()), 0.01);  // the outside point is lit
    EXPECT_GE(inside, 5);  // and most points really are darkened
  }
}

// Points on the floor and on the walls (sloped in light space), lit by a map holding exactly
// the box: no self-shadowing anywhere inside the shadow frustum. Points stay 0.3 away from the
// concave edges where another surface is within the filter's reach (2.5 texels of ~0.06 at the
// floor): there a few-texel contact shadow is the expected shadow-map limitation, not acne.
TEST(Light, BoxDepthMapHasNoAcne) {
  LightFixture fx(128);
  auto map = fx.shadow_map(box_hit);
  std::vector<Point> pts;
  const glm::vec3 grey(0.5f);
  for (int j = 0; j < 12; ++j) {
    for (int i = 0; i < 12; ++i) {
      float a = -0.7f + 1.4f * float(i) / 11.0f, b = -0.7f + 1.4f * float(j) / 11.0f;
      float h = -0.98f + 1.38f * float(j) / 11.0f;  // wall heights up to 0.4 (inside the frustum)
      pts.push_back({{a, -1.0f, b}, {0, 1, 0}, grey});      // floor
      pts.push_back({{-1.0f, h, a}, {1, 0, 0}, grey});      // left wall
      pts.push_back({{a, h, -1.0f}, {0, 0, 1}, grey});      // back wall
    }
  }
  int checked = 0;
  for (ShadowMode filter : kAllFilters) {
    for (uint32_t frame = 0; frame < 3; ++frame) {
      auto hdr = fx.run(pts, map, filter, frame, 16);
      for (size_t i = 0; i < pts.size(); ++i) {
        checked += !outside_shadow_frustum(fx.light(), pts[i].p);
        expect_radiance(hdr, i, radiance_ref(pts[i], fx.light(), 1.0), "box");
      }
    }
  }
  EXPECT_GT(checked, 6 * 400);  // most points are inside the frustum, so the map is consulted
}

// Visibility recovered from the output: hdr / unshadowed direct (no indirect light here).
double visibility_of(const std::vector<float>& hdr, size_t i, const Point& pt,
                     const rp::scene::PointLight& light) {
  double direct = double(pt.albedo.x) * kIntensity.x * direct_ref(pt, light);
  return hdr[i * 4] / direct;
}

TEST(Light, SquareOccluderCastsShadow) {
  LightFixture fx(128);  // texel ~0.057 on the floor: PCF reaches +-0.15
  auto map = fx.shadow_map(floor_and_occluder_hit);
  // A row of floor points at z = -0.55 from x = 0 (under the occluder) to x = 0.95; the shadow
  // edge on the floor is at x = 0.3 * 2.1 / 1.1 = 0.573.
  std::vector<Point> row;
  for (int i = 0; i < 64; ++i)
    row.push_back({{0.95f * float(i) / 63.0f, -1.0f, -0.55f}, {0, 1, 0}, {0.5f, 0.5f, 0.5f}});
  const rp::scene::PointLight& light = fx.light();

  auto hard = fx.run(row, map, ShadowMode::kHard, 0, 16);
  auto pcf = fx.run(row, map, ShadowMode::kPcf, 0, 16);
  int pcf_partial = 0;
  for (size_t i = 0; i < row.size(); ++i) {
    const double x = row[i].p.x;
    const double v1 = visibility_of(hard, i, row[i], light);
    const double v8 = visibility_of(pcf, i, row[i], light);
    // One tap: all or nothing.
    EXPECT_TRUE(std::abs(v1) < 1e-4 || std::abs(v1 - 1.0) < 1e-4) << "x " << x << " vis " << v1;
    // PCF: multiples of 1/8 (8 taps).
    EXPECT_NEAR(v8 * 8.0, std::round(v8 * 8.0), 1e-3) << "x " << x;
    pcf_partial += v8 > 0.01 && v8 < 0.99;
    if (x < 0.4) {  // well inside the umbra
      EXPECT_NEAR(v1, 0.0, 1e-4) << "x " << x;
      EXPECT_NEAR(v8, 0.0, 1e-4) << "x " << x;
    }
    if (x > 0.78) {  // well outside
      EXPECT_NEAR(v1, 1.0, 1e-4) << "x " << x;
      EXPECT_NEAR(v8, 1.0, 1e-4) << "x " << x;
    }
  }
  EXPECT_GE(pcf_partial, 2);  // a soft edge, not a hard step
}

TEST(Light, DeterministicPerFrameNoise) {
  LightFixture fx(64);
  auto map = fx.shadow_map(floor_and_occluder_hit);
  std::vector<Point> band;  // points around the shadow edge, where the one-tap noise shows
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 16; ++i)
      band.push_back({{0.45f + 0.25f * float(i) / 15.0f, -1.0f, -0.7f + 0.05f * float(j)},
                      {0, 1, 0},
                      {0.5f, 0.5f, 0.5f}});
  auto a = fx.run(band, map, ShadowMode::kPcf, 5, 16);
  auto b = fx.run(band, map, ShadowMode::kPcf, 5, 16);
  auto c = fx.run(band, map, ShadowMode::kPcf, 6, 16);
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(float)));  // bit-identical
  int lit = 0, differs = 0;
  for (size_t i = 0; i < band.size(); ++i) {
    lit += visibility_of(a, i, band[i], fx.light()) > 0.5;
    differs += a[i * 4] != c[i * 4];
  }
  EXPECT_GT(lit, 0);
  EXPECT_LT(lit, int(band.size()));  // a noisy penumbra, not all lit or all dark
  EXPECT_GT(differs, 0);             // the rotation changes with the frame index
}

using rp::test::cone::random_chain;

// Direct + albedo * (the six-cone irradiance / pi of the reference) + emission.
TEST(Light, ConeTracedIndirectMatchesReference) {
  LightFixture fx(32);
  auto pts = box_points(fx.light().position);
  // Points inside the box with oblique normals too.
  pts.push_back({{0.2f, -0.3f, 0.1f}, glm::normalize(glm::vec3(0.3f, 0.8f, -0.5f)), {0.7f, 0.6f, 0.5f}});
  pts.push_back({{-0.5f, 0.4f, -0.2f}, glm::normalize(glm::vec3(-0.6f, -0.2f, 0.7f)), {0.3f, 0.9f, 0.4f}});
  const rp::test::cone::Chain chain = random_chain(16, 77);
  auto hdr = fx.run(pts, std::vector<float>(32 * 32, 1.0f), ShadowMode::kHard, 0, 8,
                    chain);
  int lit = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    const glm::dvec3 indirect =
        glm::dvec3(pts[i].albedo) * rp::test::cone::diffuse(chain, pts[i].p, pts[i].n);
    lit += indirect.x > 0.01;
    const glm::dvec3 want = radiance_ref(pts[i], fx.light(), 1.0) + indirect;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(hdr[i * 4 + c], want[c], 1e-5 * std::abs(want[c]) + 1e-5)
          << "point " << i << " channel " << c;
    EXPECT_EQ(hdr[i * 4 + 3], 1.0f);
  }
  EXPECT_GE(lit, 8);  // the chain really lights most points
}

// The split variant writes direct and indirect separately; hdr is bit-identical to the lean path.
TEST(Light, SplitVariantWritesTheComponents) {
  LightFixture fx(32);
  auto pts = box_points(fx.light().position);
  const rp::test::cone::Chain chain = random_chain(16, 5);
  const std::vector<float> map(32 * 32, 1.0f);
  std::vector<float> direct, indirect;
  auto lean = fx.run(pts, map, ShadowMode::kHard, 0, 8, chain);
  auto split = fx.run(pts, map, ShadowMode::kHard, 0, 8, chain,
                      LightFixture::Mode::kConesSplit, &direct, &indirect);
  EXPECT_EQ(0, std::memcmp(lean.data(), split.data(), lean.size() * sizeof(float)));
  for (size_t i = 0; i < pts.size(); ++i) {
    const glm::dvec3 want_direct = radiance_ref(pts[i], fx.light(), 1.0) -
                                   glm::dvec3(pts[i].emission);
    const glm::dvec3 want_indirect =
        glm::dvec3(pts[i].albedo) * rp::test::cone::diffuse(chain, pts[i].p, pts[i].n);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(direct[i * 4 + c], want_direct[c], 1e-5 * std::abs(want_direct[c]) + 1e-6)
          << "direct, point " << i;
      EXPECT_NEAR(indirect[i * 4 + c], want_indirect[c], 1e-5) << "indirect, point " << i;
    }
    EXPECT_EQ(direct[i * 4 + 3], 1.0f);
    EXPECT_EQ(indirect[i * 4 + 3], 1.0f);
  }
  for (size_t i = pts.size(); i < lean.size() / 4; ++i)
    for (int c = 0; c < 4; ++c) {
      EXPECT_EQ(direct[i * 4 + c], 0.0f) << "background " << i;
      EXPECT_EQ(indirect[i * 4 + c], 0.0f) << "background " << i;
    }
}

// The surface model in the light pass (kernels/common/brdf.h) against its C++ reference
// (shading::shade_lamp) on hand-made glossy GBuffer points, lit through an empty shadow map:
// direct = (albedo * w_d + pi f_spec) * I * cos / (d^2 + a^2) * falloff, the specular buffer its
// specular part (no indirect light: empty voxel chain).
TEST(Light, GlossySurfacesMatchTheBrdfReference) {
  using rp::shading::gloss_code;
  LightFixture fx(32);
  const glm::vec3 cam = rp::scene::Camera{}.position, lamp = fx.light().position;
  const float floor = gloss_code(rp::scene::demo::kFloorSpecular);
  const float lacquer = gloss_code(rp::scene::demo::kTumblerSpecular);
  const float marble = gloss_code(rp::scene::demo::kMarbleSpecular);
  const float gold = gloss_code(rp::scene::Specular{0.3f, 0.0f, true});
  // a point turned so the lamp's mirror image lies on its normal: the highlight's peak
  auto mirror = [&](glm::vec3 p, glm::vec3 albedo, float gloss) {
    const glm::vec3 h = glm::normalize(glm::normalize(cam - p) + glm::normalize(lamp - p));
    return Point{p, h, albedo, glm::vec3(0.0f), gloss};
  };
  std::vector<Point> pts = {
      {{0.0f, -1.0f, 0.0f}, {0, 1, 0}, {0.6f, 0.5f, 0.4f}, {}, floor},
      {{0.7f, -1.0f, 0.8f}, {0, 1, 0}, {0.6f, 0.5f, 0.4f}, {}, floor},
      {{-0.4f, -0.8f, 0.3f}, glm::normalize(glm::vec3(-0.5f, 0.6f, 0.6f)), {0.8f, 0.1f, 0.1f}, {}, lacquer},
      mirror({0.2f, -0.7f, 0.1f}, {0.8f, 0.1f, 0.1f}, lacquer),
      mirror({-0.3f, -0.9f, 0.5f}, {0.3f, 0.6f, 0.9f}, marble),
      mirror({0.5f, -0.5f, -0.2f}, {1.0f, 0.78f, 0.34f}, gold),
      {{0.5f, -0.5f, -0.2f}, glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f)), {1.0f, 0.78f, 0.34f}, {}, gold},
      {{-1.0f, 0.0f, 0.0f}, {1, 0, 0}, {0.9f, 0.5f, 0.1f}},  // matte in the same chunk
      {{0.1f, -0.6f, 0.0f}, glm::normalize(glm::vec3(0.0f, -0.3f, 1.0f)), glm::vec3(0.5f), {}, lacquer},
  };
  const std::vector<float> map(32 * 32, 1.0f);
  std::vector<float> direct, indirect, specular;
  auto hdr = fx.run(pts, map, ShadowMode::kHard, 0, 8, empty_chain(),
                    LightFixture::Mode::kConesSplit, &direct, &indirect, &specular);
  const rp::shading::BrdfTables& tables = rp::shading::BrdfTables::get();
  const rp::scene::PointLight& light = fx.light();
  const double ze = double(light.position.y) - 1.0;
  const double a = std::sqrt(double(light.lamp_radius) * light.lamp_radius - ze * ze);
  for (size_t i = 0; i < pts.size(); ++i) {
    const Point& pt = pts[i];
    const rp::shading::SurfaceBsdf bsdf =
        rp::shading::make_bsdf(rp::shading::decode_gloss(pt.gloss), pt.albedo);
    const glm::vec3 wo = glm::normalize(cam - pt.p), wi = glm::normalize(lamp - pt.p);
    const glm::dvec3 disk(light.position.x, 1.0, light.position.z);
    const float widen = float(0.5 * a / glm::length(disk - glm::dvec3(pt.p)));
    const rp::shading::LampShading l = rp::shading::shade_lamp(bsdf, pt.n, wo, wi, widen, tables);
    const double k = direct_ref(pt, light);
    const glm::dvec3 spec = glm::dvec3(l.specular) * glm::dvec3(kIntensity) * k;
    const glm::dvec3 want = glm::dvec3(pt.albedo * l.diffuse_weight) * glm::dvec3(kIntensity) * k + spec;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(direct[i * 4 + c], want[c], 2e-3 * std::abs(want[c]) + 1e-6)
          << "direct, point " << i << " channel " << c;
      EXPECT_NEAR(specular[i * 4 + c], spec[c], 2e-3 * std::abs(spec[c]) + 1e-6)
          << "specular, point " << i << " channel " << c;
      EXPECT_NEAR(hdr[i * 4 + c], want[c], 2e-3 * std::abs(want[c]) + 1e-6) << "hdr, point " << i;
    }
    if (pt.gloss != 0.0f && k > 0.0) {
      EXPECT_GT(spec.x, 0.0) << "point " << i;
    }
  }
  // the mirror points' highlights: the lacquer's peak outshines its diffuse light
  EXPECT_GT(specular[3 * 4 + 1], direct[3 * 4 + 1] * 0.5f);
}

// The specular indirect light of the reference mode (light_shade) against its
// C++ reference on a random 16^3 chain: indirect = albedo * w_i * cones16 + E_spec(mu_o) *
// cone(r), r = reflect(-v, n), the cone's tan from the roughness (shading::spec_cone_tan),
// quadrilinear half-diameter steps from the diffuse apex (cone_reference's trace_aperture);
// w_i = 1 - E_spec(mu_o) (0 for a metal), E_spec from shading::coat_albedo_at. The specular
// buffer holds the reflection's part (no direct light: the lamp is shadowed everywhere). Matte
// pixels in the same chunk keep the Lambertian result. Every point faces the camera (as GBuffer
// pixels do; the kernel clamps n.v at 0 for the mirror direction).
TEST(Light, ReflectionConeMatchesReference) {
  using rp::shading::gloss_code;
  LightFixture fx(32);
  const glm::vec3 cam = rp::scene::Camera{}.position;
  const float floor = gloss_code(rp::scene::demo::kFloorSpecular);
  const float lacquer = gloss_code(rp::scene::demo::kTumblerSpecular);
  const float marble = gloss_code(rp::scene::demo::kMarbleSpecular);
  const float gold = gloss_code(rp::scene::Specular{0.3f, 0.0f, true});
  const float rough = gloss_code(rp::scene::Specular{0.9f, 0.05f, false});
  std::vector<Point> pts = {
      {{0.03f, -0.9f, 0.02f}, {0, 1, 0}, {0.6f, 0.5f, 0.4f}, {}, floor},
      {{0.52f, -0.8f, 0.61f}, {0, 1, 0}, {0.6f, 0.5f, 0.4f}, {}, floor},
      {{-0.4f, -0.5f, 0.3f}, glm::normalize(glm::vec3(-0.5f, 0.6f, 0.6f)), {0.8f, 0.1f, 0.1f}, {}, lacquer},
      {{0.2f, -0.3f, 0.1f}, glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f)), {0.3f, 0.6f, 0.9f}, {}, marble},
      {{0.5f, -0.5f, -0.2f}, glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f)), {1.0f, 0.78f, 0.34f}, {}, gold},
      {{-0.5f, 0.4f, -0.2f}, glm::normalize(glm::vec3(-0.6f, -0.2f, 0.7f)), {0.5f, 0.5f, 0.5f}, {}, rough},
      {{-0.7f, 0.0f, 0.0f}, {1, 0, 0}, {0.9f, 0.5f, 0.1f}},  // matte in the same chunk
  };
  const rp::test::cone::Chain chain = random_chain(16, 91);
  const std::vector<float> dark(32 * 32, 0.0f);  // every point in the lamp's shadow
  std::vector<float> direct, indirect, specular;
  auto hdr = fx.run(pts, dark, ShadowMode::kHard, 0, 8, chain, LightFixture::Mode::kConesSplit,
                    &direct, &indirect, &specular);
  const rp::shading::BrdfTables& tables = rp::shading::BrdfTables::get();
  int reflecting = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    const Point& pt = pts[i];
    const rp::scene::Specular coat = rp::shading::decode_gloss(pt.gloss);
    const rp::shading::SurfaceBsdf bsdf = rp::shading::make_bsdf(coat, pt.albedo);
    const glm::dvec3 n(pt.n), v = glm::normalize(glm::dvec3(cam) - glm::dvec3(pt.p));
    ASSERT_GT(glm::dot(n, v), 0.05) << "point " << i << " must face the camera";
    const glm::dvec3 r = 2.0 * glm::dot(n, v) * n - v;
    const glm::dvec3 e(rp::shading::coat_albedo_at(bsdf, float(glm::dot(n, v)), tables));
    const glm::dvec3 diffuse = rp::test::cone::diffuse(chain, glm::dvec3(pt.p), n);
    glm::dvec3 cone(0.0);
    if (pt.gloss != 0.0f)
      cone = glm::dvec3(rp::test::cone::trace_aperture(
          chain, glm::dvec3(pt.p) + n * (2.0 / 16.0), r, rp::shading::spec_cone_tan(coat.roughness)));
    const glm::dvec3 wi = bsdf.metal ? glm::dvec3(0.0) : 1.0 - e;
    const glm::dvec3 spec = e * cone;
    const glm::dvec3 want = glm::dvec3(pt.albedo) * wi * diffuse + spec;
    reflecting += spec.x > 0.01;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(indirect[i * 4 + c], want[c], 2e-3 * std::abs(want[c]) + 2e-5)
          << "indirect, point " << i << " channel " << c;
      EXPECT_NEAR(specular[i * 4 + c], spec[c], 2e-3 * std::abs(spec[c]) + 2e-5)
          << "specular, point " << i << " channel " << c;
      EXPECT_NEAR(hdr[i * 4 + c], want[c] + pt.emission[c], 2e-3 * std::abs(want[c]) + 2e-5)
          << "hdr, point " << i;
      EXPECT_NEAR(direct[i * 4 + c], 0.0f, 1e-6) << "point " << i;
    }
  }
  EXPECT_GE(reflecting, 3);  // the chain is really reflected
}

TEST(Light, RejectsAVoxelChainThatDoesNotFit) {
  auto& ctx = rp::test::context();
  LightFixture fx(32);
  fx.run(box_points(fx.light().position), std::vector<float>(32 * 32, 1.0f),
         ShadowMode::kHard);  // sets up the scene for an 8x2 frame
  rp::render::GBuffer gb;
  gb.resize(ctx.context, 8, 2);
  rp::render::ShadowMap sm;
  sm.resize(ctx.context, 32);
  ::cl::Buffer hdr(ctx.context, CL_MEM_READ_WRITE, 8 * 2 * 16);
  const size_t total16 = rp::gpu::rp_voxel_total(16, 5);
  ::cl::Buffer voxels(ctx.context, CL_MEM_READ_ONLY, total16 * 16);
  rp::cl::Profiler profiler(ctx.queue);
  rp::passes::LightPass pass(ctx, rp::test::programs(), ShadowMode::kHard);
  auto message = [&](uint32_t resolution, uint32_t levels, const ::cl::Buffer& buffer) {
    try {
      pass.run(profiler, fx.scene(), gb, sm, buffer, resolution, levels, hdr);
    } catch (const rp::cl::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(48, 5, voxels).find("not a power of two"), std::string::npos);
  EXPECT_NE(message(16, 6, voxels).find("voxel levels"), std::string::npos);
  EXPECT_NE(message(32, 6, voxels).find("bytes"), std::string::npos);  // buffer too small
  ::cl::Buffer small(ctx.context, CL_MEM_READ_ONLY, (total16 - 1) * 16);
  EXPECT_NE(message(16, 5, small).find("bytes"), std::string::npos);
  EXPECT_EQ(message(16, 5, voxels), "");
  EXPECT_EQ(message(16, 3, voxels), "");  // fewer levels than the full chain are fine
  profiler.collect();
}

}  // namespace
