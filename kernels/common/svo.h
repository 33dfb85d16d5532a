/* Reading the sparse voxel octree (OpenCL C only): node descent and brick samples. Layout and
 * the meaning of nodes and bricks: shared/svo_layout.h. Used by the builder (svo.cl) and by
 * the cone tracer when the GI volume is the octree (common/cone_trace.h with RP_GI_SVO).
 *
 * Samples are packed (RGB9E5 uint + opacity byte, shared/svo_layout.h) unless the kernel is
 * built with -DRP_SVO_FLOAT_SAMPLES=1 (float4; the host writes the matching
 * RP_SVO_HDR_SAMPLE_BYTES).
 */
#ifndef ROLYPOLY_COMMON_SVO_H
#define ROLYPOLY_COMMON_SVO_H

#include "shared/svo_layout.h"

#ifndef RP_SVO_FLOAT_SAMPLES
#define RP_SVO_FLOAT_SAMPLES 0
#endif

/* Header word w of the octree buffer. */
inline uint rp_svo_header(__global const float4* svo, uint w) {
  return ((__global const uint*)svo)[w];
}

/* The node pool (2 uints per node). */
inline __global const uint* rp_svo_nodes(__global const float4* svo) {
  return (__global const uint*)(svo + RP_SVO_HEADER_FLOAT4S);
}

/* RGB9E5 -> rgb: mantissa * 2^(exponent - 15 - 9). */
inline float3 rp_svo_unpack_rgb(uint w) {
  const float scale = as_float(((w >> 27) + 103u) << 23); /* 2^(e - 24), e - 24 + 127 */
  return (float3)((float)(w & 511u), (float)((w >> 9) & 511u), (float)((w >> 18) & 511u)) *
         scale;
}

/* Sample s of a sample pool whose rgb plane starts at `pool` and opacity plane at `alpha`. */
inline float4 rp_svo_pool_load(__global const uint* pool, __global const uchar* alpha, uint s) {
#if RP_SVO_FLOAT_SAMPLES
  (void)alpha;
  return ((__global const float4*)pool)[s];
#else
  return (float4)(rp_svo_unpack_rgb(pool[s]), (float)alpha[s] * (1.0f / 255.0f));
#endif
}

/* The brick table (RP_SVO_TABLE_WORDS uints per brick, shared/svo_layout.h). */
inline __global const uint* rp_svo_table(__global const float4* svo) {
  return (__global const uint*)svo + rp_svo_header(svo, RP_SVO_HDR_TABLE_OFFSET);
}

/* Sample s = brick address + 27 d + rp_svo_sample(i, j, k) (premultiplied rgb, opacity): the
 * own sample of the brick's node or, for a border sample, of its neighbour a + e, reached by
 * the table's face links (x, then y, then z); 0 where a link or the own samples are missing
 * (shared/svo_layout.h: then the sample is empty). */
inline float4 rp_svo_load(__global const float4* svo, uint s) {
  uint own;
  const uint e = rp_svo_locate(s & ((1u << RP_SVO_BRICK_SHIFT) - 1u), &own);
  __global const uint* table = rp_svo_table(svo);
  uint b = s >> RP_SVO_BRICK_SHIFT;
  for (uint axis = 0u; axis < 3u && b != RP_SVO_NO_LINK; ++axis)
    if ((e >> axis) & 1u) b = table[RP_SVO_TABLE_WORDS * b + 1u + axis] & RP_SVO_LINK_MASK;
  if (b == RP_SVO_NO_LINK) return (float4)(0.0f);
  const uint first = table[RP_SVO_TABLE_WORDS * b];
  if (first == RP_SVO_NO_BRICK) return (float4)(0.0f);
  const uint slot =
      rp_svo_own_slot(table[RP_SVO_TABLE_WORDS * b + 1u] >> RP_SVO_MASK_SHIFT, own);
  if (slot == RP_SVO_NO_BRICK) return (float4)(0.0f);
  __global const uint* pool =
      (__global const uint*)(svo + rp_svo_header(svo, RP_SVO_HDR_BRICK_OFFSET));
  __global const uchar* alpha =
      (__global const uchar*)svo + rp_svo_header(svo, RP_SVO_HDR_ALPHA_OFFSET);
  return rp_svo_pool_load(pool, alpha, first + slot);
}

/* The node at `depth` with coordinate a (0 <= a < 2^depth per axis, unchecked): its index, or
 * 0xFFFFFFFF when an ancestor has no children (the node is not in the tree). Descends from
 * the root, one child block per depth: child o = (bit depth-j of a) for the j-th step. */
inline uint rp_svo_find(__global const uint* nodes, uint depth, uint3 a) {
  uint idx = 0u;
  for (uint j = depth; j > 0u; --j) {
    const uint child = nodes[2u * idx] & RP_SVO_NODE_CHILD_MASK;
    if (child == 0u) return 0xFFFFFFFFu;
    const uint s = j - 1u;
    idx = child + (((a.x >> s) & 1u) | (((a.y >> s) & 1u) << 1) | (((a.z >> s) & 1u) << 2));
  }
  return idx;
}

/* First sample of the brick of the node at `depth` with coordinate a, or RP_SVO_NO_BRICK. */
inline uint rp_svo_find_brick(__global const uint* nodes, uint depth, uint3 a) {
  const uint idx = rp_svo_find(nodes, depth, a);
  return idx == 0xFFFFFFFFu ? RP_SVO_NO_BRICK : nodes[2u * idx + 1u];
}

/* Voxel v of volume `dir` at `level` (dir ignored at level 0), as rp_voxel_fetch reads the
 * dense chain: zero outside the volume or where the octree has no brick. Levels 0 .. D-1. */
inline float4 rp_svo_fetch(__global const float4* svo, uint resolution, uint level, uint dir,
                           int3 v) {
  const int n = (int)(resolution >> level);
  if (v.x < 0 || v.y < 0 || v.z < 0 || v.x >= n || v.y >= n || v.z >= n) return (float4)(0.0f);
  const uint depths = rp_svo_header(svo, RP_SVO_HDR_DEPTHS);
  if (level >= depths) return (float4)(0.0f);
  const uint3 u = convert_uint3(v);
  const uint3 a = u >> 1;
  const uint brick = rp_svo_find_brick(rp_svo_nodes(svo), depths - 1u - level, a);
  if (brick == RP_SVO_NO_BRICK) return (float4)(0.0f);
  const uint3 o = u - 2u * a;
  return rp_svo_load(svo, brick + (level == 0u ? 0u : RP_SVO_BRICK_SAMPLES * dir) +
                              rp_svo_sample(o.x, o.y, o.z));
}

/* Trilinear footprint of point p at a level with n voxels per side, as the dense sampler
 * (common/cone_trace.h rp_cone_footprint): taps x0 = floor(u), x0 + 1 of
 * u = clamp((p + 1) n / 2 - 1/2, 0, n - 1), fraction f = u - x0. Returns x0; the taps lie in
 * the brick of node x0 >> 1 at sample offsets (x0 & 1) and (x0 & 1) + 1. */
inline uint3 rp_svo_footprint(uint n, float3 p, float3* f) {
  const float nf = (float)n;
  const float3 u = clamp((p + 1.0f) * (0.5f * nf) - 0.5f, 0.0f, nf - 1.0f);
  const float3 fl = floor(u);
  *f = u - fl;
  return convert_uint3(fl);
}

/* The solid fraction (0..1) at p of level `level`: trilinear over the solid grid's level-l
 * cells with the dense sampler's footprint; 0 without a grid or below its first level. */
inline float rp_svo_solid(__global const float4* svo, uint resolution, uint level, float3 p) {
  const uint offset = rp_svo_header(svo, RP_SVO_HDR_SOLID_OFFSET);
  const uint first = rp_svo_header(svo, RP_SVO_HDR_SOLID_LEVEL);
  if (offset == 0u || level < first || level >= rp_svo_header(svo, RP_SVO_HDR_DEPTHS))
    return 0.0f;
  uint base = offset;
  for (uint l = first; l < level; ++l) {
    const uint m = resolution >> l;
    base += m * m * m;
  }
  __global const uchar* g = (__global const uchar*)svo + base;
  const uint n = resolution >> level;
  float3 f;
  const uint3 x0 = rp_svo_footprint(n, p, &f);
  const uint3 x1 = min(x0 + 1u, (uint3)(n - 1u));
#define RP_SVO_SOLID_TAP(X, Y, Z) ((float)g[(Z * n + Y) * n + X])
  const float c00 = mix(RP_SVO_SOLID_TAP(x0.x, x0.y, x0.z), RP_SVO_SOLID_TAP(x1.x, x0.y, x0.z), f.x);
  const float c10 = mix(RP_SVO_SOLID_TAP(x0.x, x1.y, x0.z), RP_SVO_SOLID_TAP(x1.x, x1.y, x0.z), f.x);
  const float c01 = mix(RP_SVO_SOLID_TAP(x0.x, x0.y, x1.z), RP_SVO_SOLID_TAP(x1.x, x0.y, x1.z), f.x);
  const float c11 = mix(RP_SVO_SOLID_TAP(x0.x, x1.y, x1.z), RP_SVO_SOLID_TAP(x1.x, x1.y, x1.z), f.x);
#undef RP_SVO_SOLID_TAP
  return mix(mix(c00, c10, f.y), mix(c01, c11, f.y), f.z) * (1.0f / 255.0f);
}

/* A cone sample s (premultiplied) at level `level`, point p, with the closed objects' inside
 * made opaque: opacity max(s.a, RP_SVO_SOLID_WEIGHT x solid fraction), the sample's mean
 * radiance kept (rgb scaled with the opacity; 0 where the sample holds no surface: the inside
 * itself is dark).
 * Why a weight below 1: the cone composites its samples as if each step's opacity were an
 * independent medium, T = prod (1 - a_i). A solid covering a fraction c of the footprint over
 * several steps then passes (1 - c)^steps where the rays it stands for pass 1 - c (the same
 * rays are blocked at every step), so full fractions darkened what lies behind and beside the
 * tumblers: at 360x360, 512 spp, octree 256^3, fast mode, the floor in their shadows read
 * -18.5 % indirect light against the path tracer and the lit floor -14.0 %; without the grid
 * +28.1 % and +1.0 %; at 0.6 -3.5 % and -7.1 % (squared fractions, which keep the inside
 * opaque: +2.8 % and -5.7 %, the tumblers brighter, +7.0 % against +4.8 %);
 * bench/results/zen5-2core-pocl-svo-contact-shadows.md. */
inline float4 rp_svo_solid_apply(__global const float4* svo, uint resolution, uint level,
                                 float3 p, float4 s) {
  const float solid = RP_SVO_SOLID_WEIGHT * rp_svo_solid(svo, resolution, level, p);
  if (!(solid > s.w)) return s;
  return (float4)(s.w > 0.0f ? s.xyz * (solid / s.w) : (float3)(0.0f), solid);
}

#endif
