/* Voxel volume helpers (OpenCL C only) for everything that reads or writes the radiance volume:
 * the voxelizer (voxelize.cl), the mip builder (voxel_mips.cl) and the cone tracer. The memory
 * layout itself (levels, the six directional volumes, x-fastest indexing) is defined once in
 * shared/voxel_layout.h; this header adds coordinate transforms and the direction convention.
 *
 * Coordinates
 *   world:  the volume covers the box [-1,1]^3 (shared/types.h).
 *   grid:   continuous level-0 voxel units, g = (p + 1) * R / 2 with R = voxel_resolution, so
 *           level-0 voxel (i,j,k) is the closed box [i,i+1] x [j,j+1] x [k,k+1] and its centre
 *           is (i,j,k) + 0.5. At level l a voxel spans 2^l grid units: voxel (i,j,k) of level l
 *           covers [i * 2^l, (i+1) * 2^l] along x, etc.
 *   A level-0 voxel is 2 / R world units wide; a level-l voxel 2^(l+1) / R.
 *
 * Voxel contents (every level, every direction): float4, rgb = radiance premultiplied by
 * opacity (linear, the same units as the light pass's HDR output), a = opacity in [0,1].
 * Level 0 is isotropic: opacity is coverage (1 where an opaque triangle touches the voxel,
 * the projected-area fraction for spheres: see voxelize.cl), rgb the opacity-weighted mean of
 * the outgoing radiance of what touches it (direct light with one shadow-map lookup times
 * albedo, plus emission) times that opacity.
 *
 * Direction convention (the six volumes of each level >= 1, RP_DIR_* in shared/voxel_layout.h)
 *   Volume RP_DIR_POS_X holds what a cone TRAVELLING towards +x sees through that region: the
 *   radiance arriving at the region's +x face from inside it, with the region's opacity along
 *   x. Such a cone enters each voxel through its low-x face, so when a level-l voxel is built
 *   from its 2x2x2 children, the FRONT slab (composited over the other) is:
 *       +x: the low-x children (x even)     -x: the high-x children (x odd)
 *       +y: the low-y children (y even)     -y: the high-y children (y odd)
 *       +z: the low-z children (z even)     -z: the high-z children (z odd)
 *   i.e. for direction d the front slab is the one a ray moving along d reaches first.
 *   A cone tracer with unit direction d therefore samples, for each axis, the volume facing
 *   the cone: d.x >= 0 ? RP_DIR_POS_X : RP_DIR_NEG_X (likewise y, z; rp_voxel_cone_dirs), and
 *   blends the three with weights d.x^2, d.y^2, d.z^2 (they sum to 1 for a unit d). Level 0
 *   is the same for all directions.
 *
 * Outside [-1,1]^3 the volume is empty (rp_voxel_fetch returns 0 there).
 */
#ifndef ROLYPOLY_COMMON_VOXEL_H
#define ROLYPOLY_COMMON_VOXEL_H

#include "shared/voxel_layout.h"

/* World position -> continuous level-0 grid coordinates (see the header). */
inline float3 rp_voxel_world_to_grid(float3 p, uint resolution) {
  return (p + 1.0f) * (0.5f * (float)resolution);
}

/* Continuous level-0 grid coordinates -> world position. */
inline float3 rp_voxel_grid_to_world(float3 g, uint resolution) {
  return g * (2.0f / (float)resolution) - 1.0f;
}

/* World-space centre of level-0 voxel v. */
inline float3 rp_voxel_center_world(int3 v, uint resolution) {
  return rp_voxel_grid_to_world(convert_float3(v) + 0.5f, resolution);
}

/* Width of one voxel of `level` in world units. */
inline float rp_voxel_size_world(uint resolution, uint level) {
  return (float)(2u << level) / (float)resolution;
}

/* Element index of voxel v inside one volume of n^3 voxels (x fastest), no bounds check. */
inline uint rp_voxel_index(int3 v, uint n) {
  return ((uint)v.z * n + (uint)v.y) * n + (uint)v.x;
}

/* The three directional volumes a cone travelling along d samples (x, y, z components), with
 * weights d.x^2, d.y^2, d.z^2 (see the header). */
inline uint3 rp_voxel_cone_dirs(float3 d) {
  return (uint3)(d.x >= 0.0f ? RP_DIR_POS_X : RP_DIR_NEG_X,
                 d.y >= 0.0f ? RP_DIR_POS_Y : RP_DIR_NEG_Y,
                 d.z >= 0.0f ? RP_DIR_POS_Z : RP_DIR_NEG_Z);
}

/* Voxel v of volume `dir` at `level` of the chain (dir is ignored at level 0); zero (empty,
 * transparent) outside the volume. */
inline float4 rp_voxel_fetch(__global const float4* chain, uint resolution, uint level, uint dir,
                             int3 v) {
  const int n = (int)rp_voxel_level_size(resolution, level);
  if (v.x < 0 || v.y < 0 || v.z < 0 || v.x >= n || v.y >= n || v.z >= n) return (float4)(0.0f);
  return chain[rp_voxel_offset(resolution, level, dir) + rp_voxel_index(v, (uint)n)];
}

#endif
