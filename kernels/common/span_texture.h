/* Bilinear and trilinear (mipmapped) texture sampling for pixel spans (common/span.h; OpenCL C
 * only), used by gbuffer.cl and voxelize.cl; needs shared/types.h (TextureInfo). Textures are
 * read straight from the scene's packed texel buffer (RGBA8, sRGB-encoded rgb, every mip
 * level; render/texture_mips.h): a tap is one 4-byte load and its rgb goes through the exact
 * 256-entry sRGB table (common/colour.h RP_SRGB8_TO_LINEAR), so the values are those of
 * rp_unpack_rgba8_srgb, bit for bit, and the filtering is vector arithmetic across the span.
 * (Each pass once kept a linear float4 copy, decoded once: 16 bytes a
 * texel, 8 MiB per pass for the demo's textures. Per-tap decoding measured the same time on
 * the busy 720 frame and saves that memory and the decode kernels.) */
#ifndef ROLYPOLY_COMMON_SPAN_TEXTURE_H
#define ROLYPOLY_COMMON_SPAN_TEXTURE_H

#include "common/colour.h"
#include "common/span.h"

/* Folds texel column (or row) c and c + 1 into [0, size) per lane by the lane's wrap mode
 * (RP_WRAP_*, shared/types.h; the rules of the path tracer's textures, src/truth): c is an
 * integer held in float (the floor of the footprint's first tap). */
inline void rp_span_wrap_taps(rp_spanf c, rp_spanf size, rp_spanu mode, rp_spani* i0,
                              rp_spani* i1) {
  /* Repeat: wrap in float (exact for integers below 2^24), so huge uv (tiling) cannot overflow
   * the int conversion; the int result may still be size after rounding or -1 for a tiny
   * negative quotient: fold those back. */
  const rp_spani n = rp_span_convert_int(size);
  rp_spani r0 = rp_span_convert_int(c - floor(c / size) * size);
  r0 = select(r0, r0 - n, r0 >= n);
  r0 = select(r0, r0 + n, r0 < 0);
  *i0 = r0;
  *i1 = select(r0 + 1, (rp_spani)(0), r0 + 1 == n);
  const rp_spani clamp_mode = mode == RP_WRAP_CLAMP;
  const rp_spani mirror_mode = mode == RP_WRAP_MIRROR;
  if (!rp_span_any(clamp_mode | mirror_mode)) return;
  /* Clamp to edge: c limited to [-1, size] first (any farther is the same edge texel). */
  const rp_spani k = rp_span_convert_int(clamp(c, -1.0f, size));
  const rp_spani zero = (rp_spani)(0), last = n - 1;
  *i0 = select(*i0, clamp(k, zero, last), clamp_mode);
  *i1 = select(*i1, clamp(k + 1, zero, last), clamp_mode);
  /* Mirrored repeat: position in the period of 2 size, the second half read backwards. */
  const rp_spani n2 = 2 * n;
  rp_spani m0 = rp_span_convert_int(c - floor(c / (2.0f * size)) * (2.0f * size));
  m0 = select(m0, m0 - n2, m0 >= n2);
  m0 = select(m0, m0 + n2, m0 < 0);
  const rp_spani m1 = select(m0 + 1, zero, m0 + 1 == n2);
  *i0 = select(*i0, select(m0, n2 - 1 - m0, m0 >= n), mirror_mode);
  *i1 = select(*i1, select(m1, n2 - 1 - m1, m1 >= n), mirror_mode);
}

/* The four taps of a bilinear footprint at (u, v) of a w x h texture (or mip level) whose first
 * texel is `offset`: texel indices (offset + row * width + column) per lane, in arrays for the
 * lane-by-lane reads, and the weights' fractions. */
inline void rp_span_texture_taps(rp_spani textured, rp_spanf w, rp_spanf h, rp_spanu offset,
                                 rp_spanu wrap, rp_spanf u, rp_spanf v, uint* i00, uint* i10,
                                 uint* i01, uint* i11, rp_spanf* fx, rp_spanf* fy) {
  /* Untextured lanes sample (0, 0) of a 1x1 texture (ignored by the callers): no NaN reaches
   * the int conversions. */
  u = select((rp_spanf)(0.0f), u, textured);
  v = select((rp_spanf)(0.0f), v, textured);
  const rp_spanf x = u * w - 0.5f;
  const rp_spanf y = (1.0f - v) * h - 0.5f;
  const rp_spanf x0f = floor(x), y0f = floor(y);
  *fx = x - x0f;
  *fy = y - y0f;
  rp_spani x0, x1, y0, y1;
  rp_span_wrap_taps(x0f, w, wrap & 3u, &x0, &x1);
  rp_span_wrap_taps(y0f, h, (wrap >> 2) & 3u, &y0, &y1);
  const rp_spani wi = rp_span_convert_int(w);
  const rp_spanu row0 = offset + rp_span_convert_uint(y0 * wi);
  const rp_spanu row1 = offset + rp_span_convert_uint(y1 * wi);
  RP_SPAN_TO_ARRAY(row0 + rp_span_convert_uint(x0), i00);
  RP_SPAN_TO_ARRAY(row0 + rp_span_convert_uint(x1), i10);
  RP_SPAN_TO_ARRAY(row1 + rp_span_convert_uint(x0), i01);
  RP_SPAN_TO_ARRAY(row1 + rp_span_convert_uint(x1), i11);
}

/* Bilinear texture sample of the lanes with `textured` set (the arithmetic of sampling.h's
 * rp_texture_bilinear on decoded texels, so the same values): (w, h) the lane's texture (or
 * mip level) size in texels, offset its first texel in texels (packed RGBA8 sRGB per texel,
 * rows top to bottom), wrap its RP_WRAP_PACK modes. Writes the sampled (r, g, b); untextured
 * lanes and lanes >= n read nothing and get 0. */
inline void rp_span_texture_sample_coded(__global const uint* texels, rp_spani textured,
                                         rp_spanf w, rp_spanf h, rp_spanu offset,
                                         rp_spanu wrap, rp_spanf u, rp_spanf v, int n,
                                         int srgb, rp_spanf* r, rp_spanf* g, rp_spanf* b);
inline void rp_span_texture_sample(__global const uint* texels, rp_spani textured,
                                   rp_spanf w, rp_spanf h, rp_spanu offset, rp_spanu wrap,
                                   rp_spanf u, rp_spanf v, int n, rp_spanf* r, rp_spanf* g,
                                   rp_spanf* b) {
  rp_span_texture_sample_coded(texels, textured, w, h, offset, wrap, u, v, n, 1, r, g, b);
}

/* rp_span_texture_sample with the rgb codes read as sRGB (srgb != 0: the table) or as linear
 * 8-bit values (code / 255: normal and metallic-roughness maps, glTF's non-colour data). */
inline void rp_span_texture_sample_coded(__global const uint* texels, rp_spani textured,
                                         rp_spanf w, rp_spanf h, rp_spanu offset,
                                         rp_spanu wrap, rp_spanf u, rp_spanf v, int n,
                                         int srgb, rp_spanf* r, rp_spanf* g, rp_spanf* b) {
  uint i00[RP_SPAN], i10[RP_SPAN], i01[RP_SPAN], i11[RP_SPAN];
  rp_spanf fx, fy;
  rp_span_texture_taps(textured, w, h, offset, wrap, u, v, i00, i10, i01, i11, &fx, &fy);
  int on[RP_SPAN];
  RP_SPAN_TO_ARRAY(textured, on);
  /* The four taps per lane, decoded (untextured lanes keep code 0, which decodes to 0). */
  float r00a[RP_SPAN], g00a[RP_SPAN], b00a[RP_SPAN], r10a[RP_SPAN], g10a[RP_SPAN], b10a[RP_SPAN];
  float r01a[RP_SPAN], g01a[RP_SPAN], b01a[RP_SPAN], r11a[RP_SPAN], g11a[RP_SPAN], b11a[RP_SPAN];
  for (int i = 0; i < RP_SPAN; ++i) {
    uint t00 = 0u, t10 = 0u, t01 = 0u, t11 = 0u;
    if (i < n && on[i]) {
      t00 = texels[i00[i]];
      t10 = texels[i10[i]];
      t01 = texels[i01[i]];
      t11 = texels[i11[i]];
    }
#define RP_TAP_DECODE_(t, rr, gg, bb)                                                    \
  if (srgb) {                                                                            \
    rr[i] = RP_SRGB8_TO_LINEAR[(t) & 0xFFu];                                             \
    gg[i] = RP_SRGB8_TO_LINEAR[((t) >> 8) & 0xFFu];                                      \
    bb[i] = RP_SRGB8_TO_LINEAR[((t) >> 16) & 0xFFu];                                     \
  } else {                                                                               \
    rr[i] = (float)((t) & 0xFFu) * (1.0f / 255.0f);                                      \
    gg[i] = (float)(((t) >> 8) & 0xFFu) * (1.0f / 255.0f);                               \
    bb[i] = (float)(((t) >> 16) & 0xFFu) * (1.0f / 255.0f);                              \
  }
    RP_TAP_DECODE_(t00, r00a, g00a, b00a);
    RP_TAP_DECODE_(t10, r10a, g10a, b10a);
    RP_TAP_DECODE_(t01, r01a, g01a, b01a);
    RP_TAP_DECODE_(t11, r11a, g11a, b11a);
#undef RP_TAP_DECODE_
  }
  const rp_spanf r00 = RP_SPAN_FROM_ARRAY(r00a), g00 = RP_SPAN_FROM_ARRAY(g00a),
                 b00 = RP_SPAN_FROM_ARRAY(b00a);
  const rp_spanf r10 = RP_SPAN_FROM_ARRAY(r10a), g10 = RP_SPAN_FROM_ARRAY(g10a),
                 b10 = RP_SPAN_FROM_ARRAY(b10a);
  const rp_spanf r01 = RP_SPAN_FROM_ARRAY(r01a), g01 = RP_SPAN_FROM_ARRAY(g01a),
                 b01 = RP_SPAN_FROM_ARRAY(b01a);
  const rp_spanf r11 = RP_SPAN_FROM_ARRAY(r11a), g11 = RP_SPAN_FROM_ARRAY(g11a),
                 b11 = RP_SPAN_FROM_ARRAY(b11a);
  *r = mix(mix(r00, r10, fx), mix(r01, r11, fx), fy);
  *g = mix(mix(g00, g10, fx), mix(g01, g11, fx), fy);
  *b = mix(mix(b00, b10, fx), mix(b01, b11, fx), fy);
}

/* Bilinear sample of the alpha channel (linear, the top byte) of the lanes with `textured`
 * set (arguments as rp_span_texture_sample): alpha-mask tests (common/alpha_mask.h). Lanes
 * not textured or >= n get 1. */
inline rp_spanf rp_span_texture_alpha(__global const uint* texels, rp_spani textured,
                                      rp_spanf w, rp_spanf h, rp_spanu offset, rp_spanu wrap,
                                      rp_spanf u, rp_spanf v, int n) {
  uint i00[RP_SPAN], i10[RP_SPAN], i01[RP_SPAN], i11[RP_SPAN];
  rp_spanf fx, fy;
  rp_span_texture_taps(textured, w, h, offset, wrap, u, v, i00, i10, i01, i11, &fx, &fy);
  int on[RP_SPAN];
  RP_SPAN_TO_ARRAY(textured, on);
  float a00[RP_SPAN], a10[RP_SPAN], a01[RP_SPAN], a11[RP_SPAN];
  for (int i = 0; i < RP_SPAN; ++i) {
    const bool read = i < n && on[i];
    a00[i] = read ? (float)(texels[i00[i]] >> 24) / 255.0f : 1.0f;
    a10[i] = read ? (float)(texels[i10[i]] >> 24) / 255.0f : 1.0f;
    a01[i] = read ? (float)(texels[i01[i]] >> 24) / 255.0f : 1.0f;
    a11[i] = read ? (float)(texels[i11[i]] >> 24) / 255.0f : 1.0f;
  }
  /* a + (b - a) t per row, then between the rows (the path tracer's sample_alpha) */
  const rp_spanf p00 = RP_SPAN_FROM_ARRAY(a00), p10 = RP_SPAN_FROM_ARRAY(a10),
                 p01 = RP_SPAN_FROM_ARRAY(a01), p11 = RP_SPAN_FROM_ARRAY(a11);
  const rp_spanf top = p00 + (p10 - p00) * fx, bottom = p01 + (p11 - p01) * fx;
  return top + (bottom - top) * fy;
}

/* Bilinear texture sampling of the lanes with `textured` set at level 0 (arguments as
 * rp_span_texture_sample): multiplies (r, g, b) of those lanes in place. */
inline void rp_span_texture_linear(__global const uint* texels, rp_spani textured,
                                   rp_spanf w, rp_spanf h, rp_spanu offset, rp_spanu wrap,
                                   rp_spanf u, rp_spanf v, int n, rp_spanf* r, rp_spanf* g,
                                   rp_spanf* b) {
  rp_spanf cr, cg, cb;
  rp_span_texture_sample(texels, textured, w, h, offset, wrap, u, v, n, &cr, &cg, &cb);
  *r = select(*r, *r * cr, textured);
  *g = select(*g, *g * cg, textured);
  *b = select(*b, *b * cb, textured);
}

/* Mip level `level` (per lane, 0 .. levels - 1) of the lanes' textures (index into the
 * TextureInfo table, level-0 size w0 x h0): its size max(1, w0 >> level) x max(1, h0 >> level)
 * and its first texel from the table (shared/types.h), sampled bilinearly into (r, g, b). */
inline void rp_span_texture_level(__global const uint* texels,
                                  __global const TextureInfo* textures, rp_spani textured,
                                  rp_spanu index, rp_spani w0, rp_spani h0, rp_spani level,
                                  rp_spanf u, rp_spanf v, int n, rp_spanf* r, rp_spanf* g,
                                  rp_spanf* b) {
  rp_spani wl = w0 >> level, hl = h0 >> level;
  wl = select(wl, (rp_spani)(1), wl < 1);
  hl = select(hl, (rp_spani)(1), hl < 1);
  uint idx[RP_SPAN], off[RP_SPAN], wrap[RP_SPAN];
  int lvl[RP_SPAN], on[RP_SPAN];
  RP_SPAN_TO_ARRAY(index, idx);
  RP_SPAN_TO_ARRAY(level, lvl);
  RP_SPAN_TO_ARRAY(textured, on);
  for (int i = 0; i < RP_SPAN; ++i) {
    const bool read = i < n && on[i];
    off[i] = read ? textures[idx[i]].level_offset[lvl[i]] : 0u;
    wrap[i] = read ? textures[idx[i]].wrap : RP_WRAP_REPEAT;
  }
  rp_span_texture_sample(texels, textured, rp_span_convert_float(wl),
                         rp_span_convert_float(hl), RP_SPAN_FROM_ARRAY(off),
                         RP_SPAN_FROM_ARRAY(wrap), u, v, n, r, g, b);
}

/* Trilinear sample at level of detail `lod` (per lane; clamped to [0, levels - 1]): bilinear
 * in levels floor(lod) and the next, mixed by the fraction. The second level is read only when
 * some lane's fraction is not 0 (magnified or clamped lanes need one level). */
/* stochastic != 0: each lane reads ONE level, floor(lod) + 1
 * with probability frac(lod) (pick: per-lane random numbers in [0, 1)), else floor(lod): the
 * trilinear result in expectation at half the taps (the renderer does this under TAA, which
 * averages the frames; kernels/gbuffer.cl). stochastic == 0: the deterministic blend. */
inline void rp_span_texture_trilinear(__global const uint* texels,
                                      __global const TextureInfo* textures, rp_spani textured,
                                      rp_spanu index, rp_spani w0, rp_spani h0, rp_spani levels,
                                      rp_spanf lod, rp_spanf u, rp_spanf v, int n,
                                      int stochastic, rp_spanf pick, rp_spanf* r, rp_spanf* g,
                                      rp_spanf* b) {
  const rp_spanf top = rp_span_convert_float(levels - 1);
  lod = fmin(fmax(lod, 0.0f), top); /* NaN (a degenerate footprint) becomes 0 */
  lod = select((rp_spanf)(0.0f), lod, textured);
  const rp_spanf l0f = floor(lod);
  const rp_spanf frac = lod - l0f;
  const rp_spani l0 = rp_span_convert_int(l0f);
  if (stochastic) {
    const rp_spani up = textured & (pick < frac);
    rp_span_texture_level(texels, textures, textured, index, w0, h0,
                          select(l0, l0 + 1, up), u, v, n, r, g, b);
    return;
  }
  rp_span_texture_level(texels, textures, textured, index, w0, h0, l0, u, v, n, r, g, b);
  const rp_spani blend = textured & (frac > 0.0f);
  int lb[RP_SPAN];
  RP_SPAN_TO_ARRAY(blend, lb);
  bool any_blend = false;
  for (int i = 0; i < n; ++i) any_blend = any_blend || lb[i] != 0;
  if (!any_blend) return;
  rp_spanf r1, g1, b1;
  rp_span_texture_level(texels, textures, blend, index, w0, h0, l0 + 1, u, v, n, &r1,
                        &g1, &b1);
  *r = select(*r, mix(*r, r1, frac), blend);
  *g = select(*g, mix(*g, g1, frac), blend);
  *b = select(*b, mix(*b, b1, frac), blend);
}

#endif
