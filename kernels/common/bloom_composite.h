/* The bloom's last tent upsample and its composite into the full-resolution image (OpenCL only;
 * kernels/bloom.cl has the derivation of the tent). Shared by bloom.cl (bloom_mix) and
 * motion_blur.cl, which composites the bloom while it writes its output (saving a
 * full-resolution float4 write and read). Every variant evaluates each pixel with the same
 * operations in the same order (vertical weights, then horizontal, then the mix), so a pixel
 * gets the same bits whichever kernel writes it; include this file before any FP_CONTRACT
 * pragma so the contraction is the same everywhere too.
 *
 * level1: U1, planar: plane c (0 = r, 1 = g, 2 = b) at c * cw * ch floats, row-major. A
 * full-resolution pixel i = 2m + p reads level-1 texels m-1, m, m+1 (indices clamped) with
 * weights (5, 10, 1) / 16 for p = 0 and (1, 10, 5) / 16 for p = 1, per axis. Composite:
 * out.rgb = colour.rgb * keep + up(U1) * scale (keep = 1 - f, scale = f / N), out.a = colour.a.
 * Images are float4 per pixel, row-major.
 */
#ifndef ROLYPOLY_COMMON_BLOOM_COMPOSITE_H
#define ROLYPOLY_COMMON_BLOOM_COMPOSITE_H

/* Composite of one pixel. */
inline float4 rp_bloom_mix_pixel(float4 colour, float r, float g, float b, float keep,
                                 float scale) {
  return (float4)(colour.x * keep + r * scale, colour.y * keep + g * scale,
                  colour.z * keep + b * scale, colour.w);
}

/* ---- rows: 16 pixels x 2 rows per work-item (what the whole-image kernels use) ---- */

/* Level-1 texels m0-1 .. m0+8 of one row (clamped): s0 .. s9 of the result (sa .. sf 0). */
inline float16 rp_bloom_row10(__global const float* row, int m0, int cw) {
  if (m0 >= 1 && m0 + 8 < cw)
    return (float16)(vload8(0, row + m0 - 1), vload2(0, row + m0 + 7), 0.0f, 0.0f, 0.0f, 0.0f,
                     0.0f, 0.0f);
  float t[16];
  for (int i = 0; i < 10; ++i) t[i] = row[clamp(m0 - 1 + i, 0, cw - 1)];
  for (int i = 10; i < 16; ++i) t[i] = 0.0f;
  return vload16(0, t);
}

/* One channel of up(U1) for pixels 2m0 .. 2m0+15 of rows 2n and 2n+1: *even_x / *odd_x hold
 * pixels 2m0 + 2i / 2m0 + 2i + 1 of row 2n, *even_x1 / *odd_x1 those of row 2n+1. */
inline void rp_bloom_tent_rows(__global const float* plane, int cw, int ch, int m0, int n,
                               float8* even_x, float8* odd_x, float8* even_x1, float8* odd_x1) {
  const float16 a = rp_bloom_row10(plane + clamp(n - 1, 0, ch - 1) * cw, m0, cw);
  const float16 b = rp_bloom_row10(plane + min(n, ch - 1) * cw, m0, cw);
  const float16 c = rp_bloom_row10(plane + min(n + 1, ch - 1) * cw, m0, cw);
  const float16 v0 = 0.3125f * a + 0.625f * b + 0.0625f * c; /* row 2n */
  const float16 v1 = 0.0625f * a + 0.625f * b + 0.3125f * c; /* row 2n+1 */
  *even_x = 0.3125f * v0.s01234567 + 0.625f * v0.s12345678 + 0.0625f * v0.s23456789;
  *odd_x = 0.0625f * v0.s01234567 + 0.625f * v0.s12345678 + 0.3125f * v0.s23456789;
  *even_x1 = 0.3125f * v1.s01234567 + 0.625f * v1.s12345678 + 0.0625f * v1.s23456789;
  *odd_x1 = 0.0625f * v1.s01234567 + 0.625f * v1.s12345678 + 0.3125f * v1.s23456789;
}

/* The composite of pixels 16gx .. 16gx+15 of rows 2n, 2n+1 from in to out (pixels outside the
 * image are neither read nor written). out may be in. */
inline void rp_bloom_composite_rows(__global const float4* in, __global const float* level1,
                                    int cw, int ch, __global float4* out, int width, int height,
                                    int gx, int n, float keep, float scale) {
  const int m0 = 8 * gx, x0 = 16 * gx, plane = cw * ch;
  float8 e0[3], o0[3], e1[3], o1[3]; /* per channel: row 2n even / odd pixels, row 2n+1 */
  for (int c = 0; c < 3; ++c)
    rp_bloom_tent_rows(level1 + c * plane, cw, ch, m0, n, &e0[c], &o0[c], &e1[c], &o1[c]);
  const int n_x = min(width - x0, 16);
  const bool row1 = 2 * n + 1 < height;
  __global const float4* in0 = in + 2 * n * width + x0;
  __global float4* out0 = out + 2 * n * width + x0;
#define RP_BLOOM_PIXEL(k)                                                                       \
  if (2 * k < n_x)                                                                              \
    out0[2 * k] = rp_bloom_mix_pixel(in0[2 * k], e0[0].s##k, e0[1].s##k, e0[2].s##k, keep,      \
                                     scale);                                                    \
  if (2 * k + 1 < n_x)                                                                          \
    out0[2 * k + 1] = rp_bloom_mix_pixel(in0[2 * k + 1], o0[0].s##k, o0[1].s##k, o0[2].s##k,    \
                                         keep, scale);                                          \
  if (row1 && 2 * k < n_x)                                                                      \
    out0[width + 2 * k] = rp_bloom_mix_pixel(in0[width + 2 * k], e1[0].s##k, e1[1].s##k,        \
                                             e1[2].s##k, keep, scale);                          \
  if (row1 && 2 * k + 1 < n_x)                                                                  \
    out0[width + 2 * k + 1] = rp_bloom_mix_pixel(in0[width + 2 * k + 1], o1[0].s##k,            \
                                                 o1[1].s##k, o1[2].s##k, keep, scale);
  RP_BLOOM_PIXEL(0)
  RP_BLOOM_PIXEL(1)
  RP_BLOOM_PIXEL(2)
  RP_BLOOM_PIXEL(3)
  RP_BLOOM_PIXEL(4)
  RP_BLOOM_PIXEL(5)
  RP_BLOOM_PIXEL(6)
  RP_BLOOM_PIXEL(7)
#undef RP_BLOOM_PIXEL
}

/* ---- blocks: 4x4 pixels (what motion blur's per-tile reconstruction uses) ---- */

/* Level-1 texels m0-1 .. m0+2 of one row (clamped). */
inline float4 rp_bloom_row4(__global const float* row, int m0, int cw) {
  if (m0 >= 1 && m0 + 2 < cw) return vload4(0, row + m0 - 1);
  return (float4)(row[clamp(m0 - 1, 0, cw - 1)], row[min(m0, cw - 1)], row[min(m0 + 1, cw - 1)],
                  row[min(m0 + 2, cw - 1)]);
}

/* Horizontal weights of a row of four level-1 texels c (m0-1 .. m0+2) for pixels 2m0 .. 2m0+3. */
inline float4 rp_bloom_tent_x4(float4 c) {
  return (float4)(0.3125f, 0.0625f, 0.3125f, 0.0625f) * c.s0011 + 0.625f * c.s1122 +
         (float4)(0.0625f, 0.3125f, 0.0625f, 0.3125f) * c.s2233;
}

/* One channel of up(U1) over the 4x4 block at pixel (4bx, 4by): out[j] = pixels 4bx .. 4bx+3
 * of row 4by + j. */
inline void rp_bloom_tent_block(__global const float* plane, int cw, int ch, int bx, int by,
                                float4 out[4]) {
  const int m0 = 2 * bx, n0 = 2 * by;
  const float4 r0 = rp_bloom_row4(plane + clamp(n0 - 1, 0, ch - 1) * cw, m0, cw);
  const float4 r1 = rp_bloom_row4(plane + min(n0, ch - 1) * cw, m0, cw);
  const float4 r2 = rp_bloom_row4(plane + min(n0 + 1, ch - 1) * cw, m0, cw);
  const float4 r3 = rp_bloom_row4(plane + min(n0 + 2, ch - 1) * cw, m0, cw);
  out[0] = rp_bloom_tent_x4(0.3125f * r0 + 0.625f * r1 + 0.0625f * r2);
  out[1] = rp_bloom_tent_x4(0.0625f * r0 + 0.625f * r1 + 0.3125f * r2);
  out[2] = rp_bloom_tent_x4(0.3125f * r1 + 0.625f * r2 + 0.0625f * r3);
  out[3] = rp_bloom_tent_x4(0.0625f * r1 + 0.625f * r2 + 0.3125f * r3);
}

#endif
