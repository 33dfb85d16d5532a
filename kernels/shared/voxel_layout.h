/* Layout of the voxel radiance volume and its anisotropic mip chain, shared by host and kernels.
 *
 * The volume covers the box [-1,1]^3. Level 0 has R = voxel_resolution voxels per side; level l
 * has n_l = R >> l per side, down to 1 (levels = log2(R) + 1).
 *
 * One float4 buffer holds everything, back to back:
 *   level 0:        one isotropic volume of R^3 voxels
 *   level l >= 1:   six directional volumes of n_l^3 voxels each, in direction order
 *                   +x, -x, +y, -y, +z, -z (RP_DIR_*): volume d of level l holds what a cone
 *                   travelling along direction d sees when it looks through that region.
 * Inside a volume voxels are x fastest: index = (z * n + y) * n + x, voxel (0,0,0) at the
 * corner (-1,-1,-1).
 * A voxel is float4: rgb = radiance premultiplied by opacity, a = opacity in [0,1].
 */
#ifndef ROLYPOLY_SHARED_VOXEL_LAYOUT_H
#define ROLYPOLY_SHARED_VOXEL_LAYOUT_H

#define RP_DIR_POS_X 0u
#define RP_DIR_NEG_X 1u
#define RP_DIR_POS_Y 2u
#define RP_DIR_NEG_Y 3u
#define RP_DIR_POS_Z 4u
#define RP_DIR_NEG_Z 5u

/* Facing coverage (the voxelizer's scratch `accum`, 8 uints per level-0 voxel): words 0-3 the
 * fixed-point radiance and opacity sums, words 4, 5, 6 the facing coverage along x, y, z, word
 * 7 unused. A word's low 16 bits sum what faces the + direction of its axis (surfaces with
 * n_i > 0), the high 16 bits what faces the - direction; each surface adds
 * round(a |n_i| / max_j |n_j| * RP_VOXEL_FACING_UNIT) (a plane crossing the voxel covers its
 * projection onto the face across axis i by that fraction), a sphere round(a * UNIT) to both
 * halves of every axis. A cone travelling along +x sees what faces -x: its coverage is
 * min(high half / UNIT, 1). A half holds 511 full contributions before it would carry into its
 * neighbour (the demo's voxels hold a few dozen). */
#define RP_VOXEL_ACCUM_WORDS 8u
#define RP_VOXEL_FACING_UNIT 128.0f

#ifdef __OPENCL_VERSION__
#define RP_VOXEL_FN static inline
#define RP_VOXEL_UINT uint
#else
#include <cstdint>
#define RP_VOXEL_FN inline
#define RP_VOXEL_UINT uint32_t
namespace rp::gpu {
#endif

/* Voxels per side at `level`. */
RP_VOXEL_FN RP_VOXEL_UINT rp_voxel_level_size(RP_VOXEL_UINT resolution, RP_VOXEL_UINT level) {
  return resolution >> level;
}

/* First voxel (in float4 elements) of direction `dir` at `level` (dir ignored for level 0). */
RP_VOXEL_FN RP_VOXEL_UINT rp_voxel_offset(RP_VOXEL_UINT resolution, RP_VOXEL_UINT level,
                                          RP_VOXEL_UINT dir) {
  if (level == 0u) return 0u;
  RP_VOXEL_UINT offset = resolution * resolution * resolution;
  for (RP_VOXEL_UINT l = 1u; l < level; ++l) {
    RP_VOXEL_UINT n = resolution >> l;
    offset += 6u * n * n * n;
  }
  RP_VOXEL_UINT n = resolution >> level;
  return offset + dir * n * n * n;
}

/* Total float4 elements for a chain with `levels` levels. */
RP_VOXEL_FN RP_VOXEL_UINT rp_voxel_total(RP_VOXEL_UINT resolution, RP_VOXEL_UINT levels) {
  return rp_voxel_offset(resolution, levels, 0u);
}

#ifndef __OPENCL_VERSION__
}  // namespace rp::gpu
#endif
#undef RP_VOXEL_FN
#undef RP_VOXEL_UINT
#endif
