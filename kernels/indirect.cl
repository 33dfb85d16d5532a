/* Indirect light at reduced resolution (the fast quality mode): one cone per 4x4 pixel
 * block per frame, a geometry-aware spatial filter over the 16 interleaved cone directions, and
 * temporal accumulation. The light pass upsamples the result (light.cl, light_compose).
 * Grid, sample pixel, cone and jitter choice, geometry weight, padded planar layout:
 * common/indirect.h.
 *
 * Low-resolution planes (padded, `plane` floats apart, row stride `stride`):
 *   radiance  3 planes: r, g, b radiance of this frame's one cone (rp_cone_trace_jittered)
 *   position  4 planes: the sample's world position x, y, z and its view depth (0 background)
 *   geom      4 planes: the sample's unit normal x, y, z and its plane offset dot(n, p);
 *             all 0 on background and padding (every geometry weight is then 0)
 *   specular  3 planes: r, g, b radiance of this frame's reflection cone at the sample
 *             (coated surfaces, common/spec_cone.h and common/ssr.h; -1: a hole of the
 *             checkerboard, RP_INDIRECT_SPEC_CHECKER_TAN; -2: no coat; -3: background, and
 *             the padding, filled with -3 by the host: every value >= 0 is a traced coat), and 3
 *             more planes of the same after indirect_filter filled the holes (double-buffered
 *             by the host). Not reprojected: a reflection moves with the view, not with the
 *             surface, so the surface's reprojection would drag it. Only while the camera
 *             stands still does a block blend its own previous value, clamped (see
 *             indirect_filter). The light pass upsamples the filled value with the same
 *             geometry weights as the irradiance.
 *   history   5 planes: accumulated irradiance / pi r, g, b, its age in frames (0: none) and
 *             the accumulated second moment of its luminance (0.2126 r + 0.7152 g + 0.0722 b)
 * geom and history are double-buffered by the host: this frame's and the previous frame's.
 *
 * indirect_trace (one work-item per sample): GBuffer at the sample pixel, one cone (a loop with
 * early exit: scalar code), and on coated surfaces the reflection cone.
 * indirect_filter (8 samples of a row per work-item, float8 code, common/indirect_simd.h):
 *   spatial: weighted mean of the cone radiances over the 5x5 samples around it, tap weights
 *     (0.5, 1, 1, 1, 0.5) per axis (symmetric, and every residue mod 4 - every cone of the set -
 *     gets the same total weight 1) times the tap's geometry weight for the centre sample (0 off
 *     the grid): the 16-cone estimate S of irradiance / pi;
 *   temporal: the history of a sample is its block's accumulated irradiance, located at the
 *     block's centre (4 i + 2 in pixels) whichever pixel of the block was sampled (so the
 *     history integrates the 16 sample positions of a block over frames). The sample's world
 *     position is reprojected with prev_view_proj_unjittered and shifted by (block centre -
 *     sample pixel centre) = 1.5 - O(f) pixels; the 2x2 previous blocks around that point,
 *     bilinear weights times the geometry weights of their (previous) samples for this sample,
 *     give the history H and its age a (weighted means). A still camera lands exactly on the
 *     block's own history. After a change of the render size the previous frame's planes
 *     have the old size's layout (IndirectFilterParams.prev_planes) and are read as such, so
 *     the blocks keep their light across the change. Total weight < RP_INDIRECT_MIN_HISTORY
 *     (moved, disoccluded, off screen) or history_valid = 0 (reset, camera cut): no history,
 *     a = 0. out = H + alpha (S - H), age min(a + 1, 255), alpha = max(1 / (a + 1), alpha_c):
 *     a plain running mean for the first frames after a reset, then an exponential one whose
 *     weight alpha_c grows from alpha_min (a still scene: low flicker) to RP_INDIRECT_ALPHA_FAST
 *     as S's luminance leaves H's by 2 to 4 standard deviations (the light changed: little lag);
 *     the standard deviation comes from the accumulated second moment (fifth plane), blended
 *     with the same alpha.
 * No atomics, no local memory: bit-identical runs.
 */
#include "shared/types.h"
#include "shared/pass_params.h"
#include "common/math.h"
#include "common/random.h"
#include "common/cone_trace.h"
#include "common/spec_cone.h"
#include "common/ssr.h"
#include "common/indirect.h"
#include "common/indirect_simd.h"

/* 1: the cone with full-diameter steps and position + level jitter (rp_cone_trace_coarse);
 * 0: half-diameter steps with level jitter (rp_cone_trace_jittered). */
#ifndef RP_INDIRECT_COARSE
#define RP_INDIRECT_COARSE 1
#endif

/* 1: indirect_trace traces all 16 cones per block and averages them (the build used while there
 * is no history: first frame, reset, camera cut); 0: one cone per block (steady state). */
#ifndef RP_INDIRECT_WARM_START
#define RP_INDIRECT_WARM_START 0
#endif

/* Extra per-axis weight of every tap of the 3x3 history neighbourhood (see indirect_filter). */
#ifndef RP_INDIRECT_RING
#define RP_INDIRECT_RING 0.1f
#endif

/* Largest blend weight of a changed estimate (variance-guided blend, see indirect_filter). */
#ifndef RP_INDIRECT_ALPHA_FAST
#define RP_INDIRECT_ALPHA_FAST 0.35f
#endif

/* Smallest total reprojection weight that counts as history. */
#ifndef RP_INDIRECT_MIN_HISTORY
#define RP_INDIRECT_MIN_HISTORY 0.05f
#endif

/* Coats whose reflection cone is at least this wide (tan of the half-angle;
 * rp_brdf_spec_cone_tan) trace their reflection (screen-space ray and cone) on the checkerboard
 * of samples with (i + j) even only; indirect_filter fills the others from their four
 * neighbours (geometry weighted). 0 (default): every coat, half the rays; > 1: every coated
 * sample traces. Measured at 720x720 busy (indirect_trace, against no reflections): every
 * sample +1.4 ms (cones only), checkerboard on the floor only (0.15) +0.8 ms, on every coat
 * +0.75 ms with the cones only and +1.0 ms with the screen-space rays (16 steps). */
#ifndef RP_INDIRECT_SPEC_CHECKER_TAN
#define RP_INDIRECT_SPEC_CHECKER_TAN 0.0f
#endif
/* The still-camera reflection history's weight of the current frame (indirect_filter). */
#ifndef RP_INDIRECT_SPEC_ALPHA
#define RP_INDIRECT_SPEC_ALPHA 0.1f
#endif

/* Radiance of cone k of the set from sample (i, j)'s surface point p (normal n, basis t, b, sky
 * table row `cells`) in frame f, with the block's position and level jitters. */
inline float3 indirect_cone(__global const FrameConstants* frame, __global const float4* sky,
                            __global const float4* voxels, uint voxel_resolution,
                            uint voxel_levels, float3 p, float3 n, float3 t, float3 b,
                            RpSkyCells cells, uint k, uint i, uint j, uint f) {
  const float3 dir = rp_cone_set16_dir(n, t, b, k);
#if RP_INDIRECT_COARSE
  const float4 cone = rp_cone_trace_coarse(voxels, voxel_resolution, voxel_levels,
                                           rp_cone_apex(p, n, voxel_resolution), dir,
                                           rp_indirect_position_jitter(i, j, f),
                                           rp_indirect_level_jitter(i, j, f));
  return rp_sky_behind_diffuse_cone(frame, sky, cone, cells, k, RP_CONE_OPAQUE_COARSE);
#else
  const float4 cone = rp_cone_trace_jittered(voxels, voxel_resolution, voxel_levels,
                                             rp_cone_apex(p, n, voxel_resolution), dir,
                                             rp_indirect_level_jitter(i, j, f));
  return rp_sky_behind_diffuse_cone(frame, sky, cone, cells, k, RP_CONE_OPAQUE);
#endif
}

__kernel void indirect_trace(__global const FrameConstants* frame,
                             __global const float4* normal_depth_plane,
                             __global const float4* position_plane,
                             __global const float4* emission_plane,
                             __global const float4* voxels,
                             __global const float4* sky,
                             __global float* radiance,
                             __global float* position,
                             __global float* geom,
                             __global float* specular,
                             __global const float* ssr_depth,
                             __global const float* ssr_hiz,
                             __global const float4* prev_hdr,
                             __global const float2* velocity,
                             const IndirectTraceParams params) {
  const uint voxel_resolution = params.voxel_resolution, voxel_levels = params.voxel_levels;
  const uint lr_width = params.planes.width, lr_height = params.planes.height;
  const uint stride = params.planes.stride, plane = params.planes.plane;
  const uint ssr_top = params.ssr_top, ssr_history = params.ssr_history;
  const uint i = (uint)get_global_id(0), j = (uint)get_global_id(1);
  if (i >= lr_width || j >= lr_height) return;
  const uint s = (uint)rp_indirect_index((int)i, (int)j, (int)stride);
  const uint f = frame->frame_index;
  const uint cell = rp_indirect_sample_cell(f);
  const uint x = min(i * RP_INDIRECT_SCALE + (cell & 3u), frame->width - 1u);
  const uint y = min(j * RP_INDIRECT_SCALE + (cell >> 2), frame->height - 1u);
  const uint pixel = y * frame->width + x;
  const float4 pos = position_plane[pixel];
  float3 c = (float3)(0.0f), n = (float3)(0.0f), p = (float3)(0.0f), sc = (float3)(-3.0f);
  float d = 0.0f, depth = 0.0f;
  if (pos.w != 0.0f) {
    p = pos.xyz;
    const float4 nd = normal_depth_plane[pixel];
    n = nd.xyz;
    depth = nd.w;
    float3 t, b;
    rp_cone_sky_basis(frame, n, &t, &b);
    const RpSkyCells cells = rp_sky_cells(frame, n);
#if RP_INDIRECT_WARM_START
    /* No history yet (first frame, reset, camera cut): every cone of the set, so the
     * first frame shows the whole estimate instead of one cone per block. */
    for (uint k = 0u; k < 16u; ++k)
      c += indirect_cone(frame, sky, voxels, voxel_resolution, voxel_levels, p, n, t, b, cells,
                         k, i, j, f);
    c *= 1.0f / 16.0f;
#else
    c = indirect_cone(frame, sky, voxels, voxel_resolution, voxel_levels, p, n, t, b, cells,
                      rp_indirect_cone_index(i, j, f), i, j, f);
#endif
    c *= 1.0f - rp_cone_near_occlusion(voxels, voxel_resolution, voxel_levels, p, n);
    d = dot(n, p);
    /* coated surfaces: the reflection cone (common/spec_cone.h, single-level samples) */
    const float code = emission_plane[pixel].w;
    sc = (float3)(-2.0f); /* no coat: indirect_filter writes 0, and no hole takes it */
    if (code != 0.0f) {
      const float rough = rp_brdf_code_roughness(code);
      if (((i ^ j) & 1u) != 0u && rp_brdf_spec_cone_tan(rough) >= RP_INDIRECT_SPEC_CHECKER_TAN) {
        sc = (float3)(-1.0f); /* a hole: indirect_filter fills it from its neighbours */
      } else {
        /* screen-space reflection first (sharp coats, common/ssr.h); the cone where the
         * screen has no full answer */
        const float3 v = normalize(frame->camera_pos.xyz - p);
        const float3 r = 2.0f * fmax(dot(n, v), 0.0f) * n - v;
        const float4 ssr = rp_ssr(frame, ssr_depth, ssr_hiz, normal_depth_plane, prev_hdr,
                                  velocity, ssr_top, ssr_history, p, r, rough);
        if (ssr.w >= 1.0f) {
          sc = ssr.xyz;
        } else {
          sc = rp_spec_cone(frame, sky, voxels, voxel_resolution, voxel_levels, code, p, n, 0);
          sc += ssr.w * (ssr.xyz - sc);
        }
      }
    }
  }
  specular[s] = sc.x;
  specular[plane + s] = sc.y;
  specular[2u * plane + s] = sc.z;
  radiance[s] = c.x;
  radiance[plane + s] = c.y;
  radiance[2u * plane + s] = c.z;
  position[s] = p.x;
  position[plane + s] = p.y;
  position[2u * plane + s] = p.z;
  position[3u * plane + s] = depth;
  geom[s] = n.x;
  geom[plane + s] = n.y;
  geom[2u * plane + s] = n.z;
  geom[3u * plane + s] = d;
}

/* Lane-wise gather: v[idx.sk] for every lane k. */
inline float8 indirect_gather8(__global const float* v, int8 idx) {
  return (float8)(v[idx.s0], v[idx.s1], v[idx.s2], v[idx.s3], v[idx.s4], v[idx.s5], v[idx.s6],
                  v[idx.s7]);
}

/* v[idx] lane by lane; one vector load when the lanes' indices are consecutive (`seq`: a still
 * camera, where every sample reprojects next to its neighbour's). */
inline float8 indirect_load8(__global const float* v, int8 idx, int seq) {
  return seq ? vload8(0, v + idx.s0) : indirect_gather8(v, idx);
}

/* Stores lanes 0 .. n-1 of v at p[0 .. n-1]. */
inline void indirect_store8(__global float* p, uint n, float8 v) {
  if (n == 8u) {
    vstore8(v, 0, p);
    return;
  }
  for (uint k = 0; k < n; ++k) p[k] = rp_lane8(v, k);
}

/* pixel_scale: world size of one full-resolution pixel per unit of view depth. Global size:
 * (ceil(lr_width / 8), lr_height) rounded up to the work-group. */
__kernel void indirect_filter(__global const FrameConstants* restrict frame,
                              __global const float* restrict radiance,
                              __global const float* restrict position,
                              __global const float* restrict geom,
                              __global const float* restrict prev_geom,
                              __global const float* restrict prev_history,
                              __global float* restrict history,
                              __global const float* restrict specular,
                              __global const float* restrict prev_specular_out,
                              __global float* restrict specular_out,
                              const IndirectFilterParams params) {
  const uint lr_width = params.planes.width, lr_height = params.planes.height;
  const uint stride = params.planes.stride, plane = params.planes.plane;
  const float pixel_scale = params.planes.pixel_scale, alpha_min = params.alpha_min;
  const uint history_valid = params.history_valid, specular_history = params.specular_history;
  const uint i0 = 8u * (uint)get_global_id(0), j = (uint)get_global_id(1);
  if (i0 >= lr_width || j >= lr_height) return;
  const uint lanes = min(8u, lr_width - i0);
  const int st = (int)stride, pl = (int)plane;
  const int c = rp_indirect_index((int)i0, (int)j, st);

  const float8 px = vload8(0, position + c), py = vload8(0, position + pl + c);
  const float8 pz = vload8(0, position + 2 * pl + c), depth = vload8(0, position + 3 * pl + c);
  const float8 nx = vload8(0, geom + c), ny = vload8(0, geom + pl + c);
  const float8 nz = vload8(0, geom + 2 * pl + c);
  const int8 valid = nx * nx + ny * ny + nz * nz > 0.5f;
  const float8 inv_sigma = rp_indirect_inv_sigma8(depth, pixel_scale);

  /* Spatial: 5x5 taps, per-axis weights (0.5, 1, 1, 1, 0.5); padding weighs 0. */
  float8 sr = 0.0f, sg = 0.0f, sb = 0.0f, wsum = 0.0f;
  for (int dy = -2; dy <= 2; ++dy) {
    const float wy = (dy == -2 || dy == 2) ? 0.5f : 1.0f;
    for (int dx = -2; dx <= 2; ++dx) {
      const float wxy = wy * ((dx == -2 || dx == 2) ? 0.5f : 1.0f);
      const int t = c + dy * st + dx;
      const float8 w =
          wxy * rp_indirect_geometry_weight8(nx, ny, nz, px, py, pz, vload8(0, geom + t),
                                             vload8(0, geom + pl + t),
                                             vload8(0, geom + 2 * pl + t),
                                             vload8(0, geom + 3 * pl + t), inv_sigma);
      sr += w * vload8(0, radiance + t);
      sg += w * vload8(0, radiance + pl + t);
      sb += w * vload8(0, radiance + 2 * pl + t);
      wsum += w;
    }
  }
  const float8 inv_w = 1.0f / fmax(wsum, 1.0e-6f);
  sr *= inv_w;
  sg *= inv_w;
  sb *= inv_w;

  /* Reflections: samples left as holes by indirect_trace (-1, the checkerboard) take the
   * geometry-weighted mean of their traced edge neighbours (coated samples: a value >= 0;
   * uncoated ones hold -2, background and padding -3), else the plain mean of those (no
   * neighbour on the same surface: a one-block sliver), else 0; traced samples pass through,
   * uncoated ones and the background become 0. Not accumulated over a moving view (see the
   * header). One loop over the 3x3 neighbours: the edge ones (q < 4) fill the holes, all eight
   * bound the still-camera history below. */
  {
    const float8 s0 = vload8(0, specular + c), s1 = vload8(0, specular + pl + c);
    const float8 s2 = vload8(0, specular + 2 * pl + c);
    const int8 none = s0 < -1.5f;
    const int8 hole = (s0 < 0.0f) & (s0 >= -1.5f);
    const int fill = any(hole);
    const int still = specular_history != 0u;
    const float8 zero8 = 0.0f;
    float8 fr = select(s0, zero8, none), fg = select(s1, zero8, none), fb = select(s2, zero8, none);
    /* the range of this frame's traced values in the 3x3 neighbourhood, the sample included if
     * traced (+-1e30 where none: those lanes keep this frame's value, see below) */
    const int8 self = s0 >= 0.0f;
    float8 lo_r = select((float8)(1.0e30f), s0, self), hi_r = select((float8)(-1.0e30f), s0, self);
    float8 lo_g = select((float8)(1.0e30f), s1, self), hi_g = select((float8)(-1.0e30f), s1, self);
    float8 lo_b = select((float8)(1.0e30f), s2, self), hi_b = select((float8)(-1.0e30f), s2, self);
    float8 ar = 0.0f, ag = 0.0f, ab = 0.0f, aw = 0.0f, mr = 0.0f, mg = 0.0f, mb = 0.0f, mw = 0.0f;
    const int offs[8] = {-1, 1, -st, st, -st - 1, -st + 1, st - 1, st + 1};
    const int taps = still ? 8 : (fill ? 4 : 0);
    for (int q = 0; q < taps; ++q) {
      const int t = c + offs[q];
      const float8 t0 = vload8(0, specular + t), t1 = vload8(0, specular + pl + t);
      const float8 t2 = vload8(0, specular + 2 * pl + t);
      const int8 traced = t0 >= 0.0f;
      if (fill && q < 4) {
        const float8 on = select((float8)(0.0f), (float8)(1.0f), traced);
        const float8 w = on * rp_indirect_geometry_weight8(
                                  nx, ny, nz, px, py, pz, vload8(0, geom + t),
                                  vload8(0, geom + pl + t), vload8(0, geom + 2 * pl + t),
                                  vload8(0, geom + 3 * pl + t), inv_sigma);
        ar += w * t0;
        ag += w * t1;
        ab += w * t2;
        aw += w;
        mr += on * t0;
        mg += on * t1;
        mb += on * t2;
        mw += on;
      }
      if (still) { /* compare-selects: fmin / fmax cost about three instructions each. The
                    * maximum needs no mask: what is not traced is negative in every channel
                    * (-1, -2, -3), below any traced value; with nothing traced hi < lo. */
        lo_r = select(lo_r, t0, traced & (t0 < lo_r));
        lo_g = select(lo_g, t1, traced & (t1 < lo_g));
        lo_b = select(lo_b, t2, traced & (t2 < lo_b));
        hi_r = select(hi_r, t0, t0 > hi_r);
        hi_g = select(hi_g, t1, t1 > hi_g);
        hi_b = select(hi_b, t2, t2 > hi_b);
      }
    }
    if (fill) {
      const int8 geo = aw >= 1.0e-4f;
      const float8 inv_a = 1.0f / fmax(aw, 1.0e-4f), inv_m = 1.0f / fmax(mw, 1.0f); /* mw 0: 0 */
      fr = select(fr, select(mr * inv_m, ar * inv_a, geo), hole);
      fg = select(fg, select(mg * inv_m, ag * inv_a, geo), hole);
      fb = select(fb, select(mb * inv_m, ab * inv_a, geo), hole);
    }
    /* Still camera (specular_history, set by the host only when this frame's unjittered view
     * equals the previous one, the history is valid and the size unchanged: prev_geom is
     * read at this frame's index): the reflection seen from a block
     * stays where it was, so the previous frame's filled value at the same block is blended in
     * with weight 1 - RP_INDIRECT_SPEC_ALPHA where the block still sees the same surface, so
     * that the sample point's rotation through the block (and the TAA jitter) no longer
     * flickers. It is first clamped to the range of this frame's traced values at the block and
     * its eight neighbours, so a reflected object that moved leaves no trail. Eight, not the
     * four edge ones: on the checkerboard a traced sample's edge neighbours are all holes, and
     * its range was then its own value alone, which undid the blend on half the blocks
     * (quality test flicker 0.498 -> 0.486 with eight, -> 0.4845 with weight 0.1 instead of
     * 0.25; the reference mode: 0.480). A moving camera uses this frame's value alone. */
    if (still) {
      const float8 g = rp_indirect_geometry_weight8(
          nx, ny, nz, px, py, pz, vload8(0, prev_geom + c), vload8(0, prev_geom + pl + c),
          vload8(0, prev_geom + 2 * pl + c), vload8(0, prev_geom + 3 * pl + c), inv_sigma);
      /* s0 >= -1.5: a coat (not `none == 0`, a negated mask oclgrind 21.10 mis-evaluates) */
      const int8 keep = (g > 0.5f) & (s0 >= -1.5f) & valid & (lo_r <= hi_r);
      const float8 pr = clamp(vload8(0, prev_specular_out + c), lo_r, hi_r);
      const float8 pg = clamp(vload8(0, prev_specular_out + pl + c), lo_g, hi_g);
      const float8 pb = clamp(vload8(0, prev_specular_out + 2 * pl + c), lo_b, hi_b);
      fr = select(fr, pr + RP_INDIRECT_SPEC_ALPHA * (fr - pr), keep);
      fg = select(fg, pg + RP_INDIRECT_SPEC_ALPHA * (fg - pg), keep);
      fb = select(fb, pb + RP_INDIRECT_SPEC_ALPHA * (fb - pb), keep);
    }
    indirect_store8(specular_out + c, lanes, fr);
    indirect_store8(specular_out + pl + c, lanes, fg);
    indirect_store8(specular_out + 2 * pl + c, lanes, fb);
  }

  /* Temporal: the previous frame's samples around the reprojected positions, in the previous
   * frame's planes (prev_planes: another layout when the render size changed, the history
   * then resampled to the new blocks instead of dropped). */
  const int pst = (int)params.prev_planes.stride, ppl = (int)params.prev_planes.plane;
  const uint prev_lr_width = params.prev_planes.width, prev_lr_height = params.prev_planes.height;
  const rp_mat4 m = frame->prev_view_proj_unjittered;
  const float8 cx = m.c[0].x * px + m.c[1].x * py + m.c[2].x * pz + m.c[3].x;
  const float8 cy = m.c[0].y * px + m.c[1].y * py + m.c[2].y * pz + m.c[3].y;
  const float8 cw = m.c[0].w * px + m.c[1].w * py + m.c[2].w * pz + m.c[3].w;
  const int8 in_front = cw > 0.0f;
  const float8 iw = 1.0f / select((float8)(1.0f), cw, in_front);
  const float w_px = (float)params.prev_width, h_px = (float)params.prev_height;
  const float8 sx = (cx * iw * 0.5f + 0.5f) * w_px; /* previous pixel coordinates */
  const float8 sy = (0.5f - cy * iw * 0.5f) * h_px;
  /* History lives at block centres (4 i + 2 in pixels): shift the reprojected sample by its
   * block's centre minus the sample pixel's centre, 1.5 - O(f) (this frame's pixels, times
   * the previous pixels per pixel: 1 at an unchanged size), so that with a still camera
   * every block finds exactly its own history (no resampling blur, whichever pixel sampled). */
  const float rx = w_px / (float)frame->width, ry = h_px / (float)frame->height;
  const uint cell = rp_indirect_sample_cell(frame->frame_index);
  const float8 ux = (sx - (float)(cell & 3u) * rx - 0.5f * rx) * (1.0f / RP_INDIRECT_SCALE);
  const float8 uy = (sy - (float)(cell >> 2) * ry - 0.5f * ry) * (1.0f / RP_INDIRECT_SCALE);
  /* The 3x3 previous blocks around the nearest one (clamped into the padding, weight 0, before
   * the int conversion: far-off positions find no history). Tap weight: the bilinear tent
   * max(0, 1 - |u - t|) per axis plus a ring weight RP_INDIRECT_RING * (1 - g), g the nearest
   * block's geometry weight, times the tap's geometry weight. With a still camera the block's
   * own history has tent weight 1 and its neighbours only the ring weight, which is 0 while
   * the block still sees its surface; the ring lets a block whose sample moved onto another
   * surface (TAA jitter at a silhouette) continue its neighbours' history of that surface
   * instead of starting over (measured: less flicker at silhouettes, no blur elsewhere). */
  const float8 ur = floor(clamp(ux, -1.0f, (float)prev_lr_width) + 0.5f);
  const float8 vr = floor(clamp(uy, -1.0f, (float)prev_lr_height) + 0.5f);
  const int8 t11 =
      (convert_int8(vr) + RP_INDIRECT_PAD) * pst + convert_int8(ur) + RP_INDIRECT_PAD;
  const int seq = all(t11 == t11.s0 + (int8)(0, 1, 2, 3, 4, 5, 6, 7));
  const float8 g11 = rp_indirect_geometry_weight8(
      nx, ny, nz, px, py, pz, indirect_load8(prev_geom, t11, seq),
      indirect_load8(prev_geom + ppl, t11, seq), indirect_load8(prev_geom + 2 * ppl, t11, seq),
      indirect_load8(prev_geom + 3 * ppl, t11, seq), inv_sigma);
  const float8 ring = RP_INDIRECT_RING * (1.0f - g11);
  float8 hr = 0.0f, hg = 0.0f, hb = 0.0f, ha = 0.0f, hm = 0.0f, hw = 0.0f;
  for (int b = -1; b <= 1; ++b) {
    const float8 wy = fmax(1.0f - fabs(uy - (vr + (float)b)), 0.0f) + ring;
    for (int a = -1; a <= 1; ++a) {
      const int8 t = t11 + (b * pst + a);
      const float8 wx = fmax(1.0f - fabs(ux - (ur + (float)a)), 0.0f) + ring;
      const float8 w = wx * wy *
                       rp_indirect_geometry_weight8(
                           nx, ny, nz, px, py, pz, indirect_load8(prev_geom, t, seq),
                           indirect_load8(prev_geom + ppl, t, seq),
                           indirect_load8(prev_geom + 2 * ppl, t, seq),
                           indirect_load8(prev_geom + 3 * ppl, t, seq), inv_sigma);
      hr += w * indirect_load8(prev_history, t, seq);
      hg += w * indirect_load8(prev_history + ppl, t, seq);
      hb += w * indirect_load8(prev_history + 2 * ppl, t, seq);
      ha += w * indirect_load8(prev_history + 3 * ppl, t, seq);
      hm += w * indirect_load8(prev_history + 4 * ppl, t, seq);
      hw += w;
    }
  }
  const int8 has = (history_valid != 0u ? (int8)(-1) : (int8)(0)) & in_front &
                   (hw >= RP_INDIRECT_MIN_HISTORY);
  /* selects, not products with 0: rejected history may hold anything */
  const float8 inv_h = select((float8)(0.0f), 1.0f / fmax(hw, 1.0e-6f), has);
  const float8 h0 = select((float8)(0.0f), hr * inv_h, has);
  const float8 h1 = select((float8)(0.0f), hg * inv_h, has);
  const float8 h2 = select((float8)(0.0f), hb * inv_h, has);
  const float8 age = select((float8)(0.0f), ha * inv_h, has);
  const float8 m2 = select((float8)(0.0f), hm * inv_h, has);
  /* Variance-guided blend: luminance of this estimate against the history's mean and
   * standard deviation (from its second moment m2): within 2 sigma (the frame-to-frame noise
   * of the rotating cones and jitters) the slow alpha_min, beyond 4 sigma (the light changed: a
   * fireball moved) up to RP_INDIRECT_ALPHA_FAST, smoothly in between. */
  const float8 lum_s = 0.2126f * sr + 0.7152f * sg + 0.0722f * sb;
  const float8 lum_h = 0.2126f * h0 + 0.7152f * h1 + 0.0722f * h2;
  const float8 sigma = sqrt(fmax(m2 - lum_h * lum_h, 0.0f)) + 0.02f * lum_h + 1.0e-4f;
  const float8 z = clamp((fabs(lum_s - lum_h) / sigma - 2.0f) * 0.5f, 0.0f, 1.0f);
  const float8 alpha_change = alpha_min + (RP_INDIRECT_ALPHA_FAST - alpha_min) * z * z * (3.0f - 2.0f * z);
  const float8 alpha = fmax(1.0f / (age + 1.0f), alpha_change);
  const float8 zero = 0.0f;
  indirect_store8(history + c, lanes, select(zero, h0 + alpha * (sr - h0), valid));
  indirect_store8(history + pl + c, lanes, select(zero, h1 + alpha * (sg - h1), valid));
  indirect_store8(history + 2 * pl + c, lanes, select(zero, h2 + alpha * (sb - h2), valid));
  indirect_store8(history + 3 * pl + c, lanes, select(zero, fmin(age + 1.0f, 255.0f), valid));
  indirect_store8(history + 4 * pl + c, lanes,
                  select(zero, m2 + alpha * (lum_s * lum_s - m2), valid));
}
