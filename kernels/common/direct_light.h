/* Direct light from the lamp (SPEC 6.5), shared by every pass that lights a surface point: the
 * light pass (light.cl) and the voxelizer (voxelize.cl). OpenCL C only.
 *
 *   direct radiance = albedo * I * cos(theta) / (d^2 + a^2) * falloff(l.y) * shadow
 *
 * I = FrameConstants.light_intensity.rgb (radiant intensity), l = unit vector from the surface
 * point to the lamp centre (FrameConstants.light_pos), theta the angle between l and the surface
 * normal.
 *
 * Near field (the lamp's disk model): seen from below, the lamp cap's outline is a disk of
 * radius a = sqrt(R^2 - z_e^2) in the ceiling (R = light_pos.w, z_e the centre's height above
 * the ceiling), d is the distance to that disk's centre. The cap's radiance is uniform, so on
 * the disk's axis the irradiance is the disk's projected solid angle: pi a^2 / (a^2 + d^2)
 * against the far field's pi a^2 / d^2 = the point model (the path tracer's --lamp area: the
 * floor under the lamp gets 7 % more than 1 / |p - centre|^2 says). Off the axis it is an
 * approximation (bench --accuracy against the area-lamp truth at 0 bounces: bias on the lit
 * floor -4.6 % with the point model, +0.8 % with this; direct PSNR of the image 32.5 -> 33.4 dB;
 * taking l towards the disk's centre as well gave 32.2 dB: the falloff fit is in the centre's
 * frame).
 *
 * Directional falloff: the lamp is the part of a sphere (radius 0.35, centre 0.1 above the
 * ceiling) below the ceiling, so points that see it from the side see less of it. falloff(s),
 * s = l.y = sine of the lamp's elevation seen from the point, is the visible projected area of
 * that cap relative to seeing it from straight below, integrated numerically and fitted by a
 * quadratic (max error 0.02 over s in [0,1]):
 *     falloff(s) = 0.35 + s * (0.446 + 0.204 s),  falloff(1) = 1, falloff(0) = 0.35.
 *
 * Shadow (shadow map = FrameConstants.light_view_proj depth, z_ndc * 0.5 + 0.5, 1.0 = empty;
 * texel rows top to bottom like the camera image, shared/types.h): rp_shadow_lookup pushes the
 * receiver along its normal by `normal_offset` texels and compares in linear light depth (clip
 * w) with a bias of (depth_bias + filter_reach * tan(theta)) texels, where one texel is its
 * world size at the receiver's distance and filter_reach is how far (texels) the caller's taps
 * reach from the receiver. rp_shadow_tap then reads the texel under the receiver plus an
 * offset in texels (one call per tap: the voxelizer's 4 taps). Points outside the shadow
 * frustum are lit. The light pass's shadow modes (hard, pcf, pcss, vssm) live in
 * common/soft_shadow.h (eight pixels at once, receiver-plane bias).
 */
#ifndef ROLYPOLY_COMMON_DIRECT_LIGHT_H
#define ROLYPOLY_COMMON_DIRECT_LIGHT_H

#include "shared/types.h"
#include "common/math.h"

/* The ceiling's height: the lamp's emitting disk lies in it (types.h: the box is [-1, 1]^3). */
#define RP_CEILING_Y 1.0f

/* Largest tan(theta) the slope bias follows (grazing light: ~83 degrees). */
#define RP_DIRECT_MAX_SLOPE 8.0f

/* Visible projected area of the lamp cap relative to straight below (see the header). */
inline float rp_lamp_falloff(float s) {
  s = clamp(s, 0.0f, 1.0f);
  return mad(s, mad(s, 0.204f, 0.446f), 0.35f);
}

/* Linear light depth (distance along the light axis) of a stored shadow-map depth;
 * +inf-like for an empty texel (1.0). near/far: FrameConstants.clip.zw. */
inline float rp_shadow_linear_depth(float d, float near, float far) {
  float z_ndc = d * 2.0f - 1.0f;
  float lin = 2.0f * near * far / ((far + near) - z_ndc * (far - near));
  return d >= 1.0f ? 3.0e38f : lin;
}

/* The lamp's emitting disk (see the header's "Near field"): its centre's height and a^2. */
inline float rp_lamp_disk_a2(float4 light_pos) {
  const float ze = light_pos.y - RP_CEILING_Y;
  return fmax(light_pos.w * light_pos.w - ze * ze, 0.0f);
}

/* cos(theta) / (d^2 + a^2) * falloff(l.y) at point p with unit normal n, without the shadow
 * (l, d: towards and from the lamp disk's centre); 0 when the surface faces away from the lamp.
 * *cos_theta receives dot(n, l) (for the shadow bias). */
inline float rp_direct_unshadowed(float4 light_pos, float3 p, float3 n, float* cos_theta) {
  const float3 to_light = light_pos.xyz - p;
  const float3 to_disk = (float3)(light_pos.x, RP_CEILING_Y, light_pos.z) - p;
  const float d2 = dot(to_disk, to_disk);
  const float inv_d = rsqrt(dot(to_light, to_light));
  const float3 l = to_light * inv_d;
  const float c = dot(n, l);
  *cos_theta = c;
  return c > 0.0f ? c * rp_lamp_falloff(l.y) / (d2 + rp_lamp_disk_a2(light_pos)) : 0.0f;
}

/* A receiver projected into the shadow map, ready for taps. */
typedef struct {
  float sx, sy;     /* texel coordinates (top-left origin, texel centres at +0.5) */
  float receiver;   /* biased linear light depth of the receiver */
  float near, far;  /* light clip planes */
  int size;         /* shadow map is size x size */
  int inside;       /* 0: outside the shadow frustum, every tap reports lit */
} RpShadowLookup;

/* Projects world point p (unit normal n, cos_theta = dot(n, l)) into the shadow map. Offsets
 * and bias in texels (see the header). */
inline RpShadowLookup rp_shadow_lookup(__global const FrameConstants* frame, float3 p, float3 n,
                                       float cos_theta, float normal_offset, float depth_bias,
                                       float filter_reach) {
  const rp_mat4 lvp = frame->light_view_proj;
  RpShadowLookup s;
  s.size = (int)frame->shadow_size;
  s.near = frame->clip.z;
  s.far = frame->clip.w;

  /* World size of one shadow texel at the receiver: the frustum is 2 w / |row0.xyz| wide at
   * clip w (row0 = P00 times the light's unit right axis for a symmetric projection). */
  const float w0 = rp_mat4_mul_point(lvp, p).w;
  const float4 row0 = rp_mat4_row(lvp, 0);
  const float texel = 2.0f * fabs(w0) / ((float)s.size * length(row0.xyz));

  const float c = max(cos_theta, 1.0e-4f);
  const float tan_theta = min(sqrt(max(1.0f - c * c, 0.0f)) / c, RP_DIRECT_MAX_SLOPE);
  const float3 q = p + n * (texel * normal_offset);
  const float4 clip = rp_mat4_mul_point(lvp, q);
  const float3 ndc = clip.xyz / clip.w;
  s.inside = !(clip.w <= 0.0f || fabs(ndc.x) > 1.0f || fabs(ndc.y) > 1.0f || ndc.z > 1.0f);
  s.receiver = clip.w - texel * (depth_bias + filter_reach * tan_theta);
  s.sx = (ndc.x * 0.5f + 0.5f) * (float)s.size;
  s.sy = (0.5f - ndc.y * 0.5f) * (float)s.size;
  return s;
}

/* 1 if the texel at the receiver + `offset` (texels) is farther than the receiver, else 0;
 * 1 outside the shadow frustum. Addressing clamps to the map's edge. */
inline float rp_shadow_tap(__global const float* shadow, const RpShadowLookup* s, float2 offset) {
  if (!s->inside) return 1.0f;
  const int tx = clamp((int)floor(s->sx + offset.x), 0, s->size - 1);
  const int ty = clamp((int)floor(s->sy + offset.y), 0, s->size - 1);
  return s->receiver <= rp_shadow_linear_depth(shadow[ty * s->size + tx], s->near, s->far) ? 1.0f
                                                                                         : 0.0f;
}

#endif
