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
 *   1. motion_blur_tile_max: one 1x20 work-group per 20x20 tile, each item one pixel row of it
 *      (20 pixels in vector arithmetic), then a reduction over the rows in local memory.
 *      Writes the tile's max-magnitude V (float2 per tile; ties: lower pixel index y * width + x
 *      wins; the magnitude compared is that of the unclamped V, the stored V is clamped).
 *   2. motion_blur_neighbour_max: one item per tile, max |V| over the 3x3 tiles around it
 *      (clamped at the border; ties: first in row-major order of the neighbourhood wins), and a
 *      flag per tile: does the reconstruction read this tile's depth/speed plane.
 *   3. motion_blur_depth_speed (prepass): the depth/speed plane, one half2 per pixel (linear
 *      depth, |V| clamped, in pixels) rounded to nearest even as vstore_half2 does, only in
 *      flagged tiles, so a still frame costs almost nothing; one item per tile row of 20 pixels.
 *   4. motion_blur_composite: the image outside the moving tiles, 16 pixels of two rows per
 *      item: the output is the input, with the bloom composited when the bloom is fused in
 *      (common/bloom_composite.h; without it the host copies the whole buffer instead).
 *   5. motion_blur_reconstruct: one item per 4x4 pixel block, over every tile; blocks in tiles
 *      whose neighbourhood max is at most half a pixel return at once (step 4 wrote them).
 *      Else S samples along +-V_max (jittered per pixel; S = 2 ceil(|V_max|) + 1, at most
 *      RP_MB_SAMPLES: about one sample per pixel of the streak) are weighted by a soft depth
 *      comparison and the speed cones: a foreground sample whose own blur reaches the pixel, a
 *      background sample seen through the pixel's own blur, and both blurry (cylinders). The
 *      static background therefore does not smear. The block's 16 pixels are the 16 lanes of
 *      float16 vectors (PoCL does not vectorize this loop across work-items, DESIGN.md); the
 *      samples are gathered per lane. The bloom, when fused, is composited onto the result.
 *
 * Buffers: hdr float4 per pixel (rgb linear radiance, a passed through the same filter);
 * velocity float2 per pixel; normal_depth float4 per pixel (w linear depth); depth_speed
 * 2 halves per pixel; tile buffers float2 (plane_needed uint) per tile, tiles_x = ceil(width / 20)
 * per row.
 */
#include "shared/types.h"
#include "shared/pass_params.h"
#include "common/bloom_composite.h" /* before the pragma: same contraction as bloom.cl */
#include "common/random.h"
#include "common/depth_speed.h"

/* Keep a * b + c as two rounded operations so the C++ reference reproduces the sample
 * positions and magnitudes bit for bit (tests/passes/motion_blur_reference.*). */
#pragma OPENCL FP_CONTRACT OFF

#define RP_MB_TILE 20u
#ifndef RP_MB_SAMPLES
#define RP_MB_SAMPLES 15 /* odd: the middle sample (the pixel itself) is skipped */
#endif
/* Depth difference (scene units; the box spans 2) over which "in front" fades to "behind". */
#ifndef RP_MB_SOFT_Z
#define RP_MB_SOFT_Z 0.02f
#endif
/* A 4x4 block of a moving tile is "quiet" when every blur radius within reach of it (its pixels'
 * samples lie at most ceil(|V_max|) + 1 px away) is at most this: then every sample at a
 * distance >= 1 px gets weight 0 exactly (the cone needs radius > distance; the cylinder's smooth
 * step ends at distance / radius = 1.05 < 1 / 0.95) and the samples on the pixel itself give its
 * own colour, so the filter returns the pixel (up to rounding) and the block is copied. */
#define RP_MB_QUIET_SPEED 0.95f

inline float rp_mb_len2(float2 v) { return v.x * v.x + v.y * v.y; }

/* Clamps |v| to RP_MB_MAX_RADIUS (direction kept). */
inline float2 rp_mb_clamp(float2 v) {
  float len2 = rp_mb_len2(v);
  if (len2 > RP_MB_MAX_RADIUS * RP_MB_MAX_RADIUS) v *= RP_MB_MAX_RADIUS / sqrt(len2);
  return v;
}

/* The half vectors of 20 consecutive pixels of a row (pixels x0 .. x0+19 of the float2 velocity
 * row `row`; lanes at or beyond `width` - x0 are zero) as 16 + 4 lanes, and their squared
 * magnitudes (-1 for lanes outside the image, so they never win a max). */
inline void rp_mb_row20(__global const float* row, int x0, int width, float shutter,
                        float16* hx, float16* hy, float4* hx4, float4* hy4, float16* len2,
                        float4* len2_4) {
  float16 a, b;
  float8 c;
  if (x0 + 19 < width) {
    a = vload16(0, row + 2 * x0);
    b = vload16(1, row + 2 * x0);
    c = vload8(4, row + 2 * x0);
  } else {
    float t[40];
    for (int i = 0; i < 20; ++i) {
      const bool inside = x0 + i < width;
      t[2 * i] = inside ? row[2 * (x0 + i)] : 0.0f;
      t[2 * i + 1] = inside ? row[2 * (x0 + i) + 1] : 0.0f;
    }
    a = vload16(0, t);
    b = vload16(1, t);
    c = vload8(4, t);
  }
  const float k = shutter * 0.5f;
  float16 vx = (float16)(a.even, b.even) * k, vy = (float16)(a.odd, b.odd) * k;
  float4 vx4 = c.even * k, vy4 = c.odd * k;
  /* Half blur vectors V = velocity * shutter / 2; non-finite velocities count as still. */
  const int16 finite = isfinite(vx) & isfinite(vy);
  const int4 finite4 = isfinite(vx4) & isfinite(vy4);
  vx = select((float16)0.0f, vx, finite);
  vy = select((float16)0.0f, vy, finite);
  vx4 = select((float4)0.0f, vx4, finite4);
  vy4 = select((float4)0.0f, vy4, finite4);
  const int16 lane = (int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const float16 l2 = vx * vx + vy * vy;
  const float4 l2_4 = vx4 * vx4 + vy4 * vy4;
  *len2 = select(l2, (float16)-1.0f, x0 + lane >= width);
  *len2_4 = select(l2_4, (float4)-1.0f, x0 + 16 + lane.s0123 >= width);
  *hx = vx;
  *hy = vy;
  *hx4 = vx4;
  *hy4 = vy4;
}

/* Step 1. Grid: (tiles_x, 20 * tiles_y), local (1, 20): one work-group per tile, one work-item
 * per pixel row of it. Each item finds its row's largest |V| (ties: the leftmost) with vector
 * arithmetic; the group then reduces the 20 rows in local memory, top to bottom with a strict
 * ">", so the lowest pixel index wins a tie. */
__kernel __attribute__((reqd_work_group_size(1, RP_MB_TILE, 1)))
void motion_blur_tile_max(__global const float2* restrict velocity,
                          __global float2* restrict tile_max, const MotionBlurParams params) {
  const uint width = params.width, height = params.height;
  const float shutter = params.shutter;
  __local float2 best_v[RP_MB_TILE];
  __local float best_len2[RP_MB_TILE];

  const int row = (int)get_local_id(1);
  const int x0 = (int)get_group_id(0) * (int)RP_MB_TILE;
  const int y = (int)get_group_id(1) * (int)RP_MB_TILE + row;
  float2 my_v = (float2)(0.0f, 0.0f);
  float my_len2 = -1.0f; /* below any real magnitude: a row outside the image never wins */
  if (y < (int)height) {
    float16 hx, hy, len2;
    float4 hx4, hy4, len2_4;
    rp_mb_row20((__global const float*)(velocity + y * (int)width), x0, (int)width, shutter, &hx,
                &hy, &hx4, &hy4, &len2, &len2_4);
    const float8 m8 = fmax(len2.lo, len2.hi);
    const float4 m4 = fmax(fmax(m8.lo, m8.hi), len2_4);
    const float m = fmax(fmax(m4.x, m4.y), fmax(m4.z, m4.w));
    /* The leftmost lane holding the max. */
    const int16 lane = (int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const int16 first16 = select((int16)99, lane, len2 == m);
    const int4 first4 = select((int4)99, lane.s0123 + 16, len2_4 == m);
    const int8 f8 = min(first16.lo, first16.hi);
    const int4 f4 = min(min(f8.lo, f8.hi), first4);
    const int first = min(min(f4.x, f4.y), min(f4.z, f4.w));
    float vxs[20], vys[20];
    vstore16(hx, 0, vxs);
    vstore4(hx4, 0, vxs + 16);
    vstore16(hy, 0, vys);
    vstore4(hy4, 0, vys + 16);
    my_v = (float2)(vxs[first], vys[first]);
    my_len2 = m;
  }
  best_v[row] = my_v;
  best_len2[row] = my_len2;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (row == 0) {
    float2 v = best_v[0];
    float l = best_len2[0];
    for (int r = 1; r < (int)RP_MB_TILE; ++r)
      if (best_len2[r] > l) {
        l = best_len2[r];
        v = best_v[r];
      }
    tile_max[get_group_id(1) * get_num_groups(0) + get_group_id(0)] = rp_mb_clamp(v);
  }
}

/* Grid: (tiles_x, tiles_y), any local size. */
__kernel void motion_blur_neighbour_max(__global const float2* restrict tile_max,
                                        __global float2* restrict neighbour_max,
                                        __global uint* restrict plane_needed,
                                        const MotionBlurParams params) {
  const uint tiles_x = params.tiles_x, tiles_y = params.tiles_y;
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

/* Step 3, the prepass: the depth/speed plane, one half2 per pixel (linear depth clamped to
 * [0, 60000], clamped blur radius |V| in pixels; stored as one uint per pixel, depth in the low
 * half as vstore_half2 would on the little-endian devices OpenCL runs on), only in tiles flagged
 * by motion_blur_neighbour_max (the rest is never read). Grid: (tiles_x, 20 * tiles_y), any
 * local size: one work-item per pixel row of a tile, 20 pixels in vector arithmetic. */
__kernel void motion_blur_depth_speed(__global const float2* restrict velocity,
                                      __global const float4* restrict normal_depth,
                                      __global const uint* restrict plane_needed,
                                      __global half* restrict depth_speed,
                                      const MotionBlurParams params) {
  const uint width = params.width, height = params.height, tiles_x = params.tiles_x;
  const float shutter = params.shutter;
  const int tx = (int)get_global_id(0), y = (int)get_global_id(1);
  if (tx >= (int)tiles_x || y >= (int)height) return;
  if (plane_needed[(y / (int)RP_MB_TILE) * (int)tiles_x + tx] == 0u) return;
  const int x0 = tx * (int)RP_MB_TILE, row = y * (int)width;
  float16 hx, hy, len2;
  float4 hx4, hy4, len2_4;
  rp_mb_row20((__global const float*)(velocity + row), x0, (int)width, shutter, &hx, &hy, &hx4,
              &hy4, &len2, &len2_4);
  /* |V| clamped to RP_MB_MAX_RADIUS as rp_mb_clamp does: v * (R / sqrt(len2)) when longer. */
  const int16 longer = len2 > RP_MB_MAX_RADIUS * RP_MB_MAX_RADIUS;
  const int4 longer4 = len2_4 > RP_MB_MAX_RADIUS * RP_MB_MAX_RADIUS;
  const float16 k = RP_MB_MAX_RADIUS / sqrt(len2);
  const float4 k4 = RP_MB_MAX_RADIUS / sqrt(len2_4);
  hx = select(hx, hx * k, longer);
  hy = select(hy, hy * k, longer);
  hx4 = select(hx4, hx4 * k4, longer4);
  hy4 = select(hy4, hy4 * k4, longer4);
  const float16 speed = sqrt(hx * hx + hy * hy);
  const float4 speed4 = sqrt(hx4 * hx4 + hy4 * hy4);
  float d[20];
  for (int i = 0; i < 20; ++i) d[i] = normal_depth[row + min(x0 + i, (int)width - 1)].w;
  const float16 depth = clamp(vload16(0, d), 0.0f, RP_MB_MAX_DEPTH);
  const float4 depth4 = clamp(vload4(0, d + 16), 0.0f, RP_MB_MAX_DEPTH);
  const uint16 packed = rp_mb_float_to_half16(depth) | (rp_mb_float_to_half16(speed) << 16);
  const uint4 packed4 = rp_mb_float_to_half4(depth4) | (rp_mb_float_to_half4(speed4) << 16);
  __global uint* out = (__global uint*)depth_speed + row + x0;
  if (x0 + 19 < (int)width) {
    vstore16(packed, 0, out);
    vstore4(packed4, 0, out + 16);
    return;
  }
  uint t[20];
  vstore16(packed, 0, t);
  vstore4(packed4, 0, t + 16);
  for (int i = 0; x0 + i < (int)width; ++i) out[i] = t[i];
}

/* Weights on 16 lanes. Soft depth comparison: 1 when za (sample) is in front of zb (pixel),
 * fading to 0 over RP_MB_SOFT_Z behind it. */
inline float16 rp_mb_soft_depth_compare16(float16 za, float16 zb) {
  return clamp(1.0f - (za - zb) * (1.0f / RP_MB_SOFT_Z), 0.0f, 1.0f);
}

/* Both speed terms of a sample from q = dist / speed (dist: pixels from the pixel to the sample,
 * speed: a blur radius in pixels, >= 0.5): the cone (does a blur of that radius cover a point
 * dist away: 1 -> 0) and the cylinder (~1 inside the radius, ~0 outside, a smooth step over
 * +-5 % of it: t = (dist - 0.95 speed) / (0.1 speed) = (q - 0.95) * 10). */
inline float16 rp_mb_cone16(float16 q) { return clamp(1.0f - q, 0.0f, 1.0f); }
inline float16 rp_mb_cylinder16(float16 q) {
  const float16 t = clamp((q - 0.95f) * 10.0f, 0.0f, 1.0f);
  return 1.0f - t * t * (3.0f - 2.0f * t);
}

/* Step 4. Grid: (ceil(width / 16), ceil(height / 2)), any local size. Items whose pixels all
 * lie in moving tiles (neighbourhood max above half a pixel) are left to step 5; the others are
 * written whole (step 5 overwrites their moving part). */
__kernel void motion_blur_composite(__global const float4* restrict hdr_in,
                                    __global const float* restrict bloom_level1,
                                    __global const float2* restrict neighbour_max,
                                    __global float4* restrict hdr_out,
                                    const MotionBlurParams params) {
  const int level1_w = (int)params.bloom_width, level1_h = (int)params.bloom_height;
  const float keep = params.bloom_keep, scale = params.bloom_scale;
  const int tiles_x = (int)params.tiles_x, width = (int)params.width,
            height = (int)params.height;
  const int gx = (int)get_global_id(0), n = (int)get_global_id(1);
  const int x0 = 16 * gx;
  if (x0 >= width || 2 * n >= height) return;
  /* Rows 2n and 2n+1 share a tile row (the tile side is even); columns x0 .. x0+15 span at
   * most two tiles. */
  __global const float2* tiles = neighbour_max + (2 * n / (int)RP_MB_TILE) * tiles_x;
  if (rp_mb_len2(tiles[x0 / (int)RP_MB_TILE]) > 0.25f &&
      rp_mb_len2(tiles[min(x0 + 15, width - 1) / (int)RP_MB_TILE]) > 0.25f)
    return;
  rp_bloom_composite_rows(hdr_in, bloom_level1, level1_w, level1_h, hdr_out, width, height, gx,
                          n, keep, scale);
}

/* Samples for a neighbourhood max radius of sqrt(len2) pixels (len2 > 0.25): odd, 3 .. 15. */
inline int rp_mb_sample_count(float len2) {
  return min(2 * (int)ceil(sqrt(len2)) + 1, RP_MB_SAMPLES);
}

/* rp_hash_u32 (common/random.h) on 16 lanes. */
inline uint16 rp_mb_hash16(uint16 v) {
  const uint16 state = v * 747796405u + 2891336453u;
  const uint16 word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

/* IEEE binary16 bits (low 16 bits of h) to float on 16 lanes, exact for every value (what
 * vload_half does; done here in vector arithmetic because the gathers load the half2 pairs as
 * uints, and a per-lane vload_half2 costs more than the filter's arithmetic on PoCL). */
inline float16 rp_mb_half_to_float16(uint16 h) {
  const uint16 sign = (h & 0x8000u) << 16, exponent = (h >> 10) & 0x1Fu, mantissa = h & 0x3FFu;
  /* Normal: rebias the exponent (127 - 15 = 112); infinity / NaN: all-ones exponent. */
  const uint16 normal = ((exponent + 112u) << 23) | (mantissa << 13);
  const uint16 special = 0x7F800000u | (mantissa << 13);
  /* Subnormal and zero: mantissa * 2^-24, exact in float. */
  const uint16 tiny = as_uint16(convert_float16(mantissa) * 5.9604644775390625e-8f);
  const uint16 bits = exponent == 0u ? tiny : (exponent == 31u ? special : normal);
  return as_float16(bits | sign);
}

/* Lane l of a 16-vector by a constant index, for the per-lane gathers. */
#define RP_MB_LANES(M) M(0) M(1) M(2) M(3) M(4) M(5) M(6) M(7) M(8) M(9) M(a) M(b) M(c) M(d) M(e) M(f)

/* McGuire's filter for the 16 pixels of a block (xs, ys: their coordinates, clamped into the
 * image; result: their colours on entry, the filtered colours on return). */
inline void rp_mb_filter_block(__global const float4* restrict hdr_in,
                               __global const half* restrict depth_speed, float2 vn, int samples,
                               int16 xs, int16 ys, int width, int height, float4 result[16]) {
  /* The depth/speed plane as one uint per pixel: depth in the low half, speed in the high. */
  __global const uint* zs_plane = (__global const uint*)depth_speed;
  const int16 centre = ys * width + xs;
  uint16 zs_x;
#define RP_MB_CENTRE(L) zs_x.s##L = zs_plane[centre.s##L];
  RP_MB_LANES(RP_MB_CENTRE)
#undef RP_MB_CENTRE
  const float16 z_x = rp_mb_half_to_float16(zs_x);
  const float16 speed_x = fmax(rp_mb_half_to_float16(zs_x >> 16), 0.5f);
  float16 weight = 1.0f / speed_x;
  float4 sum[16];
#define RP_MB_INIT(L) sum[0x##L] = result[0x##L] * weight.s##L;
  RP_MB_LANES(RP_MB_INIT)
#undef RP_MB_INIT
  /* Jitter in [-0.5, 0.5): fixed per pixel (no frame index), so a still frame is stable. */
  const uint16 hash = rp_mb_hash16(convert_uint16(xs) ^
                                   rp_mb_hash16(convert_uint16(ys) ^ rp_hash_u32(0u)));
  const float16 j = convert_float16(hash >> 8) * (1.0f / 16777216.0f) - 0.5f;
  const float16 px = convert_float16(xs) + 0.5f, py = convert_float16(ys) + 0.5f;
  /* Sample s sits at t = (s + 1 + j) * 2 / (samples + 1) - 1 in (-1, 1) along +-V_max. */
  const float step = 2.0f / (float)(samples + 1);
  for (int s = 0; s < samples; ++s) {
    if (s == (samples - 1) / 2) continue;
    const float16 t = ((float)s + 1.0f + j) * step - 1.0f;
    const int16 sx =
        clamp(convert_int16(floor(px + vn.x * t)), (int16)0, (int16)(width - 1));
    const int16 sy =
        clamp(convert_int16(floor(py + vn.y * t)), (int16)0, (int16)(height - 1));
    const int16 k = sy * width + sx;
    uint16 zs_y;
#define RP_MB_GATHER(L) zs_y.s##L = zs_plane[k.s##L];
    RP_MB_LANES(RP_MB_GATHER)
#undef RP_MB_GATHER
    const float16 z_y = rp_mb_half_to_float16(zs_y);
    const float16 speed_y = fmax(rp_mb_half_to_float16(zs_y >> 16), 0.5f);
    const float16 ddx = convert_float16(sx - xs), ddy = convert_float16(sy - ys);
    const float16 dist = sqrt(ddx * ddx + ddy * ddy);
    const float16 f = rp_mb_soft_depth_compare16(z_y, z_x); /* sample in front of pixel */
    const float16 b = rp_mb_soft_depth_compare16(z_x, z_y); /* sample behind the pixel */
    const float16 q_y = dist / speed_y, q_x = dist / speed_x;
    const float16 alpha = f * rp_mb_cone16(q_y) + b * rp_mb_cone16(q_x) +
                          rp_mb_cylinder16(q_y) * rp_mb_cylinder16(q_x) * 2.0f;
    weight += alpha;
#define RP_MB_ACCUMULATE(L) sum[0x##L] += hdr_in[k.s##L] * alpha.s##L;
    RP_MB_LANES(RP_MB_ACCUMULATE)
#undef RP_MB_ACCUMULATE
  }
#define RP_MB_RESULT(L) result[0x##L] = sum[0x##L] / weight.s##L;
  RP_MB_LANES(RP_MB_RESULT)
#undef RP_MB_RESULT
}

/* Step 3b. The largest blur radius (pixels, from the half plane) of every 4x4 pixel block of the
 * flagged tiles: float per block, blocks_x = 5 * tiles_x per row. Grid: (5 * tiles_x,
 * 5 * tiles_y), any local size. */
__kernel void motion_blur_block_max(__global const half* restrict depth_speed,
                                    __global const uint* restrict plane_needed,
                                    __global float* restrict block_speed,
                                    const MotionBlurParams params) {
  const int width = (int)params.width, height = (int)params.height,
            tiles_x = (int)params.tiles_x;
  const int bx = (int)get_global_id(0), by = (int)get_global_id(1);
  const int x0 = 4 * bx, y0 = 4 * by;
  if (x0 >= width || y0 >= height) return;
  if (plane_needed[(y0 / (int)RP_MB_TILE) * tiles_x + x0 / (int)RP_MB_TILE] == 0u) return;
  const int16 lane = (int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const int16 xs = min(x0 + (lane & 3), (int16)(width - 1));
  const int16 ys = min(y0 + (lane >> 2), (int16)(height - 1));
  const int16 index = ys * width + xs;
  __global const uint* zs_plane = (__global const uint*)depth_speed;
  uint16 zs;
#define RP_MB_LOAD(L) zs.s##L = zs_plane[index.s##L];
  RP_MB_LANES(RP_MB_LOAD)
#undef RP_MB_LOAD
  const float16 speed = rp_mb_half_to_float16(zs >> 16);
  const float8 m8 = fmax(speed.lo, speed.hi);
  const float4 m4 = fmax(m8.lo, m8.hi);
  block_speed[by * 5 * tiles_x + bx] = fmax(fmax(m4.x, m4.y), fmax(m4.z, m4.w));
}

/* Step 5. Grid: (5 * tiles_x, 5 * tiles_y), any local size: item (bx, by) is the block at
 * pixel (4bx, 4by) (five blocks per tile side). bloom_level1 is read only when fuse_bloom != 0
 * (it may be any buffer otherwise). */
__kernel void motion_blur_reconstruct(__global const float4* restrict hdr_in,
                                      __global const half* restrict depth_speed,
                                      __global const float2* restrict neighbour_max,
                                      __global const float* restrict block_speed,
                                      __global const float* restrict bloom_level1,
                                      __global float4* restrict hdr_out,
                                      const MotionBlurParams params) {
  const int level1_w = (int)params.bloom_width, level1_h = (int)params.bloom_height;
  const float keep = params.bloom_keep, scale = params.bloom_scale;
  const int fuse_bloom = (int)params.fuse_bloom;
  const int width = (int)params.width, height = (int)params.height,
            tiles_x = (int)params.tiles_x;
  const int bx = (int)get_global_id(0), by = (int)get_global_id(1);
  const int x0 = 4 * bx, y0 = 4 * by;
  if (x0 >= width || y0 >= height) return;
  const int tx = x0 / (int)RP_MB_TILE, ty = y0 / (int)RP_MB_TILE;
  const float2 vn = neighbour_max[ty * tiles_x + tx];
  const float vn_len2 = rp_mb_len2(vn);
  if (vn_len2 <= 0.25f) return; /* max radius <= half a pixel: step 4 wrote these pixels */
  const int samples = rp_mb_sample_count(vn_len2);
  /* Quiet block? The blocks within reach, inside the tile's 3x3 neighbourhood (where every
   * sample lies) and the image. */
  const int reach = (int)ceil(sqrt(vn_len2)) + 1;
  const int blocks_x = 5 * tiles_x;
  const int bx_lo = max(max(x0 - reach, 0) / 4, 5 * (tx - 1));
  const int bx_hi = min(min(x0 + 3 + reach, width - 1) / 4, 5 * (tx + 2) - 1);
  const int by_lo = max(max(y0 - reach, 0) / 4, 5 * (ty - 1));
  const int by_hi = min(min(y0 + 3 + reach, height - 1) / 4, 5 * (ty + 2) - 1);
  float reach_speed = 0.0f;
  for (int j = by_lo; j <= by_hi; ++j)
    for (int i = bx_lo; i <= bx_hi; ++i) reach_speed = fmax(reach_speed, block_speed[j * blocks_x + i]);

  /* The block's pixels (lane l = 4j + i is pixel (x0 + i, y0 + j)), clamped into the image for
   * reading; only pixels inside it are written. */
  const int16 lane = (int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  /* (Integer min / clamp take vector bounds: oclgrind 21.10 broadcasts a scalar bound to the
   * first lane only.) */
  const int16 xs = min(x0 + (lane & 3), (int16)(width - 1));
  const int16 ys = min(y0 + (lane >> 2), (int16)(height - 1));
  const int16 centre = ys * width + xs;
  float4 result[16];
#define RP_MB_CENTRE(L) result[0x##L] = hdr_in[centre.s##L];
  RP_MB_LANES(RP_MB_CENTRE)
#undef RP_MB_CENTRE
  if (reach_speed > RP_MB_QUIET_SPEED)
    rp_mb_filter_block(hdr_in, depth_speed, vn, samples, xs, ys, width, height, result);
  float4 bloom_r[4], bloom_g[4], bloom_b[4];
  if (fuse_bloom) {
    const int plane = level1_w * level1_h;
    rp_bloom_tent_block(bloom_level1, level1_w, level1_h, bx, by, bloom_r);
    rp_bloom_tent_block(bloom_level1 + plane, level1_w, level1_h, bx, by, bloom_g);
    rp_bloom_tent_block(bloom_level1 + 2 * plane, level1_w, level1_h, bx, by, bloom_b);
  }
  for (int jj = 0; jj < 4; ++jj) {
    const int y = y0 + jj;
    if (y >= height) break;
    for (int ii = 0; ii < 4 && x0 + ii < width; ++ii) {
      float4 out = result[4 * jj + ii];
      if (fuse_bloom) {
        const float4 br = bloom_r[jj], bg = bloom_g[jj], bb = bloom_b[jj];
        out = rp_bloom_mix_pixel(out, ((float*)&br)[ii], ((float*)&bg)[ii], ((float*)&bb)[ii],
                                 keep, scale);
      }
      hdr_out[y * width + x0 + ii] = out;
    }
  }
}
