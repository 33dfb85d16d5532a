/* Layout of the shadow map's mip chain (kernels/shadow_filter.cl), shared by host and kernels.
 *
 * The shadow map is size x size depths (z_ndc * 0.5 + 0.5, 1.0 = empty). Its mips hold LINEAR
 * light depth z (clip w: distance along the lamp's axis, world units; an empty texel counts as
 * the far plane): level l >= 1 has n_l = ceil(n_{l-1} / 2) texels per side (n_0 = size), texel
 * (i, j) of level l covering level-0 texels [i 2^l, (i + 1) 2^l) x [j 2^l, (j + 1) 2^l) (edge
 * texels of odd sizes repeat their last row / column). Levels 1 .. RP_SHADOW_MIP_LEVELS, fewer
 * when the map runs out (n_l == 1 is the last).
 *
 * One float buffer, planar: plane c (RP_SHADOW_MIP_MIN, _MEAN, _MEAN2) of every level back to
 * back, plane c at c * rp_shadow_mip_total(size); inside a plane, level l at
 * rp_shadow_mip_offset(size, l), rows top to bottom like the map, x fastest.
 *   MIN:   min z over the texel's footprint (PCSS: a conservative "no blocker here" test)
 *   MEAN:  mean z, MEAN2: mean z^2 (VSSM: the depth moments)
 * PCSS builds the MIN plane only (the buffer then holds one plane).
 */
#ifndef ROLYPOLY_SHARED_SHADOW_MIPS_H
#define ROLYPOLY_SHARED_SHADOW_MIPS_H

/* Most levels: 2^7 = 128 level-0 texels per texel. The light pass's lookups stay below: PCSS
 * reads at most 4x4 texels at the first level a third of its box wide (boxes <= 2 x 64 texels
 * plus the 8 lanes' spread), VSSM a level under its disk's width (<= 128 texels). Each level
 * is a launch (~20-30 us on PoCL), so the chain stops there rather than at 1x1. */
#define RP_SHADOW_MIP_LEVELS 7
#define RP_SHADOW_MIP_MIN 0
#define RP_SHADOW_MIP_MEAN 1
#define RP_SHADOW_MIP_MEAN2 2

#ifdef __OPENCL_VERSION__
#define RP_SMIP_FN static inline
#define RP_SMIP_UINT uint
#else
#include <cstdint>
#define RP_SMIP_FN inline
#define RP_SMIP_UINT uint32_t
namespace rp::gpu {
#endif

/* Texels per side at level l (l = 0: the map itself). */
RP_SMIP_FN RP_SMIP_UINT rp_shadow_mip_size(RP_SMIP_UINT size, RP_SMIP_UINT level) {
  RP_SMIP_UINT n = size;
  for (RP_SMIP_UINT l = 0u; l < level; ++l) n = (n + 1u) / 2u;
  return n;
}

/* Levels the chain has (0 for a 1x1 map). */
RP_SMIP_FN RP_SMIP_UINT rp_shadow_mip_levels(RP_SMIP_UINT size) {
  RP_SMIP_UINT levels = 0u;
  for (RP_SMIP_UINT n = size; n > 1u && levels < RP_SHADOW_MIP_LEVELS; n = (n + 1u) / 2u)
    ++levels;
  return levels;
}

/* First texel of level l (1 .. levels) inside a plane. */
RP_SMIP_FN RP_SMIP_UINT rp_shadow_mip_offset(RP_SMIP_UINT size, RP_SMIP_UINT level) {
  RP_SMIP_UINT offset = 0u;
  for (RP_SMIP_UINT l = 1u; l < level; ++l) {
    const RP_SMIP_UINT n = rp_shadow_mip_size(size, l);
    offset += n * n;
  }
  return offset;
}

/* Texels of one plane (all levels). */
RP_SMIP_FN RP_SMIP_UINT rp_shadow_mip_total(RP_SMIP_UINT size) {
  return rp_shadow_mip_offset(size, rp_shadow_mip_levels(size) + 1u);
}

#ifndef __OPENCL_VERSION__
}  // namespace rp::gpu
#endif
#undef RP_SMIP_FN
#undef RP_SMIP_UINT
#endif
