/* The environment light in the real-time modes (OpenCL C only): radiance from a direction,
 * prefiltered for a cone's aperture, read from the mip chain that FrameConstants.sky describes
 * (shared/types.h: SkyGpu; host: src/render/sky_texture.h).
 *
 * Prefilter: the map's mip chain, each level the solid-angle weighted 2x2 mean of the one
 * below, sampled bilinearly (u wraps, v clamps) and linearly between the two levels whose
 * texels are as tall as the cone is wide: level L = log2(2 atan(tan_half) height / pi), the
 * level-0 texel being pi / height radians tall. SH of 9 or 25 coefficients would ring around
 * a bright sun and cannot follow the narrow specular cones; the chain costs 4/3 of the map.
 *
 * Through the cones: a cone that ends with occlusion A takes the sky in its direction weighted
 * by what the volume left of it, 1 - A / opaque (clamped to [0, 1]): a cone that stopped at its
 * opacity threshold `opaque` counts as closed, so sky light does not leak through walls by the
 * few per cent a marching cone never accumulates. The diffuse cones read the sky prefiltered
 * for their own aperture (RP_SKY_DIFFUSE_TAN = RP_CONE_TAN_HALF: 16 caps of 21.8 degrees cover
 * 7.2 of the hemisphere's 6.3 sr). A wider prefilter smooths the 16 samples but lets a bright
 * patch of sky leak around what blocks it: measured on gen_load_scene --yard under Blender's
 * eight studio-light maps (bench --accuracy, 128x128), 36.9 degrees gave indirect L1 20-115 %
 * where 21.8 gives 14-65 % (bench/results/zen3-2core-pocl-sky-prt.md).
 */
#ifndef ROLYPOLY_COMMON_SKY_H
#define ROLYPOLY_COMMON_SKY_H

#include "shared/types.h"

/* tan of the half-angle the diffuse cones read the sky with: their own (21.8 degrees). */
#ifndef RP_SKY_DIFFUSE_TAN
#define RP_SKY_DIFFUSE_TAN 0.4f
#endif

/* A world direction in the map's frame (the path tracer's EnvironmentSampler::to_map). */
inline float3 rp_sky_to_map(float4 turn, float3 d) {
  return (float3)(turn.x * d.x - turn.y * d.z, d.y, turn.y * d.x + turn.x * d.z);
}

/* Bilinear sample of one level (offset, w x h texels) at map coordinates uv in [0, 1]^2: texel
 * centres at (i + 0.5) / w, u wraps around, v clamps at the poles' rows. */
inline float3 rp_sky_level(__global const float4* restrict texels, uint offset, uint w, uint h,
                           float2 uv) {
  const float x = uv.x * (float)w - 0.5f, y = uv.y * (float)h - 0.5f;
  const float fx = floor(x), fy = floor(y);
  const float tx = x - fx, ty = y - fy;
  const int iw = (int)w;
  int x0 = (int)fx % iw;
  if (x0 < 0) x0 += iw;
  const int x1 = x0 + 1 == iw ? 0 : x0 + 1;
  const int y0 = clamp((int)fy, 0, (int)h - 1), y1 = clamp((int)fy + 1, 0, (int)h - 1);
  const uint r0 = offset + (uint)y0 * w, r1 = offset + (uint)y1 * w;
  const float3 top = mix(texels[r0 + (uint)x0].xyz, texels[r0 + (uint)x1].xyz, tx);
  const float3 bottom = mix(texels[r1 + (uint)x0].xyz, texels[r1 + (uint)x1].xyz, tx);
  return mix(top, bottom, ty);
}

/* Radiance arriving from world direction `dir` (unit), the map prefiltered for a cone of
 * half-angle atan(tan_half) (0: the finest level, as the background shows it). Black without
 * an environment. */
inline float3 rp_sky_radiance(__global const FrameConstants* restrict frame,
                              __global const float4* restrict texels, float3 dir,
                              float tan_half) {
  __global const SkyGpu* sky = &frame->sky;
  const uint levels = sky->levels;
  if (levels == 0u) return (float3)(0.0f);
  const float4 turn = sky->turn;
  const float3 m = rp_sky_to_map(turn, dir);
  const float kInvTwoPi = 0.15915494309f, kInvPi = 0.31830988618f;
  float u = atan2(m.x, -m.z) * kInvTwoPi;
  if (u < 0.0f) u += 1.0f;
  const float2 uv = (float2)(u, acos(clamp(m.y, -1.0f, 1.0f)) * kInvPi);
  const float level = clamp(log2(fmax(2.0f * atan(tan_half) * (float)sky->height * kInvPi, 1.0f)),
                            0.0f, (float)(levels - 1u));
  const uint l0 = (uint)level, l1 = min(l0 + 1u, levels - 1u);
  const float3 a = rp_sky_level(texels, sky->level_offset[l0], max(sky->width >> l0, 1u),
                                max(sky->height >> l0, 1u), uv);
  float3 c = a;
  const float f = level - (float)l0;
  if (f > 0.0f) {
    const float3 b = rp_sky_level(texels, sky->level_offset[l1], max(sky->width >> l1, 1u),
                                  max(sky->height >> l1, 1u), uv);
    c = mix(a, b, f);
  }
  return c * turn.z;
}

/* The share of the sky a cone with occlusion `occlusion` passes on: 1 - occlusion / opaque,
 * clamped (see the header). */
inline float rp_sky_weight(float occlusion, float opaque) {
  return clamp(1.0f - occlusion / opaque, 0.0f, 1.0f);
}

/* A cone's result (radiance, occlusion) with the sky it lets through added. */
inline float3 rp_sky_behind_cone(__global const FrameConstants* restrict frame,
                                 __global const float4* restrict texels, float4 cone,
                                 float3 dir, float tan_half, float opaque) {
  if (frame->sky.levels == 0u) return cone.xyz;
  return cone.xyz +
         rp_sky_weight(cone.w, opaque) * rp_sky_radiance(frame, texels, dir, tan_half);
}

/* The same for a diffuse cone (the lit surfaces' cones, the bounce grid's): no sky where
 * precomputed radiance transfer carries the diffuse sky light instead (SkyGpu.diffuse_cones
 * 0; kernels/prt.cl), so it is not counted twice. */
inline float3 rp_sky_behind_diffuse_cone(__global const FrameConstants* restrict frame,
                                         __global const float4* restrict texels, float4 cone,
                                         float3 dir, float tan_half, float opaque) {
  if (frame->sky.diffuse_cones == 0u) return cone.xyz;
  return rp_sky_behind_cone(frame, texels, cone, dir, tan_half, opaque);
}

#endif
