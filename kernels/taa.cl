/* Temporal anti-aliasing resolve (SPEC 6.7), one work-item per pixel on a 2D range rounded up
 * to the 8x8 work-group (bounds-checked). Straight-line per-pixel float4 code, no atomics, no
 * local memory: every output depends only on the inputs, so runs are bit-identical.
 *
 * Buffers (planar, row-major, top row first; src/render/frame_buffers.h):
 *   hdr_in       float4  linear HDR radiance of this (jittered) frame, w passed through
 *   velocity     float2  pixels, this frame minus previous (+y down), unjittered
 *   normal_depth float4  w = linear view depth (picks the velocity, below)
 *   history_in   float4  previous resolved frame, TONE-MAPPED rgb T(x) = x / (1 + x), w = 1
 *   history_out  float4  this resolved frame, tone-mapped (next frame's history_in)
 *   hdr_out      float4  this resolved frame back in linear HDR: T^-1(history_out.rgb), w of hdr_in
 *
 * Per pixel, on tone-mapped values (common/colour.h):
 *   1. Current colour c = T(hdr_in) at the pixel. The jittered samples are what TAA averages:
 *      pixel p of frame k saw the scene at p - jitter_k, so accumulating them integrates the
 *      pixel footprint. With unjitter = 1, c is instead hdr_in sampled bilinearly at the pixel
 *      centre + jitter (where the unjittered pixel centre landed; the jittered view_proj moves
 *      points by +jitter pixels) - a steadier but softer image.
 *   2. 5-tap cross (centre, left, right, up, down; clamped at borders) in YCoCg: mean m and
 *      standard deviation s; box = m +- gamma * s.
 *   3. Velocity of the nearest surface in the cross (smallest depth; the centre wins ties), so
 *      the silhouettes of moving objects reproject with the object, not the background.
 *   4. History at previous position = pixel centre - velocity, bilinear (clamp to edge). Outside
 *      [0, width] x [0, height], or when history_valid = 0 (reset / resize), history = c.
 *   5. History clipped toward the box centre (common/taa.h), then
 *      out = hist * history_weight + c * (1 - history_weight).
 */
#include "common/colour.h"
#include "common/sampling.h"
#include "common/taa.h"

__kernel void taa_resolve(__global const float4* restrict hdr_in,
                          __global const float2* restrict velocity,
                          __global const float4* restrict normal_depth,
                          __global const float4* restrict history_in,
                          __global float4* restrict history_out,
                          __global float4* restrict hdr_out,
                          uint width, uint height,
                          float jitter_x, float jitter_y, /* this frame's jitter, pixels */
                          float history_weight, float gamma, uint history_valid, uint unjitter) {
  const int x = (int)get_global_id(0), y = (int)get_global_id(1);
  const int w = (int)width, h = (int)height;
  if (x >= w || y >= h) return;
  const int i = y * w + x;

  /* Cross neighbourhood indices, clamped to the image. */
  const int il = y * w + max(x - 1, 0), ir = y * w + min(x + 1, w - 1);
  const int iu = max(y - 1, 0) * w + x, id = min(y + 1, h - 1) * w + x;

  const float4 centre_hdr = hdr_in[i];
  const float3 t0 = rp_tone_map(centre_hdr.xyz);
  const float3 y0 = rp_rgb_to_ycocg(t0);
  const float3 y1 = rp_rgb_to_ycocg(rp_tone_map(hdr_in[il].xyz));
  const float3 y2 = rp_rgb_to_ycocg(rp_tone_map(hdr_in[ir].xyz));
  const float3 y3 = rp_rgb_to_ycocg(rp_tone_map(hdr_in[iu].xyz));
  const float3 y4 = rp_rgb_to_ycocg(rp_tone_map(hdr_in[id].xyz));
  const float3 mean = (y0 + y1 + y2 + y3 + y4) * 0.2f;
  const float3 mean_sq = (y0 * y0 + y1 * y1 + y2 * y2 + y3 * y3 + y4 * y4) * 0.2f;
  const float3 stddev = sqrt(fmax(mean_sq - mean * mean, (float3)(0.0f)));

  const float2 centre = (float2)((float)x + 0.5f, (float)y + 0.5f);
  float3 current = t0;
  if (unjitter != 0u)
    current = rp_tone_map(
        rp_plane_bilinear_clamp(hdr_in, w, h, centre + (float2)(jitter_x, jitter_y)).xyz);

  /* Nearest surface in the cross: its velocity (strict < so the centre wins ties). */
  int nearest = i;
  float nearest_depth = normal_depth[i].w;
  const float dl = normal_depth[il].w, dr = normal_depth[ir].w;
  const float du = normal_depth[iu].w, dd = normal_depth[id].w;
  if (dl < nearest_depth) { nearest = il; nearest_depth = dl; }
  if (dr < nearest_depth) { nearest = ir; nearest_depth = dr; }
  if (du < nearest_depth) { nearest = iu; nearest_depth = du; }
  if (dd < nearest_depth) { nearest = id; nearest_depth = dd; }
  const float2 prev = centre - velocity[nearest];

  const bool on_screen = prev.x >= 0.0f && prev.y >= 0.0f && prev.x <= (float)w &&
                         prev.y <= (float)h;
  float3 result = current;
  if (history_valid != 0u && on_screen) {
    const float3 hist = rp_plane_bilinear_clamp(history_in, w, h, prev).xyz;
    const float3 clipped =
        rp_ycocg_to_rgb(rp_taa_clip(rp_rgb_to_ycocg(hist), mean, gamma * stddev));
    result = clamp(clipped * history_weight + current * (1.0f - history_weight), 0.0f, 1.0f);
  }
  history_out[i] = (float4)(result, 1.0f);
  hdr_out[i] = (float4)(rp_tone_map_inverse(result), centre_hdr.w);
}
