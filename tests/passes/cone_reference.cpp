#include "cone_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/shared/voxel_layout.h"

namespace rp::test::cone {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kOpaque = 0.95;
constexpr int kMaxSteps = 16;  // half-diameter steps; twice as many quarter-diameter steps

}  // namespace

Chain::Chain(uint32_t r, uint32_t l)
    : resolution(r), levels(l), voxels(gpu::rp_voxel_total(r, l), glm::vec4(0.0f)) {}

glm::vec4& Chain::at(uint32_t level, uint32_t dir, uint32_t x, uint32_t y, uint32_t z) {
  const uint32_t n = size(level);
  return voxels[gpu::rp_voxel_offset(resolution, level, dir) + (size_t(z) * n + y) * n + x];
}

const glm::vec4& Chain::at(uint32_t level, uint32_t dir, uint32_t x, uint32_t y,
                           uint32_t z) const {
  return const_cast<Chain*>(this)->at(level, dir, x, y, z);
}

void Chain::build_mips() { build_mips(nullptr); }

void Chain::build_mips(
    const std::function<double(uint32_t, uint32_t, uint32_t, uint32_t)>& facing) {
  // Child (x, y, z) of level `level` as direction `dir` sees it.
  auto child_value = [&](uint32_t level, uint32_t dir, uint32_t x, uint32_t y, uint32_t z) {
    const glm::dvec4 v(at(level, dir, x, y, z));
    if (level > 0 || !facing) return v;
    if (v.w <= 0.0) return glm::dvec4(0.0);
    const double c = std::min(std::min(facing(x, y, z, dir), 1.0), v.w);
    return glm::dvec4(glm::dvec3(v) * (c / v.w), c);
  };
  for (uint32_t level = 1; level < levels; ++level) {
    const uint32_t n = size(level);
    for (uint32_t dir = 0; dir < 6; ++dir) {
      const int axis = int(dir / 2);
      const bool negative = dir % 2 == 1;  // -axis: the high child is in front
      for (uint32_t z = 0; z < n; ++z)
        for (uint32_t y = 0; y < n; ++y)
          for (uint32_t x = 0; x < n; ++x) {
            glm::dvec4 sum(0.0);
            for (uint32_t a = 0; a < 2; ++a)
              for (uint32_t b = 0; b < 2; ++b) {
                glm::dvec4 slab[2];
                for (uint32_t k = 0; k < 2; ++k) {
                  glm::uvec3 child(2 * x, 2 * y, 2 * z);
                  const int across0 = (axis + 1) % 3, across1 = (axis + 2) % 3;
                  child[axis] += k;
                  child[across0] += a;
                  child[across1] += b;
                  slab[k] = child_value(level - 1, dir, child.x, child.y, child.z);
                }
                const glm::dvec4 front = negative ? slab[1] : slab[0];
                const glm::dvec4 back = negative ? slab[0] : slab[1];
                sum += front + (1.0 - front.w) * back;
              }
            at(level, dir, x, y, z) = glm::vec4(sum * 0.25);
          }
    }
  }
}

double tan_half_angle() { return 0.4; }
double first_distance_in_voxels() { return 1.0 / (2.0 * tan_half_angle()); }
double growth(bool fine) { return 1.0 + 2.0 * (fine ? 0.25 : 0.5) * tan_half_angle(); }
double normal_offset_in_voxels() { return 1.0; }
int top_level(const Chain& c) { return std::max(int(c.levels) - 2, 0); }

glm::dvec4 trilinear(const Chain& c, uint32_t level, uint32_t dir, const glm::dvec3& p) {
  const int n = int(c.size(level));
  const double size = 2.0 / n;  // voxel width
  glm::dvec4 sum(0.0);
  // Continuous index of p, clamped to the outermost voxel centres.
  glm::dvec3 u;
  for (int i = 0; i < 3; ++i) u[i] = std::clamp((p[i] + 1.0) / size - 0.5, 0.0, double(n - 1));
  const glm::ivec3 lo(glm::floor(u));
  const glm::dvec3 f = u - glm::dvec3(lo);
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const double w = (dx ? f.x : 1.0 - f.x) * (dy ? f.y : 1.0 - f.y) * (dz ? f.z : 1.0 - f.z);
        const int x = std::min(lo.x + dx, n - 1), y = std::min(lo.y + dy, n - 1),
                  z = std::min(lo.z + dz, n - 1);
        sum += w * glm::dvec4(c.at(level, dir, uint32_t(x), uint32_t(y), uint32_t(z)));
      }
  return sum;
}

glm::dvec4 directional(const Chain& c, uint32_t level, const glm::dvec3& d, const glm::dvec3& p,
                       const glm::dvec3* apex) {
  glm::dvec4 sum(0.0);
  const int n = int(c.size(level));
  const double size = 2.0 / n;
  for (uint32_t axis = 0; axis < 3; ++axis) {
    const bool negative = d[axis] < 0.0;
    const uint32_t dir = 2 * axis + (negative ? 1u : 0u);
    if (!apex) {
      sum += d[axis] * d[axis] * trilinear(c, level, dir, p);
      continue;
    }
    // Rows along `axis` that a cone travelling this way enters at or behind its apex (the
    // apex's row and those behind it) count as empty; an apex beyond the box has row -1 or n.
    const int apex_row =
        int(std::clamp(std::floor(((*apex)[axis] + 1.0) / size), -1.0, double(n)));
    glm::dvec3 u;
    for (int i = 0; i < 3; ++i) u[i] = std::clamp((p[i] + 1.0) / size - 0.5, 0.0, double(n - 1));
    const glm::ivec3 lo(glm::floor(u));
    const glm::dvec3 f = u - glm::dvec3(lo);
    for (int dz = 0; dz < 2; ++dz)
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const glm::ivec3 v(std::min(lo.x + dx, n - 1), std::min(lo.y + dy, n - 1),
                             std::min(lo.z + dz, n - 1));
          if (negative ? v[axis] >= apex_row : v[axis] <= apex_row) continue;
          const double w =
              (dx ? f.x : 1.0 - f.x) * (dy ? f.y : 1.0 - f.y) * (dz ? f.z : 1.0 - f.z);
          sum += d[axis] * d[axis] * w *
                 glm::dvec4(c.at(level, dir, uint32_t(v.x), uint32_t(v.y), uint32_t(v.z)));
        }
  }
  return sum;
}

glm::dvec4 quadrilinear(const Chain& c, const glm::dvec3& d, const glm::dvec3& p, double level,
                        const glm::dvec3* apex, int top) {
  if (top < 0) top = int(c.levels) - 1;
  level = std::clamp(level, 0.0, double(top));
  const uint32_t lo = uint32_t(std::floor(level));
  const double f = level - lo;
  auto at_level = [&](uint32_t l) { return l == 0 ? trilinear(c, 0, 0, p) : directional(c, l, d, p, apex); };
  if (f == 0.0) return at_level(lo);
  return (1.0 - f) * at_level(lo) + f * at_level(lo + 1);
}

glm::dvec4 exit_sample(const Chain& c, const glm::dvec3& origin, const glm::dvec3& dir,
                       double level) {
  const int top = top_level(c);
  if (top == 0) return glm::dvec4(0.0);
  double t = std::numeric_limits<double>::infinity();
  int axis = 0;
  for (int i = 0; i < 3; ++i) {
    if (dir[i] == 0.0) continue;
    const double face = dir[i] >= 0.0 ? 1.0 : -1.0;
    const double ti = (face - origin[i]) / dir[i];
    if (ti < t) {  // strictly nearer: ties keep the lower axis
      t = ti;
      axis = i;
    }
  }
  const uint32_t volume = uint32_t(2 * axis + (dir[axis] < 0.0 ? 1 : 0));
  const uint32_t l = uint32_t(std::clamp(std::floor(level), 1.0, double(top)));
  return trilinear(c, l, volume, origin + dir * t);
}

namespace {

// Composites the exit sample behind (colour, alpha).
void add_exit(const Chain& c, const glm::dvec3& origin, const glm::dvec3& dir, double level,
              glm::dvec3& colour, double& alpha) {
  const glm::dvec4 e = exit_sample(c, origin, dir, level);
  colour += (1.0 - alpha) * glm::dvec3(e);
  alpha += (1.0 - alpha) * e.w;
}

glm::dvec4 trace_coarse(const Chain& c, const glm::dvec3& origin, const glm::dvec3& dir,
                        const March& march) {
  const double v0 = 2.0 / c.resolution, growth = 1.0 + 2.0 * tan_half_angle();
  const glm::dvec3* apex = march.skip_behind_apex ? &origin : nullptr;
  glm::dvec3 colour(0.0);
  double alpha = 0.0;
  for (int k = 0; k < int(c.levels); ++k) {  // one sample per level at most
    const double steps = k + march.position_jitter;
    const glm::dvec3 q = origin + dir * (first_distance_in_voxels() * v0 * std::pow(growth, steps));
    const double level = std::floor(steps * std::log2(growth) + march.jitter);
    if (std::abs(q.x) > 1.0 || std::abs(q.y) > 1.0 || std::abs(q.z) > 1.0) {
      if (march.exit_term) add_exit(c, origin, dir, level, colour, alpha);  // the wall there
      break;
    }
    const glm::dvec4 s = quadrilinear(c, dir, q, level, apex, top_level(c));
    colour += (1.0 - alpha) * glm::dvec3(s);  // a full-diameter step: the voxel as it is
    alpha += (1.0 - alpha) * s.w;
    if (alpha >= 0.9) break;  // the coarse cone's own threshold
  }
  return glm::dvec4(colour, alpha);
}

}  // namespace

glm::dvec4 trace(const Chain& c, const glm::dvec3& origin, const glm::dvec3& dir,
                 const March& march) {
  if (march.coarse) return trace_coarse(c, origin, dir, march);
  const double v0 = 2.0 / c.resolution;
  const double step = march.fine ? 0.25 : 0.5;  // of the diameter
  const int max_steps = march.fine ? 2 * kMaxSteps : kMaxSteps;
  double t = first_distance_in_voxels() * v0;
  glm::dvec3 colour(0.0);
  double alpha = 0.0;
  const glm::dvec3* apex = march.skip_behind_apex ? &origin : nullptr;
  for (int k = 0; k < max_steps; ++k) {
    const glm::dvec3 q = origin + dir * t;
    // Sampled voxel = cone diameter 2 t tan_h = v0 * growth^k: level k * log2(growth).
    double level = k * std::log2(growth(march.fine));
    if (march.jitter >= 0.0) level = std::floor(level + march.jitter);
    if (std::abs(q.x) > 1.0 || std::abs(q.y) > 1.0 || std::abs(q.z) > 1.0) {
      if (march.exit_term) add_exit(c, origin, dir, level, colour, alpha);  // the wall there
      break;
    }
    const glm::dvec4 s = quadrilinear(c, dir, q, level, apex, top_level(c));
    // The step is a fraction `step` of the sampled voxel: opacity of that thickness.
    const double a = std::clamp(s.w, 0.0, 1.0);
    const double a_step = 1.0 - std::pow(1.0 - a, step);
    const double scale = a > 0.0 ? a_step / a : step;
    colour += (1.0 - alpha) * glm::dvec3(s) * scale;
    alpha += (1.0 - alpha) * s.w * scale;
    if (alpha >= kOpaque) break;
    t += step * (2.0 * t * tan_half_angle());
  }
  return glm::dvec4(colour, alpha);
}

glm::dvec4 trace_aperture(const Chain& c, const glm::dvec3& origin, const glm::dvec3& dir,
                          double tan_half, const Aperture& a) {
  const double v0 = 2.0 / c.resolution;
  const double step = a.fine ? 0.5 : 1.0;  // of the diameter
  const int max_steps = a.fine ? 2 * a.max_steps : a.max_steps;
  const double d_min = (a.fine ? 1.0 : a.min_diameter) * v0;
  double t = first_distance_in_voxels() * v0;  // 1.25 v0, as the diffuse cones
  glm::dvec3 colour(0.0);
  double alpha = 0.0;
  for (int k = 0; k < max_steps; ++k) {
    const glm::dvec3 q = origin + dir * t;
    const double d = std::max(2.0 * tan_half * t, d_min);
    double level = std::log2(d / v0);
    if (std::abs(q.x) > 1.0 || std::abs(q.y) > 1.0 || std::abs(q.z) > 1.0) {
      add_exit(c, origin, dir, level, colour, alpha);  // the wall there
      break;
    }
    if (!a.fine) level = std::floor(level + 0.5);  // one level: the nearest
    const glm::dvec4 s = quadrilinear(c, dir, q, level, &origin, top_level(c));
    // half-diameter steps: the sample is half its voxel thick; full: the voxel as it is
    const double sa = std::clamp(s.w, 0.0, 1.0);
    const double scale = a.fine ? (sa > 0.0 ? (1.0 - std::sqrt(1.0 - sa)) / sa : 0.5) : 1.0;
    colour += (1.0 - alpha) * glm::dvec3(s) * scale;
    alpha += (1.0 - alpha) * s.w * scale;
    if (alpha >= a.opaque) break;
    t += step * d;
  }
  return glm::dvec4(colour, alpha);
}

void diffuse_cones(const glm::dvec3& n, glm::dvec3 dirs[16]) {
  // Duff et al. 2017 basis.
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  const glm::dvec3 t(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::dvec3 bt(b, sign + n.y * n.y * a, -n.y);
  // Equal-area cells of the cosine-weighted hemisphere (uniform in sin^2 theta): the centre
  // disk and rings of 5 and 10 cells, each cone through its cell's middle (in sin^2 theta).
  auto cone = [&](double sin2, double azimuth_deg) {
    const double s = std::sqrt(sin2), phi = azimuth_deg * kPi / 180.0;
    return s * (std::cos(phi) * t + std::sin(phi) * bt) + std::sqrt(1.0 - sin2) * n;
  };
  dirs[0] = n;
  for (int k = 0; k < 5; ++k) dirs[1 + k] = cone(3.5 / 16.0, 72.0 * k);
  for (int k = 0; k < 10; ++k) dirs[6 + k] = cone(11.0 / 16.0, 18.0 + 36.0 * k);
}

double near_occlusion(const Chain& c, const glm::dvec3& p, const glm::dvec3& n) {
  if (c.levels < 2) return 0.0;
  const glm::dvec3 apex = p + n * (normal_offset_in_voxels() * 2.0 / c.resolution);
  const glm::dvec3 mirror = p - n * (normal_offset_in_voxels() * 2.0 / c.resolution);
  const bool behind = std::max({std::abs(mirror.x), std::abs(mirror.y), std::abs(mirror.z)}) <= 1.0;
  double a = 0.0;
  for (uint32_t axis = 0; axis < 3; ++axis)
    a += n[axis] * n[axis] * trilinear(c, 1, 2 * axis + (n[axis] < 0.0 ? 1u : 0u), apex).w;
  if (a > 0.0 && behind)
    for (uint32_t axis = 0; axis < 3; ++axis)
      a -= n[axis] * n[axis] * trilinear(c, 1, 2 * axis + (n[axis] < 0.0 ? 1u : 0u), mirror).w;
  return std::clamp(a * kNearOcclusion, 0.0, 1.0);
}

glm::dvec3 diffuse(const Chain& c, const glm::dvec3& p, const glm::dvec3& n, bool skip_behind_apex,
                   bool issue14) {
  glm::dvec3 dirs[16];
  diffuse_cones(n, dirs);
  const glm::dvec3 origin = p + n * (normal_offset_in_voxels() * 2.0 / c.resolution);
  March march;
  march.fine = true;
  march.skip_behind_apex = skip_behind_apex;
  march.exit_term = issue14;
  glm::dvec3 sum(0.0);
  for (const glm::dvec3& d : dirs) sum += glm::dvec3(trace(c, origin, d, march));
  return sum / 16.0 * (issue14 ? 1.0 - near_occlusion(c, p, n) : 1.0);
}

Chain random_chain(uint32_t resolution, uint32_t seed) {
  uint32_t levels = 1;
  while ((resolution >> (levels - 1)) > 1) ++levels;
  Chain c(resolution, levels);
  uint32_t state = seed;
  auto next = [&state] {  // small LCG: deterministic, platform independent
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) / double(1u << 24);
  };
  for (glm::vec4& v : c.voxels) {
    if (&v - c.voxels.data() >= ptrdiff_t(resolution) * resolution * resolution) break;
    if (next() > 0.3) continue;
    double a = 0.6 * next();
    v = glm::vec4(glm::dvec4(3.0 * a * next(), 3.0 * a * next(), 3.0 * a * next(), a));
  }
  c.build_mips();
  return c;
}

}  // namespace rp::test::cone
