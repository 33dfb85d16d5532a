/* Voxel mips pass (SPEC 6.4): the anisotropic mip chain of the radiance volume. Host side:
 * src/passes/voxel_mips.cpp. Layout: shared/voxel_layout.h; direction convention:
 * common/voxel.h.
 *
 * voxel_mips_build runs once per level l = 1 .. levels-1, in order, one work-item per voxel of
 * level l (n = R >> l per side), and writes that voxel in all six directional volumes. Its
 * 2x2x2 children at level l-1 are read from the isotropic level 0 when l = 1, else from the
 * SAME direction's volume at level l-1.
 *
 * For direction d along axis A, the children form two slabs across A. The FRONT slab is the
 * one a cone travelling along d enters first: the low-A children (index bit 0 along A) for
 * +x/+y/+z, the high-A children for -x/-y/-z. For each of the four columns along A
 * (front child f, back child b, premultiplied float4s):
 *     column = f + (1 - f.a) * b          (rgb and a alike: front-to-back "over")
 * and the voxel is the mean of the four columns, summed in a fixed order:
 *     ((col0 + col1) + (col2 + col3)) * 0.25
 * with columns numbered by the child index (x + 2y + 4z) of their low-A child, ascending.
 * So an opaque front child hides its back child for d but not for -d.
 *
 * FP contraction is off: tests/passes/voxel_mips_test.cpp repeats this operation for operation.
 */
#pragma OPENCL FP_CONTRACT OFF

#include "shared/voxel_layout.h"
#include "common/voxel.h"

/* The 8 children of parent voxel p in the volume at `base` (child_n per side), child index
 * i = x + 2y + 4z. */
inline void mips_load_children(__global const float4* chain, uint base, uint child_n, int3 p,
                               float4 c[8]) {
  const uint x0 = 2u * (uint)p.x, y0 = 2u * (uint)p.y, z0 = 2u * (uint)p.z;
  for (uint i = 0; i < 8u; ++i) {
    const uint x = x0 + (i & 1u), y = y0 + ((i >> 1) & 1u), z = z0 + (i >> 2);
    c[i] = chain[base + (z * child_n + y) * child_n + x];
  }
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

__kernel void voxel_mips_build(__global float4* chain, uint resolution, uint level) {
  const uint n = rp_voxel_level_size(resolution, level);
  const uint gid = (uint)get_global_id(0);
  if (level == 0u || n == 0u || gid >= n * n * n) return;
  const int3 p = (int3)((int)(gid % n), (int)((gid / n) % n), (int)(gid / (n * n)));
  const uint child_n = 2u * n;
  const uint dst = rp_voxel_index(p, n);

  float4 c[8];
  if (level == 1u) { /* all directions from the isotropic level 0: load once */
    mips_load_children(chain, rp_voxel_offset(resolution, 0u, 0u), child_n, p, c);
    for (uint dir = 0; dir < 6u; ++dir)
      chain[rp_voxel_offset(resolution, 1u, dir) + dst] = mips_composite(c, dir);
  } else {
    for (uint dir = 0; dir < 6u; ++dir) {
      mips_load_children(chain, rp_voxel_offset(resolution, level - 1u, dir), child_n, p, c);
      chain[rp_voxel_offset(resolution, level, dir) + dst] = mips_composite(c, dir);
    }
  }
}
