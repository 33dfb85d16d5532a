/* Light pass (SPEC 6.5): GBuffer + shadow map + voxel radiance chain -> HDR radiance (float4 per
 * pixel, rgb linear, a = 1 covered / 0 background).
 *
 *   L_out = albedo * I * cos(theta) / d^2 * falloff(l.y) * shadow      (direct, point lamp)
 *         + albedo * D(p, n)                                             (indirect, cone traced)
 *         + emission
 *
 * I = FrameConstants.light_intensity.rgb (radiant intensity), l = unit vector from the surface to
 * the lamp centre, d its distance. Background pixels: 0.
 * D(p, n) = rp_cone_diffuse (common/cone_trace.h): six 60-degree cones through the voxel chain,
 * weights pi/4 (normal cone) and 3 pi/20 (five cones tilted 60 degrees) normalised by pi, i.e.
 * the indirect irradiance over pi, so albedo * D is the Lambertian indirect radiance in the same
 * units as the voxels' radiance. It replaces the constant ambient of "First light".
 *
 * Variants (-D):
 *   RP_LIGHT_SPLIT=1: also writes the direct lamp term (rgb, a = covered) and the indirect term
 *     (rgb, a = covered) into two extra float4 buffers, for the debug views; emission is in
 *     neither. The default build writes only hdr.
 *   RP_LIGHT_CONSTANT_AMBIENT=1: the "First light" indirect term albedo * light_intensity.w
 *     instead of cone tracing (the voxel arguments are not read). Kept only for the renderer's
 *     entry point without a voxel chain (LightPass::run without voxels).
 *
 * Directional falloff: the lamp is the part of a sphere (radius 0.35, centre 0.1 above the
 * ceiling) below the ceiling, so points that see it from the side see less of it (000 9.2.2).
 * falloff(s), s = l.y = sine of the lamp's elevation seen from the point, is the visible
 * projected area of that cap relative to seeing it from straight below, integrated numerically
 * and fitted by a quadratic (max error 0.02 over s in [0,1]):
 *     falloff(s) = 0.35 + s * (0.446 + 0.204 s),  falloff(1) = 1, falloff(0) = 0.35.
 * Mid-wall points get ~0.78, points just under the ceiling ~0.45. No pow, three flops.
 *
 * Shadow (shadow map = FrameConstants.light_view_proj depth, z_ndc * 0.5 + 0.5, 1.0 = empty;
 * texel rows top to bottom like the camera image, types.h): the receiver is pushed along its
 * normal by RP_SHADOW_NORMAL_OFFSET texels and compared in linear light depth (clip w) with a
 * bias of (RP_SHADOW_DEPTH_BIAS + filter radius * tan(theta)) texels, where one texel is its
 * world size at the receiver's distance. Default filter: ONE tap at a Poisson-disk point
 * (radius RP_SHADOW_RADIUS texels) chosen and rotated by a hash of (pixel, frame_index), so the
 * noise is deterministic and changes per frame for TAA to average. -DRP_SHADOW_PCF5=1: the
 * 5x5 PCF reference (25 taps, one texel apart). Points outside the shadow frustum are lit.
 */
#include "shared/types.h"
#include "common/math.h"
#include "common/random.h"
#include "common/cone_trace.h"

#ifndef RP_SHADOW_NORMAL_OFFSET
#define RP_SHADOW_NORMAL_OFFSET 1.0f
#endif
#ifndef RP_SHADOW_DEPTH_BIAS
#define RP_SHADOW_DEPTH_BIAS 1.0f
#endif
#ifndef RP_SHADOW_RADIUS
#define RP_SHADOW_RADIUS 1.5f
#endif
#ifndef RP_SHADOW_PCF5
#define RP_SHADOW_PCF5 0
#endif
#ifndef RP_LIGHT_SPLIT
#define RP_LIGHT_SPLIT 0
#endif
#ifndef RP_LIGHT_CONSTANT_AMBIENT
#define RP_LIGHT_CONSTANT_AMBIENT 0
#endif
/* Largest tan(theta) the slope bias follows (grazing light: ~83 degrees). */
#define RP_SHADOW_MAX_SLOPE 8.0f

#if RP_SHADOW_PCF5
#define RP_SHADOW_FILTER_REACH 2.83f /* farthest 5x5 tap, texels */
#else
#define RP_SHADOW_FILTER_REACH RP_SHADOW_RADIUS
#endif

/* Visible projected area of the lamp cap relative to straight below (see the header). */
inline float light_lamp_falloff(float s) {
  s = clamp(s, 0.0f, 1.0f);
  return mad(s, mad(s, 0.204f, 0.446f), 0.35f);
}

/* Linear light depth (distance along the light axis) of a stored shadow-map depth;
 * +inf-like for an empty texel (1.0). near/far: FrameConstants.clip.zw. */
inline float light_linear_depth(float d, float near, float far) {
  float z_ndc = d * 2.0f - 1.0f;
  float lin = 2.0f * near * far / ((far + near) - z_ndc * (far - near));
  return d >= 1.0f ? 3.0e38f : lin;
}

/* Shadow visibility in [0,1] of world point p with unit normal n, cos_theta = dot(n, l). */
inline float light_shadow(__global const FrameConstants* frame, __global const float* shadow,
                          float3 p, float3 n, float cos_theta, uint x, uint y) {
  const rp_mat4 lvp = frame->light_view_proj;
  const int size = (int)frame->shadow_size;
  const float near = frame->clip.z, far = frame->clip.w;

  /* World size of one shadow texel at the receiver: the frustum is 2 w / |row0.xyz| wide at
   * clip w (row0 = P00 times the light's unit right axis for a symmetric projection). */
  const float w0 = rp_mat4_mul_point(lvp, p).w;
  const float4 row0 = rp_mat4_row(lvp, 0);
  const float texel = 2.0f * fabs(w0) / ((float)size * length(row0.xyz));

  const float c = max(cos_theta, 1.0e-4f);
  const float tan_theta = min(sqrt(max(1.0f - c * c, 0.0f)) / c, RP_SHADOW_MAX_SLOPE);
  const float3 q = p + n * (texel * RP_SHADOW_NORMAL_OFFSET);
  const float4 clip = rp_mat4_mul_point(lvp, q);
  const float3 ndc = clip.xyz / clip.w;
  if (clip.w <= 0.0f || fabs(ndc.x) > 1.0f || fabs(ndc.y) > 1.0f || ndc.z > 1.0f) return 1.0f;

  const float receiver = clip.w - texel * (RP_SHADOW_DEPTH_BIAS + RP_SHADOW_FILTER_REACH * tan_theta);
  const float sx = (ndc.x * 0.5f + 0.5f) * (float)size;
  const float sy = (0.5f - ndc.y * 0.5f) * (float)size;

#if RP_SHADOW_PCF5
  (void)x;
  (void)y;
  float lit = 0.0f;
  for (int j = -2; j <= 2; ++j) {
    for (int i = -2; i <= 2; ++i) {
      int tx = clamp((int)floor(sx + (float)i), 0, size - 1);
      int ty = clamp((int)floor(sy + (float)j), 0, size - 1);
      lit += receiver <= light_linear_depth(shadow[ty * size + tx], near, far) ? 1.0f : 0.0f;
    }
  }
  return lit * (1.0f / 25.0f);
#else
  const float2 off = rp_poisson_rotated(rp_hash_pixel(x, y, frame->frame_index)) * RP_SHADOW_RADIUS;
  const int tx = clamp((int)floor(sx + off.x), 0, size - 1);
  const int ty = clamp((int)floor(sy + off.y), 0, size - 1);
  return receiver <= light_linear_depth(shadow[ty * size + tx], near, far) ? 1.0f : 0.0f;
#endif
}

/* voxels: the radiance chain (shared/voxel_layout.h) of voxel_resolution^3 at level 0 with
 * voxel_levels levels. */
__kernel void light_shade(__global const FrameConstants* frame,
                          __global const float4* albedo_plane,
                          __global const float4* normal_depth_plane,
                          __global const float4* position_plane,
                          __global const float4* emission_plane,
                          __global const float* shadow,
                          __global const float4* voxels,
                          const uint voxel_resolution,
                          const uint voxel_levels,
#if RP_LIGHT_SPLIT
                          __global float4* direct_out,
                          __global float4* indirect_out,
#endif
                          __global float4* hdr) {
  const uint x = (uint)get_global_id(0), y = (uint)get_global_id(1);
  const uint width = frame->width;
  if (x >= width || y >= frame->height) return;
  const uint pixel = y * width + x;

  const float4 pos = position_plane[pixel];
  if (pos.w == 0.0f) {
    hdr[pixel] = (float4)(0.0f);
#if RP_LIGHT_SPLIT
    direct_out[pixel] = (float4)(0.0f);
    indirect_out[pixel] = (float4)(0.0f);
#endif
    return;
  }
  const float3 albedo = albedo_plane[pixel].xyz;
  const float3 n = normal_depth_plane[pixel].xyz;
  const float3 p = pos.xyz;

  const float3 to_light = frame->light_pos.xyz - p;
  const float d2 = dot(to_light, to_light);
  const float inv_d = rsqrt(d2);
  const float3 l = to_light * inv_d;
  const float cos_theta = dot(n, l);

  float direct_scale = 0.0f;
  if (cos_theta > 0.0f) {
    direct_scale = cos_theta * (inv_d * inv_d) * light_lamp_falloff(l.y) *
                   light_shadow(frame, shadow, p, n, cos_theta, x, y);
  }
  const float3 direct = albedo * (frame->light_intensity.xyz * direct_scale);
#if RP_LIGHT_CONSTANT_AMBIENT
  (void)voxels;
  (void)voxel_resolution;
  (void)voxel_levels;
  const float3 indirect = albedo * frame->light_intensity.w;
#else
  const float3 indirect = albedo * rp_cone_diffuse(voxels, voxel_resolution, voxel_levels, p, n);
#endif
  hdr[pixel] = (float4)(direct + indirect + emission_plane[pixel].xyz, 1.0f);
#if RP_LIGHT_SPLIT
  direct_out[pixel] = (float4)(direct, 1.0f);
  indirect_out[pixel] = (float4)(indirect, 1.0f);
#endif
}
