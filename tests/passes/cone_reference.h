// C++ reference of the voxel cone tracer (kernels/common/cone_trace.h), written from the rules in
// that header, in double precision: quadrilinear sampling of the anisotropic chain, one cone
// (half- or quarter-diameter steps, quadrilinear or level-jittered samples), the 16-cone diffuse
// set, the exit term (a cone leaving the box takes the wall it leaves through) and the
// near-field occlusion that scales the diffuse set. Plus helpers that build voxel chains by hand
// for the tests.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

namespace rp::test::cone {

// A whole voxel chain on the host, in the layout of kernels/shared/voxel_layout.h.
struct Chain {
  uint32_t resolution = 0, levels = 0;
  std::vector<glm::vec4> voxels;  // rgb premultiplied radiance, a opacity

  Chain(uint32_t r, uint32_t l);
  uint32_t size(uint32_t level) const { return resolution >> level; }
  // Voxel (x, y, z) of volume `dir` (RP_DIR_*; ignored at level 0) at `level`.
  glm::vec4& at(uint32_t level, uint32_t dir, uint32_t x, uint32_t y, uint32_t z);
  const glm::vec4& at(uint32_t level, uint32_t dir, uint32_t x, uint32_t y, uint32_t z) const;
  // Fills every level >= 1 from level 0: for direction d the two children along d are
  // composited front to back (the one a ray along d meets first in front), then the four
  // composited columns across d are averaged.
  void build_mips();
  // Like build_mips, but level 1 is built from one-sided level-0 voxels as voxel_mips.cl does
  // (mips_facing): facing(x, y, z, dir) is the coverage of level-0 voxel (x, y, z) for a cone
  // travelling along `dir` (RP_DIR_*; what faces -dir), and the voxel enters that direction's
  // composite with opacity c = min(facing, a) and radiance rgb * c / a.
  void build_mips(const std::function<double(uint32_t, uint32_t, uint32_t, uint32_t)>& facing);
};

// The cone's constants from their definitions: half-angle atan 0.4 (21.8 degrees).
double tan_half_angle();              // 0.4
double first_distance_in_voxels();    // t0 / v0 = 1 / (2 tan_h)
double growth(bool fine = false);     // 1 + 2 s tan_h: s = 1/2 (default) or 1/4 (fine)
double normal_offset_in_voxels();     // start offset along the normal (1 voxel)
int top_level(const Chain& c);        // coarsest level a cone samples: levels - 2

// Trilinear sample of one volume at world position p, clamp-to-edge addressing.
glm::dvec4 trilinear(const Chain& c, uint32_t level, uint32_t dir, const glm::dvec3& p);
// Three facing volumes of `level` >= 1, weighted by the squared components of unit d. With an
// apex, voxels in the apex's row along an axis, or behind it, count as empty for that axis.
glm::dvec4 directional(const Chain& c, uint32_t level, const glm::dvec3& d, const glm::dvec3& p,
                       const glm::dvec3* apex = nullptr);
// Quadrilinear sample at fractional level (isotropic level 0 blended into directional level 1),
// levels above `top` (default: the chain's last) clamped to `top`.
glm::dvec4 quadrilinear(const Chain& c, const glm::dvec3& d, const glm::dvec3& p, double level,
                        const glm::dvec3* apex = nullptr, int top = -1);
// How a cone steps and samples (kernels/common/cone_trace.h, rp_cone_march).
struct March {
  bool fine = false;      // quarter-diameter steps (twice the steps) instead of half
  double jitter = -1.0;   // < 0: quadrilinear samples; in [0, 1): one level, floor(L + jitter)
  bool skip_behind_apex = true;  // false: plain sampling (comparisons only; the kernel skips)
  // rp_cone_trace_coarse: full-diameter steps, samples at t0 * 1.8^(k + position_jitter),
  // level floor((k + position_jitter) log2(1.8) + jitter), no thickness correction, at most
  // `levels` samples, stops at opacity 0.9.
  bool coarse = false;
  double position_jitter = 0.0;
  bool exit_term = true;  // false: a cone leaving the box just stops (the first tracer)
};
// What a cone from `origin` along unit `dir` sees where it leaves the box (rp_cone_exit): the
// face it leaves through is the nearest of the three faces ahead of it (ties: x, then y, then
// z); the sample of the volume facing the cone across that face (the one whose axis is the
// face's), at level clamp(floor(level), 1, top), trilinear at the exit point. Zero when the
// chain has no directional level to sample (top 0).
glm::dvec4 exit_sample(const Chain& c, const glm::dvec3& origin, const glm::dvec3& dir,
                       double level);
// One cone from `origin` (its apex) along unit `dir`: (radiance, occlusion). When a sample
// point leaves the box the exit sample at the current level is composited behind what the cone
// has gathered (rp_cone_march, rp_cone_trace_coarse).
glm::dvec4 trace(const Chain& c, const glm::dvec3& origin, const glm::dvec3& dir,
                 const March& march = {});
// A cone of any aperture (rp_cone_trace_aperture, the reflection cone), tan_half the
// tan of its half-angle: diameter d(t) = max(2 t tan_half, d_min) (d_min one level-0 voxel, or
// min_diameter voxels in the fast mode), first sample at t0 = 1.25 v0, sampled level
// L = log2(d / v0); fine: quadrilinear at L, steps of d / 2 (opacity and radiance corrected to
// half a voxel's thickness), at most 2 max_steps samples; else the nearest level round(L), steps
// of d, at most max_steps samples. Stops at `opaque` or takes the exit sample where it leaves.
struct Aperture {
  bool fine = true;
  int max_steps = 24;         // RP_CONE_SPEC_MAX_STEPS
  double opaque = 0.95;       // RP_CONE_OPAQUE (fine), RP_CONE_SPEC_OPAQUE_FAST
  double min_diameter = 1.0;  // RP_CONE_SPEC_MIN_D_FAST (fast only), in level-0 voxels
};
glm::dvec4 trace_aperture(const Chain& c, const glm::dvec3& origin, const glm::dvec3& dir,
                          double tan_half, const Aperture& a = {});
// Near-field occlusion of surface point p with unit normal n (rp_cone_near_occlusion): the
// opacity the three level-1 volumes facing n (weights n^2, trilinear, no rows-behind-the-apex
// rule) show at the cones' apex p + n v0, less what they show at the mirror point p - n v0
// when it lies inside the box, times kNearOcclusion, clamped to [0, 1]; 0 for a chain without
// level 1.
constexpr double kNearOcclusion = 0.6;
double near_occlusion(const Chain& c, const glm::dvec3& p, const glm::dvec3& n);
// The 16 diffuse cones (quarter-diameter steps, quadrilinear) at surface point p with unit
// normal n: their mean radiance = irradiance / pi, times 1 - near_occlusion(p, n). issue14 =
// false leaves out the exit term and the near-field occlusion (the first tracer, for
// the tests that measure the rows-behind-the-apex rule on its own); the kernel has both.
glm::dvec3 diffuse(const Chain& c, const glm::dvec3& p, const glm::dvec3& n,
                   bool skip_behind_apex = true, bool issue14 = true);
// The 16 directions of the diffuse cone set for normal n (equal weights 1/16), in the order of
// the kernel's table.
void diffuse_cones(const glm::dvec3& n, glm::dvec3 dirs[16]);

// A random voxel chain (coloured, translucent, sparse; a small LCG from `seed`, so the same on
// every platform) of resolution^3 with every level, built with build_mips.
Chain random_chain(uint32_t resolution, uint32_t seed);

}  // namespace rp::test::cone
