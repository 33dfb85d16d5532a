/* Bilinear texture sampling for pixel spans (common/span.h; OpenCL C only), used by gbuffer.cl
 * and voxelize.cl. Textures are read as linear float4 texels (each pass decodes the scene's
 * RGBA8 sRGB texels once with rp_unpack_rgba8_srgb), so a tap is one load and the filtering is
 * vector arithmetic across the span. */
#ifndef ROLYPOLY_COMMON_SPAN_TEXTURE_H
#define ROLYPOLY_COMMON_SPAN_TEXTURE_H

#include "common/span.h"

/* Texture sampling of the lanes with `textured` set (bilinear, wrap; the arithmetic of
 * sampling.h's rp_texture_bilinear on linear texels, so the same values): (w, h) the lane's
 * texture size in texels, offset its first texel in linear_texels (float4 linear rgba per
 * texel, rows top to bottom). Multiplies (r, g, b) of those lanes in place; lanes >= n and
 * untextured lanes read nothing. */
inline void rp_span_texture_linear(__global const float4* linear_texels, rp_spani textured,
                                   rp_spanf w, rp_spanf h, rp_spanu offset, rp_spanf u,
                                   rp_spanf v, int n, rp_spanf* r, rp_spanf* g, rp_spanf* b) {
  /* Untextured lanes sample (0, 0) of a 1x1 texture (ignored below): no NaN reaches the int
   * conversions. */
  u = select((rp_spanf)(0.0f), u, textured);
  v = select((rp_spanf)(0.0f), v, textured);
  const rp_spanf x = u * w - 0.5f;
  const rp_spanf y = (1.0f - v) * h - 0.5f;
  rp_spanf x0f = floor(x), y0f = floor(y);
  const rp_spanf fx = x - x0f, fy = y - y0f;
  /* Wrap into [0, size) in float (exact for integers below 2^24), so huge uv (tiling) cannot
   * overflow the int conversion; the int result may still be size after rounding or -1 for a
   * tiny negative quotient: fold those back (the old rp_wrap_index). */
  x0f -= floor(x0f / w) * w;
  y0f -= floor(y0f / h) * h;
  const rp_spani wi = rp_span_convert_int(w), hi = rp_span_convert_int(h);
  rp_spani x0 = rp_span_convert_int(x0f), y0 = rp_span_convert_int(y0f);
  x0 = select(x0, x0 - wi, x0 >= wi);
  y0 = select(y0, y0 - hi, y0 >= hi);
  x0 = select(x0, x0 + wi, x0 < 0);
  y0 = select(y0, y0 + hi, y0 < 0);
  const rp_spani x1 = select(x0 + 1, (rp_spani)(0), x0 + 1 == wi);
  const rp_spani y1 = select(y0 + 1, (rp_spani)(0), y0 + 1 == hi);
  /* Texel indices of the four taps (offset + row * width + column). */
  const rp_spanu row0 = offset + rp_span_convert_uint(y0 * wi);
  const rp_spanu row1 = offset + rp_span_convert_uint(y1 * wi);
  uint i00[RP_SPAN], i10[RP_SPAN], i01[RP_SPAN], i11[RP_SPAN];
  int on[RP_SPAN];
  RP_SPAN_TO_ARRAY(row0 + rp_span_convert_uint(x0), i00);
  RP_SPAN_TO_ARRAY(row0 + rp_span_convert_uint(x1), i10);
  RP_SPAN_TO_ARRAY(row1 + rp_span_convert_uint(x0), i01);
  RP_SPAN_TO_ARRAY(row1 + rp_span_convert_uint(x1), i11);
  RP_SPAN_TO_ARRAY(textured, on);
  /* The four taps per lane (untextured lanes keep 0). */
  float4 q00[RP_SPAN], q10[RP_SPAN], q01[RP_SPAN], q11[RP_SPAN];
  for (int i = 0; i < RP_SPAN; ++i) {
    float4 t00 = (float4)(0.0f), t10 = t00, t01 = t00, t11 = t00;
    if (i < n && on[i]) {
      t00 = linear_texels[i00[i]];
      t10 = linear_texels[i10[i]];
      t01 = linear_texels[i01[i]];
      t11 = linear_texels[i11[i]];
    }
    q00[i] = t00;
    q10[i] = t10;
    q01[i] = t01;
    q11[i] = t11;
  }
  rp_spanf r00, g00, b00, r10, g10, b10, r01, g01, b01, r11, g11, b11;
  rp_span_from_float4s(q00, &r00, &g00, &b00);
  rp_span_from_float4s(q10, &r10, &g10, &b10);
  rp_span_from_float4s(q01, &r01, &g01, &b01);
  rp_span_from_float4s(q11, &r11, &g11, &b11);
  rp_spanf c[3];
  c[0] = mix(mix(r00, r10, fx), mix(r01, r11, fx), fy);
  c[1] = mix(mix(g00, g10, fx), mix(g01, g11, fx), fy);
  c[2] = mix(mix(b00, b10, fx), mix(b01, b11, fx), fy);
  *r = select(*r, *r * c[0], textured);
  *g = select(*g, *g * c[1], textured);
  *b = select(*b, *b * c[2], textured);
}

#endif
