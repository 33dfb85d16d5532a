/* Bounce gather (several bounces): the irradiance every face of the bounce grid
 * receives (layout and meaning: common/bounce.h), gathered by cone tracing the voxel chain the
 * frame has just built. The voxelizer adds albedo x this light to the voxels' radiance the next
 * time it runs, so the chain's light has bounced once more with every gather: the grid
 * converges to all bounces (with albedo < 1 the series is bounded). Host: src/passes/bounce.cpp.
 *
 * bounce_gather: one work-item per (cell, face), index 6 * cell + face. A cell takes part when
 * its region holds anything (the level whose voxels are the cell's size, any direction, has
 * opacity > 0); the others keep age 0 and the lookup leaves them out. The cones are the
 * 16-cone diffuse set (common/cone_trace.h) around the face's axis, from the cell's centre,
 * traced with rp_cone_trace_coarse and per-cell-face jitters.
 *   cones = 16: all of them, their mean replaces the face (the reference mode, and the warm
 *               start after a reset): age 1.
 *   cones = 1:  one face in S = RP_BOUNCE_FACE_STRIDE a frame (face index = frame mod S;
 *               the work-items cover 6 G^3 / S faces), cone (frame / S + hash) mod 16, blended
 *               into the face as a running mean for the first 16 gathers (so after 16 S
 *               frames the face is the mean of the whole set), then exponentially with weight
 *               RP_BOUNCE_ALPHA (the fast mode).
 * Cones that leave the volume bring the sky they let through (common/sky.h), so sky light
 * bounces too.
 * No atomics: bit-identical runs.
 */
#include "shared/types.h"
#include "shared/pass_params.h"
#include "shared/voxel_layout.h"
#include "common/random.h"
#include "common/cone_trace.h"
#include "common/bounce.h"

/* Blend weight of a new cone once a face has seen the whole set. */
#ifndef RP_BOUNCE_ALPHA
#define RP_BOUNCE_ALPHA (1.0f / 32.0f)
#endif

/* Whether the cell (level `lc` voxel v) holds anything. */
inline bool bounce_cell_occupied(__global const float4* voxels, uint resolution, uint lc,
                                 int3 v) {
  if (lc == 0u) return rp_cone_fetch(voxels, resolution, 0u, 0u, v).w > 0.0f;
  for (uint d = 0; d < 6u; ++d)
    if (rp_cone_fetch(voxels, resolution, lc, d, v).w > 0.0f) return true;
  return false;
}

__kernel void bounce_gather(__global const float4* voxels, __global float4* bounce,
                            __global const FrameConstants* constants,
                            __global const float4* sky, const BounceParams params) {
  const uint resolution = params.resolution, levels = params.levels;
  const uint frame = params.frame, cones = params.cones;
  const uint cells = rp_bounce_cells(resolution);
  /* one cone: one face in RP_BOUNCE_FACE_STRIDE per frame, the next ones the next frames */
  const uint gid = cones >= RP_CONE_SET_SIZE
                       ? (uint)get_global_id(0)
                       : RP_BOUNCE_FACE_STRIDE * (uint)get_global_id(0) +
                             frame % RP_BOUNCE_FACE_STRIDE;
  if (gid >= 6u * cells * cells * cells) return;
  const uint cell = gid / 6u, face = gid - 6u * cell;
  const int3 v = (int3)((int)(cell % cells), (int)((cell / cells) % cells),
                        (int)(cell / (cells * cells)));
  uint lc = 0u;
  while ((cells << lc) < resolution) ++lc;
  if (!bounce_cell_occupied(voxels, resolution, lc, v)) {
    bounce[gid] = (float4)(0.0f);
    return;
  }
  const float3 origin = (convert_float3(v) + 0.5f) * (2.0f / (float)cells) - 1.0f;
  const float sign = (face & 1u) ? -1.0f : 1.0f;
  const uint axis = face >> 1;
  const float3 n = (float3)(axis == 0u ? sign : 0.0f, axis == 1u ? sign : 0.0f,
                            axis == 2u ? sign : 0.0f);
  float3 t, b;
  rp_cone_sky_basis(constants, n, &t, &b);
  const RpSkyCells sky_cells = rp_sky_cells(constants, n);
  const uint h = rp_hash_u32(gid ^ 0x68bc21ebu);
  const float u_pos = rp_hash_to_unit(rp_hash_u32(h ^ frame));
  const float u_level = rp_hash_to_unit(rp_hash_u32(h + 0x9e3779b9u * (frame + 1u)));
  if (cones >= RP_CONE_SET_SIZE) {
    float3 sum = (float3)(0.0f);
    for (uint k = 0; k < RP_CONE_SET_SIZE; ++k) {
      const float up = u_pos + 0.618034f * (float)k, ul = u_level + 0.754877666f * (float)k;
      const float3 dir = rp_cone_set16_dir(n, t, b, k);
      sum += rp_sky_behind_diffuse_cone(constants, sky,
                                        rp_cone_trace_coarse(voxels, resolution, levels, origin,
                                                             dir, up - floor(up), ul - floor(ul)),
                                        sky_cells, k, RP_CONE_OPAQUE_COARSE);
    }
    bounce[gid] = (float4)(sum * (1.0f / (float)RP_CONE_SET_SIZE), 1.0f);
    return;
  }
  const uint k = (frame / RP_BOUNCE_FACE_STRIDE + h) & (RP_CONE_SET_SIZE - 1u);
  const float3 dir = rp_cone_set16_dir(n, t, b, k);
  const float3 s = rp_sky_behind_diffuse_cone(
      constants, sky, rp_cone_trace_coarse(voxels, resolution, levels, origin, dir, u_pos, u_level),
      sky_cells, k, RP_CONE_OPAQUE_COARSE);
  const float4 old = bounce[gid];
  const float age = old.w;
  const float alpha = fmax(1.0f / (age + 1.0f), RP_BOUNCE_ALPHA);
  bounce[gid] = (float4)(mix(old.xyz, s, alpha), fmin(age + 1.0f, 255.0f));
}
