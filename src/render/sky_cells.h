// The diffuse cones' sky (kernels/common/sky.h: rp_sky_cells): each of the 16 diffuse cones
// (kernels/common/cone_trace.h: rp_cone_set16_dir) stands for one cell of the cosine-weighted
// hemisphere, 1/16 of the irradiance, so what it passes on of the sky must be the map averaged
// over that cell with weight cos theta, not the map prefiltered around its axis: a 45-degree
// wide filter around a cone of the outer ring reads bright patches that lie near the horizon
// (cosine 0.02-0.07) with the ring's cosine (0.56), and the map's lower half across the horizon.
// Measured by a host emulation of the 16 prefiltered lookups on studio.exr's residual: 1.96x
// the exact irradiance for an upward normal (bench/results/zen5-2core-pocl-cone-thin-surfaces.md).
//
// The table depends on the normal only through the cells, so it is made once per map for an
// octahedral grid of normals in the map's frame (kernels/shared/types.h: RP_SKY_CELL_SIDE);
// the kernels build the cones' basis in the map's frame too (rp_cone_sky_basis), so a turn of
// the environment reads the same table, and interpolate it between the four grid normals
// around theirs (that basis is continuous, so neighbouring normals have neighbouring cells).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "render/gpu_types.h"

namespace rp::render {

// An equirectangular map (rows top to bottom, u = atan2(x, -z) / 2 pi, v = acos(y) / pi, as the
// path tracer's EnvironmentSampler reads it): width x height rgb triples.
struct SkyCellSource {
  int width = 0, height = 0;
  const double* rgb = nullptr;
};

// Unit normal of grid point (i, j) of the side x side octahedral grid (types.h).
glm::dvec3 sky_cell_normal(int i, int j, int side = int(RP_SKY_CELL_SIDE));

// The axis of the cones' basis (kernels/common/sky.h: RP_SKY_BASIS_AXIS).
inline constexpr glm::vec3 kSkyBasisAxis(0.36f, 0.48f, 0.8f);

// The cones' basis of unit n in the map's frame (kernels/common/cone_trace.h:
// rp_cone_sky_basis): t = normalize(axis x n), b = n x t.
void sky_cell_basis(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b);

// The cone (0..15) whose cell holds the direction with local coordinates (x along t, y along
// b, z along n; unit length), -1 below the horizon (z <= 0): cone 0 for sin^2 theta < 1/16, the
// inner ring 1..5 (sin^2 < 6/16) by 72-degree sectors centred on 0, 72, .. degrees of azimuth,
// the outer ring 6..15 by 36-degree sectors centred on 18, 54, .. degrees.
int sky_cone_cell(const glm::dvec3& local);

// The table: side^2 x 16 texels, texel (j * side + i) * 16 + k the map's radiance averaged over
// cone k's cell around grid normal (i, j), weighted by cos theta and each texel's solid angle
// (texel centres decide the cell; a cell no texel centre falls in takes the texel at its cone's
// axis), the 16 then scaled together so that their mean is the hemisphere's cosine-weighted mean.
std::vector<gpu::rp_float4> sky_cell_table(const SkyCellSource& map,
                                           int side = int(RP_SKY_CELL_SIDE));

}  // namespace rp::render
