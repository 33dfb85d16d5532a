/* Software sampling of textures and planes stored in plain buffers (OpenCL C only; DESIGN.md:
 * buffers, not images). */
#ifndef ROLYPOLY_COMMON_SAMPLING_H
#define ROLYPOLY_COMMON_SAMPLING_H

#include "common/colour.h"
#include "shared/types.h"

/* i modulo n in [0, n) for any int i (n > 0). */
inline int rp_wrap_index(int i, int n) {
  int r = i % n;
  return r < 0 ? r + n : r;
}

/* Bilinear sample of an RGBA8 sRGB texture with wrap (repeat) addressing, filtered in linear
 * space (each texel decoded first). uv: u right, v up; texel (tx, ty) covers
 * u in [tx, tx+1) / width and (1 - v) in [ty, ty+1) / height (rows top to bottom, types.h),
 * texel centres at +0.5. Returns linear rgb and alpha. */
inline float4 rp_texture_bilinear(__global const uint* texels, __global const TextureInfo* info,
                                  float2 uv) {
  int w = (int)info->width, h = (int)info->height;
  float x = uv.x * (float)w - 0.5f;
  float y = (1.0f - uv.y) * (float)h - 0.5f;
  float x0f = floor(x), y0f = floor(y);
  float fx = x - x0f, fy = y - y0f;
  /* Reduce before converting to int so huge uv (tiling) cannot overflow. */
  x0f -= floor(x0f / (float)w) * (float)w;
  y0f -= floor(y0f / (float)h) * (float)h;
  int x0 = rp_wrap_index((int)x0f, w), y0 = rp_wrap_index((int)y0f, h);
  int x1 = x0 + 1 == w ? 0 : x0 + 1;
  int y1 = y0 + 1 == h ? 0 : y0 + 1;
  __global const uint* base = texels + info->offset;
  float4 t00 = rp_unpack_rgba8_srgb(base[y0 * w + x0]);
  float4 t10 = rp_unpack_rgba8_srgb(base[y0 * w + x1]);
  float4 t01 = rp_unpack_rgba8_srgb(base[y1 * w + x0]);
  float4 t11 = rp_unpack_rgba8_srgb(base[y1 * w + x1]);
  return mix(mix(t00, t10, fx), mix(t01, t11, fx), fy);
}

/* Bilinear sample of a planar float4 image (width x height, row-major, top row first) at pixel
 * coordinates `pos` (pixel centres at +0.5), clamp-to-edge addressing. */
inline float4 rp_plane_bilinear_clamp(__global const float4* plane, int width, int height,
                                      float2 pos) {
  float x = clamp(pos.x - 0.5f, 0.0f, (float)(width - 1));
  float y = clamp(pos.y - 0.5f, 0.0f, (float)(height - 1));
  int x0 = (int)x, y0 = (int)y;
  float fx = x - (float)x0, fy = y - (float)y0;
  int x1 = min(x0 + 1, width - 1), y1 = min(y0 + 1, height - 1);
  float4 a = mix(plane[y0 * width + x0], plane[y0 * width + x1], fx);
  float4 b = mix(plane[y1 * width + x0], plane[y1 * width + x1], fx);
  return mix(a, b, fy);
}

#endif
