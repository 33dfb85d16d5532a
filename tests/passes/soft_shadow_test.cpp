// The light pass's shadow modes (kernels/common/soft_shadow.h) and the shadow filter pass's mips
// (kernels/shadow_filter.cl) against C++ references on synthetic shadow maps rendered by ray
// casting from the lamp centre:
//   - the mips (min, mean z, mean z^2 of linear depth) against a direct C++ reduction;
//   - hard: exactly the one texel under the receiver;
//   - pcf: exactly the explicit sum over the rotated Poisson taps (hash and table mirrored);
//   - pcss and vssm: a square occluder plate parallel to the floor; the visibility along a row
//     of floor points crossing its shadow edge, averaged over 64 frames (the per-frame rotations
//     TAA would average), against the visible fraction of the lamp's disk (radius
//     sqrt(R^2 - 0.1^2) in the ceiling, integrated on a 201x201 grid); the penumbra width (the
//     distance between the 10 % and 90 % crossings) against the same reference and the
//     formula 2 a (z_r - z_b) / (z_b - z_e) (0 % to 100 %); likewise a ball resting on the
//     floor and a tall box (thick blockers, where one blocker depth is an approximation:
//     looser bounds, stated there);
//   - no acne: tilted planes lit at grazing angles (the map holds exactly the plane) stay lit;
//   - no peter-panning: floor points under a plate 0.02 above the floor stay shadowed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "cone_reference.h"
#include "kernels/shared/shadow_mips.h"
#include "passes/light.h"
#include "passes/shadow_filter.h"
#include "render/gpu_scene.h"
#include "support/cl_fixture.h"
#include "support/direct_light_ref.h"

namespace {

using rp::render::ShadowMode;

struct Point {
  glm::vec3 p, n;
};

// cos / d^2 * falloff: the unshadowed direct factor (support/direct_light_ref.h).
double direct_ref(const Point& pt, const rp::scene::PointLight& light) {
  return rp::test::direct_factor_ref(pt.p, pt.n, light);
}

class Shadows {
 public:
  explicit Shadows(uint32_t shadow_size) : size_(shadow_size) {
    auto& ctx = rp::test::context();
    scene_ = std::make_unique<rp::render::GpuScene>(ctx.context, ctx.queue,
                                                    rp::scene::SceneAssets{});
  }
  const rp::scene::PointLight& light() const { return frame_.light; }
  uint32_t size() const { return size_; }

  // Texel (tx, ty) holds the depth of the first hit of the lamp ray through its centre, and in
  // the second plane of its last exit (`exit`; without it the occluders are sheets).
  std::vector<float> map(const std::function<double(glm::dvec3, glm::dvec3)>& hit,
                         const std::function<double(glm::dvec3, glm::dvec3)>& exit =
                             nullptr) const {
    return rp::test::shadow_map_ref(frame_.light, size_, hit, exit);
  }

  // Builds the mips of `map` (moments too) and reads them back (3 planes).
  std::vector<float> mips(const std::vector<float>& map) {
    auto& ctx = rp::test::context();
    frame_.frame_index = 0;
    scene_->update(frame_, 8, 8, size_);
    rp::render::ShadowMap sm;
    sm.resize(ctx.context, size_);
    ctx.queue.enqueueWriteBuffer(sm.depth, CL_TRUE, 0, map.size() * 4, map.data());
    rp::cl::Profiler profiler(ctx.queue);
    rp::passes::ShadowFilterPass pass(ctx, rp::test::programs());
    pass.run(profiler, *scene_, sm, true);
    profiler.collect();
    std::vector<float> out(size_t(rp::gpu::rp_shadow_mip_total(size_)) * 3);
    ctx.queue.enqueueReadBuffer(sm.mips, CL_TRUE, 0, out.size() * 4, out.data());
    return out;
  }

  // Visibility per point (hdr over the unshadowed direct light; empty voxel chain).
  // checkerboard: the light pass's chunk checkerboard (off by default here: these point lists
  // are rows of unrelated points, not an image whose neighbouring chunks see neighbouring
  // surfaces).
  // raw: when given, also the visibility kernel's own output per pixel (width x height).
  std::vector<double> visibility(const std::vector<Point>& points, const std::vector<float>& map,
                                 ShadowMode filter, uint32_t frame_index, uint32_t width = 16,
                                 bool checkerboard = false, std::vector<float>* raw = nullptr) {
    auto& ctx = rp::test::context();
    const uint32_t height = uint32_t((points.size() + width - 1) / width);
    frame_.frame_index = frame_index;
    scene_->update(frame_, width, height, size_);
    const size_t n = size_t(width) * height;
    std::vector<float> albedo(n * 4, 0.0f), normal_depth(n * 4, 0.0f), position(n * 4, 0.0f),
        emission(n * 4, 0.0f);
    for (size_t i = 0; i < points.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        albedo[i * 4 + c] = 1.0f;
        normal_depth[i * 4 + c] = points[i].n[c];
        position[i * 4 + c] = points[i].p[c];
      }
      albedo[i * 4 + 3] = normal_depth[i * 4 + 3] = position[i * 4 + 3] = 1.0f;
    }
    rp::render::GBuffer gb;
    gb.resize(ctx.context, width, height);
    ctx.queue.enqueueWriteBuffer(gb.albedo, CL_TRUE, 0, n * 16, albedo.data());
    ctx.queue.enqueueWriteBuffer(gb.normal_depth, CL_TRUE, 0, n * 16, normal_depth.data());
    ctx.queue.enqueueWriteBuffer(gb.position, CL_TRUE, 0, n * 16, position.data());
    ctx.queue.enqueueWriteBuffer(gb.emission, CL_TRUE, 0, n * 16, emission.data());
    rp::render::ShadowMap sm;
    sm.resize(ctx.context, size_);
    ctx.queue.enqueueWriteBuffer(sm.depth, CL_TRUE, 0, map.size() * 4, map.data());
    static const rp::test::cone::Chain chain(16, 5);
    ::cl::Buffer voxels(ctx.context, CL_MEM_READ_ONLY, chain.voxels.size() * 16);
    ctx.queue.enqueueWriteBuffer(voxels, CL_TRUE, 0, chain.voxels.size() * 16,
                                 chain.voxels.data());
    ::cl::Buffer hdr(ctx.context, CL_MEM_READ_WRITE, n * 16);
    rp::cl::Profiler profiler(ctx.queue);
    if (const uint32_t planes = rp::render::shadow_mip_planes(filter); planes > 0) {
      rp::passes::ShadowFilterPass mips(ctx, rp::test::programs());
      mips.run(profiler, *scene_, sm, planes > 1);
    }
    rp::passes::LightPass pass(ctx, rp::test::programs(), filter);
    pass.set_shadow_checkerboard(checkerboard);
    pass.run(profiler, *scene_, gb, sm, voxels, chain.resolution, chain.levels, hdr);
    profiler.collect();
    if (raw != nullptr) {
      raw->resize(n);
      ctx.queue.enqueueReadBuffer(pass.visibility(), CL_TRUE, 0, n * 4, raw->data());
    }
    std::vector<float> out(n * 4);
    ctx.queue.enqueueReadBuffer(hdr, CL_TRUE, 0, n * 16, out.data());
    std::vector<double> vis(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      const double k = direct_ref(points[i], frame_.light) * frame_.light.intensity.x;
      vis[i] = k > 0.0 ? out[i * 4] / k : 1.0;
    }
    return vis;
  }

  // Mean visibility over `frames` frame indices.
  // `width`: points per image row (the kernel pools pcss searches over 2x2 pixel quads).
  std::vector<double> mean_visibility(const std::vector<Point>& points,
                                      const std::vector<float>& map, ShadowMode filter,
                                      uint32_t frames, uint32_t width = 16) {
    std::vector<double> sum(points.size(), 0.0);
    for (uint32_t f = 0; f < frames; ++f) {
      auto v = visibility(points, map, filter, f, width);
      for (size_t i = 0; i < v.size(); ++i) sum[i] += v[i] / frames;
    }
    return sum;
  }

 private:
  uint32_t size_;
  rp::scene::FrameScene frame_;
  std::unique_ptr<rp::render::GpuScene> scene_;
};

double floor_hit(glm::dvec3 o, glm::dvec3 d) { return d.y < 0 ? (-1.0 - o.y) / d.y : -1.0; }

// A square plate at height `h`, |x - cx| < half, |z| < half, above the floor.
struct Plate {
  double h, cx, half;
  bool covers(double x, double z) const { return std::abs(x - cx) < half && std::abs(z) < half; }
  double hit(glm::dvec3 o, glm::dvec3 d) const {
    if (d.y < 0) {
      const double t = (h - o.y) / d.y;
      const glm::dvec3 q = o + d * t;
      if (covers(q.x, q.z)) return t;
    }
    return floor_hit(o, d);
  }
};

// The lamp's disk: centre on the lamp's axis in the ceiling (y = 1), radius sqrt(R^2 - 0.1^2).
double lamp_disk_radius(const rp::scene::PointLight& l) {
  const double ze = l.position.y - 1.0;
  return std::sqrt(double(l.lamp_radius) * l.lamp_radius - ze * ze);
}

// Visible fraction of the lamp's disk from floor point p past the plate: 201x201 grid over the
// disk, each sample's ray to p tested against the plate's plane.
double disk_visibility(const rp::scene::PointLight& l, const Plate& plate, glm::dvec3 p) {
  const double a = lamp_disk_radius(l);
  int seen = 0, total = 0;
  for (int j = -100; j <= 100; ++j)
    for (int i = -100; i <= 100; ++i) {
      const double u = i / 100.0, v = j / 100.0;
      if (u * u + v * v > 1.0) continue;
      ++total;
      const glm::dvec3 e(l.position.x + a * u, 1.0, l.position.z + a * v);
      const double t = (plate.h - p.y) / (e.y - p.y);
      const glm::dvec3 q = p + (e - p) * t;
      seen += !plate.covers(q.x, q.z);
    }
  return double(seen) / total;
}

// x where the profile (increasing along xs) first reaches `level` (linear interpolation).
double crossing(const std::vector<double>& xs, const std::vector<double>& v, double level) {
  for (size_t i = 1; i < xs.size(); ++i)
    if (v[i - 1] < level && v[i] >= level)
      return xs[i - 1] + (xs[i] - xs[i - 1]) * (level - v[i - 1]) / (v[i] - v[i - 1]);
  return std::nan("");
}

// A row of floor points at z = 0 from x0 to x1, with the reference profile of the plate.
struct Row {
  std::vector<Point> points;
  std::vector<double> xs, truth;
};

Row floor_row(const rp::scene::PointLight& l, const Plate& plate, double x0, double x1, int n) {
  Row r;
  for (int i = 0; i < n; ++i) {
    const double x = x0 + (x1 - x0) * i / (n - 1);
    r.points.push_back({{float(x), -1.0f, 0.0f}, {0, 1, 0}});
    r.xs.push_back(x);
    r.truth.push_back(disk_visibility(l, plate, {x, -1.0, 0.0}));
  }
  return r;
}

// PCSS and VSSM against the lamp disk's visible fraction across the edge of a plate at height
// 0 (z_b = 1.1, z_r = 2.1 below the lamp centre): penumbra 2 a (2.1 - 1.1) / (1.1 - 0.1) = 0.67
// wide, centred on the plate edge's projection through the disk's centre.
void expect_plate_penumbra(ShadowMode filter, double max_mean_error, double width_tolerance,
                           double max_point_error) {
  Shadows s(256);
  const Plate plate{0.0, -0.4, 0.4};  // edge at x = 0, penumbra over x in (-0.33, 0.33)
  auto map = s.map([&](glm::dvec3 o, glm::dvec3 d) { return plate.hit(o, d); });
  Row row = floor_row(s.light(), plate, -0.6, 0.6, 96);
  auto vis = s.mean_visibility(row.points, map, filter, 64);
  double sum_error = 0.0;
  for (size_t i = 0; i < vis.size(); ++i) {
    sum_error += std::abs(vis[i] - row.truth[i]);
    EXPECT_NEAR(vis[i], row.truth[i], max_point_error) << "x " << row.xs[i];
  }
  EXPECT_LT(sum_error / double(vis.size()), max_mean_error);
  // the formula's full width against the disk integration (0.5 % and 99.5 % crossings: the
  // tails of a circular segment grow as h^1.5, so these sit ~2 % of the width inside its ends)
  const double a = lamp_disk_radius(s.light());
  const double formula = 2.0 * a * (2.1 - 1.1) / (1.1 - 0.1);
  const double full = crossing(row.xs, row.truth, 0.995) - crossing(row.xs, row.truth, 0.005);
  EXPECT_NEAR(full, formula, 0.06 * formula);
  // 10 % - 90 % widths of the kernel and of the reference
  const double want = crossing(row.xs, row.truth, 0.9) - crossing(row.xs, row.truth, 0.1);
  const double got = crossing(row.xs, vis, 0.9) - crossing(row.xs, vis, 0.1);
  EXPECT_NEAR(got, want, width_tolerance * want) << "10-90 % penumbra width";
  std::printf("%s: mean |error| %.4f, 10-90 %% width %.4f (reference %.4f), full width %.4f "
              "(formula %.4f)\n",
              filter == ShadowMode::kPcss ? "pcss" : "vssm", sum_error / double(vis.size()), got,
              want, full, formula);
}

TEST(SoftShadow, PcssPenumbraMatchesTheLampDisk) {
  expect_plate_penumbra(ShadowMode::kPcss, 0.012, 0.10, 0.2);
}

// VSSM's penumbra on the plate comes out about 0.4x the reference's width (a bilinear mip
// lookup is a tent, not the disk, and Chebyshev's bound with light-bleeding reduction sharpens
// it): a looser bound, the measured figure in the notes.
TEST(SoftShadow, VssmPenumbraMatchesTheLampDisk) {
  expect_plate_penumbra(ShadowMode::kVssm, 0.08, 0.7, 0.35);
}

// In a frame, a pixel's quad neighbours mostly lie on its surface, and pcss pools their
// blocker searches (soft_shadow.h, step 2). The plate's edge with the floor row laid out as
// an image of two rows 0.004 apart (every quad on one surface, all four searches pooled): the
// same bounds as the row alone.
TEST(SoftShadow, PcssPooledQuadsMatchTheLampDisk) {
  Shadows s(256);
  const Plate plate{0.0, -0.4, 0.4};
  const auto map = s.map([&](glm::dvec3 o, glm::dvec3 d) { return plate.hit(o, d); });
  const Row row = floor_row(s.light(), plate, -0.6, 0.6, 96);
  std::vector<Point> pts = row.points;
  for (Point p : row.points) {
    p.p.z += 0.004f;
    pts.push_back(p);
  }
  const auto vis = s.mean_visibility(pts, map, ShadowMode::kPcss, 64, 96);
  double sum_error = 0.0;
  for (size_t i = 0; i < pts.size(); ++i) {
    sum_error += std::abs(vis[i] - row.truth[i % 96]);
    EXPECT_NEAR(vis[i], row.truth[i % 96], 0.2) << i;
  }
  EXPECT_LT(sum_error / double(pts.size()), 0.011);
  const std::vector<double> top(vis.begin(), vis.begin() + 96);
  const double want = crossing(row.xs, row.truth, 0.9) - crossing(row.xs, row.truth, 0.1);
  const double got = crossing(row.xs, top, 0.9) - crossing(row.xs, top, 0.1);
  EXPECT_NEAR(got, want, 0.10 * want) << "10-90 % penumbra width";
  std::printf("pcss pooled quads: mean |error| %.4f, 10-90 %% width %.4f (reference %.4f)\n",
              sum_error / double(pts.size()), got, want);
}

// No pooling across surfaces: floor points across the penumbra of a plate at height 0 (A),
// each in a quad with floor points across the penumbra of a lower plate (B, height -0.7: its
// blockers lie at another depth) 0.7 away, must shade exactly as in quads with lit floor
// points 0.7 away on the other side: A's receivers are too far from either to share a search,
// so neither may change A's blocker estimate. (With the pooling gate always open, A's
// estimate takes B's blockers in: this test fails.)
TEST(SoftShadow, PcssDoesNotPoolAcrossSurfaces) {
  Shadows s(256);
  const Plate a{0.0, -0.4, 0.4};
  const auto map = s.map([&](glm::dvec3 o, glm::dvec3 d) {
    if (d.y < 0) {
      const double t = (-0.7 - o.y) / d.y;  // plate B: x in (-0.8, 0), z in (0.55, 0.85)
      const glm::dvec3 q = o + d * t;
      if (q.x > -0.8 && q.x < 0.0 && q.z > 0.55 && q.z < 0.85) return t;
    }
    return a.hit(o, d);
  });
  std::vector<Point> with_b, with_lit;  // rows of two: (A point, the other)
  for (int i = 0; i < 48; ++i) {
    const float x = -0.3f + 0.6f * float(i) / 47.0f;
    for (auto* pts : {&with_b, &with_lit}) pts->push_back({{x, -1.0f, 0.0f}, {0, 1, 0}});
    with_b.push_back({{x, -1.0f, 0.7f}, {0, 1, 0}});
    with_lit.push_back({{x + 0.7f, -1.0f, 0.0f}, {0, 1, 0}});
  }
  double b_mean = 0.0;
  for (uint32_t frame = 0; frame < 8; ++frame) {
    const auto vb = s.visibility(with_b, map, ShadowMode::kPcss, frame, 2);
    const auto vl = s.visibility(with_lit, map, ShadowMode::kPcss, frame, 2);
    for (size_t i = 0; i < vb.size(); i += 2) {
      EXPECT_EQ(vb[i], vl[i]) << "A point " << i / 2 << ", frame " << frame;
      b_mean += vb[i + 1] / (8.0 * 48.0);
    }
  }
  EXPECT_GT(b_mean, 0.1);  // B's row does cross a penumbra (the test has something to leak)
  EXPECT_LT(b_mean, 0.9);
}

// A receiver that pools with no quad neighbour (the floor beside an object's outline in the
// picture) searches with the whole tap set itself, so it shades as a receiver whose three quad
// neighbours stand on the same spot and share their quarters of the set with it. Floor points
// in the penumbra of a ball resting on the floor (its blockers at many depths), each at a
// quad's top-left pixel, once with lit floor points far away as its neighbours and once with
// itself; the quad's search rotation and the pixel's filter rotation are the same in both.
// (With half the set the two differed by 0.0111 on average: the float sums differ only in
// order, so they now agree to 0.0000.)
TEST(SoftShadow, PcssUnpooledReceiversSearchTheWholeSet) {
  Shadows s(1024);
  const glm::dvec3 centre(0.3, -0.75, 0.4);
  const double radius = 0.25;
  auto ball_t = [&](glm::dvec3 o, glm::dvec3 d, bool exit) {
    const glm::dvec3 oc = o - centre;
    const double b = glm::dot(oc, d), disc = b * b - (glm::dot(oc, oc) - radius * radius);
    if (disc <= 0 || -b - std::sqrt(disc) <= 0) return -1.0;
    return exit ? -b + std::sqrt(disc) : -b - std::sqrt(disc);
  };
  const auto map = s.map(
      [&](glm::dvec3 o, glm::dvec3 d) {
        const double t = ball_t(o, d, false);
        return t > 0 ? t : floor_hit(o, d);
      },
      [&](glm::dvec3 o, glm::dvec3 d) {
        const double t = ball_t(o, d, true);
        return t > 0 ? t : floor_hit(o, d);
      });
  // width 4, two quads a row pair: (p, x, q, x) over (x, x, x, x) alone, (p, p, q, q) twice
  // pooled (x: a lit floor point far away)
  const glm::dvec3 dir = glm::normalize(glm::dvec3(centre.x, 0.0, centre.z));
  std::vector<Point> alone, pooled;
  for (int k = 0; k < 16; ++k) {
    auto at = [&](double along) {
      const glm::dvec3 p = glm::dvec3(centre.x, -1.0, centre.z) + dir * along;
      return Point{glm::vec3(p), {0, 1, 0}};
    };
    const Point p = at(0.2 + 0.015 * k), q = at(0.26 + 0.015 * k);
    const Point x{{-0.8f, -1.0f, -0.8f}, {0, 1, 0}};
    for (const Point& v : {p, x, q, x, x, x, x, x}) alone.push_back(v);
    for (const Point& v : {p, p, q, q, p, p, q, q}) pooled.push_back(v);
  }
  double diff = 0.0, mean = 0.0;
  int n = 0;
  for (uint32_t frame = 0; frame < 8; ++frame) {
    const auto va = s.visibility(alone, map, ShadowMode::kPcss, frame, 4);
    const auto vp = s.visibility(pooled, map, ShadowMode::kPcss, frame, 4);
    for (size_t i = 0; i < va.size(); i += 8)
      for (size_t c : {size_t(0), size_t(2)}) {
        diff += std::abs(va[i + c] - vp[i + c]);
        mean += vp[i + c];
        ++n;
      }
  }
  std::printf("pcss unpooled receivers: mean |alone - pooled| %.4f (mean visibility %.3f)\n",
              diff / n, mean / n);
  EXPECT_GT(mean / n, 0.2);  // the points do lie in the penumbra
  EXPECT_LT(mean / n, 0.8);
  EXPECT_LT(diff / n, 0.001);
}

// ---- exact references: mips, hard, pcf ----

// kernels/common/random.h's hash and Poisson disk.
uint32_t hash_u32(uint32_t v) {
  const uint32_t state = v * 747796405u + 2891336453u;
  const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
const double kDisk[16][2] = {
    {0.3972, 0.6871},   {0.9056, -0.0336},  {-0.7300, -0.2740}, {-0.0751, -0.5619},
    {-0.4080, 0.8898},  {-0.3577, 0.4519},  {0.5044, 0.2503},   {0.4689, -0.8088},
    {0.1092, -0.0942},  {0.8308, 0.5409},   {-0.7750, 0.2014},  {-0.4490, -0.8619},
    {-0.0158, -0.9943}, {0.0188, 0.9827},   {0.5436, -0.2779},  {-0.3392, -0.0255}};

// What the hard and pcf modes compute for one receiver, in double (see soft_shadow.h).
struct Receiver {
  bool inside = false;
  double sx = 0, sy = 0, zr = 0, texel = 0, tan_theta = 0, inv0 = 0, gx = 0, gy = 0;
};

Receiver project(const rp::scene::PointLight& light, uint32_t size, const Point& pt) {
  const glm::dmat4 m(light.view_proj());
  const glm::dvec3 p(pt.p), n(pt.n);
  auto row = [&](int r) { return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
  const glm::dvec4 r0 = row(0), r1 = row(1), r3 = row(3);
  const double l0 = glm::dot(glm::dvec3(r0), glm::dvec3(r0));
  const double l1 = glm::dot(glm::dvec3(r1), glm::dvec3(r1));
  Receiver r;
  const double w0 = glm::dot(r3, glm::dvec4(p, 1.0));
  r.texel = std::abs(w0) * 2.0 / (size * std::sqrt(l0));
  const glm::dvec3 l = glm::normalize(glm::dvec3(light.position) - p);
  const double c = glm::dot(n, l);
  const double cc = std::max(c, 1e-4);
  r.tan_theta = std::min(std::sqrt(std::max(1.0 - cc * cc, 0.0)) / cc, 8.0);
  const glm::dvec3 q = p + n * r.texel;
  const glm::dvec4 clip = m * glm::dvec4(q, 1.0);
  const double ndx = clip.x / clip.w, ndy = clip.y / clip.w, ndz = clip.z / clip.w;
  r.inside = clip.w > 0 && std::abs(ndx) <= 1 && std::abs(ndy) <= 1 && ndz <= 1 && c > 0;
  r.sx = (ndx * 0.5 + 0.5) * size;
  r.sy = (0.5 - ndy * 0.5) * size;
  r.zr = clip.w;
  r.inv0 = 1.0 / (clip.w - r.texel);
  const double n_r = glm::dot(n, glm::dvec3(r0)) / l0, n_u = glm::dot(n, glm::dvec3(r1)) / l1;
  const double n_d = glm::dot(n, glm::dvec3(r3)) + ndx * n_r + ndy * n_u;
  r.gx = std::clamp(2.0 / size * n_r / n_d, -0.5, 0.5);
  r.gy = std::clamp(-2.0 / size * n_u / n_d, -0.5, 0.5);
  return r;
}

double stored(const std::vector<float>& map, uint32_t size, double tx, double ty) {
  const auto clampi = [&](double v) {
    return size_t(std::clamp(v, 0.0, double(size) - 1.0));
  };
  return map[clampi(ty) * size + clampi(tx)];
}

double inverse_depth(const rp::scene::PointLight& light, double d) {
  const double n = light.shadow_near, f = light.shadow_far;
  return 1.0 / n - d * (f - n) / (n * f);
}

double hard_ref(const rp::scene::PointLight& light, const std::vector<float>& map,
                uint32_t size, const Point& pt) {
  const Receiver r = project(light, size, pt);
  if (!r.inside) return 1.0;
  const double d = stored(map, size, r.sx, r.sy);
  const double receiver = r.zr - r.texel * (1.0 + r.tan_theta);
  return d < 1.0 && inverse_depth(light, d) * receiver > 1.0 ? 0.0 : 1.0;
}

// RP_PCF_TAPS = 8 taps, points 0, 2, .., 14 of the disk, RP_PCF_RADIUS = 2.5 texels, rotated by
// 2 pi k / 16, k = the top 4 bits of the pixel's hash plus the frame index (mod 16).
double pcf_ref(const rp::scene::PointLight& light, const std::vector<float>& map, uint32_t size,
               const Point& pt, uint32_t x, uint32_t y, uint32_t frame) {
  const Receiver r = project(light, size, pt);
  if (!r.inside) return 1.0;
  const uint32_t h = hash_u32(x ^ hash_u32(y));
  const double angle = 2.0 * M_PI * double(((h >> 28) + frame) & 15u) / 16.0;
  const double ca = std::cos(angle), sa = std::sin(angle);
  int lit = 0;
  for (int t = 0; t < 8; ++t) {
    const double* dp = kDisk[2 * t];
    const double tx = r.sx + (ca * dp[0] - sa * dp[1]) * 2.5;
    const double ty = r.sy + (sa * dp[0] + ca * dp[1]) * 2.5;
    const double ratio = std::max(1.0 + r.gx * (tx - r.sx) + r.gy * (ty - r.sy), 1.0);
    const double d = stored(map, size, tx, ty);
    lit += !(inverse_depth(light, d) > r.inv0 * ratio && d < 1.0);
  }
  return lit / 8.0;
}

// The floor, a plate and a ball: a map with edges of several depths.
double busy_hit(glm::dvec3 o, glm::dvec3 d) {
  double t = Plate{-0.3, 0.3, 0.25}.hit(o, d);
  const glm::dvec3 c(-0.4, -0.6, 0.2), oc = o - c;
  const double b = glm::dot(oc, d), disc = b * b - (glm::dot(oc, oc) - 0.3 * 0.3);
  if (disc > 0 && -b - std::sqrt(disc) > 0) t = std::min(t, -b - std::sqrt(disc));
  return t;
}

std::vector<Point> floor_grid(int n) {
  std::vector<Point> pts;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      pts.push_back({{-0.95f + 1.9f * float(i) / float(n - 1), -1.0f,
                      -0.95f + 1.9f * float(j) / float(n - 1)},
                     {0, 1, 0}});
  return pts;
}

// The pcss chunk checkerboard (kernels/shadow_visibility.cl) on an image of the floor under a
// plate and a ball (neighbouring pixels see neighbouring floor points), against the full
// evaluation: the chunks of the frame's parity are computed (equal to the full pass), every
// other chunk is filled with 1 (0) exactly when all its edge neighbours came out all 1 (all 0),
// and is computed otherwise; the fill loses nothing visible here, and covers much of the image.
TEST(SoftShadow, PcssCheckerboardFillsOnlyWhereTheNeighboursAgree) {
  constexpr uint32_t kN = 96, kCx = kN / 4, kCy = kN / 2;  // chunks of 4 x 2 pixels
  Shadows s(256);
  const auto map = s.map(busy_hit);
  const std::vector<Point> floor = floor_grid(int(kN));
  size_t filled = 0, differ = 0, chunks = 0;
  for (uint32_t frame = 0; frame < 2; ++frame) {
    std::vector<float> full, got;
    const auto full_image = s.visibility(floor, map, ShadowMode::kPcss, frame, kN, false, &full);
    const auto got_image = s.visibility(floor, map, ShadowMode::kPcss, frame, kN, true, &got);
    const auto chunk_value = [&](const std::vector<float>& v, uint32_t ci, uint32_t cj) {
      // 1 or 0 when the chunk's 8 pixels all are exactly that, else -1
      const float first = v[size_t(2 * cj) * kN + 4 * ci];
      for (uint32_t k = 0; k < 8; ++k)
        if (v[size_t(2 * cj + k / 4) * kN + 4 * ci + k % 4] != first) return -1.0f;
      return first == 1.0f || first == 0.0f ? first : -1.0f;
    };
    for (uint32_t cj = 0; cj < kCy; ++cj)
      for (uint32_t ci = 0; ci < kCx; ++ci) {
        ++chunks;
        float agreed = -2.0f;  // the neighbours' common verdict; -1 when they disagree
        if (((ci + cj + frame) & 1u) != 0u) {
          const int dx[4] = {-1, 1, 0, 0}, dy[4] = {0, 0, -1, 1};
          for (int n = 0; n < 4; ++n) {
            const int x = int(ci) + dx[n], y = int(cj) + dy[n];
            if (x < 0 || y < 0 || x >= int(kCx) || y >= int(kCy)) continue;
            const float v = chunk_value(got, uint32_t(x), uint32_t(y));
            agreed = agreed == -2.0f || agreed == v ? v : -1.0f;
          }
        }
        for (uint32_t k = 0; k < 8; ++k) {
          const size_t i = size_t(2 * cj + k / 4) * kN + 4 * ci + k % 4;
          const float want = agreed >= 0.0f ? agreed : full[i];
          EXPECT_EQ(got[i], want) << "chunk " << ci << "," << cj << " pixel " << k << " frame "
                                  << frame << (agreed >= 0.0f ? " (filled)" : " (computed)");
          differ += got[i] != full[i];
          EXPECT_EQ(got_image[i], agreed >= 0.0f && got[i] != full[i] ? got_image[i]
                                                                      : full_image[i]);
        }
        filled += agreed >= 0.0f;
      }
  }
  EXPECT_GT(double(filled), 0.2 * double(chunks)) << "the fill must cover much of the image";
  EXPECT_LT(double(differ), 0.002 * double(chunks) * 8.0) << "filled pixels the full pass shades";
}

// The limit the checkerboard accepts: a shadow smaller than a chunk whose neighbours are all lit
// is filled over in the frames where its chunk is not computed, and seen in the others (the
// checkerboard alternates). A ball of radius 0.01 on the lit floor (a 1024^2 map resolves it):
// its umbra covers one pixel (0.02 units), pixel (80, 80) of a 96 x 96 image, chunk (20, 40):
// computed in even frames, filled in odd ones.
TEST(SoftShadow, PcssCheckerboardMissesASubChunkShadowEveryOtherFrame) {
  constexpr uint32_t kN = 96;
  const double step = 1.9 / double(kN - 1);
  const glm::dvec3 centre(-0.95 + 80 * step, -1.0 + 0.01, -0.95 + 80 * step);
  Shadows s(1024);
  const auto map = s.map([&](glm::dvec3 o, glm::dvec3 d) {
    const glm::dvec3 oc = o - centre;
    const double b = glm::dot(oc, d), disc = b * b - (glm::dot(oc, oc) - 0.01 * 0.01);
    double t = floor_hit(o, d);
    if (disc > 0 && -b - std::sqrt(disc) > 0) t = std::min(t, -b - std::sqrt(disc));
    return t;
  });
  const std::vector<Point> floor = floor_grid(int(kN));
  const size_t ball = size_t(80) * kN + 80;
  for (uint32_t frame = 0; frame < 4; ++frame) {
    std::vector<float> full, got;
    s.visibility(floor, map, ShadowMode::kPcss, frame, kN, false, &full);
    s.visibility(floor, map, ShadowMode::kPcss, frame, kN, true, &got);
    ASSERT_LT(full[ball], 0.9f) << "the ball's shadow must show in the full evaluation";
    if (frame % 2 == 0) {
      EXPECT_EQ(got[ball], full[ball]) << "computed chunk, frame " << frame;
    } else {
      EXPECT_EQ(got[ball], 1.0f) << "filled chunk, frame " << frame;
    }
  }
}

TEST(SoftShadow, MipsMatchAReduction) {
  for (uint32_t size : {37u, 64u}) {
    Shadows s(size);
    std::vector<float> map(size_t(size) * size);
    uint32_t state = size;
    for (float& d : map) {
      state = state * 1664525u + 1013904223u;
      d = (state >> 28) == 0 ? 1.0f : 0.5f + 0.4999f * float(state >> 8) / float(1u << 24);
    }
    const auto got = s.mips(map);
    const rp::scene::PointLight& light = s.light();
    const double n = light.shadow_near, f = light.shadow_far;
    // level 0 as linear depth (empty = far), then 2x2 reductions with the edge repeated
    std::vector<double> mn(map.size()), mean(map.size()), mean2(map.size());
    for (size_t i = 0; i < map.size(); ++i) {
      const double z = map[i] >= 1.0f ? f : 2 * n * f / ((f + n) - (2.0 * map[i] - 1) * (f - n));
      mn[i] = mean[i] = z;
      mean2[i] = z * z;
    }
    uint32_t m = size;
    const uint32_t plane = rp::gpu::rp_shadow_mip_total(size);
    const uint32_t levels = rp::gpu::rp_shadow_mip_levels(size);
    EXPECT_EQ(levels, size == 37 ? 6u : 6u);
    for (uint32_t l = 1; l <= levels; ++l) {
      const uint32_t k = (m + 1) / 2;
      std::vector<double> a(size_t(k) * k), b(a.size()), c(a.size());
      for (uint32_t j = 0; j < k; ++j)
        for (uint32_t i = 0; i < k; ++i) {
          const uint32_t xs[2] = {2 * i, std::min(2 * i + 1, m - 1)};
          const uint32_t ys[2] = {2 * j, std::min(2 * j + 1, m - 1)};
          double lo = 1e30, s1 = 0, s2 = 0;
          for (uint32_t y : ys)
            for (uint32_t x : xs) {
              lo = std::min(lo, mn[y * m + x]);
              s1 += mean[y * m + x] / 4;
              s2 += mean2[y * m + x] / 4;
            }
          a[j * k + i] = lo;
          b[j * k + i] = s1;
          c[j * k + i] = s2;
          const size_t at = rp::gpu::rp_shadow_mip_offset(size, l) + j * k + i;
          EXPECT_NEAR(got[at], lo, 1e-6 * lo) << "min, level " << l;
          EXPECT_NEAR(got[plane + at], s1, 1e-5 * s1) << "mean, level " << l;
          EXPECT_NEAR(got[2 * plane + at], s2, 1e-5 * s2) << "mean z^2, level " << l;
        }
      mn = a;
      mean = b;
      mean2 = c;
      m = k;
    }
    EXPECT_EQ(m, 1u);
  }
}

TEST(SoftShadow, HardIsOneTapAtTheReceiver) {
  Shadows s(128);
  const auto map = s.map(busy_hit);
  const auto pts = floor_grid(40);
  const auto vis = s.visibility(pts, map, ShadowMode::kHard, 3);
  int shadowed = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    EXPECT_EQ(vis[i] < 0.5 ? 0.0 : 1.0, hard_ref(s.light(), map, s.size(), pts[i])) << i;
    EXPECT_TRUE(std::abs(vis[i]) < 1e-5 || std::abs(vis[i] - 1.0) < 1e-5) << vis[i];
    shadowed += vis[i] < 0.5;
  }
  EXPECT_GT(shadowed, 100);
  EXPECT_LT(shadowed, int(pts.size()) - 100);
}

TEST(SoftShadow, PcfIsTheRotatedTapSum) {
  Shadows s(128);
  const auto map = s.map(busy_hit);
  const auto pts = floor_grid(40);
  int partial = 0, off = 0;
  for (uint32_t frame : {0u, 7u}) {
    const auto vis = s.visibility(pts, map, ShadowMode::kPcf, frame);
    for (size_t i = 0; i < pts.size(); ++i) {
      const double want = pcf_ref(s.light(), map, s.size(), pts[i], uint32_t(i % 16),
                                  uint32_t(i / 16), frame);
      // a tap exactly on a texel border may round either way: one tap (1/8) at a few points
      EXPECT_NEAR(vis[i], want, 0.125 + 1e-5) << i;
      off += std::abs(vis[i] - want) > 1e-5;
      partial += want > 0.01 && want < 0.99;
    }
  }
  EXPECT_LE(off, 8);
  EXPECT_GT(partial, 40);  // the edges are soft
}

// Planes through (0, -0.5, 0) tilted by up to 80 degrees from the floor's orientation, the map
// holding exactly the plane: every lit point stays lit in every mode (no acne).
TEST(SoftShadow, TiltedPlanesStayLit) {
  Shadows s(256);
  for (double deg : {0.0, 30.0, 60.0, 75.0, 80.0}) {
    const double a = deg * M_PI / 180.0;
    const glm::dvec3 n(std::sin(a), std::cos(a), 0.0), c(0.0, -0.5, 0.0);
    const auto map = s.map([&](glm::dvec3 o, glm::dvec3 d) {
      const double den = glm::dot(d, n);
      if (std::abs(den) < 1e-9) return -1.0;
      const double t = glm::dot(c - o, n) / den;
      return t > 0 ? t : -1.0;
    });
    const glm::dvec3 u = glm::normalize(glm::cross(n, glm::dvec3(0, 0, 1)));
    std::vector<Point> pts;
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i) {
        const glm::dvec3 p =
            c + u * (-0.45 + 0.9 * i / 11.0) + glm::dvec3(0, 0, -0.6 + 1.2 * j / 11.0);
        pts.push_back({glm::vec3(p), glm::vec3(n)});
      }
    for (ShadowMode f : {ShadowMode::kHard, ShadowMode::kPcf, ShadowMode::kPcss,
                           ShadowMode::kVssm}) {
      const auto vis = s.visibility(pts, map, f, 1);
      for (size_t i = 0; i < pts.size(); ++i) {
        if (direct_ref(pts[i], s.light()) <= 0.0) continue;
        EXPECT_GT(vis[i], f == ShadowMode::kVssm ? 0.95 : 0.999)
            << "tilt " << deg << " mode " << int(f) << " point " << i;
      }
    }
  }
}

// Floor points under a plate 0.02 above the floor (2.8 texels of a 1024 map there), at least
// 0.05 inside its edges: shadowed in every mode (no peter-panning; the normal offset and the
// bias are one texel each).
TEST(SoftShadow, ContactStaysShadowed) {
  Shadows s(1024);
  const Plate plate{-0.98, 0.3, 0.3};
  const auto map = s.map([&](glm::dvec3 o, glm::dvec3 d) { return plate.hit(o, d); });
  std::vector<Point> pts;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i)
      pts.push_back({{0.05f + 0.5f * float(i) / 7.0f, -1.0f, -0.25f + 0.5f * float(j) / 7.0f},
                     {0, 1, 0}});
  for (ShadowMode f :
       {ShadowMode::kHard, ShadowMode::kPcf, ShadowMode::kPcss, ShadowMode::kVssm}) {
    const auto vis = s.mean_visibility(pts, map, f, 4);
    for (size_t i = 0; i < pts.size(); ++i)
      EXPECT_LT(vis[i], f == ShadowMode::kVssm ? 0.05 : 0.01) << "mode " << int(f) << " " << i;
  }
}

// A ball resting on the floor (a tumbler's body): floor points around it against the lamp
// disk's visible fraction past the ball (ray-sphere tests from the disk samples).
TEST(SoftShadow, BallOnTheFloorMatchesTheLampDisk) {
  Shadows s(1024);
  const glm::dvec3 centre(0.3, -0.75, 0.4);
  const double radius = 0.25;
  auto ball = [&](glm::dvec3 o, glm::dvec3 d) {
    const glm::dvec3 oc = o - centre;
    const double b = glm::dot(oc, d), disc = b * b - (glm::dot(oc, oc) - radius * radius);
    const double t = disc > 0 ? -b - std::sqrt(disc) : -1.0;
    return t > 0 ? t : floor_hit(o, d);
  };
  auto ball_exit = [&](glm::dvec3 o, glm::dvec3 d) {
    const glm::dvec3 oc = o - centre;
    const double b = glm::dot(oc, d), disc = b * b - (glm::dot(oc, oc) - radius * radius);
    return disc > 0 && -b - std::sqrt(disc) > 0 ? -b + std::sqrt(disc) : floor_hit(o, d);
  };
  const auto map = s.map(ball, ball_exit);
  const double a = lamp_disk_radius(s.light());
  auto truth = [&](glm::dvec3 p) {
    int seen = 0, total = 0;
    for (int j = -40; j <= 40; ++j)
      for (int i = -40; i <= 40; ++i) {
        const double u = i / 40.0, v = j / 40.0;
        if (u * u + v * v > 1.0) continue;
        ++total;
        const glm::dvec3 d = glm::normalize(glm::dvec3(a * u, 1.0, a * v) - p);
        const glm::dvec3 oc = p - centre;
        const double b = glm::dot(oc, d), disc = b * b - (glm::dot(oc, oc) - radius * radius);
        seen += !(disc > 0 && -b - std::sqrt(disc) > 0);
      }
    return double(seen) / total;
  };
  // a row along the line from the lamp's foot through the ball's contact point, beyond it
  std::vector<Point> pts;
  std::vector<double> want;
  const glm::dvec3 dir = glm::normalize(glm::dvec3(centre.x, 0.0, centre.z));
  for (int i = 0; i < 32; ++i) {
    const glm::dvec3 p = glm::dvec3(centre.x, -1.0, centre.z) + dir * (0.2 + 0.6 * i / 31.0);
    pts.push_back({glm::vec3(p), {0, 1, 0}});
    want.push_back(truth(p));
  }
  std::vector<double> xs;
  for (int i = 0; i < 32; ++i) xs.push_back(0.2 + 0.6 * i / 31.0);
  const double want_width = crossing(xs, want, 0.9) - crossing(xs, want, 0.1);
  for (ShadowMode f : {ShadowMode::kPcss, ShadowMode::kVssm}) {
    const bool pcss = f == ShadowMode::kPcss;
    const auto vis = s.mean_visibility(pts, map, f, 32);
    double sum = 0.0;
    for (size_t i = 0; i < pts.size(); ++i) sum += std::abs(vis[i] - want[i]);
    const double width = crossing(xs, vis, 0.9) - crossing(xs, vis, 0.1);
    std::printf("%s ball: mean |error| %.4f, 10-90 %% width %.4f (reference %.4f)\n",
                pcss ? "pcss" : "vssm", sum / double(pts.size()), width, want_width);
    EXPECT_LT(sum / double(pts.size()), pcss ? 0.009 : 0.05);
    EXPECT_NEAR(width, want_width, (pcss ? 0.25 : 0.5) * want_width);
    EXPECT_LT(vis[0], 0.01);  // the umbra under the ball
  }
}

// A tall box standing on the floor (a tumbler's height): floor points beyond its corner, away
// from the lamp, against the lamp disk's visible fraction past the box (slab tests from disk
// samples), averaged over 32 frames.
TEST(SoftShadow, ColumnOnTheFloorMatchesTheLampDisk) {
  Shadows s(1024);
  const glm::dvec3 lo(0.3, -1.0, 0.3), hi(0.5, -0.4, 0.5);
  // entry (or, with `exit`, exit) distance along the ray; -1 when it misses
  auto box_t = [&](glm::dvec3 o, glm::dvec3 d, bool exit = false) {
    double t0 = 0.0, t1 = 1e30;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(d[k]) < 1e-12) {
        if (o[k] < lo[k] || o[k] > hi[k]) return -1.0;
        continue;
      }
      double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
    return t0 <= t1 && t0 > 1e-9 ? (exit ? t1 : t0) : -1.0;
  };
  const auto map = s.map(
      [&](glm::dvec3 o, glm::dvec3 d) {
        const double t = box_t(o, d);
        return t > 0 ? t : floor_hit(o, d);
      },
      [&](glm::dvec3 o, glm::dvec3 d) {
        const double t = box_t(o, d, true);
        return t > 0 ? t : floor_hit(o, d);
      });
  const double a = lamp_disk_radius(s.light());
  auto truth = [&](glm::dvec3 p) {
    int seen = 0, total = 0;
    for (int j = -40; j <= 40; ++j)
      for (int i = -40; i <= 40; ++i) {
        const double u = i / 40.0, v = j / 40.0;
        if (u * u + v * v > 1.0) continue;
        ++total;
        const glm::dvec3 d = glm::normalize(glm::dvec3(a * u, 1.0, a * v) - p);
        seen += box_t(p + d * 1e-6, d) < 0;
      }
    return double(seen) / total;
  };
  std::vector<Point> pts;
  std::vector<double> want, xs;
  const glm::dvec3 dir = glm::normalize(glm::dvec3(1.0, 0.0, 1.0));
  for (int i = 0; i < 32; ++i) {
    const glm::dvec3 p = glm::dvec3(0.5, -1.0, 0.5) + dir * (0.01 + 0.5 * i / 31.0);
    pts.push_back({glm::vec3(p), {0, 1, 0}});
    want.push_back(truth(p));
    xs.push_back(0.01 + 0.5 * i / 31.0);
  }
  const double want_width = crossing(xs, want, 0.9) - crossing(xs, want, 0.1);
  for (ShadowMode f : {ShadowMode::kPcss, ShadowMode::kVssm}) {
    const bool pcss = f == ShadowMode::kPcss;
    const auto vis = s.mean_visibility(pts, map, f, 32);
    double sum = 0.0, bias = 0.0;
    for (size_t i = 0; i < pts.size(); ++i) {
      sum += std::abs(vis[i] - want[i]);
      bias += vis[i] - want[i];
    }
    const double width = crossing(xs, vis, 0.9) - crossing(xs, vis, 0.1);
    std::printf("%s column: mean |error| %.4f, bias %+.4f, 10-90 %% width %.4f (reference %.4f)\n",
                pcss ? "pcss" : "vssm", sum / double(pts.size()), bias / double(pts.size()),
                width, want_width);
    // PCSS: mean |error| 0.011, bias +0.000 with filter taps uniform over the lamp's disk
    // (0.025 and +0.021 with the rim-heavy Poisson set); VSSM bleeds light at the contact
    EXPECT_LT(sum / double(pts.size()), pcss ? 0.018 : 0.1);
    if (pcss) {
      EXPECT_LT(std::abs(bias / double(pts.size())), 0.01);
    }
    EXPECT_NEAR(width, want_width, (pcss ? 0.15 : 0.6) * want_width);
    EXPECT_LT(vis[0], pcss ? 0.01 : 0.4);  // at the column's foot
  }
}

}  // namespace
