/* Eight pixels per work-item (OpenCL C only), for the straight-line kernels of the fast light
 * path (light.cl: light_compose; indirect.cl: indirect_filter). DESIGN.md's PoCL facts: float4
 * code per pixel is not vectorized across work-items, and PoCL's own work-item vectorizer is
 * easily defeated (the compiler merges pairs of similar scalar operations into 2-wide vectors
 * first, measured); explicit float8 arithmetic on eight pixels of a row always runs 8-wide and is
 * plain element-wise code on a GPU.
 *
 * A "chunk" is 8 consecutive pixels of one row, x0 = 8 * get_global_id(0). A chunk that runs
 * past the row's end (width not a multiple of 8) repeats its last pixel in the missing lanes
 * for loads and stores only the lanes inside the row.
 */
#ifndef ROLYPOLY_COMMON_INDIRECT_SIMD_H
#define ROLYPOLY_COMMON_INDIRECT_SIMD_H

/* Components of the float4 pixels x0 .. x0+7 of a plane of float4 read as floats (row starts at
 * element `row`, i.e. 4 * y * width), n = valid lanes (1..8). */
inline void rp_load8_float4(__global const float* plane, uint row, uint x0, uint n, float8* x,
                            float8* y, float8* z, float8* w) {
  float16 a, b;
  if (n == 8u) {
    __global const float* p = plane + row + 4u * x0;
    a = vload16(0, p);
    b = vload16(1, p);
  } else {
    float4 v[8];
    for (uint k = 0; k < 8u; ++k) v[k] = vload4(0, plane + row + 4u * (x0 + min(k, n - 1u)));
    a = (float16)(v[0], v[1], v[2], v[3]);
    b = (float16)(v[4], v[5], v[6], v[7]);
  }
  *x = (float8)(a.s048c, b.s048c);
  *y = (float8)(a.s159d, b.s159d);
  *z = (float8)(a.s26ae, b.s26ae);
  *w = (float8)(a.s37bf, b.s37bf);
}

/* Stores four float8 components as the float4 pixels x0 .. x0+n-1 (layout as above). */
inline void rp_store8_float4(__global float* plane, uint row, uint x0, uint n, float8 x, float8 y,
                             float8 z, float8 w) {
  const float16 lo = (float16)(x.s0, y.s0, z.s0, w.s0, x.s1, y.s1, z.s1, w.s1, x.s2, y.s2, z.s2,
                               w.s2, x.s3, y.s3, z.s3, w.s3);
  const float16 hi = (float16)(x.s4, y.s4, z.s4, w.s4, x.s5, y.s5, z.s5, w.s5, x.s6, y.s6, z.s6,
                               w.s6, x.s7, y.s7, z.s7, w.s7);
  __global float* p = plane + row + 4u * x0;
  if (n == 8u) {
    vstore16(lo, 0, p);
    vstore16(hi, 1, p);
    return;
  }
  const float* l = (const float*)&lo;
  const float* h = (const float*)&hi;
  for (uint k = 0; k < n; ++k) vstore4(vload4(0, k < 4u ? l + 4u * k : h + 4u * (k - 4u)), 0, p + 4u * k);
}

/* rp_hash_u32 (common/random.h) on eight lanes. */
inline uint8 rp_hash8_u32(uint8 v) {
  const uint8 state = v * 747796405u + 2891336453u;
  const uint8 word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

/* Lane k of v (k < 8). */
inline float rp_lane8(float8 v, uint k) {
  const float* p = (const float*)&v;
  return p[k];
}

#endif
