/* Physically based bloom (SPEC 6.6, after Jimenez, "Next Generation Post Processing in Call of
 * Duty: Advanced Warfare", SIGGRAPH 2014). Host side and the chain's bookkeeping:
 * src/passes/bloom.{h,cpp}.
 *
 * Images. The input and output are float4 per pixel (rgb linear HDR, a), row-major, top row
 * first. The chain's levels are PLANAR rgb: plane c (0 = r, 1 = g, 2 = b) of level k holds
 * Wk x Hk floats at offset c * Wk * Hk, row-major (alpha is not filtered: it is not displayed,
 * and the mix keeps the input's alpha). Pixel centres at +0.5. Level 0 is the input (W0 x H0);
 * level k is ceil(W(k-1) / 2) x ceil(H(k-1) / 2). Coarse texel m covers fine texels 2m and 2m+1
 * (the second one does not exist for the last texel of an odd-sized level: clamp-to-edge repeats
 * the edge), so a fine-level position p (in pixels) is coarse position p / 2. All sampling is
 * clamp-to-edge.
 *
 * Downsample (13 taps): destination texel (x, y) is centred on the source texel CORNER
 * (2x+1, 2y+1); the 13 bilinear taps sit at source offsets {-2, 0, 2}^2 and {-1, 1}^2 from it.
 * Every tap lands on a texel corner, so each is exactly the mean of a 2x2 texel box, and the 13
 * taps together read the 6x6 source texels 2x-2 .. 2x+3 (the 36-texel footprint). They form five
 * overlapping 2x2 groups of taps: the inner group (the four {-1, 1}^2 taps), weight 0.5, and the
 * four outer corner groups (e.g. offsets (-2,-2), (0,-2), (-2,0), (0,0)), weight 0.125 each.
 * The four taps of a group tile a 4x4 texel box, so each group is the plain mean of 16 texels:
 * inner = texels 2x-1 .. 2x+2 (both axes), outer = 2x-2 .. 2x+1 or 2x .. 2x+3 per axis. Without
 * the Karis average the four outer groups add up to the separable weights h x h, h = (1 1 2 2 1 1)
 * over the footprint, so dst = (h x h) / 128 + (g x g) / 32 with g = (0 1 1 1 1 0): that is what
 * bloom_downsample evaluates (two row sums per source row, then the rows). Interior energy is
 * conserved: every source texel's weights over all destination texels sum to exactly 1/4.
 *
 * Karis average (first downsample only): each group's mean colour G is weighted by
 * 1 / (1 + luma(G)) (Rec. 709 luma, clamped at 0) on top of its 0.5 / 0.125, and the result is
 * divided by the sum of those weights. A single very bright texel then contributes a bounded
 * amount, so a particle moving by one pixel does not make the bloom flicker.
 *
 * Upsample (3x3 tent, radius 1 texel of the DESTINATION level = 0.5 texel of the coarse level):
 * nine bilinear taps of the coarse level at the destination texel centre + {-1, 0, 1}^2
 * destination texels, weights (1 2 1)/4 x (1 2 1)/4. The taps sit at fixed fractions (+-0.25 and
 * +-0.75 of a coarse texel from the coarse texel centres), so the nine taps collapse exactly
 * into a separable 3x3 texel stencil: destination texel i = 2m + p (parity p) reads coarse
 * texels m-1, m, m+1 with weights (5/16, 10/16, 1/16) for p = 0 and (1/16, 10/16, 5/16) for
 * p = 1 (clamping the texel index equals clamping the bilinear taps). Like the downsample it
 * conserves interior energy. tests/passes/bloom_test.cpp checks the kernels against the literal
 * taps.
 *
 * Accumulation, down levels D1 .. DN: UN = DN, Uk = Dk + up(U(k+1)), bloom = up(U1) / N.
 * Uk holds N-k+1 copies of the energy, so dividing by N makes the bloom's total energy equal the
 * input's (each level weighted 1/N). The mix at full resolution (bloom_mix, or fused into
 * motion_blur) is in common/bloom_composite.h.
 *
 * PoCL (DESIGN.md): per-work-item float4 code is not vectorized across work-items, and clamped
 * (gathered) loads defeat the work-item vectorizer, so the kernels vectorize explicitly: each
 * work-item makes a run of 8 (downsamples) or 16 (upsample, mix) texels of a row with float8 /
 * float16 arithmetic per channel and unit-stride vector loads (clamped scalar loads only at the
 * level's left and right edges). The first downsample splits the float4 input into channels as
 * it loads it, and makes two destination rows per work-item (their footprints share four of
 * their six source rows). Planar levels instead of float4 texels: 3 floats per texel instead of
 * 4 and no per-texel shuffles (measured: float4-per-texel versions of the first downsample and
 * of the mix were 1.4x and 1.8x slower). Deterministic: gathers only, no atomics.
 */
#include "shared/types.h"
#include "shared/pass_params.h"
#include "common/bloom_composite.h"

/* 20 consecutive texels of a planar row starting at column c0 (clamped to [0, w - 1]): lo holds
 * c0 .. c0+15, hi c0+16 .. c0+19. */
inline void rp_bloom_load20(__global const float* row, int c0, int w, float16* lo, float4* hi) {
  if (c0 >= 0 && c0 + 19 < w) {
    *lo = vload16(0, row + c0);
    *hi = vload4(0, row + c0 + 16);
    return;
  }
  float t[20];
  for (int i = 0; i < 20; ++i) t[i] = row[clamp(c0 + i, 0, w - 1)];
  *lo = vload16(0, t);
  *hi = vload4(0, t + 16);
}

/* 10 consecutive texels starting at column c0 (clamped): s0 .. s9 of the result (sa .. sf 0). */
inline float16 rp_bloom_load10(__global const float* row, int c0, int w) {
  if (c0 >= 0 && c0 + 9 < w)
    return (float16)(vload8(0, row + c0), vload2(0, row + c0 + 8), 0.0f, 0.0f, 0.0f, 0.0f, 0.0f,
                     0.0f);
  float t[16];
  for (int i = 0; i < 10; ++i) t[i] = row[clamp(c0 + i, 0, w - 1)];
  for (int i = 10; i < 16; ++i) t[i] = 0.0f;
  return vload16(0, t);
}

/* Stores the first n (<= 8) lanes of v at p. */
inline void rp_bloom_store8(float8 v, __global float* p, int n) {
  if (n >= 8) {
    vstore8(v, 0, p);
    return;
  }
  float t[8];
  vstore8(v, 0, t);
  for (int i = 0; i < n; ++i) p[i] = t[i];
}

/* Horizontal sums of one source row for 8 destination texels: the window is texels
 * c0 .. c0+19 with c0 = 2x-2 of the first destination texel x, destination j covers window
 * texels 2j .. 2j+5. *outer = sum with h = (1 1 2 2 1 1), *inner = sum with g = (0 1 1 1 1 0). */
inline void rp_bloom_row_sums(float16 lo, float4 hi, float8* outer, float8* inner) {
  /* p[j] = t[2j] + t[2j+1] (j = 0..9), q[j] = t[2j+1] + t[2j+2] (j = 0..8). */
  const float16 even = (float16)(lo.even, hi.even, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
  const float16 odd = (float16)(lo.odd, hi.odd, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
  const float16 p = even + odd;
  const float16 q = odd + even.s123456789abcdef0;
  /* h x row = (p[j] + p[j+1]) + (p[j+1] + p[j+2]); g x row = q[j] + q[j+1]. */
  *outer = (p.s01234567 + p.s12345678) + (p.s12345678 + p.s23456789);
  *inner = q.s01234567 + q.s12345678;
}

/* Plain 13-tap downsample, planar -> planar. Grid: (ceil(dst_w / 8), dst_h, 3 channels), any
 * local size (bounds-checked); each work-item writes destination texels 8i .. 8i+7 of one row of
 * one channel. */
__kernel void bloom_downsample(__global const float* restrict src, __global float* restrict dst,
                               const BloomStep step) {
  const int src_w = step.src_width, src_h = step.src_height;
  const int dst_w = step.dst_width, dst_h = step.dst_height;
  const int x = 8 * (int)get_global_id(0), y = (int)get_global_id(1), c = (int)get_global_id(2);
  if (x >= dst_w || y >= dst_h) return;
  __global const float* plane = src + c * src_w * src_h;
  /* Source rows 2y-2 .. 2y+3 with vertical weights h = (1 1 2 2 1 1) and g = (0 1 1 1 1 0). */
  float8 o[6], n[6];
  for (int r = 0; r < 6; ++r) {
    float16 lo;
    float4 hi;
    rp_bloom_load20(plane + clamp(2 * y - 2 + r, 0, src_h - 1) * src_w, 2 * x - 2, src_w, &lo,
                    &hi);
    rp_bloom_row_sums(lo, hi, &o[r], &n[r]);
  }
  const float8 outer = ((o[0] + o[1]) + (o[4] + o[5])) + 2.0f * (o[2] + o[3]);
  const float8 inner = (n[1] + n[2]) + (n[3] + n[4]);
  rp_bloom_store8(outer * (1.0f / 128.0f) + inner * (1.0f / 32.0f),
                  dst + c * dst_w * dst_h + y * dst_w + x, dst_w - x);
}

/* Karis weight of groups' summed colours (16 texels each): 1 / (1 + luma(sum / 16)), luma
 * Rec. 709, negative luma as 0; 1 without the Karis average. */
inline float8 rp_bloom_karis_weight(float8 r, float8 g, float8 b, int karis) {
  const float8 luma = (0.2126f * r + 0.7152f * g + 0.0722f * b) * (1.0f / 16.0f);
  return karis ? 1.0f / (1.0f + fmax(luma, 0.0f)) : (float8)(1.0f);
}

/* 4-texel row sums of one channel's source row for 8 destination texels (window texels
 * c0 .. c0+19, c0 = 2x-2; destination j covers window texels 2j .. 2j+5): *left = texels
 * 2j .. 2j+3 (outer groups on the left), *mid = 2j+1 .. 2j+4 (inner group), *right =
 * 2j+2 .. 2j+5 (outer groups on the right). */
inline void rp_bloom_group_rows(float16 lo, float4 hi, float8* left, float8* mid, float8* right) {
  const float16 even = (float16)(lo.even, hi.even, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
  const float16 odd = (float16)(lo.odd, hi.odd, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
  const float16 p = even + odd;                      /* t[2j] + t[2j+1] */
  const float16 q = odd + even.s123456789abcdef0;   /* t[2j+1] + t[2j+2] */
  *left = p.s01234567 + p.s12345678;
  *mid = q.s01234567 + q.s12345678;
  *right = p.s12345678 + p.s23456789;
}

/* 20 consecutive float4 pixels of a row from column c0 (clamped), split into channels: lo holds
 * pixels c0 .. c0+15, hi c0+16 .. c0+19. */
inline void rp_bloom_load20_rgb(__global const float4* row, int c0, int w, float16* lo_r,
                                float4* hi_r, float16* lo_g, float4* hi_g, float16* lo_b,
                                float4* hi_b) {
  float16 v0, v1, v2, v3, v4;
  if (c0 >= 0 && c0 + 19 < w) {
    __global const float* p = (__global const float*)(row + c0);
    v0 = vload16(0, p);
    v1 = vload16(1, p);
    v2 = vload16(2, p);
    v3 = vload16(3, p);
    v4 = vload16(4, p);
  } else {
    float4 t[20];
    for (int i = 0; i < 20; ++i) t[i] = row[clamp(c0 + i, 0, w - 1)];
    v0 = vload16(0, (float*)t);
    v1 = vload16(1, (float*)t);
    v2 = vload16(2, (float*)t);
    v3 = vload16(3, (float*)t);
    v4 = vload16(4, (float*)t);
  }
  *lo_r = (float16)(v0.s048c, v1.s048c, v2.s048c, v3.s048c);
  *lo_g = (float16)(v0.s159d, v1.s159d, v2.s159d, v3.s159d);
  *lo_b = (float16)(v0.s26ae, v1.s26ae, v2.s26ae, v3.s26ae);
  *hi_r = v4.s048c;
  *hi_g = v4.s159d;
  *hi_b = v4.s26ae;
}

/* One destination row of the first downsample from the per-source-row sums of its six source
 * rows (index 0 = source row 2y-2), stored at dst + i in each plane. */
inline void rp_bloom_first_row(const float8 l[3][6], const float8 m[3][6], const float8 r[3][6],
                               int karis, __global float* dst, int plane, int i, int n) {
  float8 tl[3], tr[3], bl[3], br[3], in[3];
  for (int c = 0; c < 3; ++c) {
    /* Group sums (16 texels): top = rows 0..3, bottom = rows 2..5, inner = rows 1..4. */
    tl[c] = (l[c][0] + l[c][1]) + (l[c][2] + l[c][3]);
    bl[c] = (l[c][2] + l[c][3]) + (l[c][4] + l[c][5]);
    tr[c] = (r[c][0] + r[c][1]) + (r[c][2] + r[c][3]);
    br[c] = (r[c][2] + r[c][3]) + (r[c][4] + r[c][5]);
    in[c] = (m[c][1] + m[c][2]) + (m[c][3] + m[c][4]);
  }
  const float8 w_in = 0.5f * rp_bloom_karis_weight(in[0], in[1], in[2], karis);
  const float8 w_tl = 0.125f * rp_bloom_karis_weight(tl[0], tl[1], tl[2], karis);
  const float8 w_tr = 0.125f * rp_bloom_karis_weight(tr[0], tr[1], tr[2], karis);
  const float8 w_bl = 0.125f * rp_bloom_karis_weight(bl[0], bl[1], bl[2], karis);
  const float8 w_br = 0.125f * rp_bloom_karis_weight(br[0], br[1], br[2], karis);
  /* Divide by 16 (group mean) and by the weight sum. */
  const float8 norm = (1.0f / 16.0f) / (w_in + ((w_tl + w_tr) + (w_bl + w_br)));
  for (int c = 0; c < 3; ++c)
    rp_bloom_store8(
        (w_in * in[c] + ((w_tl * tl[c] + w_tr * tr[c]) + (w_bl * bl[c] + w_br * br[c]))) * norm,
        dst + c * plane + i, n);
}

/* First downsample (full resolution float4 -> planar level 1), with the Karis average when
 * `karis` is non-zero. Grid: (ceil(dst_w / 8), ceil(dst_h / 2)), any local size; each work-item
 * makes destination texels 8i .. 8i+7 of rows 2j and 2j+1, all three channels: source pixels
 * 16i-2 .. 16i+17 of rows 4j-2 .. 4j+5 (the two rows' footprints share four source rows). */
__kernel void bloom_downsample_first(__global const float4* restrict src,
                                     __global float* restrict dst, const BloomStep step) {
  const int src_w = step.src_width, src_h = step.src_height;
  const int dst_w = step.dst_width, dst_h = step.dst_height, karis = step.karis;
  const int x = 8 * (int)get_global_id(0), y = 2 * (int)get_global_id(1);
  if (x >= dst_w || y >= dst_h) return;
  /* Row sums per source row and channel: l (left outer), m (inner), r (right outer). */
  float8 l[3][8], m[3][8], r[3][8];
  for (int row = 0; row < 8; ++row) {
    float16 lo_r, lo_g, lo_b;
    float4 hi_r, hi_g, hi_b;
    rp_bloom_load20_rgb(src + clamp(2 * y - 2 + row, 0, src_h - 1) * src_w, 2 * x - 2, src_w,
                        &lo_r, &hi_r, &lo_g, &hi_g, &lo_b, &hi_b);
    rp_bloom_group_rows(lo_r, hi_r, &l[0][row], &m[0][row], &r[0][row]);
    rp_bloom_group_rows(lo_g, hi_g, &l[1][row], &m[1][row], &r[1][row]);
    rp_bloom_group_rows(lo_b, hi_b, &l[2][row], &m[2][row], &r[2][row]);
  }
  const int plane = dst_w * dst_h, n = dst_w - x;
  float8 l6[3][6], m6[3][6], r6[3][6];
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 6; ++k) {
      l6[c][k] = l[c][k];
      m6[c][k] = m[c][k];
      r6[c][k] = r[c][k];
    }
  rp_bloom_first_row(l6, m6, r6, karis, dst, plane, y * dst_w + x, n);
  if (y + 1 >= dst_h) return;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 6; ++k) {
      l6[c][k] = l[c][k + 2];
      m6[c][k] = m[c][k + 2];
      r6[c][k] = r[c][k + 2];
    }
  rp_bloom_first_row(l6, m6, r6, karis, dst, plane, (y + 1) * dst_w + x, n);
}

/* U(k) = D(k) + up(U(k+1)), planar. Grid: (ceil(dst_w / 16), dst_h, 3 channels), any local
 * size; each work-item writes texels 16i .. 16i+15 of one row of one channel, from coarse
 * texels 8i-1 .. 8i+8 of coarse rows n-1 .. n+1 (n = row / 2). */
__kernel void bloom_upsample_add(__global const float* restrict coarse,
                                 __global const float* restrict level,
                                 __global float* restrict dst, const BloomStep step) {
  const int coarse_w = step.src_width, coarse_h = step.src_height;
  const int dst_w = step.dst_width, dst_h = step.dst_height;
  const int x = 16 * (int)get_global_id(0), y = (int)get_global_id(1), c = (int)get_global_id(2);
  if (x >= dst_w || y >= dst_h) return;
  __global const float* plane = coarse + c * coarse_w * coarse_h;
  const int n = y >> 1, m0 = x >> 1;
  const float wy0 = (y & 1) ? 0.0625f : 0.3125f, wy2 = 0.375f - wy0;
  const float16 ra = rp_bloom_load10(plane + max(n - 1, 0) * coarse_w, m0 - 1, coarse_w);
  const float16 rb = rp_bloom_load10(plane + min(n, coarse_h - 1) * coarse_w, m0 - 1, coarse_w);
  const float16 rc = rp_bloom_load10(plane + min(n + 1, coarse_h - 1) * coarse_w, m0 - 1, coarse_w);
  const float16 v = wy0 * ra + 0.625f * rb + wy2 * rc; /* coarse texels m0-1 .. m0+8 */
  const float8 left = v.s01234567, mid = v.s12345678, right = v.s23456789;
  const float8 even = 0.3125f * left + 0.625f * mid + 0.0625f * right;
  const float8 odd = 0.0625f * left + 0.625f * mid + 0.3125f * right;
  const float16 up = (float16)(even.s0, odd.s0, even.s1, odd.s1, even.s2, odd.s2, even.s3, odd.s3,
                               even.s4, odd.s4, even.s5, odd.s5, even.s6, odd.s6, even.s7, odd.s7);
  const int offset = c * dst_w * dst_h + y * dst_w + x;
  if (x + 16 <= dst_w) {
    vstore16(vload16(0, level + offset) + up, 0, dst + offset);
    return;
  }
  float t[16];
  vstore16(up, 0, t);
  for (int i = 0; i < dst_w - x; ++i) dst[offset + i] = level[offset + i] + t[i];
}

/* Full resolution: out.rgb = in.rgb * keep + up(U1) * scale, out.a = in.a, with keep = 1 - f and
 * scale = f / N (common/bloom_composite.h). Grid: (ceil(width / 16), ceil(height / 2)), any
 * local size; each work-item writes 16 pixels of two rows. out may be the same buffer as in
 * (each work-item reads and writes only its own pixels), hence no restrict. */
__kernel void bloom_mix(__global const float4* hdr_in, __global const float* restrict level1,
                        __global float4* hdr_out, const BloomStep step) {
  const int level1_w = step.src_width, level1_h = step.src_height;
  const int width = step.dst_width, height = step.dst_height;
  const float keep = step.keep, scale = step.scale;
  const int gx = (int)get_global_id(0), n = (int)get_global_id(1);
  if (16 * gx >= width || 2 * n >= height) return;
  rp_bloom_composite_rows(hdr_in, level1, level1_w, level1_h, hdr_out, width, height, gx, n,
                          keep, scale);
}
