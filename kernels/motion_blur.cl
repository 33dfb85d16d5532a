/* Motion blur (SPEC 6.8): the reconstruction filter of McGuire, Hennessy, Bukowski and Osman,
 * "A reconstruction filter for plausible motion blur" (I3D 2012), on plain buffers.
 *
 * Velocity convention. The GBuffer velocity is the screen motion over one frame in pixels
 * (current - previous). The blur vector b = velocity * shutter is the streak an object leaves
 * while the shutter is open; the shutter is centred on the frame time, so the object smears
 * b/2 to each side of where it is drawn. The filter works with that half vector
 * V = velocity * shutter / 2 (McGuire's V) and clamps |V| to RP_MB_MAX_RADIUS = the tile size
 * (20 px, so a streak is at most 40 px long): a pixel can then only be reached by blur from
 * objects inside its 3x3 tile neighbourhood, which is what the neighbourhood max covers.
 *
 * Steps (all deterministic: no atomics; every reduction uses a strict total order):
 *   1. motion_blur_tile_max: one 10x10 work-group per 20x20 tile, each item covering 2x2 pixels.
 *      Writes the tile's max-magnitude V (float2 per tile; ties: lower pixel index y * width + x
 *      wins; the magnitude compared is that of the unclamped V, the stored V is clamped).
 *   2. motion_blur_neighbour_max: one item per tile, max |V| over the 3x3 tiles around it
 *      (clamped at the border; ties: first in row-major order of the neighbourhood wins), and a
 *      flag per tile: does the reconstruction read this tile's depth/speed plane.
 *   3. motion_blur_depth_speed (prepass): the depth/speed plane, one half2 per pixel (linear
 *      depth, |V| clamped, in pixels) written with vstore_half2 (round to nearest even), only in
 *      flagged tiles, so a still frame costs almost nothing.
 *   4. motion_blur_reconstruct: one item per pixel. If the neighbourhood max is at most half a
 *      pixel the input is copied unchanged. Else RP_MB_SAMPLES samples along +-V_max (jittered per
 *      pixel) are weighted by a soft depth comparison and the speed cones: a foreground sample
 *      whose own blur reaches the pixel, a background sample seen through the pixel's own blur,
 *      and both blurry (cylinders). The static background therefore does not smear.
 *
 * Buffers: hdr float4 per pixel (rgb linear radiance, a passed through the same filter);
 * velocity float2 per pixel; normal_depth float4 per pixel (w linear depth); depth_speed
 * 2 halves per pixel; tile buffers float2 (plane_needed uint) per tile, tiles_x = ceil(width / 20)
 * per row.
 */
#include "common/random.h"

/* Keep a * b + c as two rounded operations so the C++ reference reproduces the sample
 * positions and magnitudes bit for bit (tests/passes/motion_blur_reference.*). */
#pragma OPENCL FP_CONTRACT OFF

#define RP_MB_TILE 20u
#define RP_MB_GROUP 10u /* work-group side of the tile kernel: 2x2 pixels per item */
#define RP_MB_GROUP_ITEMS (RP_MB_GROUP * RP_MB_GROUP)
#define RP_MB_MAX_RADIUS 20.0f
#ifndef RP_MB_SAMPLES
#define RP_MB_SAMPLES 15 /* odd: the middle sample (the pixel itself) is skipped */
#endif
/* Depth difference (scene units; the box spans 2) over which "in front" fades to "behind". */
#ifndef RP_MB_SOFT_Z
#define RP_MB_SOFT_Z 0.02f
#endif
/* Depths above this go to the half plane as this (half max is 65504; inf - inf would be NaN). */
#define RP_MB_MAX_DEPTH 60000.0f

/* Half blur vector of one pixel before the clamp; non-finite velocities count as still. */
inline float2 rp_mb_half_vector(float2 velocity, float shutter) {
  float2 v = velocity * (shutter * 0.5f);
  return isfinite(v.x) && isfinite(v.y) ? v : (float2)(0.0f, 0.0f);
}

inline float rp_mb_len2(float2 v) { return v.x * v.x + v.y * v.y; }

/* Clamps |v| to RP_MB_MAX_RADIUS (direction kept). */
inline float2 rp_mb_clamp(float2 v) {
  float len2 = rp_mb_len2(v);
  if (len2 > RP_MB_MAX_RADIUS * RP_MB_MAX_RADIUS) v *= RP_MB_MAX_RADIUS / sqrt(len2);
  return v;
}

/* Grid: (tiles_x * 10, tiles_y * 10), local (10, 10). */
__kernel __attribute__((reqd_work_group_size(RP_MB_GROUP, RP_MB_GROUP, 1)))
void motion_blur_tile_max(__global const float2* restrict velocity,
                          __global float2* restrict tile_max, uint width, uint height,
                          float shutter) {
  __local float2 best_v[RP_MB_GROUP_ITEMS];
  __local float best_len2[RP_MB_GROUP_ITEMS];
  __local uint best_index[RP_MB_GROUP_ITEMS];

  const uint lx = (uint)get_local_id(0), ly = (uint)get_local_id(1);
  const uint item = ly * RP_MB_GROUP + lx;
  float2 my_v = (float2)(0.0f, 0.0f);
  float my_len2 = -1.0f; /* below any real magnitude: an empty (outside) item never wins */
  uint my_index = 0xFFFFFFFFu;
  for (uint k = 0; k < 4u; ++k) {
    const uint x = (uint)get_group_id(0) * RP_MB_TILE + lx * 2u + (k & 1u);
    const uint y = (uint)get_group_id(1) * RP_MB_TILE + ly * 2u + (k >> 1);
    if (x >= width || y >= height) continue;
    const uint i = y * width + x;
    const float2 v = rp_mb_half_vector(velocity[i], shutter);
    const float len2 = rp_mb_len2(v);
    /* Pixels are visited in increasing index within an item, so ">" keeps the lower index. */
    if (len2 > my_len2) {
      my_v = v;
      my_len2 = len2;
      my_index = i;
    }
  }
  best_v[item] = my_v;
  best_len2[item] = my_len2;
  best_index[item] = my_index;
  barrier(CLK_LOCAL_MEM_FENCE);

  /* Tree reduction over 100 items (strides 64, 32, ..., 1; the first folds items 64..99). The
   * order (larger len2, then lower index) is total, so the winner does not depend on the tree. */
  for (uint stride = 64u; stride > 0u; stride >>= 1) {
    const uint other = item + stride;
    if (item < stride && other < RP_MB_GROUP_ITEMS) {
      const float l = best_len2[other];
      const uint idx = best_index[other];
      if (l > best_len2[item] || (l == best_len2[item] && idx < best_index[item])) {
        best_v[item] = best_v[other];
        best_len2[item] = l;
        best_index[item] = idx;
      }
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (item == 0u)
    tile_max[get_group_id(1) * get_num_groups(0) + get_group_id(0)] = rp_mb_clamp(best_v[0]);
}

/* Grid: (tiles_x, tiles_y), any local size. */
__kernel void motion_blur_neighbour_max(__global const float2* restrict tile_max,
                                        __global float2* restrict neighbour_max,
                                        __global uint* restrict plane_needed, uint tiles_x,
                                        uint tiles_y) {
  const int tx = (int)get_global_id(0), ty = (int)get_global_id(1);
  if (tx >= (int)tiles_x || ty >= (int)tiles_y) return;
  /* The reconstruction reads the depth/speed plane at its pixel and at samples up to 20 px
   * (one tile) away, and runs where a tile within one tile moves: so the plane is needed where
   * any tile within two tiles (5x5) has a blur radius above half a pixel. */
  uint needed = 0u;
  for (int y = max(ty - 2, 0); y <= min(ty + 2, (int)tiles_y - 1); ++y)
    for (int x = max(tx - 2, 0); x <= min(tx + 2, (int)tiles_x - 1); ++x)
      needed |= rp_mb_len2(tile_max[y * (int)tiles_x + x]) > 0.25f ? 1u : 0u;
  plane_needed[ty * (int)tiles_x + tx] = needed;
  float2 best = (float2)(0.0f, 0.0f);
  float best_len2 = -1.0f;
  for (int dy = -1; dy <= 1; ++dy) {
    const int y = ty + dy;
    if (y < 0 || y >= (int)tiles_y) continue;
    for (int dx = -1; dx <= 1; ++dx) {
      const int x = tx + dx;
      if (x < 0 || x >= (int)tiles_x) continue;
      const float2 v = tile_max[y * (int)tiles_x + x];
      const float len2 = rp_mb_len2(v);
      if (len2 > best_len2) { /* strict: the first in row-major order wins a tie */
        best = v;
        best_len2 = len2;
      }
    }
  }
  neighbour_max[ty * (int)tiles_x + tx] = best;
}

/* The prepass: depth/speed plane, one half2 per pixel (linear depth clamped to [0, 60000],
 * clamped blur radius |V| in pixels), only in tiles flagged by motion_blur_neighbour_max (the
 * rest is never read). Straight-line per-pixel code: PoCL vectorizes it across work-items.
 * Grid: (width, height), any local size. */
__kernel void motion_blur_depth_speed(__global const float2* restrict velocity,
                                      __global const float4* restrict normal_depth,
                                      __global const uint* restrict plane_needed,
                                      __global half* restrict depth_speed, uint width,
                                      uint height, uint tiles_x, float shutter) {
  const uint x = (uint)get_global_id(0), y = (uint)get_global_id(1);
  if (x >= width || y >= height) return;
  if (plane_needed[(y / RP_MB_TILE) * tiles_x + x / RP_MB_TILE] == 0u) return;
  const uint i = y * width + x;
  const float2 v = rp_mb_clamp(rp_mb_half_vector(velocity[i], shutter));
  const float depth = clamp(normal_depth[i].w, 0.0f, RP_MB_MAX_DEPTH);
  vstore_half2((float2)(depth, sqrt(rp_mb_len2(v))), i, depth_speed);
}

/* 1 when za (sample) is in front of zb (pixel), fading to 0 over RP_MB_SOFT_Z behind it. */
inline float rp_mb_soft_depth_compare(float za, float zb) {
  return clamp(1.0f - (za - zb) * (1.0f / RP_MB_SOFT_Z), 0.0f, 1.0f);
}

/* Blur of speed `speed` (pixels, >= 0.5) covers a point `dist` pixels away: a cone 1 -> 0. */
inline float rp_mb_cone(float dist, float speed) {
  return clamp(1.0f - dist / speed, 0.0f, 1.0f);
}

/* ~1 inside the blur radius, ~0 outside, a smooth step over +-5 % of it. */
inline float rp_mb_cylinder(float dist, float speed) {
  const float e0 = 0.95f * speed, e1 = 1.05f * speed;
  const float t = clamp((dist - e0) / (e1 - e0), 0.0f, 1.0f);
  return 1.0f - t * t * (3.0f - 2.0f * t);
}

/* Grid: (width, height), any local size. */
__kernel void motion_blur_reconstruct(__global const float4* restrict hdr_in,
                                      __global const half* restrict depth_speed,
                                      __global const float2* restrict neighbour_max,
                                      __global float4* restrict hdr_out, uint width,
                                      uint height, uint tiles_x) {
  const uint x = (uint)get_global_id(0), y = (uint)get_global_id(1);
  if (x >= width || y >= height) return;
  const uint i = y * width + x;
  const float2 vn = neighbour_max[(y / RP_MB_TILE) * tiles_x + x / RP_MB_TILE];
  if (rp_mb_len2(vn) <= 0.25f) { /* max radius <= half a pixel: nothing visibly moves here */
    hdr_out[i] = hdr_in[i];
    return;
  }
  const float2 zs_x = vload_half2(i, depth_speed);
  const float speed_x = fmax(zs_x.y, 0.5f);
  const float4 c_x = hdr_in[i];
  float weight = 1.0f / speed_x;
  float4 sum = c_x * weight;
  /* Jitter in [-0.5, 0.5): fixed per pixel (no frame index), so a still frame is stable. */
  const float j = rp_hash_to_unit(rp_hash_pixel(x, y, 0u)) - 0.5f;
  const float px = (float)x + 0.5f, py = (float)y + 0.5f;
  for (int s = 0; s < RP_MB_SAMPLES; ++s) {
    if (s == (RP_MB_SAMPLES - 1) / 2) continue;
    const float t = -1.0f + 2.0f * (((float)s + j + 1.0f) / (float)(RP_MB_SAMPLES + 1));
    const int sx = clamp((int)floor(px + vn.x * t), 0, (int)width - 1);
    const int sy = clamp((int)floor(py + vn.y * t), 0, (int)height - 1);
    const uint k = (uint)sy * width + (uint)sx;
    const float2 zs_y = vload_half2(k, depth_speed);
    const float speed_y = fmax(zs_y.y, 0.5f);
    const float ddx = (float)sx - (float)x, ddy = (float)sy - (float)y;
    const float dist = sqrt(ddx * ddx + ddy * ddy);
    const float f = rp_mb_soft_depth_compare(zs_y.x, zs_x.x); /* sample in front of pixel */
    const float b = rp_mb_soft_depth_compare(zs_x.x, zs_y.x); /* sample behind the pixel */
    const float alpha = f * rp_mb_cone(dist, speed_y) + b * rp_mb_cone(dist, speed_x) +
                        rp_mb_cylinder(dist, speed_y) * rp_mb_cylinder(dist, speed_x) * 2.0f;
    weight += alpha;
    sum += hdr_in[k] * alpha;
  }
  hdr_out[i] = sum / weight;
}
