/* TAA helpers (OpenCL C only; SPEC 6.7): YCoCg colour space and the history clip.
 * Used by kernels/taa.cl; tests/passes/taa_test.cpp runs them through a probe kernel against
 * C++ references.
 *
 * YCoCg (exactly invertible linear transform, luma Y and two chroma axes):
 *   Y  =  R/4 + G/2 + B/4      R = Y - Cg + Co
 *   Co =  R/2       - B/2      G = Y + Cg
 *   Cg = -R/4 + G/2 - B/4      B = Y - Cg - Co
 * The neighbourhood box is tighter around real colour distributions in YCoCg than in RGB
 * (luma and chroma vary independently), so clipping rejects less valid history.
 */
#ifndef ROLYPOLY_COMMON_TAA_H
#define ROLYPOLY_COMMON_TAA_H

inline float3 rp_rgb_to_ycocg(float3 c) {
  return (float3)(0.25f * c.x + 0.5f * c.y + 0.25f * c.z, 0.5f * c.x - 0.5f * c.z,
                  -0.25f * c.x + 0.5f * c.y - 0.25f * c.z);
}

inline float3 rp_ycocg_to_rgb(float3 c) {
  const float t = c.x - c.z;
  return (float3)(t + c.y, c.x + c.z, t - c.y);
}

/* Smallest box half-extent per channel: keeps the division finite where the neighbourhood is
 * flat in a channel (stddev 0); any history that differs there then clips onto the centre. */
#define RP_TAA_MIN_EXTENT 1.0e-6f

/* Clips `q` to the axis-aligned box centre +- extent (extent >= 0 per channel) along the line
 * from q to the box centre: a point inside (or on) the box is returned unchanged (bit-exact);
 * a point outside moves to where that line crosses the box surface, i.e.
 *   centre + (q - centre) / max_c(|q_c - centre_c| / extent_c).
 * Unlike a per-channel clamp this keeps the history's hue direction relative to the centre. */
inline float3 rp_taa_clip(float3 q, float3 centre, float3 extent) {
  const float3 v = q - centre;
  const float3 e = fmax(extent, (float3)(RP_TAA_MIN_EXTENT));
  const float3 a = fabs(v) / e;
  const float m = fmax(a.x, fmax(a.y, a.z));
  return m > 1.0f ? centre + v / m : q;
}

#endif
