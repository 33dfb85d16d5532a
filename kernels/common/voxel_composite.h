/* The anisotropic mip step on one parent voxel (OpenCL C only), shared by the dense chain
 * (voxel_mips.cl) and the sparse voxel octree (svo.cl) so both compute a parent from its
 * children with the same operations in the same order (the octree's tests compare the two
 * bit for bit). Conventions: common/voxel.h; the rule: voxel_mips.cl's header. Include it
 * after `#pragma OPENCL FP_CONTRACT OFF`.
 */
#ifndef ROLYPOLY_COMMON_VOXEL_COMPOSITE_H
#define ROLYPOLY_COMMON_VOXEL_COMPOSITE_H

#include "shared/voxel_layout.h"

/* Level-0 voxel `iso` (isotropic) as a cone travelling along `dir` sees it, from its facing
 * coverage words (x, y, z: shared/voxel_layout.h): opacity c = the coverage of what faces the
 * cone (at most iso.a), radiance the voxel's mean radiance times c. A wall's voxels thus exist
 * only for cones that look at the wall's front: cones leaving the wall pass through them. */
inline float4 mips_facing(float4 iso, uint4 facing, uint dir) {
  const uint axis = dir >> 1;
  const uint word = axis == 0u ? facing.x : (axis == 1u ? facing.y : facing.z);
  const uint half_sum = (dir & 1u) == 0u ? word >> 16 : word & 0xFFFFu; /* +dir sees -facing */
  const float c = fmin(fmin((float)half_sum * (1.0f / RP_VOXEL_FACING_UNIT), 1.0f), iso.w);
  return iso.w > 0.0f ? (float4)(iso.xyz * (c / iso.w), c) : (float4)(0.0f);
}

/* The parent value seen along direction `dir` (see the header). */
inline float4 mips_composite(const float4 c[8], uint dir) {
  const uint axis = dir >> 1;          /* RP_DIR_POS_X, NEG_X = 0, 1; Y: 2, 3; Z: 4, 5 */
  const uint step = 1u << axis;        /* child index step along the axis */
  const bool positive = (dir & 1u) == 0u;
  float4 col[4];
  uint k = 0;
  for (uint i = 0; i < 8u; ++i) {
    if ((i & step) != 0u) continue;    /* i: a low-A child, one per column, ascending */
    const float4 lo = c[i], hi = c[i + step];
    const float4 f = positive ? lo : hi;
    const float4 b = positive ? hi : lo;
    col[k++] = f + (1.0f - f.w) * b;
  }
  return ((col[0] + col[1]) + (col[2] + col[3])) * 0.25f;
}

#endif
