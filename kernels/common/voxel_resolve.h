/* The voxelizer's resolve rule, shared by the dense volume (kernels/voxelize.cl,
 * voxelize_resolve) and the octree's leaves (kernels/svo.cl, svo_leaves), so that both give a
 * voxel the same value bit for bit. OpenCL C only; needs -DRP_VOXEL_FIXED_BITS and
 * -DRP_VOXEL_SATURATED (shared/voxel_layout.h's host constants).
 *
 * sums: the voxel's fixed-point sums of (L.rgb * a, a) (2^RP_VOXEL_FIXED_BITS per unit);
 * overflow: bit c set when channel c wrapped past 2^32 (then it reads RP_VOXEL_SATURATED).
 * Returns (S.rgb / max(S.a, 1), min(S.a, 1)), S = sums / 2^bits: the opacity-weighted mean
 * radiance times the clamped opacity (premultiplied). */
#ifndef ROLYPOLY_COMMON_VOXEL_RESOLVE_H
#define ROLYPOLY_COMMON_VOXEL_RESOLVE_H

inline float4 rp_voxel_resolve(uint4 sums, uint overflow) {
  float4 sum = convert_float4(sums) * (1.0f / (float)(1u << RP_VOXEL_FIXED_BITS));
  if (overflow != 0u) {
    if (overflow & 1u) sum.x = RP_VOXEL_SATURATED;
    if (overflow & 2u) sum.y = RP_VOXEL_SATURATED;
    if (overflow & 4u) sum.z = RP_VOXEL_SATURATED;
    if (overflow & 8u) sum.w = RP_VOXEL_SATURATED;
  }
  const float inv = 1.0f / fmax(sum.w, 1.0f);
  return (float4)(sum.xyz * inv, fmin(sum.w, 1.0f));
}

#endif
