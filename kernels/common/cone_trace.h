/* Voxel cone tracing through the anisotropic mip chain (OpenCL C only; SPEC 6.4-6.5).
 *
 * The chain is one float4 buffer laid out as kernels/shared/voxel_layout.h says: level 0 one
 * isotropic R^3 volume, every level l >= 1 six directional volumes (+x,-x,+y,-y,+z,-z) of
 * n_l = R >> l voxels per side; voxel = (premultiplied radiance rgb, opacity a). The box is
 * [-1,1]^3, so a level-l voxel is s_l = 2 / n_l wide (v0 = 2 / R at level 0). Volume +x holds
 * what a cone travelling towards +x sees (common/voxel.h: composited front to back from the
 * low-x face).
 *
 * Sampling (quadrilinear): trilinear inside a level with clamp-to-edge addressing (voxel
 * centres at -1 + (i + 0.5) s_l; positions beyond the outermost centres take the edge voxel:
 * cones stop at the box's faces, so samples lie inside the box and read the voxel covering
 * them), linear between the two levels around the fractional level L:
 *   L = 0:          the isotropic level 0
 *   0 < L < 1:      mix(isotropic level 0, directional level 1, L)
 *   1 <= L < top:   mix(directional floor(L), directional floor(L) + 1, fract(L))
 *   L >= top:       directional level `top`
 * "Directional level l" for a cone travelling along unit d is the sum of three volumes, the
 * ones facing the cone (+x if d.x >= 0 else -x, likewise y and z), weighted by d.x^2, d.y^2,
 * d.z^2 (the weights sum to 1): rp_voxel_cone_dirs (common/voxel.h, the convention's one
 * definition).
 *
 * Rows behind the apex. A directional voxel is composited as if the cone entered it through its
 * face; a voxel that contains the cone's apex (or lies behind it) was entered behind the apex,
 * and its composite shows what lies behind the cone: for a cone leaving the floor along +y,
 * every +y voxel of the floor's row shows the floor in front. Plain quadrilinear sampling
 * therefore makes surfaces see themselves: measured with the C++ reference on a 64^3 Cornell
 * box (lit walls, one block) against brute-force hemisphere integration over level 0, a floor
 * point got 0.46 indirect (0.85 from itself) where the truth is 0.15, the ceiling 0.06 where the
 * truth is 0.33 (it saw its own dark voxels), mean error 0.28 over nine points. So, per axis,
 * the taps in the apex's row along that axis or behind it (row index <= the apex's for a cone
 * going +axis, >= for -axis, at the sampled level) count as empty in that axis's volume, and
 * cones sample at most level top = levels - 2 (the 1^3 level always contains the apex, so it
 * would always read as empty). Same test: mean error 0.13, floor 0.23, ceiling 0.18. The price
 * is that content sharing the apex's row at a coarse level is seen only at finer levels.
 * Level 0 (isotropic) has no such rule: its taps are clear of the surface's own voxel by the
 * start offset (at most 7 % of one tap's weight for the tilted cones' first sample).
 *
 * One cone (half-angle atan 0.4 = 21.80 degrees, diameter d(t) = 2 t tan_h = 0.8 t at distance t
 * from its apex):
 *   first sample at t0 = v0 / (2 tan_h) = 1.25 v0, where the diameter is one level-0 voxel (L = 0);
 *   each step advances by a fraction s of the current diameter (s = 1/2 by default, 1/4 for
 *   the reference mode's "twice the steps"), t' = t (1 + 2 s tan_h), so the diameter and the
 *   sampled voxel size grow by the constant factor g = 1 + 2 s tan_h per step (1.4 for s = 1/2,
 *   1.2 for s = 1/4) and the level by the constant log2(g) (0.48543 / 0.26303): L_k = k log2 g,
 *   stepped by an addition (no log2 or pow per sample);
 *   since a step is a fraction s of the sampled voxel, each sample's opacity is corrected to
 *   that thickness, a' = 1 - (1 - a)^s, and its premultiplied radiance by the same factor a'/a
 *   (1/s steps through a uniform voxel composite to exactly that voxel): with r = 1 - a,
 *   a'/a = 1 / (1 + sqrt r) for s = 1/2 and 1 / ((1 + q)(1 + q^2)), q = r^(1/4), for s = 1/4;
 *   front-to-back accumulation c += (1 - A) c_s, A += (1 - A) a_s;
 *   stop when A >= RP_CONE_OPAQUE, when the sample point leaves [-1,1]^3, or after the step
 *   limit (RP_CONE_MAX_STEPS = 16 for s = 1/2: 1.4^16 t0 = 272 v0 lies past the box's diagonal
 *   for R <= 128; 32 for s = 1/4: 1.2^32 t0 = 428 v0; more past R = 128: rp_cone_max_steps).
 * The result is (c, A): c the radiance arriving along the cone (mean over its cross-section),
 * A its occlusion.
 *
 * Measured with bench --accuracy against the path tracer (360x360): level 1 is built
 * from one-sided (facing) voxels (voxel_mips.cl), so cones leaving a wall do not see it; a cone
 * that leaves the box takes the wall it leaves through (rp_cone_exit); and the diffuse estimate
 * is scaled by the near-field occlusion at the apex (rp_cone_near_occlusion). Together: fast
 * mode vs the 1-bounce truth, indirect L1 38 % -> 10 %.
 *
 * Level jitter (the fast mode's cheaper cone, rp_cone_trace_jittered): instead of the
 * quadrilinear blend of the two levels around L (two directional lookups, 48 float4 loads),
 * each sample reads ONE level, floor(L + u) for a jitter u in [0, 1) chosen per cone and frame
 * (clamped to the top level): its expectation over u is the linear blend, so temporal
 * accumulation integrates the quadrilinear sample at half the loads.
 *
 * Diffuse cone set (16 cones, rp_cone_set16_dir): the cosine-weighted hemisphere mapped to the
 * unit disk (r = sin theta: cosine-weighted measure is uniform in disk area, i.e. in r^2) cut
 * into 16 cells of equal area, one cone through each cell's centre (r^2 midway in its ring):
 *   cone 0:       along n (the disk r^2 < 1/16)
 *   cones 1..5:   sin^2 theta = 3.5/16 (theta = 27.89 deg), azimuths 0, 72, .., 288 deg
 *                 (ring 1/16 < r^2 < 6/16)
 *   cones 6..15:  sin^2 theta = 11/16 (theta = 56.01 deg), azimuths 18 + 36 k deg
 *                 (ring 6/16 < r^2 < 1, interleaved with ring 1)
 * in the per-pixel orthonormal basis (t, b, n) of Duff et al. 2017 (a function of n only). Each
 * cone carries 1/16 of the cosine-weighted hemisphere (integral of cos = pi), so the plain mean
 * of the 16 cone radiances is the irradiance over pi: a Lambertian surface reflects indirect
 * radiance albedo * mean, and a uniform surrounding radiance L gives exactly albedo * L. The
 * 21.8-degree cones (0.449 sr each, 7.2 sr together) cover the hemisphere with a little
 * overlap. The cones start at p + n * RP_CONE_NORMAL_OFFSET * v0 (that point is their apex) so
 * a surface does not see its own voxels at level 0.
 * rp_cone_diffuse16 traces all 16 with quarter-diameter steps (the reference mode, per pixel);
 * the fast mode (kernels/indirect.cl) traces one cone of the set per low-resolution pixel.
 *
 * The GI volume. Everything above reads the volume through three functions:
 * rp_cone_volume (trilinear sample of one volume: a level and direction), rp_cone_directional
 * (the three facing volumes of a level, rows behind the apex empty) and rp_cone_fetch (one
 * voxel). By default they read the dense chain; built with -DRP_GI_SVO, `voxels` is the sparse
 * voxel octree's buffer (shared/svo_layout.h) and they descend it to the node holding the
 * footprint's first tap and read its 3^3 brick: the same taps, fractions and mixing order, so
 * the same values (bit for bit with float brick samples; tests/passes/svo_test.cpp). Callers
 * (the light, indirect, bounce and debug passes) pass the octree buffer, R and levels = log2 R
 * + 1 unchanged, and pick the variant with the build option.
 */
#ifndef ROLYPOLY_COMMON_CONE_TRACE_H
#define ROLYPOLY_COMMON_CONE_TRACE_H

#include "shared/voxel_layout.h"
#include "common/sky.h"
#include "common/voxel.h"
#ifdef RP_GI_SVO
#include "common/svo.h"
#endif

/* Cone start offset along the surface normal, in level-0 voxels. */
#ifndef RP_CONE_NORMAL_OFFSET
#define RP_CONE_NORMAL_OFFSET 1.0f
#endif
/* Accumulated opacity at which a cone stops. */
#ifndef RP_CONE_OPAQUE
#define RP_CONE_OPAQUE 0.95f
#endif
/* Most samples per cone with half-diameter steps (twice that with quarter-diameter steps). */
#ifndef RP_CONE_MAX_STEPS
#define RP_CONE_MAX_STEPS 16
#endif

#define RP_CONE_TAN_HALF 0.4f            /* tan of the half-angle, 21.80 degrees */
#define RP_CONE_T0 1.25f                 /* first sample distance in level-0 voxels: 1 / (2 tan_h) */
#define RP_CONE_GROWTH 1.4f              /* t factor per half-diameter step: 1 + tan_h */
#define RP_CONE_LEVEL_STEP 0.485426827f  /* log2(1.4) */
#define RP_CONE_GROWTH_FINE 1.2f         /* t factor per quarter-diameter step: 1 + tan_h / 2 */
#define RP_CONE_LEVEL_STEP_FINE 0.263034406f /* log2(1.2) */
#define RP_CONE_GROWTH_COARSE 1.8f       /* t factor per full-diameter step: 1 + 2 tan_h */
#define RP_CONE_LEVEL_STEP_COARSE 0.847996907f /* log2(1.8) */
/* The coarse cone stops at this accumulated opacity, and after `levels` samples (1.25 v0 1.8^6 =
 * 43-76 v0 for R = 64, R = 2^(levels - 1): most of the box). Measured at 128x128 against the
 * reference mode: PSNR unchanged (36.93 -> 36.98 / 36.99 dB for each), trace time -15 % each. */
#ifndef RP_CONE_OPAQUE_COARSE
#define RP_CONE_OPAQUE_COARSE 0.9f
#endif
#define RP_CONE_SET_SIZE 16
/* Strength of the near-field occlusion (rp_cone_near_occlusion). */
#ifndef RP_CONE_NEAR_OCCLUSION
#define RP_CONE_NEAR_OCCLUSION 0.6f
#endif

/* First float4 of level `level` >= 1 (its +x volume): R^3 for level 0, then six volumes of
 * (R >> k)^3 per level k. With R = 2^m the sum over k = 1 .. l-1 is the geometric series
 * (R^3 - (R >> (l-1))^3) / 7, exact in integers; equals rp_voxel_offset(R, l, 0). */
inline uint rp_cone_level_base(uint resolution, uint level) {
  const uint r3 = resolution * resolution * resolution;
  const uint m = resolution >> (level - 1u);
  return r3 + 6u * ((r3 - m * m * m) / 7u);
}

/* Trilinear footprint of point p in a volume of n^3 voxels over [-1,1]^3: the 8 voxel indices
 * (relative to the volume's first voxel) and the fractional position between them. */
typedef struct {
  uint i000, i100, i010, i110, i001, i101, i011, i111;
  uint x0, x1, y0, y1, z0, z1; /* the voxel coordinates the taps use */
  float3 f;
} ConeFootprint;

inline ConeFootprint rp_cone_footprint(uint n, float3 p) {
  const float nf = (float)n;
  const float3 u = clamp((p + 1.0f) * (0.5f * nf) - 0.5f, 0.0f, nf - 1.0f);
  const float3 fl = floor(u);
  const uint x0 = (uint)fl.x, y0 = (uint)fl.y, z0 = (uint)fl.z;
  const uint x1 = min(x0 + 1u, n - 1u), y1 = min(y0 + 1u, n - 1u), z1 = min(z0 + 1u, n - 1u);
  ConeFootprint fp;
  fp.f = u - fl;
  fp.x0 = x0; fp.x1 = x1; fp.y0 = y0; fp.y1 = y1; fp.z0 = z0; fp.z1 = z1;
  const uint r00 = (z0 * n + y0) * n, r10 = (z0 * n + y1) * n;
  const uint r01 = (z1 * n + y0) * n, r11 = (z1 * n + y1) * n;
  fp.i000 = r00 + x0; fp.i100 = r00 + x1;
  fp.i010 = r10 + x0; fp.i110 = r10 + x1;
  fp.i001 = r01 + x0; fp.i101 = r01 + x1;
  fp.i011 = r11 + x0; fp.i111 = r11 + x1;
  return fp;
}

inline float4 rp_cone_trilinear_mix(float4 c000, float4 c100, float4 c010, float4 c110,
                                    float4 c001, float4 c101, float4 c011, float4 c111,
                                    float3 f) {
  const float4 c00 = mix(c000, c100, f.x), c10 = mix(c010, c110, f.x);
  const float4 c01 = mix(c001, c101, f.x), c11 = mix(c011, c111, f.x);
  return mix(mix(c00, c10, f.y), mix(c01, c11, f.y), f.z);
}

/* Trilinear sample of one volume (first voxel `vol`, n^3 voxels) at p. */
inline float4 rp_cone_trilinear(__global const float4* vol, uint n, float3 p) {
  const ConeFootprint fp = rp_cone_footprint(n, p);
  return rp_cone_trilinear_mix(vol[fp.i000], vol[fp.i100], vol[fp.i010], vol[fp.i110],
                               vol[fp.i001], vol[fp.i101], vol[fp.i011], vol[fp.i111], fp.f);
}

#ifndef RP_GI_SVO
/* Trilinear sample of volume `dir` (ignored at level 0) of level `level` at p. */
inline float4 rp_cone_volume(__global const float4* voxels, uint resolution, uint level,
                             uint dir, float3 p) {
  if (level == 0u) return rp_cone_trilinear(voxels, resolution, p);
  const uint n = resolution >> level;
  return rp_cone_trilinear(voxels + rp_cone_level_base(resolution, level) + dir * n * n * n, n,
                           p);
}

/* Voxel v of volume `dir` at `level` (rp_voxel_fetch). */
inline float4 rp_cone_fetch(__global const float4* voxels, uint resolution, uint level, uint dir,
                            int3 v) {
  return rp_voxel_fetch(voxels, resolution, level, dir, v);
}

/* Directional sample of level `level` >= 1 for a cone whose three facing volumes are dirs
 * (RP_DIR_* indices) with weights w (the squared direction components), apex at `apex`: the
 * weighted sum of the three trilinear samples, evaluated as one trilinear mix of the weighted
 * voxel sums. Along each axis, voxels in the apex's row or behind it (for the cone's direction
 * along that axis) count as empty in that axis's volume: see "Rows behind the apex" above. */
inline float4 rp_cone_directional(__global const float4* voxels, uint resolution, uint level,
                                  uint3 dirs, float3 w, float3 p, float3 apex) {
  const uint n = resolution >> level;
  const uint n3 = n * n * n;
  const uint base = rp_cone_level_base(resolution, level);
  __global const float4* vx = voxels + base + dirs.x * n3;
  __global const float4* vy = voxels + base + dirs.y * n3;
  __global const float4* vz = voxels + base + dirs.z * n3;
  const ConeFootprint fp = rp_cone_footprint(n, p);
  const float nf = (float)n;
  /* the apex's row along each axis: -1 / n when it lies beyond the box (nothing skipped) */
  const int3 ar = convert_int3(clamp(floor((apex + 1.0f) * (0.5f * nf)), -1.0f, nf));
  const int ax = ar.x, ay = ar.y, az = ar.z;
  const int x0 = (int)fp.x0, x1 = (int)fp.x1, y0 = (int)fp.y0, y1 = (int)fp.y1;
  const int z0 = (int)fp.z0, z1 = (int)fp.z1;
  /* weight of each volume for the low (0) and high (1) tap along its own axis */
  const bool px = dirs.x == RP_DIR_POS_X, py = dirs.y == RP_DIR_POS_Y, pz = dirs.z == RP_DIR_POS_Z;
  const float wx0 = (px ? x0 > ax : x0 < ax) ? w.x : 0.0f;
  const float wx1 = (px ? x1 > ax : x1 < ax) ? w.x : 0.0f;
  const float wy0 = (py ? y0 > ay : y0 < ay) ? w.y : 0.0f;
  const float wy1 = (py ? y1 > ay : y1 < ay) ? w.y : 0.0f;
  const float wz0 = (pz ? z0 > az : z0 < az) ? w.z : 0.0f;
  const float wz1 = (pz ? z1 > az : z1 < az) ? w.z : 0.0f;
#define RP_CONE_TAP(X, Y, Z) \
  (vx[fp.i##X##Y##Z] * wx##X + vy[fp.i##X##Y##Z] * wy##Y + vz[fp.i##X##Y##Z] * wz##Z)
  const float4 s = rp_cone_trilinear_mix(RP_CONE_TAP(0, 0, 0), RP_CONE_TAP(1, 0, 0),
                                         RP_CONE_TAP(0, 1, 0), RP_CONE_TAP(1, 1, 0),
                                         RP_CONE_TAP(0, 0, 1), RP_CONE_TAP(1, 0, 1),
                                         RP_CONE_TAP(0, 1, 1), RP_CONE_TAP(1, 1, 1), fp.f);
#undef RP_CONE_TAP
  return s;
}

#else /* RP_GI_SVO: the same three functions on the octree (common/svo.h) */

/* The brick holding the trilinear footprint of p at `level` (RP_SVO_NO_BRICK: none, and then
 * every tap is empty) and the taps' first sample offset o inside it; x0: the first taps. */
inline uint rp_cone_svo_brick(__global const float4* svo, uint resolution, uint level, float3 p,
                              uint3* x0, float3* f) {
  const uint depths = rp_svo_header(svo, RP_SVO_HDR_DEPTHS);
  *x0 = rp_svo_footprint(resolution >> level, p, f);
  if (level >= depths) return RP_SVO_NO_BRICK;
  return rp_svo_find_brick(rp_svo_nodes(svo), depths - 1u - level, *x0 >> 1);
}

inline float4 rp_cone_volume(__global const float4* voxels, uint resolution, uint level,
                             uint dir, float3 p) {
  uint3 x0;
  float3 f;
  const uint brick = rp_cone_svo_brick(voxels, resolution, level, p, &x0, &f);
  if (brick == RP_SVO_NO_BRICK) return (float4)(0.0f);
  const uint3 o = x0 & 1u;
  const uint b = brick + (level == 0u ? 0u : RP_SVO_BRICK_SAMPLES * dir) +
                 rp_svo_sample(o.x, o.y, o.z);
  /* sample offsets of the taps: +1 along x, +3 along y, +9 along z */
  return rp_cone_trilinear_mix(rp_svo_load(voxels, b), rp_svo_load(voxels, b + 1u),
                               rp_svo_load(voxels, b + 3u), rp_svo_load(voxels, b + 4u),
                               rp_svo_load(voxels, b + 9u), rp_svo_load(voxels, b + 10u),
                               rp_svo_load(voxels, b + 12u), rp_svo_load(voxels, b + 13u), f);
}

inline float4 rp_cone_fetch(__global const float4* voxels, uint resolution, uint level, uint dir,
                            int3 v) {
  return rp_svo_fetch(voxels, resolution, level, dir, v);
}

/* rp_cone_directional of the dense chain (above) on the octree: one brick holds the taps of
 * all three volumes. The taps' coordinates for the rows-behind-the-apex rule are the dense
 * sampler's (x1 = min(x0 + 1, n - 1)). */
inline float4 rp_cone_directional(__global const float4* voxels, uint resolution, uint level,
                                  uint3 dirs, float3 w, float3 p, float3 apex) {
  const uint n = resolution >> level;
  uint3 x0u;
  float3 f;
  const uint brick = rp_cone_svo_brick(voxels, resolution, level, p, &x0u, &f);
  if (brick == RP_SVO_NO_BRICK) return (float4)(0.0f);
  const float nf = (float)n;
  const int3 ar = convert_int3(clamp(floor((apex + 1.0f) * (0.5f * nf)), -1.0f, nf));
  const int ax = ar.x, ay = ar.y, az = ar.z;
  const int x0 = (int)x0u.x, y0 = (int)x0u.y, z0 = (int)x0u.z;
  const int last = (int)n - 1;
  const int x1 = min(x0 + 1, last), y1 = min(y0 + 1, last), z1 = min(z0 + 1, last);
  const bool px = dirs.x == RP_DIR_POS_X, py = dirs.y == RP_DIR_POS_Y, pz = dirs.z == RP_DIR_POS_Z;
  const float wx0 = (px ? x0 > ax : x0 < ax) ? w.x : 0.0f;
  const float wx1 = (px ? x1 > ax : x1 < ax) ? w.x : 0.0f;
  const float wy0 = (py ? y0 > ay : y0 < ay) ? w.y : 0.0f;
  const float wy1 = (py ? y1 > ay : y1 < ay) ? w.y : 0.0f;
  const float wz0 = (pz ? z0 > az : z0 < az) ? w.z : 0.0f;
  const float wz1 = (pz ? z1 > az : z1 < az) ? w.z : 0.0f;
  const uint3 o = x0u & 1u;
  const uint s0 = rp_svo_sample(o.x, o.y, o.z);
  const uint bx = brick + RP_SVO_BRICK_SAMPLES * dirs.x + s0;
  const uint by = brick + RP_SVO_BRICK_SAMPLES * dirs.y + s0;
  const uint bz = brick + RP_SVO_BRICK_SAMPLES * dirs.z + s0;
#define RP_CONE_SVO_TAP(X, Y, Z)                                            \
  (rp_svo_load(voxels, bx + (X) + 3u * (Y) + 9u * (Z)) * wx##X +           \
   rp_svo_load(voxels, by + (X) + 3u * (Y) + 9u * (Z)) * wy##Y +           \
   rp_svo_load(voxels, bz + (X) + 3u * (Y) + 9u * (Z)) * wz##Z)
  const float4 s = rp_cone_trilinear_mix(RP_CONE_SVO_TAP(0, 0, 0), RP_CONE_SVO_TAP(1, 0, 0),
                                         RP_CONE_SVO_TAP(0, 1, 0), RP_CONE_SVO_TAP(1, 1, 0),
                                         RP_CONE_SVO_TAP(0, 0, 1), RP_CONE_SVO_TAP(1, 0, 1),
                                         RP_CONE_SVO_TAP(0, 1, 1), RP_CONE_SVO_TAP(1, 1, 1), f);
#undef RP_CONE_SVO_TAP
  return rp_svo_solid_apply(voxels, resolution, level, p, s);
}
#endif /* RP_GI_SVO */

/* Quadrilinear sample at p and fractional level `level` >= 0 (see the header for the rule),
 * levels coarser than `top` clamped to `top`; apex: the cone's apex. */
inline float4 rp_cone_sample(__global const float4* voxels, uint resolution, uint top,
                             uint3 dirs, float3 w, float3 p, float level, float3 apex) {
  if (level < 1.0f || top == 0u) {
    const float4 iso = rp_cone_volume(voxels, resolution, 0u, 0u, p);
    if (level <= 0.0f || top == 0u) return iso;
    return mix(iso, rp_cone_directional(voxels, resolution, 1u, dirs, w, p, apex), level);
  }
  const float lf = floor(level);
  const uint l = (uint)lf;
  if (l >= top) return rp_cone_directional(voxels, resolution, top, dirs, w, p, apex);
  const float4 lo = rp_cone_directional(voxels, resolution, l, dirs, w, p, apex);
  const float4 hi = rp_cone_directional(voxels, resolution, l + 1u, dirs, w, p, apex);
  return mix(lo, hi, level - lf);
}

/* Single-level sample at integer level `level` (0: isotropic), clamped to `top`. */
inline float4 rp_cone_sample_level(__global const float4* voxels, uint resolution, uint top,
                                   uint3 dirs, float3 w, float3 p, uint level, float3 apex) {
  if (level == 0u || top == 0u) return rp_cone_volume(voxels, resolution, 0u, 0u, p);
  return rp_cone_directional(voxels, resolution, min(level, top), dirs, w, p, apex);
}

/* Coarsest level a cone samples: levels - 2 (the 1^3 level contains every apex, so with the
 * rows-behind-the-apex rule it would always read as empty). */
inline uint rp_cone_top_level(uint levels) { return levels >= 2u ? levels - 2u : 0u; }

/* What a cone that leaves the box sees in the face it leaves through: the box's walls lie on
 * its faces, so a ray that reaches a face ends on the wall there (or in the open, where the
 * volume is empty). A cone steps in growing strides and reads the walls' voxels through the
 * d^2-weighted blend of three volumes, of which only the one across the wall sees the wall
 * (the others see it edge on), so without this term a cone meeting a wall at 45 degrees would
 * take half its light: measured on the demo, indirect light 40 % short everywhere. Returns the
 * sample of the volume facing the cone across that face (premultiplied) at level
 * clamp(floor(level), 1, top) at the exit point. */
inline float4 rp_cone_exit(__global const float4* voxels, uint resolution, uint top, uint3 dirs,
                           float3 origin, float3 dir, float level) {
  if (top == 0u) return (float4)(0.0f);
  const float3 face = (float3)(dir.x >= 0.0f ? 1.0f : -1.0f, dir.y >= 0.0f ? 1.0f : -1.0f,
                               dir.z >= 0.0f ? 1.0f : -1.0f);
  const float big = 1.0e30f;
  const float tx = dir.x != 0.0f ? (face.x - origin.x) / dir.x : big;
  const float ty = dir.y != 0.0f ? (face.y - origin.y) / dir.y : big;
  const float tz = dir.z != 0.0f ? (face.z - origin.z) / dir.z : big;
  const float t = fmin(fmin(tx, ty), tz);
  const uint volume_dir = t == tx ? dirs.x : (t == ty ? dirs.y : dirs.z);
  const uint l = (uint)clamp(floor(level), 1.0f, (float)top);
  return rp_cone_volume(voxels, resolution, l, volume_dir, origin + dir * t);
}

/* Doublings of the resolution past 128 (levels - 8 for levels > 8, else 0): the step limits
 * below were set for R <= 128, where a cone's last sample lies past the box's diagonal
 * (sqrt 3 R voxels); at R = 256 and 512 (the octree) a cone would stop halfway, so each
 * doubling adds two half-diameter steps (1.4^2 ~ 2), four quarter-diameter steps and one
 * full-diameter step (1.8). R <= 128 is unchanged. */
inline int rp_cone_extra_levels(uint levels) {
  /* in floats: the integer form compiles to llvm.usub.sat, which oclgrind 21.10 cannot run */
  return (int)fmax((float)levels - 8.0f, 0.0f);
}

/* Half-diameter steps of a cone: RP_CONE_MAX_STEPS, + 2 per doubling past R = 128. */
inline int rp_cone_max_steps(uint levels) {
  return RP_CONE_MAX_STEPS + 2 * rp_cone_extra_levels(levels);
}

/* One cone from `origin` along unit `dir` (apex at origin): (radiance rgb, occlusion a).
 * fine = 0: half-diameter steps, 1: quarter-diameter steps (compile-time constants at every call
 * site, so the branches fold). jitter < 0: quadrilinear samples; jitter in [0, 1): single-level
 * samples at floor(L + jitter) (see "Level jitter" above). */
inline float4 rp_cone_march(__global const float4* voxels, uint resolution, uint levels,
                            float3 origin, float3 dir, const int fine, float jitter) {
  const float3 w = dir * dir;
  const uint3 dirs = rp_voxel_cone_dirs(dir);
  const uint top = rp_cone_top_level(levels);
  const float v0 = 2.0f / (float)resolution;
  const float growth = fine ? RP_CONE_GROWTH_FINE : RP_CONE_GROWTH;
  const float level_step = fine ? RP_CONE_LEVEL_STEP_FINE : RP_CONE_LEVEL_STEP;
  const int max_steps = (fine ? 2 : 1) * rp_cone_max_steps(levels);
  float t = RP_CONE_T0 * v0;
  float level = jitter < 0.0f ? 0.0f : jitter;
  float4 acc = (float4)(0.0f);
  for (int k = 0; k < max_steps; ++k) {
    const float3 q = origin + dir * t;
    if (fmax(fmax(fabs(q.x), fabs(q.y)), fabs(q.z)) > 1.0f) { /* left the box: its wall */
      const float4 e = rp_cone_exit(voxels, resolution, top, dirs, origin, dir, level);
      acc.xyz += (1.0f - acc.w) * e.xyz;
      acc.w += (1.0f - acc.w) * e.w;
      break;
    }
    float4 s = jitter < 0.0f
                   ? rp_cone_sample(voxels, resolution, top, dirs, w, q, level, origin)
                   : rp_cone_sample_level(voxels, resolution, top, dirs, w, q, (uint)level, origin);
    /* thickness of a step: a' / a = 1 / (1 + sqrt r) (half) or 1 / ((1 + q)(1 + q^2)),
     * q = r^(1/4) (quarter), r = 1 - a; radiance scaled alike */
    const float r = sqrt(fmax(1.0f - s.w, 0.0f));
    if (fine) {
      const float q4 = sqrt(r);
      s *= 1.0f / ((1.0f + q4) * (1.0f + r));
    } else {
      s *= 1.0f / (1.0f + r);
    }
    acc.xyz += (1.0f - acc.w) * s.xyz;
    acc.w += (1.0f - acc.w) * s.w;
    if (acc.w >= RP_CONE_OPAQUE) break;
    t *= growth;
    level += level_step;
  }
  return acc;
}

/* One cone, half-diameter steps, quadrilinear samples. */
inline float4 rp_cone_trace(__global const float4* voxels, uint resolution, uint levels,
                            float3 origin, float3 dir) {
  return rp_cone_march(voxels, resolution, levels, origin, dir, 0, -1.0f);
}

/* One cone, quarter-diameter steps (twice the steps), quadrilinear samples. */
inline float4 rp_cone_trace_fine(__global const float4* voxels, uint resolution, uint levels,
                                 float3 origin, float3 dir) {
  return rp_cone_march(voxels, resolution, levels, origin, dir, 1, -1.0f);
}

/* One cone, half-diameter steps, single-level samples at floor(L + jitter), jitter in [0, 1). */
inline float4 rp_cone_trace_jittered(__global const float4* voxels, uint resolution, uint levels,
                                     float3 origin, float3 dir, float jitter) {
  return rp_cone_march(voxels, resolution, levels, origin, dir, 0, jitter);
}

/* One cone with full-diameter steps (t' = 1.8 t: about half the samples of rp_cone_trace) and two
 * jitters in [0, 1): the samples sit at t_k = t0 * 1.8^(k + u_pos) (the first sample slides
 * over one step, so over frames the samples cover the whole axis) and read the single level
 * floor(L_k + u_level), L_k = (k + u_pos) * log2(1.8). A step is one sampled voxel thick, so
 * opacity and radiance are used as they are. Stops at RP_CONE_OPAQUE_COARSE or after `levels`
 * samples (see there). The fast mode's cone (see "Level jitter"). */
inline float4 rp_cone_trace_coarse(__global const float4* voxels, uint resolution, uint levels,
                                   float3 origin, float3 dir, float u_pos, float u_level) {
  const float3 w = dir * dir;
  const uint3 dirs = rp_voxel_cone_dirs(dir);
  const uint top = rp_cone_top_level(levels);
  const float v0 = 2.0f / (float)resolution;
  float level = u_pos * RP_CONE_LEVEL_STEP_COARSE;
  float t = RP_CONE_T0 * v0 * exp2(level);
  level += u_level;
  float4 acc = (float4)(0.0f);
  const int max_steps = (int)levels + rp_cone_extra_levels(levels);
  for (int k = 0; k < max_steps; ++k) {
    const float3 q = origin + dir * t;
    if (fmax(fmax(fabs(q.x), fabs(q.y)), fabs(q.z)) > 1.0f) { /* left the box: its wall */
      const float4 e = rp_cone_exit(voxels, resolution, top, dirs, origin, dir, level);
      acc.xyz += (1.0f - acc.w) * e.xyz;
      acc.w += (1.0f - acc.w) * e.w;
      break;
    }
    const float4 s = rp_cone_sample_level(voxels, resolution, top, dirs, w, q, (uint)level, origin);
    acc.xyz += (1.0f - acc.w) * s.xyz;
    acc.w += (1.0f - acc.w) * s.w;
    if (acc.w >= RP_CONE_OPAQUE_COARSE) break;
    t *= RP_CONE_GROWTH_COARSE;
    level += RP_CONE_LEVEL_STEP_COARSE;
  }
  return acc;
}

/* Specular cones: one cone of any aperture, tan_half = tan of its half-angle
 * (the caller maps the coat's roughness to it: common/brdf.h, rp_brdf_spec_cone_tan), from
 * `origin` (its apex) along unit `dir`. The diameter at distance t is
 * d(t) = max(2 t tan_half, v0): a cone thinner than one level-0 voxel samples level 0 (the
 * volume cannot resolve less) and steps as if it were one voxel wide. The sampled level is
 * L = log2(d / v0) (one log2 per sample: the growth is not constant while d is clamped).
 * First sample at t0 = RP_CONE_T0 v0 (the diffuse cones' start, clear of the surface's own
 * voxels by the apex offset); each step advances a fraction s of d (t' = t + s d), so a sample
 * is s of its voxel thick and its opacity and radiance are corrected as in rp_cone_march.
 *   fine = 1 (the reference mode): s = 1/2, quadrilinear samples (rp_cone_sample);
 *   fine = 0 (the fast mode): s = 1, single-level samples at round(L) (one directional
 *     lookup per sample instead of two; deterministic, so nothing to accumulate over frames).
 * Stops at RP_CONE_OPAQUE, on leaving the box (rp_cone_exit: the wall there), or after
 * RP_CONE_SPEC_MAX_STEPS samples (2x for fine). Steps needed to cross the box (2 units,
 * R = 64 voxels) at the narrowest aperture RP_CONE_SPEC_MIN_TAN = 0.1: 4 voxel-wide steps to
 * t = 5 v0, then t grows 1.2x per step, 1.2^18 = 27 -> 22 steps (44 for fine). */
#ifndef RP_CONE_SPEC_MAX_STEPS
#define RP_CONE_SPEC_MAX_STEPS 24
#endif
/* The fast mode's reflection cone stops at this opacity (as the coarse diffuse cone). */
#ifndef RP_CONE_SPEC_OPAQUE_FAST
#define RP_CONE_SPEC_OPAQUE_FAST 0.95f
#endif
/* The fast mode's smallest cone diameter, in level-0 voxels. */
#ifndef RP_CONE_SPEC_MIN_D_FAST
#define RP_CONE_SPEC_MIN_D_FAST 1.0f
#endif
inline float4 rp_cone_trace_aperture(__global const float4* voxels, uint resolution, uint levels,
                                     float3 origin, float3 dir, float tan_half, const int fine) {
  const float3 w = dir * dir;
  const uint3 dirs = rp_voxel_cone_dirs(dir);
  const uint top = rp_cone_top_level(levels);
  const float v0 = 2.0f / (float)resolution;
  const float inv_v0 = 0.5f * (float)resolution;
  const float s = fine ? 0.5f : 1.0f;
  const float d_min = fine ? v0 : RP_CONE_SPEC_MIN_D_FAST * v0;
  const float opaque = fine ? RP_CONE_OPAQUE : RP_CONE_SPEC_OPAQUE_FAST;
  const int max_steps = fine ? 2 * RP_CONE_SPEC_MAX_STEPS : RP_CONE_SPEC_MAX_STEPS;
  float t = RP_CONE_T0 * v0;
  float4 acc = (float4)(0.0f);
  for (int k = 0; k < max_steps; ++k) {
    const float3 q = origin + dir * t;
    const float d = fmax(2.0f * tan_half * t, d_min);
    const float level = log2(d * inv_v0);
    if (fmax(fmax(fabs(q.x), fabs(q.y)), fabs(q.z)) > 1.0f) { /* left the box: its wall */
      const float4 e = rp_cone_exit(voxels, resolution, top, dirs, origin, dir, level);
      acc.xyz += (1.0f - acc.w) * e.xyz;
      acc.w += (1.0f - acc.w) * e.w;
      break;
    }
    float4 smp;
    if (fine) {
      smp = rp_cone_sample(voxels, resolution, top, dirs, w, q, level, origin);
      smp *= 1.0f / (1.0f + sqrt(fmax(1.0f - smp.w, 0.0f))); /* half a voxel thick */
    } else {
      smp = rp_cone_sample_level(voxels, resolution, top, dirs, w, q, (uint)(level + 0.5f),
                                 origin);
    }
    acc.xyz += (1.0f - acc.w) * smp.xyz;
    acc.w += (1.0f - acc.w) * smp.w;
    if (acc.w >= opaque) break;
    t += s * d;
  }
  return acc;
}

/* Orthonormal basis (t, b) completing unit n to a right-handed frame (Duff et al. 2017,
 * "Building an orthonormal basis, revisited"; branch-free, continuous except across n.z = 0). */
inline void rp_cone_basis(float3 n, float3* t, float3* b) {
  const float sign = copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  *t = (float3)(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  *b = (float3)(c, sign + n.y * n.y * a, -n.y);
}

/* The diffuse set's basis for unit n in a frame with an environment whose diffuse light the
 * cones carry: in the map's frame t = normalize(RP_SKY_BASIS_AXIS x n), b = n x t, turned back
 * into the world, so each cone's cell lies in the map where the sky table's does
 * (common/sky.h: rp_sky_cells) whatever the turn. Unlike rp_cone_basis it is continuous except
 * at n = +-RP_SKY_BASIS_AXIS (no scene's axis), so neighbouring normals of the table have
 * neighbouring cells and the table can be interpolated. Otherwise rp_cone_basis(n). */
inline void rp_cone_sky_basis(__global const FrameConstants* restrict frame, float3 n,
                              float3* t, float3* b) {
  if (!RP_SKY_DIFFUSE_CONES || frame->sky.diffuse_cones == 0u) {
    rp_cone_basis(n, t, b);
    return;
  }
  const float4 turn = frame->sky.turn;
  const float3 m = rp_sky_to_map(turn, n);
  float3 c = cross(RP_SKY_BASIS_AXIS, m);
  if (dot(c, c) < 1e-12f) c = cross((float3)(1.0f, 0.0f, 0.0f), m);
  const float3 tm = normalize(c);
  *t = rp_sky_from_map(turn, tm);
  *b = rp_sky_from_map(turn, cross(m, tm));
}

/* The 16 cone directions of the diffuse set in the local frame (t, b, n) (see the header):
 * x along t, y along b, z along n. */
__constant float4 RP_CONE_SET16[RP_CONE_SET_SIZE] = {
    (float4)(0.000000000f, 0.000000000f, 1.000000000f, 0.0f),
    (float4)(0.467707173f, 0.000000000f, 0.883883476f, 0.0f),
    (float4)(0.144529465f, 0.444815955f, 0.883883476f, 0.0f),
    (float4)(-0.378383052f, 0.274911379f, 0.883883476f, 0.0f),
    (float4)(-0.378383052f, -0.274911379f, 0.883883476f, 0.0f),
    (float4)(0.144529465f, -0.444815955f, 0.883883476f, 0.0f),
    (float4)(0.788574405f, 0.256223356f, 0.559016994f, 0.0f),
    (float4)(0.487365785f, 0.670801455f, 0.559016994f, 0.0f),
    (float4)(0.000000000f, 0.829156198f, 0.559016994f, 0.0f),
    (float4)(-0.487365785f, 0.670801455f, 0.559016994f, 0.0f),
    (float4)(-0.788574405f, 0.256223356f, 0.559016994f, 0.0f),
    (float4)(-0.788574405f, -0.256223356f, 0.559016994f, 0.0f),
    (float4)(-0.487365785f, -0.670801455f, 0.559016994f, 0.0f),
    (float4)(0.000000000f, -0.829156198f, 0.559016994f, 0.0f),
    (float4)(0.487365785f, -0.670801455f, 0.559016994f, 0.0f),
    (float4)(0.788574405f, -0.256223356f, 0.559016994f, 0.0f)};

/* World direction of cone k (0..15) of the set around unit n with basis (t, b). */
inline float3 rp_cone_set16_dir(float3 n, float3 t, float3 b, uint k) {
  const float4 l = RP_CONE_SET16[k & 15u];
  return t * l.x + b * l.y + n * l.z;
}

/* Apex of the diffuse cones of surface point p with unit normal n. */
inline float3 rp_cone_apex(float3 p, float3 n, uint resolution) {
  return p + n * (RP_CONE_NORMAL_OFFSET * 2.0f / (float)resolution);
}

/* Near-field occlusion of surface point p (unit normal n): the opacity that the level-1
 * volumes facing n (weights n^2, no rows-behind-the-apex rule) show at the cones' apex, less
 * what they show at the apex's mirror point behind the surface. The volumes hold only what
 * faces the cone (voxel_mips.cl), so the surface's own voxels and flat neighbours count
 * nothing, while a surface that faces p within about two voxels (the underside of a tumbler
 * over the floor near its contact point) does: there the cones start inside or behind it and
 * would otherwise see past it. The mirror term takes out the surface's own back: a wall or
 * slab thinner than a level-1 voxel (2 v0) has its far face, which faces the cone, in the same
 * trilinear footprint, and without the term every point of it read as occluded (measured on
 * the atrium: its walls' indirect light 30-40 % short, image bias -23.0 % -> -14.0 %). A mirror
 * point outside the box reads nothing (the box's faces hold the demo's walls, with nothing
 * behind them). The diffuse light is scaled by one minus this. */
inline float rp_cone_near_occlusion(__global const float4* voxels, uint resolution, uint levels,
                                    float3 p, float3 n) {
  if (levels < 2u) return 0.0f;
  const uint3 dirs = rp_voxel_cone_dirs(n);
  const float3 w = n * n;
  const float3 apex = rp_cone_apex(p, n, resolution);
  /* volumes of weight 0 are not read (a wall's or the floor's normal reads one of three);
   * their term would add exactly 0 */
  float a = 0.0f;
  if (w.x > 0.0f) a = w.x * rp_cone_volume(voxels, resolution, 1u, dirs.x, apex).w;
  if (w.y > 0.0f) a += w.y * rp_cone_volume(voxels, resolution, 1u, dirs.y, apex).w;
  if (w.z > 0.0f) a += w.z * rp_cone_volume(voxels, resolution, 1u, dirs.z, apex).w;
  /* the mirror term only lowers a, so where the apex shows nothing it is not read */
  const float3 mirror = 2.0f * p - apex;
  if (a > 0.0f && fmax(fmax(fabs(mirror.x), fabs(mirror.y)), fabs(mirror.z)) <= 1.0f) {
    if (w.x > 0.0f) a -= w.x * rp_cone_volume(voxels, resolution, 1u, dirs.x, mirror).w;
    if (w.y > 0.0f) a -= w.y * rp_cone_volume(voxels, resolution, 1u, dirs.y, mirror).w;
    if (w.z > 0.0f) a -= w.z * rp_cone_volume(voxels, resolution, 1u, dirs.z, mirror).w;
  }
  return clamp(a * RP_CONE_NEAR_OCCLUSION, 0.0f, 1.0f);
}

/* Mean radiance of the 16 diffuse cones (quarter-diameter steps) around unit normal n at
 * surface point p, each with the sky it lets through (common/sky.h; `sky`: the frame's
 * environment texels): irradiance / pi (see the header). The reference mode's per-pixel
 * estimate. */
inline float3 rp_cone_diffuse16(__global const FrameConstants* restrict frame,
                                __global const float4* restrict sky,
                                __global const float4* voxels, uint resolution, uint levels,
                                float3 p, float3 n) {
  float3 t, b;
  rp_cone_sky_basis(frame, n, &t, &b);
  const RpSkyCells cells = rp_sky_cells(frame, n);
  const float3 o = rp_cone_apex(p, n, resolution);
  float3 sum = (float3)(0.0f);
#pragma unroll
  for (uint k = 0; k < RP_CONE_SET_SIZE; ++k) {
    const float3 dir = rp_cone_set16_dir(n, t, b, k);
    sum += rp_sky_behind_diffuse_cone(
        frame, sky, rp_cone_trace_fine(voxels, resolution, levels, o, dir), cells, k,
        RP_CONE_OPAQUE);
  }
  return sum * ((1.0f - rp_cone_near_occlusion(voxels, resolution, levels, p, n)) /
                (float)RP_CONE_SET_SIZE);
}

#endif
