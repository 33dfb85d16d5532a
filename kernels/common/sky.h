/* The environment light in the real-time modes (OpenCL C only): radiance from a direction,
 * prefiltered for a cone's aperture, read from the mip chain that FrameConstants.sky describes,
 * and the diffuse cones' sky from the table after it (shared/types.h: SkyGpu; host:
 * src/render/sky_texture.h, src/render/sky_cells.h).
 *
 * Prefilter: the map's mip chain, each level the solid-angle weighted 2x2 mean of the one
 * below, sampled bilinearly (u wraps, v clamps) and linearly between the two levels whose
 * texels are as tall as the cone is wide: level L = log2(2 atan(tan_half) height / pi), the
 * level-0 texel being pi / height radians tall. SH of 9 or 25 coefficients would ring around
 * a bright sun and cannot follow the narrow specular cones; the chain costs 4/3 of the map.
 *
 * Through the cones: a cone that ends with occlusion A takes the sky weighted by what the
 * volume left of it, 1 - A / opaque (clamped to [0, 1]): a cone that stopped at its opacity
 * threshold `opaque` counts as closed, so sky light does not leak through walls by the few per
 * cent a marching cone never accumulates. A specular cone reads the chain in its direction,
 * prefiltered for its aperture. A diffuse cone stands for one 16th of the cosine-weighted
 * hemisphere, its cell (common/cone_trace.h), and reads the map averaged over that cell with
 * weight cos theta, from a table made on the host per map for a grid of normals in the map's
 * frame (shared/types.h: RP_SKY_CELL_SIDE; src/render/sky_cells.h), interpolated. Reading
 * the chain around the cone's axis instead (a 21.8-degree prefilter) weighted a bright patch
 * near the horizon with the ring's cosine and let the map's lower half in: 1.96x the
 * irradiance of studio.exr's residual for an upward normal. Unoccluded, the 16 cells sum to
 * the irradiance / pi of the map whatever its shape.
 */
#ifndef ROLYPOLY_COMMON_SKY_H
#define ROLYPOLY_COMMON_SKY_H

#include "shared/types.h"

/* Built with -DRP_SKY_DIFFUSE_CONES=0 (frames whose diffuse cones carry no sky: the indirect
 * and bounce passes pick that variant, src/render/sky_texture.h: kNoDiffuseSkyOption), the
 * diffuse cones' sky code compiles away; otherwise SkyGpu.diffuse_cones decides per frame.
 * (The runtime test alone cost the busy demo's indirect_trace 0.3-0.5 ms of 8.5-9 at 720x720
 * on the 2-core Zen 5: PoCL computes both sides of it.) */
#ifndef RP_SKY_DIFFUSE_CONES
#define RP_SKY_DIFFUSE_CONES 1
#endif

/* A world direction in the map's frame (the path tracer's EnvironmentSampler::to_map). */
inline float3 rp_sky_to_map(float4 turn, float3 d) {
  return (float3)(turn.x * d.x - turn.y * d.z, d.y, turn.y * d.x + turn.x * d.z);
}

/* The world direction of a direction in the map's frame (rp_sky_to_map's inverse). */
inline float3 rp_sky_from_map(float4 turn, float3 m) {
  return (float3)(turn.x * m.x + turn.y * m.z, m.y, turn.x * m.z - turn.y * m.x);
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

/* The axis the diffuse cones' basis turns about with a sky (common/cone_trace.h:
 * rp_cone_sky_basis; src/render/sky_cells.h): a unit direction no axis-aligned or diagonal
 * normal is near. */
#define RP_SKY_BASIS_AXIS ((float3)(0.36f, 0.48f, 0.8f))

/* The four table rows around a world normal and their bilinear weights. */
typedef struct {
  uint4 rows;     /* first texel of each row */
  float4 weight;  /* sums to 1 */
} RpSkyCells;

/* The rows of the diffuse cones' table for world normal n (unit): the four grid normals around
 * it in the octahedral grid of the map's frame (shared/types.h), weighted bilinearly. */
inline RpSkyCells rp_sky_cells(__global const FrameConstants* restrict frame, float3 n) {
  __global const SkyGpu* sky = &frame->sky;
  RpSkyCells c;
  if (!RP_SKY_DIFFUSE_CONES || sky->diffuse_cones == 0u) { /* not read */
    c.rows = (uint4)(0u);
    c.weight = (float4)(0.0f);
    return c;
  }
  const float3 m = rp_sky_to_map(sky->turn, n);
  float2 p = m.xy * (1.0f / (fabs(m.x) + fabs(m.y) + fabs(m.z)));
  if (m.z < 0.0f)
    p = (1.0f - fabs(p.yx)) * (float2)(copysign(1.0f, p.x), copysign(1.0f, p.y));
  const float last = (float)(RP_SKY_CELL_SIDE - 1u);
  const float2 g = clamp((p + 1.0f) * (0.5f * last), 0.0f, last);
  const float2 g0 = fmin(floor(g), last - 1.0f);
  const float2 f = g - g0;
  const uint i = (uint)g0.x, j = (uint)g0.y;
  const uint r = sky->cell_offset + 16u * (j * RP_SKY_CELL_SIDE + i);
  c.rows = (uint4)(r, r + 16u, r + 16u * RP_SKY_CELL_SIDE, r + 16u * (RP_SKY_CELL_SIDE + 1u));
  c.weight = (float4)((1.0f - f.x) * (1.0f - f.y), f.x * (1.0f - f.y), (1.0f - f.x) * f.y,
                      f.x * f.y);
  return c;
}

/* A diffuse cone's result (radiance, occlusion) with the sky of its cell added: cone k of the
 * set whose table rows `cells` (rp_sky_cells) hold. Nothing where precomputed radiance
 * transfer carries the diffuse sky light instead (SkyGpu.diffuse_cones 0; kernels/prt.cl), so
 * it is not counted twice. */
inline float3 rp_sky_behind_diffuse_cone(__global const FrameConstants* restrict frame,
                                         __global const float4* restrict texels, float4 cone,
                                         RpSkyCells cells, uint k, float opaque) {
  if (!RP_SKY_DIFFUSE_CONES || frame->sky.diffuse_cones == 0u) return cone.xyz;
  const float3 s = cells.weight.x * texels[cells.rows.x + k].xyz +
                   cells.weight.y * texels[cells.rows.y + k].xyz +
                   cells.weight.z * texels[cells.rows.z + k].xyz +
                   cells.weight.w * texels[cells.rows.w + k].xyz;
  return cone.xyz + rp_sky_weight(cone.w, opaque) * frame->sky.turn.z * s;
}

#endif
