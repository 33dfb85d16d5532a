/* Matrix and projection helpers (OpenCL C only). rp_mat4 is column-major like GLM
 * (kernels/shared/types.h): m.c[k] is column k, so M * v = sum_k c[k] * v[k]. */
#ifndef ROLYPOLY_COMMON_MATH_H
#define ROLYPOLY_COMMON_MATH_H

#include "shared/types.h"

/* M * (p, 1): a point (the result keeps w; divide for projections). */
inline float4 rp_mat4_mul_point(const rp_mat4 m, float3 p) {
  return m.c[0] * p.x + m.c[1] * p.y + m.c[2] * p.z + m.c[3];
}

/* M * (d, 0) restricted to xyz: a direction (upper 3x3 only, no translation). */
inline float3 rp_mat4_mul_dir(const rp_mat4 m, float3 d) {
  return m.c[0].xyz * d.x + m.c[1].xyz * d.y + m.c[2].xyz * d.z;
}

/* M * v for a full 4-vector. */
inline float4 rp_mat4_mul(const rp_mat4 m, float4 v) {
  return m.c[0] * v.x + m.c[1] * v.y + m.c[2] * v.z + m.c[3] * v.w;
}

/* One row (x, y, z or w) of M * (x, y, z, 1) and of M * (x, y, z, 0), for scalars or for
 * spans of lanes (common/span.h): ((c0 x + c1 y) + c2 z) (+ c3). */
#define RP_MAT4_ROW_POINT(m, row, x, y, z) \
  ((m).c[0].row * (x) + (m).c[1].row * (y) + (m).c[2].row * (z) + (m).c[3].row)
#define RP_MAT4_ROW_DIR(m, row, x, y, z) \
  ((m).c[0].row * (x) + (m).c[1].row * (y) + (m).c[2].row * (z))

/* Row r (0..3) of M as a 4-vector. */
inline float4 rp_mat4_row(const rp_mat4 m, int r) {
  return r == 0   ? (float4)(m.c[0].x, m.c[1].x, m.c[2].x, m.c[3].x)
         : r == 1 ? (float4)(m.c[0].y, m.c[1].y, m.c[2].y, m.c[3].y)
         : r == 2 ? (float4)(m.c[0].z, m.c[1].z, m.c[2].z, m.c[3].z)
                  : (float4)(m.c[0].w, m.c[1].w, m.c[2].w, m.c[3].w);
}

/* Clip-space position -> pixel coordinates of a size.x by size.y image (types.h convention:
 * (0,0) top-left corner, pixel centres at +0.5, y grows downwards). */
inline float2 rp_clip_to_screen(float4 clip, float2 size) {
  float inv_w = 1.0f / clip.w;
  return (float2)((clip.x * inv_w * 0.5f + 0.5f) * size.x, (0.5f - clip.y * inv_w * 0.5f) * size.y);
}

/* Pixel coordinates -> NDC xy (inverse of rp_clip_to_screen after the divide). */
inline float2 rp_screen_to_ndc(float2 pixel, float2 size) {
  return (float2)(pixel.x / size.x * 2.0f - 1.0f, 1.0f - pixel.y / size.y * 2.0f);
}

#endif
