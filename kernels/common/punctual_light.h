/* A loaded scene's punctual lights (kernels/shared/types.h PunctualLightGpu, ShadowViewGpu):
 * the direction, attenuation and shadow of light i at a surface point. OpenCL C only; the
 * host's twin is scene/punctual_light.h (the path tracer's), with the same formulas:
 *
 *   direct radiance = albedo * intensity * cos(theta) * attenuation * visibility
 *   attenuation: directional 1; point and spot 1 / d^2 x clamp(1 - (d / range)^4, 0, 1) (range
 *   > 0) x (spot) t^2, t = clamp((cos a - cos outer) / (cos inner - cos outer), 0, 1).
 *
 * Shadow: the light's view that sees p (a point light: the cube face of the major axis of p -
 * position), the receiver pushed one texel along its normal and compared in linear depth with
 * a bias of rp_punctual_bias_texels, in one bilinear comparison (4 texel reads). Points outside
 * every view are lit. The lights are points (the path tracer's too), so their shadows are hard:
 * TAA's jitter resolves the comparison's texel steps over frames, and a wider filter only blurs
 * the shadows of features a few texels across away. Measured on the atrium at 256x256 (`bench
 * --accuracy --scene atrium`, the direct light averaged over TAA's jitter), with the sun's view
 * fitted to the scene (render/punctual_shadows.h): the mean of nine bilinear comparisons (3x3
 * texels) and a bias of 1.5 + tan(theta) texels read 25.29 dB and +3.0 % bias against the truth,
 * one comparison with the bias below 26.61 dB and +2.7 % (cornices, balustrades and the arches'
 * soffits keep their shadows), for a quarter of the texel reads.
 */
#ifndef ROLYPOLY_COMMON_PUNCTUAL_LIGHT_H
#define ROLYPOLY_COMMON_PUNCTUAL_LIGHT_H

#include "shared/types.h"
#include "common/math.h"

/* Unit vector from p towards light L and its attenuation (0: no light here). */
inline float3 rp_punctual_dir(__global const PunctualLightGpu* L, float3 p, float* atten) {
  if (L->type == RP_LIGHT_DIRECTIONAL) {
    *atten = 1.0f;
    return -L->direction.xyz;
  }
  const float3 to_light = L->position_range.xyz - p;
  const float d2 = dot(to_light, to_light);
  if (!(d2 > 0.0f)) {
    *atten = 0.0f;
    return (float3)(0.0f, 1.0f, 0.0f);
  }
  const float inv_d = rsqrt(d2);
  const float3 l = to_light * inv_d;
  float a = 1.0f / d2;
  const float range = L->position_range.w;
  if (range > 0.0f) {
    const float r = d2 * inv_d / range;
    a *= clamp(1.0f - (r * r) * (r * r), 0.0f, 1.0f);
  }
  if (L->type == RP_LIGHT_SPOT) {
    const float cos_a = -dot(l, L->direction.xyz);
    const float t = L->cone.y > 0.0f ? clamp((cos_a - L->cone.x) * L->cone.y, 0.0f, 1.0f)
                                     : (cos_a >= L->cone.x ? 1.0f : 0.0f);
    a *= t * t;
  }
  *atten = a;
  return l;
}

/* Linear depth of a stored depth d (z_ndc * 0.5 + 0.5) in view V; +inf-like where empty. */
inline float rp_punctual_linear(__global const ShadowViewGpu* V, float d) {
  const float near = V->depth.x, far = V->depth.y;
  if (d >= 1.0f) return 3.0e38f;
  if (V->depth.z != 0.0f) return near + d * (far - near);
  const float z_ndc = d * 2.0f - 1.0f;
  return 2.0f * near * far / ((far + near) - z_ndc * (far - near));
}

/* The stored depth (z_ndc * 0.5 + 0.5) of linear depth `lin` in view V: rp_punctual_linear's
 * inverse, so a texel is compared as stored (d >= this) instead of converting every tap. */
inline float rp_punctual_stored(__global const ShadowViewGpu* V, float lin) {
  const float near = V->depth.x, far = V->depth.y;
  if (V->depth.z != 0.0f) return (lin - near) / (far - near);
  if (!(lin > near)) return -INFINITY; /* nearer than anything stored: lit */
  const float z_ndc = ((far + near) - 2.0f * near * far / lin) / (far - near);
  return z_ndc * 0.5f + 0.5f;
}

/* Depth bias of a receiver whose normal is theta from the light, in texels of its view. The
 * light pass's points lie on the surface seen through the pixel; the voxelizer's anywhere on a
 * voxel's triangles, and its smaller bias darkened the voxels' light (the atrium's indirect
 * bias -16.4 -> -18.8 % with (0.5 + tan(theta) / 2) there too), so it keeps the wider one. */
#define RP_PUNCTUAL_BIAS_LIGHT_PASS 0.5f       /* texels, plus this x tan(theta) */
#define RP_PUNCTUAL_BIAS_SLOPE_LIGHT_PASS 0.5f
#define RP_PUNCTUAL_BIAS_VOXELS 1.5f
#define RP_PUNCTUAL_BIAS_SLOPE_VOXELS 1.0f
inline float rp_punctual_bias_texels(float tan_theta, int light_pass) {
  return light_pass ? RP_PUNCTUAL_BIAS_LIGHT_PASS + RP_PUNCTUAL_BIAS_SLOPE_LIGHT_PASS * tan_theta
                    : RP_PUNCTUAL_BIAS_VOXELS + RP_PUNCTUAL_BIAS_SLOPE_VOXELS * tan_theta;
}

/* 1 where texel (tx, ty) of view V (clamped to the map) is at or beyond stored depth
 * `receiver_d` (rp_punctual_stored; an empty texel, 1, always is). */
inline float rp_punctual_tap(__global const float* shadow, __global const ShadowViewGpu* V,
                             int tx, int ty, float receiver_d) {
  const int last = (int)V->size - 1;
  tx = clamp(tx, 0, last);
  ty = clamp(ty, 0, last);
  const float d = shadow[V->offset + (uint)ty * V->size + (uint)tx];
  return d >= receiver_d || d >= 1.0f ? 1.0f : 0.0f;
}

/* Visibility in [0, 1] of light L (l: towards it) at p with unit normal n; light_pass: 1 for
 * the light pass, 0 for the voxelizer (rp_punctual_bias_texels). */
inline float rp_punctual_visibility(__global const FrameConstants* frame,
                                    __global const float* shadow,
                                    __global const PunctualLightGpu* L, float3 p, float3 n,
                                    float3 l, int light_pass) {
  if (L->view_count == 0u) return 1.0f;
  __global const ShadowViewGpu* V = &frame->shadow_views[L->first_view];
  float w0;  /* the receiver's clip w in its view: a texel's size scales with it */
  if (L->type == RP_LIGHT_POINT) {
    const float3 a = fabs(p - L->position_range.xyz);
    w0 = fmax(a.x, fmax(a.y, a.z)); /* every face has the same projection */
  } else {
    w0 = V->depth.z != 0.0f ? 1.0f : fabs(rp_mat4_mul_point(V->view_proj, p).w);
  }
  const float texel = w0 * V->depth.w;
  const float c = fmax(dot(n, l), 1.0e-4f);
  const float tan_theta = fmin(sqrt(fmax(1.0f - c * c, 0.0f)) / c, 8.0f);
  const float3 q = p + n * texel; /* pushed off the surface along its normal */
  if (L->type == RP_LIGHT_POINT) {
    /* the face that sees the pushed point (near a cube edge the push may cross to the next) */
    const float3 d = q - L->position_range.xyz, a = fabs(d);
    const uint face = a.x >= a.y && a.x >= a.z ? (d.x >= 0.0f ? 0u : 1u)
                      : a.y >= a.z           ? (d.y >= 0.0f ? 2u : 3u)
                                             : (d.z >= 0.0f ? 4u : 5u);
    V += face;
  }
  const rp_mat4 vp = V->view_proj;
  const float4 clip = rp_mat4_mul_point(vp, q);
  if (clip.w <= 0.0f) return 1.0f;
  const float3 ndc = clip.xyz / clip.w;
  if (fabs(ndc.x) > 1.0f || fabs(ndc.y) > 1.0f || ndc.z > 1.0f) return 1.0f;
  const float lin = V->depth.z != 0.0f ? rp_punctual_linear(V, ndc.z * 0.5f + 0.5f) : clip.w;
  const float receiver =
      rp_punctual_stored(V, lin - texel * rp_punctual_bias_texels(tan_theta, light_pass));
  const float size = (float)V->size;
  const float x = (ndc.x * 0.5f + 0.5f) * size - 0.5f, y = (0.5f - ndc.y * 0.5f) * size - 0.5f;
  const float fx0 = floor(x), fy0 = floor(y);
  const float fx = x - fx0, fy = y - fy0;
  const int x0 = (int)fx0, y0 = (int)fy0;
  const float t00 = rp_punctual_tap(shadow, V, x0, y0, receiver);
  const float t10 = rp_punctual_tap(shadow, V, x0 + 1, y0, receiver);
  const float t01 = rp_punctual_tap(shadow, V, x0, y0 + 1, receiver);
  const float t11 = rp_punctual_tap(shadow, V, x0 + 1, y0 + 1, receiver);
  return mix(mix(t00, t10, fx), mix(t01, t11, fx), fy);
}

/* Light L's direct irradiance factor at p (normal n): intensity * cos * attenuation *
 * visibility (rgb; multiply by albedo, or by the surface model's weights); *l receives the
 * direction towards it. 0 where the surface faces away. */
inline float3 rp_punctual_direct(__global const FrameConstants* frame,
                                 __global const float* shadow, uint i, float3 p, float3 n,
                                 int light_pass, float3* l) {
  __global const PunctualLightGpu* L = &frame->punctual[i];
  float atten;
  *l = rp_punctual_dir(L, p, &atten);
  const float c = dot(n, *l);
  if (!(c > 0.0f) || !(atten > 0.0f)) return (float3)(0.0f);
  const float vis = rp_punctual_visibility(frame, shadow, L, p, n, *l, light_pass);
  return L->intensity.xyz * (c * atten * vis);
}

#endif
