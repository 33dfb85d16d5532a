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
 * Variant (-D):
 *   RP_LIGHT_SPLIT=1: also writes the direct lamp term (rgb, a = covered) and the indirect term
 *     (rgb, a = covered) into two extra float4 buffers, for the debug views; emission is in
 *     neither. The default build writes only hdr.
 *
 * The direct term (lamp falloff from l.y, shadow-map projection, bias and taps) is
 * common/direct_light.h, shared with the voxelizer; the formulas are documented there.
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
#include "common/direct_light.h"
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

#if RP_SHADOW_PCF5
#define RP_SHADOW_FILTER_REACH 2.83f /* farthest 5x5 tap, texels */
#else
#define RP_SHADOW_FILTER_REACH RP_SHADOW_RADIUS
#endif

/* Shadow visibility in [0,1] of world point p with unit normal n, cos_theta = dot(n, l): one
 * rotated Poisson tap or the 5x5 PCF (common/direct_light.h does the projection and the taps). */
inline float light_shadow(__global const FrameConstants* frame, __global const float* shadow,
                          float3 p, float3 n, float cos_theta, uint x, uint y) {
  const RpShadowLookup s = rp_shadow_lookup(frame, p, n, cos_theta, RP_SHADOW_NORMAL_OFFSET,
                                            RP_SHADOW_DEPTH_BIAS, RP_SHADOW_FILTER_REACH);
  if (!s.inside) return 1.0f;
#if RP_SHADOW_PCF5
  (void)x;
  (void)y;
  float lit = 0.0f;
  for (int j = -2; j <= 2; ++j)
    for (int i = -2; i <= 2; ++i) lit += rp_shadow_tap(shadow, &s, (float2)((float)i, (float)j));
  return lit * (1.0f / 25.0f);
#else
  const float2 off = rp_poisson_rotated(rp_hash_pixel(x, y, frame->frame_index)) * RP_SHADOW_RADIUS;
  return rp_shadow_tap(shadow, &s, off);
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

  float cos_theta;
  float direct_scale = rp_direct_unshadowed(frame->light_pos.xyz, p, n, &cos_theta);
  if (cos_theta > 0.0f) direct_scale *= light_shadow(frame, shadow, p, n, cos_theta, x, y);
  const float3 direct = albedo * (frame->light_intensity.xyz * direct_scale);
  const float3 indirect = albedo * rp_cone_diffuse(voxels, voxel_resolution, voxel_levels, p, n);
  hdr[pixel] = (float4)(direct + indirect + emission_plane[pixel].xyz, 1.0f);
#if RP_LIGHT_SPLIT
  direct_out[pixel] = (float4)(direct, 1.0f);
  indirect_out[pixel] = (float4)(indirect, 1.0f);
#endif
}
