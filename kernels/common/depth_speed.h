/* The motion blur's depth/speed plane (kernels/motion_blur.cl, step 3): a half2 per pixel, the
 * linear depth clamped to [0, RP_MB_MAX_DEPTH], then the blur radius |V| in pixels clamped to
 * RP_MB_MAX_RADIUS (V = velocity * shutter / 2; non-finite velocities count as still), both
 * rounded to nearest even. motion_blur.cl makes it from the output-size velocity and depth
 * (rp_mb_float_to_half16 / 4 below); the temporal upsampling (kernels/taa_upsample.cl), which
 * makes that velocity and knows the depth, writes it itself (rp_mb_depth_speed8). The two give
 * the same bits (tests/passes/taa_upsample_test.cpp; motion_blur_reference_test.cpp holds the
 * C++ reference). OpenCL C only.
 */
#ifndef ROLYPOLY_COMMON_DEPTH_SPEED_H
#define ROLYPOLY_COMMON_DEPTH_SPEED_H

#define RP_MB_MAX_RADIUS 20.0f
/* Depths above this go to the half plane as this (half max is 65504; inf - inf would be NaN). */
#define RP_MB_MAX_DEPTH 60000.0f

/* Float to IEEE binary16 bits, round to nearest even (what vstore_half does by default), for
 * finite values in [0, 65504] (the plane's depths and speeds are such values; done in vector
 * arithmetic because a per-lane vstore_half2 costs more than the rest of the prepass on PoCL).
 * Normal halves (x >= 2^-14): drop 13 mantissa bits with round-half-even, rebias by 112;
 * subnormal halves: x / 2^-24 rounded to the nearest even integer. */
inline uint16 rp_mb_float_to_half16(float16 x) {
  const uint16 bits = as_uint16(x);
  const uint16 normal = (bits + 0x0FFFu + ((bits >> 13) & 1u) - 0x38000000u) >> 13;
  const uint16 tiny = convert_uint16(rint(x * 16777216.0f));
  return select(normal, tiny, bits < 0x38800000u);
}
inline uint4 rp_mb_float_to_half4(float4 x) {
  const uint4 bits = as_uint4(x);
  const uint4 normal = (bits + 0x0FFFu + ((bits >> 13) & 1u) - 0x38000000u) >> 13;
  const uint4 tiny = convert_uint4(rint(x * 16777216.0f));
  return select(normal, tiny, bits < 0x38800000u);
}

/* The plane's values for eight pixels from their velocity (pixels per frame), linear depth and
 * half_shutter = shutter * 0.5 (the host's float product), before the rounding to halves:
 * depth and radius of pixel k in lanes 2k and 2k + 1, for vstore_half16 (its default rounding
 * is to nearest even; in the upsampling's resolve on PoCL cheaper than the integer rounding
 * above: the busy 720x720 frame's taa pass at scale 0.5 took 4.22 against 4.45 ms; in
 * motion_blur.cl's prepass, 16 pixels a work-item through this function cost half as much again
 * as its 20-pixel rows). One rounded operation per statement: motion_blur.cl computes the same
 * values with FP_CONTRACT OFF. */
inline float16 rp_mb_depth_speed8(float8 vx, float8 vy, float8 depth, float half_shutter) {
  float8 hx = vx * half_shutter;
  float8 hy = vy * half_shutter;
  const int8 finite = isfinite(hx) & isfinite(hy);
  hx = select((float8)(0.0f), hx, finite);
  hy = select((float8)(0.0f), hy, finite);
  const float8 xx = hx * hx;
  const float8 yy = hy * hy;
  const float8 len2 = xx + yy;
  const int8 longer = len2 > RP_MB_MAX_RADIUS * RP_MB_MAX_RADIUS;
  const float8 k = RP_MB_MAX_RADIUS / sqrt(len2);
  hx = select(hx, hx * k, longer);
  hy = select(hy, hy * k, longer);
  const float8 cx = hx * hx;
  const float8 cy = hy * hy;
  const float8 speed = sqrt(cx + cy);
  const float8 z = clamp(depth, 0.0f, RP_MB_MAX_DEPTH);
  return shuffle2(z, speed, (uint16)(0, 8, 1, 9, 2, 10, 3, 11, 4, 12, 5, 13, 6, 14, 7, 15));
}

#endif
