/* Voxel mips pass (SPEC 6.4): the anisotropic mip chain of the radiance volume. Host side:
 * src/passes/voxel_mips.cpp. Layout: shared/voxel_layout.h; direction convention:
 * common/voxel.h.
 *
 * voxel_mips_build runs once per level l = 1 .. levels-1, in order, one work-item per voxel of
 * level l (n = R >> l per side), and writes that voxel in all six directional volumes. Its
 * 2x2x2 children at level l-1 are read from the SAME direction's volume at level l-1; for
 * l = 1 from the isotropic level 0 as a cone travelling along that direction sees it
 * (mips_facing: the voxelizer's facing coverage, shared/voxel_layout.h, makes each voxel
 * one-sided: opacity = the coverage of what faces the cone, radiance scaled alike), so a wall
 * is opaque to cones that look at its front and transparent to cones leaving it (a
 * cone never gathers the light of the surface it starts from).
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
 *
 * Built with -DRP_SPAN=16 (CPUs, levels with at least 16 voxels per side) a work-item computes
 * 16 neighbouring parents along x at once: each row of 32 children is loaded as float16s and
 * split into planar channels of the even and odd children, and the same compositing runs on
 * float16 lanes (the same operations per lane, so the same results); level 1's facing words
 * come from whole rows of the voxelizer's scratch, transposed by shuffles (16 words 32 bytes
 * apart gathered per load instead cost the busy 720x720 frame's voxel_mips at scale 0.5 1.81 /
 * 1.71 / 1.71 against 1.55 / 1.52 / 1.48 ms). RP_SPAN = 1: one parent per work-item.
 */
#pragma OPENCL FP_CONTRACT OFF

#include "shared/types.h"
#include "shared/pass_params.h"
#include "shared/voxel_layout.h"
#include "common/voxel.h"
#include "common/voxel_composite.h"

#ifndef RP_SPAN
#define RP_SPAN 1
#endif
#if RP_SPAN != 1 && RP_SPAN != 16
#error "voxel_mips.cl: RP_SPAN must be 1 or 16"
#endif

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

/* Level 1 voxel p in all six directions from level 0 (isotropic values and facing coverage;
 * accum: the voxelizer's scratch, RP_VOXEL_ACCUM_WORDS uints per voxel, facing in words 4-6). */
inline void mips_build_level1(__global float4* chain, __global const uint4* accum,
                              uint resolution, int3 p) {
  const uint n = resolution >> 1, child_n = resolution;
  float4 iso[8];
  uint4 facing[8];
  mips_load_children(chain, 0u, child_n, p, iso);
  const uint x0 = 2u * (uint)p.x, y0 = 2u * (uint)p.y, z0 = 2u * (uint)p.z;
  for (uint i = 0; i < 8u; ++i) {
    const uint x = x0 + (i & 1u), y = y0 + ((i >> 1) & 1u), z = z0 + (i >> 2);
    facing[i] = accum[(RP_VOXEL_ACCUM_WORDS / 4u) * ((z * child_n + y) * child_n + x) + 1u];
  }
  const uint dst = rp_voxel_index(p, n);
  for (uint dir = 0; dir < 6u; ++dir) {
    float4 c[8];
    for (uint i = 0; i < 8u; ++i) c[i] = mips_facing(iso[i], facing[i], dir);
    chain[rp_voxel_offset(resolution, 1u, dir) + dst] = mips_composite(c, dir);
  }
}

#if RP_SPAN == 16

/* Planar channels of 16 voxels. */
typedef struct {
  float16 r, g, b, a;
} MipsLanes;

/* 4 interleaved float4 voxels per float16 (E[m]: voxels 4m..4m+3) -> planar channels. */
inline MipsLanes mips_planar(const float16 E[4]) {
  const uint16 rg = (uint16)(0, 4, 8, 12, 16, 20, 24, 28, 1, 5, 9, 13, 17, 21, 25, 29);
  const uint16 ba = (uint16)(2, 6, 10, 14, 18, 22, 26, 30, 3, 7, 11, 15, 19, 23, 27, 31);
  const uint16 lo = (uint16)(0, 1, 2, 3, 4, 5, 6, 7, 16, 17, 18, 19, 20, 21, 22, 23);
  const uint16 hi = (uint16)(8, 9, 10, 11, 12, 13, 14, 15, 24, 25, 26, 27, 28, 29, 30, 31);
  const float16 rg_a = shuffle2(E[0], E[1], rg), ba_a = shuffle2(E[0], E[1], ba);
  const float16 rg_b = shuffle2(E[2], E[3], rg), ba_b = shuffle2(E[2], E[3], ba);
  MipsLanes out;
  out.r = shuffle2(rg_a, rg_b, lo);
  out.g = shuffle2(rg_a, rg_b, hi);
  out.b = shuffle2(ba_a, ba_b, lo);
  out.a = shuffle2(ba_a, ba_b, hi);
  return out;
}

/* The 32 children starting at `first` (one row along x) -> channels of the even-x children
 * (the parents' low-x children) and of the odd-x ones. */
inline void mips_load_row(__global const float4* chain, uint first, MipsLanes* even,
                          MipsLanes* odd) {
  const uint16 ev = (uint16)(0, 1, 2, 3, 8, 9, 10, 11, 16, 17, 18, 19, 24, 25, 26, 27);
  const uint16 od = (uint16)(4, 5, 6, 7, 12, 13, 14, 15, 20, 21, 22, 23, 28, 29, 30, 31);
  __global const float* f = (__global const float*)(chain + first);
  float16 E[4], O[4];
  for (int m = 0; m < 4; ++m) {
    const float16 a = vload16(2 * m, f), b = vload16(2 * m + 1, f);
    E[m] = shuffle2(a, b, ev);
    O[m] = shuffle2(a, b, od);
  }
  *even = mips_planar(E);
  *odd = mips_planar(O);
}

/* The 8 children (index x + 2y + 4z) of parents (p.x .. p.x + 15, p.y, p.z) in the volume at
 * `base` (child_n per side). */
inline void mips_load_children16(__global const float4* chain, uint base, uint child_n, int3 p,
                                 MipsLanes c[8]) {
  for (uint yz = 0; yz < 4u; ++yz) {
    const uint y = 2u * (uint)p.y + (yz & 1u), z = 2u * (uint)p.z + (yz >> 1);
    mips_load_row(chain, base + (z * child_n + y) * child_n + 2u * (uint)p.x, &c[2u * yz],
                  &c[2u * yz + 1u]);
  }
}

/* f + (1 - f.a) b per channel. */
inline MipsLanes mips_over16(MipsLanes f, MipsLanes b) {
  const float16 t = 1.0f - f.a;
  MipsLanes r;
  r.r = f.r + t * b.r;
  r.g = f.g + t * b.g;
  r.b = f.b + t * b.b;
  r.a = f.a + t * b.a;
  return r;
}

/* mips_composite on 16 lanes. */
inline MipsLanes mips_composite16(const MipsLanes c[8], uint dir) {
  const uint step = 1u << (dir >> 1);
  const bool positive = (dir & 1u) == 0u;
  MipsLanes col[4];
  uint k = 0;
  for (uint i = 0; i < 8u; ++i) {
    if ((i & step) != 0u) continue;
    col[k++] = positive ? mips_over16(c[i], c[i + step]) : mips_over16(c[i + step], c[i]);
  }
  MipsLanes r;
  r.r = ((col[0].r + col[1].r) + (col[2].r + col[3].r)) * 0.25f;
  r.g = ((col[0].g + col[1].g) + (col[2].g + col[3].g)) * 0.25f;
  r.b = ((col[0].b + col[1].b) + (col[2].b + col[3].b)) * 0.25f;
  r.a = ((col[0].a + col[1].a) + (col[2].a + col[3].a)) * 0.25f;
  return r;
}

inline void mips_store16(__global float4* chain, uint at, MipsLanes v) {
  const uint16 zip_lo = (uint16)(0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23);
  const uint16 zip_hi = (uint16)(8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15, 31);
  const uint16 zip2_lo = (uint16)(0, 1, 16, 17, 2, 3, 18, 19, 4, 5, 20, 21, 6, 7, 22, 23);
  const uint16 zip2_hi = (uint16)(8, 9, 24, 25, 10, 11, 26, 27, 12, 13, 28, 29, 14, 15, 30, 31);
  const float16 rg_lo = shuffle2(v.r, v.g, zip_lo), rg_hi = shuffle2(v.r, v.g, zip_hi);
  const float16 ba_lo = shuffle2(v.b, v.a, zip_lo), ba_hi = shuffle2(v.b, v.a, zip_hi);
  __global float* f = (__global float*)(chain + at);
  vstore16(shuffle2(rg_lo, ba_lo, zip2_lo), 0, f);
  vstore16(shuffle2(rg_lo, ba_lo, zip2_hi), 1, f);
  vstore16(shuffle2(rg_hi, ba_hi, zip2_lo), 2, f);
  vstore16(shuffle2(rg_hi, ba_hi, zip2_hi), 3, f);
}

/* The facing words of the children in one row (y, z) of parents (p.x .. p.x + 15, p.y, p.z):
 * out[2 axis + parity] lane k = word 4 + axis of child x = 2 (p.x + k) + parity. The row's 32
 * voxels (RP_VOXEL_ACCUM_WORDS = 8 words each, from voxel `first`) load as 16 uint16 (voxels
 * 2m and 2m + 1 in V[m]) and are transposed by constant shuffles. */
inline void mips_load_facing_row16(__global const uint* accum, uint first, uint16 out[6]) {
  __global const uint* w = accum + RP_VOXEL_ACCUM_WORDS * first;
  const uint16 m1 = (uint16)(4, 5, 6, 12, 13, 14, 20, 21, 22, 28, 29, 30, 0, 0, 0, 0);
  uint16 W[8];
  for (int j = 0; j < 8; ++j) W[j] = shuffle2(vload16(2 * j, w), vload16(2 * j + 1, w), m1);
  /* W[j]: lanes 0-2 even child of parent 2j (words 4-6), 3-5 its odd child, 6-8 and 9-11 the
   * same for parent 2j + 1 */
  const uint16 me = (uint16)(0, 6, 16, 22, 1, 7, 17, 23, 2, 8, 18, 24, 0, 0, 0, 0);
  const uint16 mo = (uint16)(3, 9, 19, 25, 4, 10, 20, 26, 5, 11, 21, 27, 0, 0, 0, 0);
  uint16 XE[4], XO[4];
  for (int i = 0; i < 4; ++i) {
    XE[i] = shuffle2(W[2 * i], W[2 * i + 1], me); /* lane 4 axis + q: parent 4 i + q */
    XO[i] = shuffle2(W[2 * i], W[2 * i + 1], mo);
  }
  const uint16 cat = (uint16)(0, 1, 2, 3, 4, 5, 6, 7, 16, 17, 18, 19, 20, 21, 22, 23);
  const uint16 p0 = (uint16)(0, 1, 2, 3, 16, 17, 18, 19, 0, 0, 0, 0, 0, 0, 0, 0);
  const uint16 p1 = (uint16)(4, 5, 6, 7, 20, 21, 22, 23, 0, 0, 0, 0, 0, 0, 0, 0);
  const uint16 p2 = (uint16)(8, 9, 10, 11, 24, 25, 26, 27, 0, 0, 0, 0, 0, 0, 0, 0);
  out[0] = shuffle2(shuffle2(XE[0], XE[1], p0), shuffle2(XE[2], XE[3], p0), cat);
  out[1] = shuffle2(shuffle2(XO[0], XO[1], p0), shuffle2(XO[2], XO[3], p0), cat);
  out[2] = shuffle2(shuffle2(XE[0], XE[1], p1), shuffle2(XE[2], XE[3], p1), cat);
  out[3] = shuffle2(shuffle2(XO[0], XO[1], p1), shuffle2(XO[2], XO[3], p1), cat);
  out[4] = shuffle2(shuffle2(XE[0], XE[1], p2), shuffle2(XE[2], XE[3], p2), cat);
  out[5] = shuffle2(shuffle2(XO[0], XO[1], p2), shuffle2(XO[2], XO[3], p2), cat);
}

/* mips_facing on 16 lanes: iso seen along `dir` given the facing word of dir's axis. */
inline MipsLanes mips_facing16(MipsLanes iso, uint16 word, uint dir) {
  const uint16 half_sum = (dir & 1u) == 0u ? word >> 16 : word & (uint16)(0xFFFFu);
  const float16 c =
      fmin(fmin(convert_float16(half_sum) * (1.0f / RP_VOXEL_FACING_UNIT), 1.0f), iso.a);
  const int16 on = iso.a > 0.0f;
  const float16 k = c / iso.a;
  MipsLanes r;
  r.r = select((float16)(0.0f), iso.r * k, on);
  r.g = select((float16)(0.0f), iso.g * k, on);
  r.b = select((float16)(0.0f), iso.b * k, on);
  r.a = select((float16)(0.0f), c, on);
  return r;
}

/* One work-item per 16 parents along x (the host launches this build only for levels with a
 * multiple of 16 voxels per side). */
__kernel void voxel_mips_build(__global float4* chain, __global const uint4* accum,
                               const VoxelMipsParams params) {
  const uint resolution = params.resolution, level = params.level;
  const uint n = rp_voxel_level_size(resolution, level);
  const uint spans = n / 16u;
  const uint gid = (uint)get_global_id(0);
  if (level == 0u || spans == 0u || gid >= spans * n * n) return;
  const uint row = gid / spans;
  const int3 p = (int3)((int)((gid - row * spans) * 16u), (int)(row % n), (int)(row / n));
  const uint child_n = 2u * n;
  const uint dst = rp_voxel_index(p, n);
  MipsLanes c[8];
  if (level == 1u) { /* from level 0 and its facing coverage (mips_facing per lane) */
    MipsLanes iso[8];
    mips_load_children16(chain, rp_voxel_offset(resolution, 0u, 0u), child_n, p, iso);
    __global const uint* words = (__global const uint*)accum;
    uint16 rows[4][6];
    for (uint yz = 0; yz < 4u; ++yz) {
      const uint y = 2u * (uint)p.y + (yz & 1u), z = 2u * (uint)p.z + (yz >> 1);
      mips_load_facing_row16(words, (z * child_n + y) * child_n + 2u * (uint)p.x, rows[yz]);
    }
    for (uint axis = 0; axis < 3u; ++axis) {
      uint16 facing[8];
      for (uint i = 0; i < 8u; ++i) facing[i] = rows[i >> 1][2u * axis + (i & 1u)];
      for (uint dir = 2u * axis; dir < 2u * axis + 2u; ++dir) {
        for (uint i = 0; i < 8u; ++i) c[i] = mips_facing16(iso[i], facing[i], dir);
        mips_store16(chain, rp_voxel_offset(resolution, 1u, dir) + dst, mips_composite16(c, dir));
      }
    }
  } else {
    for (uint dir = 0; dir < 6u; ++dir) {
      mips_load_children16(chain, rp_voxel_offset(resolution, level - 1u, dir), child_n, p, c);
      mips_store16(chain, rp_voxel_offset(resolution, level, dir) + dst,
                   mips_composite16(c, dir));
    }
  }
}

#else

__kernel void voxel_mips_build(__global float4* chain, __global const uint4* accum,
                               const VoxelMipsParams params) {
  const uint resolution = params.resolution, level = params.level;
  const uint n = rp_voxel_level_size(resolution, level);
  const uint gid = (uint)get_global_id(0);
  if (level == 0u || n == 0u || gid >= n * n * n) return;
  const int3 p = (int3)((int)(gid % n), (int)((gid / n) % n), (int)(gid / (n * n)));
  const uint child_n = 2u * n;
  const uint dst = rp_voxel_index(p, n);

  float4 c[8];
  if (level == 1u) { /* from level 0 and its facing coverage */
    mips_build_level1(chain, accum, resolution, p);
  } else {
    for (uint dir = 0; dir < 6u; ++dir) {
      mips_load_children(chain, rp_voxel_offset(resolution, level - 1u, dir), child_n, p, c);
      chain[rp_voxel_offset(resolution, level, dir) + dst] = mips_composite(c, dir);
    }
  }
}

#endif
