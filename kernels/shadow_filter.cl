/* Shadow filter pass: the shadow map's mip chain of linear light depth (layout and meaning:
 * shared/shadow_mips.h), read by the light pass's soft shadows (common/soft_shadow.h): PCSS
 * reads the MIN plane (a conservative "nothing nearer than the receiver" test and the nearest
 * blocker, which bounds the blocker search), VSSM the MEAN / MEAN2 planes (depth moments).
 *
 * Kernels, one work-item per texel of the level written:
 *   shadow_filter_first  the shadow map (z_ndc * 0.5 + 0.5) -> level 1: the min of each 2x2
 *                        converted to linear z = 2 n f / ((f + n) - z_ndc (f - n)) (an empty
 *                        texel, 1.0, counts as z = f; z grows with the stored depth), and with
 *                        the moments the mean of the 4 converted z and of their squares
 *   shadow_filter_next   level l - 1 -> level l: min of the 4 mins, mean of the 4 means
 * Reads past the right / bottom edge of an odd-sized level repeat its last column / row.
 *
 * Variant (-D): RP_SHADOW_MOMENTS=1 also writes the MEAN and MEAN2 planes (VSSM); default the
 * MIN plane only (PCSS).
 *
 * Precision: z^2 of z <= far (2.5) is averaged in float over at most 4^7 texels, 7 rounding
 * steps of a relative 2^-24: the variance E[z^2] - E[z]^2 carries an absolute error around
 * 1e-6 world^2, which the reader floors away (RP_VSSM_MIN_VARIANCE in common/soft_shadow.h).
 */
#include "shared/types.h"
#include "shared/pass_params.h"
#include "shared/shadow_mips.h"

#ifndef RP_SHADOW_MOMENTS
#define RP_SHADOW_MOMENTS 0
#endif

inline float shadow_filter_linear(float d, float near, float far) {
  const float z = 2.0f * near * far / ((far + near) - (d * 2.0f - 1.0f) * (far - near));
  return d >= 1.0f ? far : z;
}

/* depth: size x size; mips: the chain (plane stride `plane`); level 1 is n1 x n1 at offset 0. */
__kernel void shadow_filter_first(__global const FrameConstants* restrict frame,
                                  __global const float* restrict depth,
                                  __global float* restrict mips, const ShadowMipStep step) {
  const uint size = step.src_size, n1 = step.dst_size, plane = step.plane;
  const uint i = (uint)get_global_id(0), j = (uint)get_global_id(1);
  if (i >= n1 || j >= n1) return;
  const float near = frame->clip.z, far = frame->clip.w;
  const uint x0 = 2u * i, y0 = 2u * j;
  const uint x1 = min(x0 + 1u, size - 1u), y1 = min(y0 + 1u, size - 1u);
  const float da = depth[y0 * size + x0], db = depth[y0 * size + x1];
  const float dc = depth[y1 * size + x0], dd = depth[y1 * size + x1];
  const uint out = j * n1 + i;
  /* linear depth grows with d: the min converts once */
  mips[out] = shadow_filter_linear(fmin(fmin(da, db), fmin(dc, dd)), near, far);
#if RP_SHADOW_MOMENTS
  const float a = shadow_filter_linear(da, near, far), b = shadow_filter_linear(db, near, far);
  const float c = shadow_filter_linear(dc, near, far), d = shadow_filter_linear(dd, near, far);
  mips[plane * RP_SHADOW_MIP_MEAN + out] = ((a + b) + (c + d)) * 0.25f;
  mips[plane * RP_SHADOW_MIP_MEAN2 + out] = ((a * a + b * b) + (c * c + d * d)) * 0.25f;
#else
  (void)plane;
#endif
}

/* Level l (n x n at offset dst) from level l - 1 (m x m at offset src). */
__kernel void shadow_filter_next(__global float* restrict mips, const ShadowMipStep step) {
  const uint src = step.src_offset, m = step.src_size, dst = step.dst_offset, n = step.dst_size;
  const uint plane = step.plane;
  const uint i = (uint)get_global_id(0), j = (uint)get_global_id(1);
  if (i >= n || j >= n) return;
  const uint x0 = 2u * i, y0 = 2u * j;
  const uint x1 = min(x0 + 1u, m - 1u), y1 = min(y0 + 1u, m - 1u);
  const uint t00 = src + y0 * m + x0, t10 = src + y0 * m + x1;
  const uint t01 = src + y1 * m + x0, t11 = src + y1 * m + x1;
  const uint out = dst + j * n + i;
  mips[out] = fmin(fmin(mips[t00], mips[t10]), fmin(mips[t01], mips[t11]));
#if RP_SHADOW_MOMENTS
  for (uint c = RP_SHADOW_MIP_MEAN; c <= RP_SHADOW_MIP_MEAN2; ++c) {
    __global float* p = mips + plane * c;
    p[out] = ((p[t00] + p[t10]) + (p[t01] + p[t11])) * 0.25f;
  }
#else
  (void)plane;
#endif
}
