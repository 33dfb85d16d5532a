/* Screen-space reflections (seed 003: a hierarchical min-Z depth march), used
 * by the fast mode's low-resolution trace (kernels/indirect.cl) and by the reference mode per
 * pixel (kernels/light.cl, light_shade) for the sharp coats; the reflection cone
 * (common/spec_cone.h) is the fallback and is blended in where the screen has no answer.
 * OpenCL C only. The reference mode has no pyramid: it marches with top = 0 (level 0, one
 * pixel per step, every pixel along the ray tested) and includes this header with
 * RP_SSR_MAX_ITER 4096, every ray marched (RP_SSR_MAX_TOWARDS_CAMERA 2) and the colour at a
 * hit averaged over the lobe (RP_SSR_FOOTPRINT 1).
 *
 * Depth: the visibility buffer's z01 = z_ndc * 0.5 + 0.5 (1 where nothing), this frame's,
 * rasterised with view_proj (jittered). The min-Z pyramid (kernels/ssr.cl, ssr_min_z): level
 * k >= 1 holds, per cell of 2^k x 2^k pixels, the smallest z01 of the pixels in it (the
 * nearest surface); sizes w_k = ceil(w_{k-1} / 2), h_k likewise, levels 1 .. top back to back
 * in one float buffer (level k starts after the sizes of levels 1 .. k-1), level 0 is the depth buffer itself.
 *
 * The march (rp_ssr_march): the ray p + t r (p the surface point, r the mirror direction),
 * up to RP_SSR_MAX_DIST world units and clipped to the near side of the camera, projected to
 * screen pixels (x right, y down, pixel (i, j) covers [i, i + 1) x [j, j + 1)) and z01. Under a
 * perspective projection z_ndc is an affine function of the screen position along a projected
 * line, so the ray's z01 is linear in the screen parameter t (pixels along the major axis): no
 * division per step. Starting RP_SSR_START pixels from its origin, at level 0:
 *   the ray's segment inside the current cell (level k) spans z01 from za (entry) to zb (exit);
 *   max(za, zb) < the cell's min-Z: the ray passes in front of everything in the cell -> move
 *     to the cell's exit and go one level up (coarser, at most `top`);
 *   else at k > 0: go one level down (finer), first moving to where the ray reaches the cell's
 *     min-Z when it recedes (the seed's "skip the range the LOD says is empty");
 *   else at level 0, a candidate pixel: a hit when the ray's linear view depth there is at most
 *     RP_SSR_THICKNESS (+ 2 % of the depth) behind the surface's (normal_depth.w); otherwise the
 *     ray passed behind a thin object: continue past this pixel at level 0.
 * Misses: the ray leaves the screen (or its length), or RP_SSR_MAX_ITER steps (16: 32 cost
 * 0.15 ms more at 720x720 busy for few more hits: the levels double the stride); rays turned
 * towards the camera (RP_SSR_MAX_TOWARDS_CAMERA) are not marched.
 * The hit's radiance is the previous frame's light pass output (hdr, before TAA) at the hit
 * pixel moved back by its own velocity (the hit surface's motion, so a moving object's image is
 * found where it was): a reflection is never reprojected with the reflecting surface's motion
 * and nothing is accumulated, so it cannot smear (one frame of lag in the reflected radiance).
 *
 * Confidence c in [0, 1] (rp_ssr_confidence): 0 for a miss, a hit on a back face (its normal
 * along r), a history-less frame, or a previous pixel off screen or uncovered; times a fade over
 * the outer RP_SSR_EDGE of the screen (the reflection fades into the cone before it would be
 * cut), times the roughness fade (1 up to RP_SSR_ROUGH_FULL, 0 from RP_SSR_ROUGH_NONE: rough
 * coats keep the cone, whose width the lobe needs). The reflection is
 * cone + c (ssr - cone).
 */
#ifndef ROLYPOLY_COMMON_SSR_H
#define ROLYPOLY_COMMON_SSR_H

#include "shared/types.h"
#include "common/math.h"

#ifndef RP_SSR_MAX_ITER
#define RP_SSR_MAX_ITER 16
#endif
/* Rays turned towards the camera (dot(r, v) above this, v the unit vector to the camera) are
 * not marched: they can only meet what lies between the surface and the camera, rarely
 * anything, and cost the most steps (they cross the screen before they miss). */
#ifndef RP_SSR_MAX_TOWARDS_CAMERA
#define RP_SSR_MAX_TOWARDS_CAMERA 0.5f
#endif
#define RP_SSR_MAX_DIST 3.0f    /* world units: more than the box's diagonal seen from inside */
#define RP_SSR_START 1.5f       /* pixels from the ray's origin before the first test */
#define RP_SSR_THICKNESS 0.06f  /* world units a surface is assumed thick (plus 2 % of depth) */
#define RP_SSR_EDGE 0.06f       /* fraction of the smaller screen side faded at the borders */
/* 1: the colour at a hit is averaged over the coat's lobe (rp_ssr_footprint; the reference
 * mode); 0: the hit pixel alone (the fast mode, whose 4x4 blocks average anyway). */
#ifndef RP_SSR_FOOTPRINT
#define RP_SSR_FOOTPRINT 0
#endif
#ifndef RP_SSR_ROUGH_FULL
#define RP_SSR_ROUGH_FULL 0.28f
#endif
#ifndef RP_SSR_ROUGH_NONE
#define RP_SSR_ROUGH_NONE 0.34f
#endif

/* The ray's screen position (x, y in pixels) and z01 for clip-space c. */
inline float3 rp_ssr_screen(float4 c, float w, float h) {
  const float iw = 1.0f / c.w;
  return (float3)((c.x * iw * 0.5f + 0.5f) * w, (0.5f - c.y * iw * 0.5f) * h,
                  c.z * iw * 0.5f + 0.5f);
}

/* Marches the mirror ray from p along unit r (see the header). Returns 1 and the hit pixel on a
 * hit, 0 on a miss. top: the coarsest pyramid level (0: level 0 only). */
inline int rp_ssr_march(__global const FrameConstants* restrict frame,
                        __global const float* restrict depth, __global const float* restrict hiz,
                        __global const float4* restrict normal_depth, uint w, uint h, uint top,
                        float3 p, float3 r, int2* hit) {
  const rp_mat4 m = frame->view_proj;
  const float4 c0 = rp_mat4_mul_point(m, p);
  const float4 cd = rp_mat4_mul(m, (float4)(r, 0.0f));
  if (c0.w <= 1.0e-3f) return 0;
  float len = RP_SSR_MAX_DIST;
  const float w_min = 0.05f; /* keep the end in front of the camera */
  if (c0.w + len * cd.w < w_min) len = (w_min - c0.w) / cd.w;
  if (!(len > 0.0f)) return 0;
  const float4 c1 = c0 + len * cd;
  const float wf = (float)w, hf = (float)h;
  const float3 s0 = rp_ssr_screen(c0, wf, hf), s1 = rp_ssr_screen(c1, wf, hf);
  const float2 delta = s1.xy - s0.xy;
  const float n = fmax(fabs(delta.x), fabs(delta.y));
  if (n < 1.0f) return 0;
  const float2 d = delta / n;
  const float dz = (s1.z - s0.z) / n;
  const float iw0 = 1.0f / c0.w, diw = (1.0f / c1.w - iw0) / n; /* 1 / view depth, linear */
  /* the screen parameter where the ray leaves the image (or its length) */
  float t_max = n;
  if (d.x > 0.0f) t_max = fmin(t_max, (wf - s0.x) / d.x);
  if (d.x < 0.0f) t_max = fmin(t_max, -s0.x / d.x);
  if (d.y > 0.0f) t_max = fmin(t_max, (hf - s0.y) / d.y);
  if (d.y < 0.0f) t_max = fmin(t_max, -s0.y / d.y);
  t_max -= 1.0e-3f;
  /* first float and width of each pyramid level, once per ray */
  uint off[8], lw_of[8];
  {
    uint lw = w, lh = h, o = 0u;
    off[0] = 0u;
    lw_of[0] = w;
    for (uint l = 1u; l <= top; ++l) {
      lw = (lw + 1u) >> 1;
      lh = (lh + 1u) >> 1;
      off[l] = o;
      lw_of[l] = lw;
      o += lw * lh;
    }
  }
  float t = RP_SSR_START;
  uint level = 0u;
  for (int it = 0; it < RP_SSR_MAX_ITER; ++it) {
    if (t >= t_max) return 0;
    const float2 pos = s0.xy + d * t;
    const float cell = (float)(1u << level);
    const float2 ci = floor(pos / cell);
    float t_exit = t_max;
    if (d.x > 0.0f) t_exit = fmin(t_exit, ((ci.x + 1.0f) * cell - s0.x) / d.x);
    if (d.x < 0.0f) t_exit = fmin(t_exit, (ci.x * cell - s0.x) / d.x);
    if (d.y > 0.0f) t_exit = fmin(t_exit, ((ci.y + 1.0f) * cell - s0.y) / d.y);
    if (d.y < 0.0f) t_exit = fmin(t_exit, (ci.y * cell - s0.y) / d.y);
    const uint lw = lw_of[level], lh = (h + (1u << level) - 1u) >> level;
    const uint cx = min((uint)ci.x, lw - 1u), cy = min((uint)ci.y, lh - 1u);
    const float zmin = level == 0u ? depth[cy * w + cx] : hiz[off[level] + cy * lw + cx];
    const float za = s0.z + dz * t, zb = s0.z + dz * t_exit;
    if (fmax(za, zb) < zmin) { /* in front of everything in the cell */
      t = t_exit + 1.0e-3f;
      level = min(level + 1u, top);
      continue;
    }
    const float t_cross = (dz > 0.0f && za < zmin) ? (zmin - s0.z) / dz : t;
    if (level > 0u) {
      t = fmax(t, t_cross);
      --level;
      continue;
    }
    /* level 0: the ray reaches this pixel's depth; hit unless it passed behind a thin object */
    const float ray_depth = 1.0f / (iw0 + diw * t_cross);
    const float surface_depth = normal_depth[cy * w + cx].w;
    if (ray_depth - surface_depth <= RP_SSR_THICKNESS + 0.02f * surface_depth) {
      *hit = (int2)((int)cx, (int)cy);
      return 1;
    }
    t = t_exit + 1.0e-3f;
  }
  return 0;
}

#if RP_SSR_FOOTPRINT
/* The reference mode's colour at a hit (RP_SSR_FOOTPRINT 1): the previous frame's light
 * output averaged over the coat's lobe where it meets the hit surface, instead of one pixel,
 * which carries that frame's shadow and jitter noise into the reflection. The lobe's radius
 * there is its half width at half maximum (rp_brdf_spec_cone_tan's formula, without the voxel
 * volume's 0.1 .. 1 clamp) times the distance from p to the hit (the hit's world position from
 * its pixel centre and z01 through inv_view_proj), in pixels at the hit's view depth
 * (view_proj's second row has length 1 / tan(fov_y / 2) before the jitter's tiny shift: h / 2
 * of them per unit of depth). Below half a pixel: the hit pixel alone (c). Else the mean of the
 * hit pixel and 8 points on that circle around `prev` (the hit moved back by its velocity),
 * those on screen and covered. */
inline float3 rp_ssr_footprint(__global const FrameConstants* restrict frame,
                               __global const float* restrict depth,
                               __global const float4* restrict normal_depth,
                               __global const float4* restrict prev_hdr, int2 hp, float2 prev,
                               float3 p, float rough, float3 c) {
  const uint w = frame->width, h = frame->height;
  const uint hit = (uint)hp.y * w + (uint)hp.x;
  const float a = fmax(rough * rough, 1.0e-4f);
  const float tan_lobe = 1.2872f * a / (1.0f - 0.41421f * a * a);
  const float3 ndc = (float3)(((float)hp.x + 0.5f) / (float)w * 2.0f - 1.0f,
                              1.0f - ((float)hp.y + 0.5f) / (float)h * 2.0f,
                              depth[hit] * 2.0f - 1.0f);
  const float4 q = rp_mat4_mul_point(frame->inv_view_proj, ndc);
  const rp_mat4 m = frame->view_proj;
  const float p11 = length((float3)(m.c[0].y, m.c[1].y, m.c[2].y));
  const float radius = length(q.xyz / q.w - p) * tan_lobe * p11 * 0.5f * (float)h /
                       normal_depth[hit].w;
  if (!(radius >= 0.5f)) return c;
  float3 sum = c;
  float n = 1.0f;
  for (int k = 0; k < 8; ++k) {
    const float ang = (float)k * 0.78539816f;
    const float2 t = prev + radius * (float2)(cos(ang), sin(ang));
    if (t.x < 0.0f || t.y < 0.0f || t.x >= (float)w || t.y >= (float)h) continue;
    const float4 v = prev_hdr[(uint)t.y * w + (uint)t.x];
    if (v.w == 0.0f) continue;
    sum += v.xyz;
    n += 1.0f;
  }
  return sum / n;
}
#endif

/* Screen-space reflection of the mirror ray from p (unit normal n) along r for a coat of
 * roughness `rough`: the previous frame's radiance at the hit (rgb) and the confidence (w);
 * see the header. history: whether prev_hdr holds the previous frame. */
inline float4 rp_ssr(__global const FrameConstants* restrict frame,
                     __global const float* restrict depth, __global const float* restrict hiz,
                     __global const float4* restrict normal_depth,
                     __global const float4* restrict prev_hdr,
                     __global const float2* restrict velocity, uint top, uint history,
                     float3 p, float3 r, float rough) {
  const float fade_r =
      clamp((RP_SSR_ROUGH_NONE - rough) * (1.0f / (RP_SSR_ROUGH_NONE - RP_SSR_ROUGH_FULL)), 0.0f,
            1.0f);
  if (history == 0u || fade_r <= 0.0f) return (float4)(0.0f);
  if (dot(r, normalize(frame->camera_pos.xyz - p)) > RP_SSR_MAX_TOWARDS_CAMERA)
    return (float4)(0.0f);
  const uint w = frame->width, h = frame->height;
  int2 hp;
  if (!rp_ssr_march(frame, depth, hiz, normal_depth, w, h, top, p, r, &hp)) return (float4)(0.0f);
  const uint hit = (uint)hp.y * w + (uint)hp.x;
  if (dot(normal_depth[hit].xyz, r) >= 0.0f) return (float4)(0.0f); /* a back face */
  const float2 prev = (float2)((float)hp.x + 0.5f, (float)hp.y + 0.5f) - velocity[hit];
  if (prev.x < 0.0f || prev.y < 0.0f || prev.x >= (float)w || prev.y >= (float)h)
    return (float4)(0.0f);
  float4 c = prev_hdr[(uint)prev.y * w + (uint)prev.x];
  if (c.w == 0.0f) return (float4)(0.0f);
#if RP_SSR_FOOTPRINT
  c.xyz = rp_ssr_footprint(frame, depth, normal_depth, prev_hdr, hp, prev, p, rough, c.xyz);
#endif
  const float edge = fmin(fmin(prev.x, (float)w - prev.x), fmin(prev.y, (float)h - prev.y)) /
                     (RP_SSR_EDGE * (float)min(w, h));
  return (float4)(c.xyz, fade_r * clamp(edge, 0.0f, 1.0f));
}

#endif
