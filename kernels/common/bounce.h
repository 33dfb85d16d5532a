/* The bounce grid (several bounces): the indirect light the voxels receive, so that
 * the voxelizer can add it to their radiance and the cones gather light that has bounced more
 * than once. Written by kernels/bounce.cl, read by kernels/voxelize.cl (OpenCL C only).
 *
 * Layout: G^3 cells over the box [-1,1]^3 (G = rp_bounce_cells(R): 32 from R = 64 up), cell
 * (i, j, k) centred at -1 + (i + 0.5) 2 / G, x fastest; per cell six float4 "faces" in the
 * order +x, -x, +y, -y, +z, -z (RP_DIR_*): face d holds, for a surface whose normal is d,
 * rgb = irradiance / pi arriving from the hemisphere around d at the cell's centre (the mean
 * of the 16-cone diffuse set, the same quantity the light pass multiplies by the albedo),
 * w = the face's age in gathers (0: nothing gathered, the face does not count).
 * Memory: G^3 * 6 * 16 bytes = 3 MiB for G = 32 (393 KiB for G = 16).
 *
 * Why 32: a cell gathers at its centre, so where a cell holds a thin wall its light on one side
 * reaches the voxels on the other. 16^3 cells over the yard under studio.exr (softboxes behind
 * its walls) made its many-bounce light 1.8x the truth's (indirect L1 19.9 %, bias +14.4 %);
 * 32^3: 14.0 %, +2.6 % (bench/results/zen5-2core-pocl-sky-prt-4096.md).
 *
 * Lookup at surface point p with unit normal n (rp_bounce_irradiance): trilinear over the 8
 * cells around p (clamped to the grid) and, per cell, the three faces facing n blended with
 * weights n.x^2, n.y^2, n.z^2 (an "ambient cube"); faces with age 0 (cells without surfaces,
 * which the gather skips) are left out and the remaining weights renormalised.
 */
#ifndef ROLYPOLY_COMMON_BOUNCE_H
#define ROLYPOLY_COMMON_BOUNCE_H

#include "shared/voxel_layout.h"

#define RP_BOUNCE_MAX_CELLS 32u

/* Cells per side for a voxel volume of R voxels per side: R up to 16, 16 up to R = 32, then
 * R / 2 up to 32 (src/passes/bounce.h: BouncePass::cells). */
inline uint rp_bounce_cells(uint resolution) {
  return resolution <= 32u ? min(resolution, 16u) : min(resolution / 2u, RP_BOUNCE_MAX_CELLS);
}

/* irradiance / pi at p for unit normal n (see the header); 0 where no face has been gathered. */
inline float3 rp_bounce_irradiance(__global const float4* bounce, uint cells, float3 p,
                                   float3 n) {
  const float gf = (float)cells;
  const float3 g = clamp((p + 1.0f) * (0.5f * gf) - 0.5f, 0.0f, gf - 1.0f);
  const float3 fl = floor(g);
  const float3 f = g - fl;
  const uint x0 = (uint)fl.x, y0 = (uint)fl.y, z0 = (uint)fl.z;
  const uint x1 = min(x0 + 1u, cells - 1u), y1 = min(y0 + 1u, cells - 1u);
  const uint z1 = min(z0 + 1u, cells - 1u);
  const uint fx = n.x >= 0.0f ? RP_DIR_POS_X : RP_DIR_NEG_X;
  const uint fy = n.y >= 0.0f ? RP_DIR_POS_Y : RP_DIR_NEG_Y;
  const uint fz = n.z >= 0.0f ? RP_DIR_POS_Z : RP_DIR_NEG_Z;
  const float3 w = n * n;
  float3 sum = (float3)(0.0f);
  float weight = 0.0f;
  for (uint c = 0; c < 8u; ++c) {
    const uint x = (c & 1u) ? x1 : x0, y = (c & 2u) ? y1 : y0, z = (c & 4u) ? z1 : z0;
    const float wc = ((c & 1u) ? f.x : 1.0f - f.x) * ((c & 2u) ? f.y : 1.0f - f.y) *
                     ((c & 4u) ? f.z : 1.0f - f.z);
    if (wc <= 0.0f) continue;
    __global const float4* cell = bounce + 6u * ((z * cells + y) * cells + x);
    /* faces with weight 0 are not loaded (a wall's normal reads one face) */
    if (w.x > 0.0f) {
      const float4 e = cell[fx];
      const float v = e.w > 0.0f ? wc * w.x : 0.0f;
      sum += v * e.xyz;
      weight += v;
    }
    if (w.y > 0.0f) {
      const float4 e = cell[fy];
      const float v = e.w > 0.0f ? wc * w.y : 0.0f;
      sum += v * e.xyz;
      weight += v;
    }
    if (w.z > 0.0f) {
      const float4 e = cell[fz];
      const float v = e.w > 0.0f ? wc * w.z : 0.0f;
      sum += v * e.xyz;
      weight += v;
    }
  }
  return weight > 0.0f ? sum / weight : (float3)(0.0f);
}

/* Mean irradiance / pi over the six faces of the cell containing p (faces not gathered left
 * out): what a particle smaller than a voxel receives on average over its surface. 6 loads. */
inline float3 rp_bounce_mean(__global const float4* bounce, uint cells, float3 p) {
  const float gf = (float)cells;
  const float3 g = clamp(floor((p + 1.0f) * (0.5f * gf)), 0.0f, gf - 1.0f);
  __global const float4* cell =
      bounce + 6u * (((uint)g.z * cells + (uint)g.y) * cells + (uint)g.x);
  float3 sum = (float3)(0.0f);
  float count = 0.0f;
  for (uint f = 0; f < 6u; ++f) {
    const float4 e = cell[f];
    if (e.w > 0.0f) {
      sum += e.xyz;
      count += 1.0f;
    }
  }
  return count > 0.0f ? sum / count : (float3)(0.0f);
}

#endif
