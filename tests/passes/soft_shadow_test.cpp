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
//     formula 2 a (z_r - z_b) / (z_b - z_e) (0 % to 100 %);
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

namespace {

using rp::passes::ShadowFilter;

struct Point {
  glm::vec3 p, n;
};

double falloff_ref(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return 0.35 + s * (0.446 + 0.204 * s);
}

// cos / d^2 * falloff: the unshadowed direct factor (light_test.cpp's reference).
double direct_ref(const Point& pt, const glm::vec3& light) {
  glm::dvec3 to = glm::dvec3(light) - glm::dvec3(pt.p);
  double d2 = glm::dot(to, to);
  glm::dvec3 l = to / std::sqrt(d2);
  double c = glm::dot(glm::dvec3(pt.n), l);
  return c <= 0.0 ? 0.0 : c / d2 * falloff_ref(l.y);
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

  // Texel (tx, ty) holds the depth of the first hit of the lamp ray through its centre.
  std::vector<float> map(const std::function<double(glm::dvec3, glm::dvec3)>& hit) const {
    const glm::dmat4 vp(frame_.light.view_proj());
    const glm::dmat4 inv = glm::inverse(vp);
    const glm::dvec3 origin(frame_.light.position);
    std::vector<float> out(size_t(size_) * size_, 1.0f);
    for (uint32_t ty = 0; ty < size_; ++ty)
      for (uint32_t tx = 0; tx < size_; ++tx) {
        double nx = (tx + 0.5) / size_ * 2.0 - 1.0, ny = 1.0 - (ty + 0.5) / size_ * 2.0;
        glm::dvec4 f = inv * glm::dvec4(nx, ny, 1.0, 1.0);
        glm::dvec3 dir = glm::normalize(glm::dvec3(f) / f.w - origin);
        double t = hit(origin, dir);
        if (t < 0) continue;
        glm::dvec4 c = vp * glm::dvec4(origin + dir * t, 1.0);
        out[size_t(ty) * size_ + tx] = float(c.z / c.w * 0.5 + 0.5);
      }
    return out;
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
  std::vector<double> visibility(const std::vector<Point>& points, const std::vector<float>& map,
                                 ShadowFilter filter, uint32_t frame_index, uint32_t width = 16) {
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
    if (const uint32_t planes = rp::passes::shadow_mip_planes(filter); planes > 0) {
      rp::passes::ShadowFilterPass mips(ctx, rp::test::programs());
      mips.run(profiler, *scene_, sm, planes > 1);
    }
    rp::passes::LightPass pass(ctx, rp::test::programs(), filter);
    pass.run(profiler, *scene_, gb, sm, voxels, chain.resolution, chain.levels, hdr);
    profiler.collect();
    std::vector<float> out(n * 4);
    ctx.queue.enqueueReadBuffer(hdr, CL_TRUE, 0, n * 16, out.data());
    std::vector<double> vis(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      const double k = direct_ref(points[i], frame_.light.position) * frame_.light.intensity.x;
      vis[i] = k > 0.0 ? out[i * 4] / k : 1.0;
    }
    return vis;
  }

  // Mean visibility over `frames` frame indices.
  std::vector<double> mean_visibility(const std::vector<Point>& points,
                                      const std::vector<float>& map, ShadowFilter filter,
                                      uint32_t frames) {
    std::vector<double> sum(points.size(), 0.0);
    for (uint32_t f = 0; f < frames; ++f) {
      auto v = visibility(points, map, filter, f);
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
void expect_plate_penumbra(ShadowFilter filter, double max_mean_error, double width_tolerance) {
  Shadows s(256);
  const Plate plate{0.0, -0.4, 0.4};  // edge at x = 0, penumbra over x in (-0.33, 0.33)
  auto map = s.map([&](glm::dvec3 o, glm::dvec3 d) { return plate.hit(o, d); });
  Row row = floor_row(s.light(), plate, -0.6, 0.6, 96);
  auto vis = s.mean_visibility(row.points, map, filter, 64);
  double sum_error = 0.0;
  for (size_t i = 0; i < vis.size(); ++i) {
    sum_error += std::abs(vis[i] - row.truth[i]);
    EXPECT_NEAR(vis[i], row.truth[i], 0.2) << "x " << row.xs[i];
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
              filter == ShadowFilter::kPcss ? "pcss" : "vssm", sum_error / double(vis.size()), got, want,
              full, formula);
}

TEST(SoftShadow, PcssPenumbraMatchesTheLampDisk) {
  expect_plate_penumbra(ShadowFilter::kPcss, 0.03, 0.15);
}

TEST(SoftShadow, VssmPenumbraMatchesTheLampDisk) {
  expect_plate_penumbra(ShadowFilter::kVssm, 0.06, 0.3);
}

}  // namespace
