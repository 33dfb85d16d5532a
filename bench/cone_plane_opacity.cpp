// bench_cone_plane: how opaque one thin surface is to the voxel cones, by angle.
//
// A 64^3 chain holds one opaque surface: level-0 row y = 40 (one voxel thick, radiance 1,
// opacity 1), one-sided as the voxelizer makes it (its facing coverage is 1 for cones that
// travel -y, 0 for every other direction), with the mips built as voxel_mips.cl builds them.
// Cones start above it (1.5 to 11.3 voxels, three x offsets) and travel down at `theta` from
// the surface's normal; the table gives the mean opacity they gather, for the three marches of
// kernels/common/cone_trace.h as tests/passes/cone_reference.h restates them (quarter-diameter
// steps: the reference mode; half-diameter; full-diameter coarse steps with level and position
// jitter averaged: the fast mode). A surface the cone crosses should read 1 at every angle:
// the shortfall is light that passes through floors and walls (and the light behind them
// that the cone takes instead). Host double precision: the same figures on every machine.
#include <cmath>
#include <cstdio>

#include "kernels/shared/voxel_layout.h"
#include "tests/passes/cone_reference.h"

namespace {

using rp::test::cone::Chain;
using rp::test::cone::March;
using rp::test::cone::trace;

constexpr uint32_t kResolution = 64, kLevels = 7, kRow = 40;
constexpr double kPi = 3.14159265358979323846;

Chain surface_chain() {
  Chain c(kResolution, kLevels);
  for (uint32_t z = 0; z < kResolution; ++z)
    for (uint32_t x = 0; x < kResolution; ++x) c.at(0, 0, x, kRow, z) = glm::vec4(1.0f);
  c.build_mips([](uint32_t, uint32_t y, uint32_t, uint32_t dir) {
    return y == kRow && dir == RP_DIR_NEG_Y ? 1.0 : 0.0;
  });
  return c;
}

// Mean opacity over the start points (and, coarse, over the jitters).
double mean_opacity(const Chain& c, double theta_deg, const March& march) {
  const double v0 = 2.0 / kResolution, plane_y = -1.0 + (kRow + 0.5) * v0;
  const double th = theta_deg * kPi / 180.0;
  const glm::dvec3 dir(-std::sin(th), -std::cos(th), 0.0);
  double sum = 0.0;
  int n = 0;
  for (double h : {1.5, 2.3, 3.7, 5.1, 7.9, 11.3})
    for (double x : {-0.31, -0.17, 0.05}) {
      const glm::dvec3 origin(x, plane_y + h * v0, 0.1);
      if (!march.coarse) {
        sum += trace(c, origin, dir, march).w;
        ++n;
        continue;
      }
      for (double u_pos : {0.1, 0.3, 0.5, 0.7, 0.9})
        for (double u_level : {0.1, 0.4, 0.6, 0.9}) {
          March m = march;
          m.position_jitter = u_pos;
          m.jitter = u_level;
          sum += trace(c, origin, dir, m).w;
          ++n;
        }
    }
  return sum / n;
}

}  // namespace

int main() {
  const Chain c = surface_chain();
  March fine, half, coarse;
  fine.fine = true;
  coarse.coarse = true;
  std::printf("| theta (deg) | quarter-diameter steps | half-diameter | coarse (fast mode) |\n");
  std::printf("|---|---|---|---|\n");
  for (double theta : {0.0, 20.0, 35.0, 50.0, 60.0, 70.0, 80.0})
    std::printf("| %.0f | %.3f | %.3f | %.3f |\n", theta, mean_opacity(c, theta, fine),
                mean_opacity(c, theta, half), mean_opacity(c, theta, coarse));
  return 0;
}
