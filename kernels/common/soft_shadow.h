/* The lamp's shadow for eight pixels at once (a 4x2 block: kernels/shadow_visibility.cl, the
 * light pass's first kernel), in four modes chosen by -DRP_SHADOW_MODE
 * (RenderSettings::shadows): 0 hard, 1 pcf, 2 pcss, 3 vssm. OpenCL C only.
 *
 * rp_shadow8 returns the visibility in [0, 1] of eight receivers p (unit normals n, cos_theta =
 * dot(n, l)); 1 outside the shadow frustum. Shadow map: FrameConstants.light_view_proj depth,
 * z_ndc * 0.5 + 0.5, rows top to bottom, two planes of size^2 floats (render::ShadowMap): the
 * nearest caster surface on each texel's ray (1.0 = empty), then the farthest (pcss's thick
 * blocker test); mips: shared/shadow_mips.h (linear depth z = clip w, the distance from the
 * lamp centre along its axis, world units).
 *
 * Receiver: p is pushed RP_SHADOW_NORMAL_OFFSET texels along n (q; a texel is its world size at
 * the receiver's depth, 2 w / (size P00)), so a surface never compares against its own texels.
 *   hard: ONE tap, the texel under q, compared with q's depth minus (RP_SHADOW_DEPTH_BIAS + 1 *
 *     tan(theta)) texels (the nearest texel centre is up to 0.71 texels away): a point lamp's hard
 *     shadow, no noise.
 *   pcf, pcss: every tap compares with the RECEIVER PLANE (the plane through q with normal n)
 *     at the tap's texel instead of q's depth, so a planar receiver never shadows itself however
 *     wide the filter: for the ray through shadow-map NDC (u, v), D(u, v) = F + u R + v U (F, R,
 *     U: rows 3, 0, 1 of light_view_proj, R and U divided by their squared lengths, so D has unit
 *     depth), the plane's inverse depth is 1 / z(u, v) = (n.D(u, v)) / (n.(q - lamp)), affine
 *     in (u, v): 1/z = (1/z_q) (1 + g . delta), delta the tap's offset from q in texels,
 *     g = (2 / size) (n.R, -n.U) / n.D(u_q, v_q) (clamped to RP_PLANE_MAX_GRADIENT per texel
 *     where n.D nears 0). A texel occludes when it is nearer than BOTH the plane there and the
 *     receiver itself (the factor taken as max(1 + g . delta, 1)) by RP_SHADOW_DEPTH_BIAS
 *     texels: a point between the receiver and the lamp's disk is always nearer than the
 *     receiver, and this keeps the floor beside a wall point (a concave corner, where the
 *     wall's plane extended lies beyond the floor or is never met by the tap's ray) from
 *     shadowing it. An empty texel (d = 1) never occludes. A stored texel's inverse depth is
 *     affine in the stored d: 1/z = 1/near - d (far - near) / (near far).
 *   pcf: RP_PCF_TAPS taps of the 16-point Poisson disk (common/random.h) scaled to
 *     RP_PCF_RADIUS texels around q, the disk rotated per pixel and frame (one of 16 angles: a
 *     hash of (x, y) plus frame_index, so any 16 consecutive frames visit every angle once) so
 *     TAA averages 16 x RP_PCF_TAPS positions: one soft edge width everywhere.
 *
 * PCSS. The emitter is the lamp cap: the part below the ceiling (y = 1) of a sphere of radius
 * R = light_pos.w around the lamp centre (light_pos, 0.1 above the ceiling). Seen from below,
 * its outline is the cut circle: a disk of radius a = sqrt(R^2 - z_e^2) (0.335 for R = 0.35)
 * at depth z_e = light_pos.y - 1 (0.1) along the lamp's axis (straight down). (From closer than
 * R^2 / z_e = 1.2 the sphere's own silhouette, angular radius asin(R / L), shows instead; at
 * L = 0.6 that is 36 degrees against the disk's 34: within a few per cent.) Depths z below are
 * along the axis from the lamp centre, lateral positions in tan units (world lateral / z):
 *   the disk lies at depth z_e, centre on the axis; a receiver at depth z_r, lateral u_r; a
 *   point at depth z (z_e < z < z_r) lies between the receiver and SOME point of the disk iff
 *   the line from the receiver through it meets the disk plane within radius a, i.e. (similar
 *   triangles) iff |u - c(z)| < r(z) with
 *       c(z) = u_r z_r (z - z_e) / (z (z_r - z_e)),     r(z) = a (z_r - z) / (z (z_r - z_e)).
 *   This is the receiver's light cone at depth z as the shadow map sees it (its centre moves
 *   towards the axis because the disk's centre, not the projection centre, is what the receiver
 *   looks at; for z_e = 0 it is the classic centred region). A blocker plane at z_b therefore
 *   hides the part of the lamp that the shadow map's disk (c(z_b), r(z_b)) covers, and moving
 *   the receiver across a straight blocker edge sweeps that disk over the edge: with
 *   dc/du_r = z_r (z_b - z_e) / (z_b (z_r - z_e)) per unit of u_r = x / z_r, the PENUMBRA WIDTH
 *   on a receiver plane parallel to the disk is (in world units)
 *       w = 2 r(z_b) z_r / (z_r dc/du_r) = 2 a (z_r - z_b) / (z_b - z_e),
 *   the textbook w_light (d_receiver - d_blocker) / d_blocker with the distances measured from
 *   the disk's plane (not the lamp centre) and w_light = 2a. PCF over the disk (c(z_b), r(z_b))
 *   with uniform taps returns exactly the visible fraction of the lamp's disk for a planar
 *   blocker parallel to it.
 *   In texels: u (tan units) -> u P00 size / 2 texels from the map centre, so a -> K = a P00
 *   size / 2; both c and r are affine in 1/z, so per tap they cost two multiply-adds.
 * Steps, per receiver:
 *   1. A conservative test on the MIN mip, per chunk of eight pixels: the union of the boxes
 *      holding each receiver's cone between depths z_n = min(RP_PCSS_NEAREST, (z_r + z_e) / 2)
 *      and z_r (its disks' union), read as a footprint of at most 4x4 texels at the first
 *      level whose texels are a third of the union's extent: min z >= every lane's z_r means
 *      nothing in front of any receiver there, so the chunk is fully lit (exact). Else that
 *      min z_min (at least z_n) bounds the search (RP_PCSS_MIN_PASSES > 1 repeats the lookup
 *      over the narrower box for z_min: a blocker at depth z lies in the box for z, which
 *      shrinks as z grows; on the busy scene it cost more than it saved). A texel nearer than
 *      z_n counts as at z_n.
 *   2. Blocker search: RP_PCSS_SEARCH_TAPS rotated Poisson taps through the cone between z_min
 *      and z_r (one rotation per 2x2 quad of pixels), pooled over the quad: see the code; a
 *      quad on one surface traces the whole set once, a quarter per pixel, and every pixel of
 *      it counts all of the quad's blockers (light pass 19.2 -> 15.4 CPU ms on the busy 720
 *      frame; bench --accuracy at 360: floor 35.5 dB, penumbrae 0.86x / 0.95x the truth's,
 *      against 35.4 dB, 0.93x / 1.02x with 12 taps per pixel). The set:
 *      the even ones uniform over the disk holding all its disks (centre halfway
 *      between c(z_min) and u_r, radius r(z_min) plus half their distance), the odd ones on the
 *      cone's disk at inverse depths from 1/z_min to 1/z_r in equal steps, the last within a
 *      texel of the receiver, so blockers near it (small disks: contact shadows) are found as
 *      well as high ones; a tap is a BLOCKER when its texel is in front of the receiver plane
 *      AND inside the cone at some depth between its own and the receiver's (|u - c(z)| <
 *      max(r(z), RP_PCSS_MIN_RADIUS texels) for some z in [z_texel, z_r): the shadow map's
 *      occluders are solid behind their front faces; in (u, 1/z) the cone is linear, so that is
 *      the convex hull of the texel depth's disk and the apex u_r), which keeps walls beside
 *      a floor point from counting (they are nearer than the floor's plane but not between it
 *      and the lamp). No blocker: lit; all blockers: umbra.
 *   3. Blocker depth z_b: halfway (in 1/z) between the harmonic mean of the blockers' depths
 *      (inverse depths average linearly: they are affine in the stored d) and the nearest
 *      blocker's (a thick blocker's outline is drawn by its near parts; bench --accuracy at
 *      360, floor PSNR: mean 35.3 dB, nearest 35.1, halfway 35.7).
 *   4. PCF: RP_PCSS_FILTER_TAPS taps over the disk (c(z_b), r(z_b)) (r clamped to
 *      [RP_PCSS_MIN_RADIUS, RP_PCSS_MAX_RADIUS] texels), each tap one point of the lamp's disk
 *      (the ray from the receiver to it crosses depth z_b at the tap), spread uniformly over
 *      its area (RP_SOFT_FILTER_POINT; the Poisson set's mean r^2 is 0.62 against the uniform
 *      disk's 0.5, which widened every penumbra: a plate's 10-90 % width 1.13x the lamp
 *      disk's without the search's lit / umbra decisions). The ray is blocked when
 *      the texel under the tap fails pcf's receiver-plane test with its caster's front at most
 *      about 7 % behind z_b (RP_PCSS_PLANE_SLACK: a caster farther behind the plane, e.g. a
 *      round tumbler's belly under the disk of a receiver in its outer penumbra, is not where
 *      the ray crosses the plane; without the condition that penumbra read too dark: bench
 *      --accuracy --size 360 --spp 512, open-floor error at lamp fraction 0.7-0.8 -0.014 after
 *      the tone map, penumbra 31.28 -> 31.80 dB with it; 0.85 31.31, 0.90 31.69, 0.92 and
 *      0.94 31.80, 0.97 31.71, 1.0 31.37 with the penumbra 0.75x the truth's), OR when one of
 *      RP_PCSS_MARCH points along it between z_b and the receiver (at 1/3 and 2/3 of the
 *      way in 1/z, so of the way in texels) lies INSIDE a caster: behind the nearest stored
 *      surface on its texel's ray and in front of the farthest (the map's second plane)
 *      plus RP_PCSS_BACK_MARGIN. That is a thick blocker's body, e.g. a tumbler's belly over the
 *      floor beside it, which the nearest depth alone cannot show, while the space under an
 *      overhang (past the farthest surface) stays open. bench --accuracy at 360, floor PSNR:
 *      nearest depth only 22.6 dB; "solid 0.2 deep behind it" (the previous rule) 28.4; the
 *      farthest plane with 1 point 31.6, 2 points 35.0 (at 1/4 and 3/4: 30.5), 3 points 33.7;
 *      margin 0 32.1, 0.02 35.3, 0.05 34.4 (with the lamp's disk model of
 *      common/direct_light.h); with the filter taps uniform over the disk, floor / penumbra
 *      PSNR: margin 0 36.1 / 30.7, 0.005 36.5 / 31.2, 0.01 36.6 / 31.3, 0.015 36.4 / 31.1,
 *      0.02 36.1 / 30.7 (the wider margin darkened the inner penumbra). Visibility = 1 -
 *      blocked taps / taps. (Not the search's cone test: the disk already is the cone at z_b,
 *      and the lamp rays cross texels diagonally: a ball's umbra came out 25 % lit.)
 *   Tap counts: 8 search taps missed the small blockers of a penumbra's outer half (the
 *   tumbler's 10-90 % penumbra came out 0.76 x the truth's); 12 search and 6 filter taps
 *   give 0.93 x and 35.4 dB for about the time of 8 and 8 (16 search taps: 0.93 x, 35.5 dB).
 *   Pooled over quads, 12 search taps (3 per pixel) still missed the outer penumbra's blockers
 *   on some pixels and frames: those came out fully lit, a stipple of lit dots beyond the
 *   tumblers' shadows that even 16 frames averaged kept (bench --accuracy at 360, penumbra PSNR
 *   29.3 dB; 16 taps 29.9, 20 taps 29.2, 24 taps 30.4 with the dots gone; at 128x128 25.9, 29.3,
 *   30.4, 30.1). 24 (6 per pixel) cost the busy 720x720 frame's light pass about 1.5 ms.
 *   Search and filter disks are rotated by independent angles per pixel and frame; TAA
 *   averages them.
 *
 * VSSM (variance soft shadow maps): step 1 as PCSS; then the mean and mean square of z over
 *   the search disk from the MEAN / MEAN2 mips (trilinear: bilinear lookups at the two levels
 *   around log2(diameter) - 1, level >= 1, as a bilinear lookup at level l spans about
 *   2^(l+1) texels), the average blocker depth from them (the
 *   VSSM paper: with the non-blockers assumed at the receiver's depth t, mu = (1 - a) t + a z_b,
 *   the fraction 1 - a of non-blockers taken as Chebyshev's one-sided bound
 *   p = s^2 / (s^2 + (t - mu)^2), s^2 = E[z^2] - mu^2 floored at RP_VSSM_MIN_VARIANCE), then the
 *   moments over the filter disk (c(z_b), r(z_b)) and visibility = that bound for t > mu (1
 *   otherwise) with light-bleeding reduction: (p - RP_VSSM_BLEED) / (1 - RP_VSSM_BLEED) clamped
 *   to [0, 1]. t is the receiver plane's depth at the disk's centre minus the bias and minus
 *   the plane's own depth spread over the disk.
 */
#ifndef ROLYPOLY_COMMON_SOFT_SHADOW_H
#define ROLYPOLY_COMMON_SOFT_SHADOW_H

#include "shared/types.h"
#include "shared/shadow_mips.h"
#include "common/direct_light.h"
#include "common/random.h"
#include "common/indirect_simd.h"

#ifndef RP_SHADOW_MODE
#define RP_SHADOW_MODE 2
#endif
#ifndef RP_SHADOW_NORMAL_OFFSET
#define RP_SHADOW_NORMAL_OFFSET 1.0f
#endif
#ifndef RP_SHADOW_DEPTH_BIAS
#define RP_SHADOW_DEPTH_BIAS 1.0f
#endif
#ifndef RP_PCF_RADIUS
#define RP_PCF_RADIUS 2.5f /* texels */
#endif
#ifndef RP_PCF_TAPS
#define RP_PCF_TAPS 8
#endif
#ifndef RP_PCSS_SEARCH_TAPS
#define RP_PCSS_SEARCH_TAPS 24
#endif
#if RP_PCSS_SEARCH_TAPS % 4 != 0
#error "RP_PCSS_SEARCH_TAPS must be a multiple of 4 (soft_shadow.h pools 2x2 quads)"
#endif
#ifndef RP_PCSS_FILTER_TAPS
#define RP_PCSS_FILTER_TAPS 6
#endif
/* Nearest blocker depth the search looks for (world units below the lamp centre: y = 0.25). */
#ifndef RP_PCSS_PAIR_TEXELS
#define RP_PCSS_PAIR_TEXELS 3.0f /* pooled searches: receivers at most this far apart */
#endif
#ifndef RP_PCSS_NEAREST
#define RP_PCSS_NEAREST 0.85f
#endif
#define RP_PCSS_MIN_RADIUS 0.75f /* texels: a texel's own extent */
#ifndef RP_PCSS_MIN_PASSES
#define RP_PCSS_MIN_PASSES 1 /* step 1's lookups */
#endif
#define RP_PCSS_MAX_RADIUS 63.0f /* texels: the coarsest mip's 2x2 footprint still covers it */
#ifndef RP_PCSS_MARCH
#define RP_PCSS_MARCH 2 /* points per filter tap's lamp ray tested against the casters' solid */
#endif
#ifndef RP_PCSS_BACK_MARGIN
#define RP_PCSS_BACK_MARGIN 0.01f /* world units beyond the farthest surface still solid */
#endif
#ifndef RP_PCSS_PLANE_SLACK
#define RP_PCSS_PLANE_SLACK 0.93f /* a filter tap's caster blocks at z_b: 1/z >= this / z_b */
#endif
#define RP_PLANE_MAX_GRADIENT 0.5f /* relative inverse-depth change per texel */
#ifndef RP_VSSM_BLEED
#define RP_VSSM_BLEED 0.2f
#endif
#define RP_VSSM_MIN_VARIANCE 1.0e-5f /* world^2 */

/* cos(2 pi k / 16), k = 0..15; sin(2 pi k / 16) = cos(2 pi (k - 4) / 16). */
#define RP_SOFT_COS16                                                                       \
  ((float16)(1.0f, 0.923879533f, 0.707106781f, 0.382683432f, 0.0f, -0.382683432f,            \
             -0.707106781f, -0.923879533f, -1.0f, -0.923879533f, -0.707106781f,              \
             -0.382683432f, 0.0f, 0.382683432f, 0.707106781f, 0.923879533f))

/* The receivers' lookup state (eight lanes). Offsets below are in texels. */
typedef struct {
  float8 sx, sy;      /* q in texel coordinates (top-left origin) */
  float8 zr;          /* q's linear depth (clip w) */
  float8 texel;       /* world size of a texel at the receiver */
  float8 tan_theta;   /* slope of the receiver against the light ray (<= RP_DIRECT_MAX_SLOPE) */
  float8 inv0;        /* biased inverse plane depth at q: 1 / (zr - bias texels) */
  float8 gx, gy;      /* relative inverse-depth gradient of the receiver plane per texel */
  float8 gx0, gy0;    /* inv0 gx, inv0 gy */
  float8 ca, sa;      /* search / hard / pcf rotation */
  float8 cb, sb;      /* filter rotation */
  int8 inside;        /* inside the frustum and facing the lamp */
  float size, near, far, inv_a, inv_b; /* 1/z of a stored d: inv_a - d inv_b */
  int isize;
} RpShadow8;

/* The eight stored depths at texel indices idx (one per lane; a gather). */
inline float8 rp_shadow_gather8(__global const float* restrict shadow, int8 idx) {
  return (float8)(shadow[idx.s0], shadow[idx.s1], shadow[idx.s2], shadow[idx.s3], shadow[idx.s4],
                  shadow[idx.s5], shadow[idx.s6], shadow[idx.s7]);
}

/* The texels at (tx, ty) (texel coordinates, clamped to the map): their casters' inverse
 * depths (*inv_tap) and where those lie in front of the receiver plane (pcf's test). */
inline int8 rp_soft_plane_test(__global const float* restrict shadow, const RpShadow8* s,
                               float8 tx, float8 ty, float8* inv_tap) {
  const float8 hi = (float8)(s->size - 1.0f), lo = (float8)(0.0f);
  const int8 idx = convert_int8(fmin(fmax(ty, lo), hi)) * s->isize +
                   convert_int8(fmin(fmax(tx, lo), hi));
  const float8 d = rp_shadow_gather8(shadow, idx);
  *inv_tap = s->inv_a - d * s->inv_b;
  const float8 thr = fmax(s->inv0 + s->gx0 * (tx - s->sx) + s->gy0 * (ty - s->sy), s->inv0);
  return (*inv_tap > thr) & (d < 1.0f);
}

/* Visibility of the texels at (tx, ty): 1 where the stored depth is not in front of the
 * receiver plane, for pcf. */
inline float8 rp_soft_plane_lit(__global const float* restrict shadow, const RpShadow8* s,
                                float8 tx, float8 ty) {
  float8 inv_tap;
  return select((float8)(1.0f), (float8)(0.0f), rp_soft_plane_test(shadow, s, tx, ty, &inv_tap));
}

/* 1 where a pcss filter tap at (tx, ty) (texel coordinates) is blocked at the blocker plane
 * (inverse depth iavg): the texel fails pcf's receiver-plane test AND its caster's front lies
 * at most about 7 % farther from the lamp than the plane (1/z >= RP_PCSS_PLANE_SLACK / z_b).
 * A caster whose front lies well behind the plane is not where the tap's lamp ray crosses
 * the plane: whether the ray meets it farther on is the march's question (step 4). */
inline float8 rp_pcss_plane_blocked(__global const float* restrict shadow, const RpShadow8* s,
                                    float8 tx, float8 ty, float8 iavg) {
  float8 inv_tap;
  const int8 in_front = rp_soft_plane_test(shadow, s, tx, ty, &inv_tap);
  return select((float8)(0.0f), (float8)(1.0f),
                in_front & (inv_tap >= iavg * RP_PCSS_PLANE_SLACK));
}

/* Rotated Poisson point k (of 16) for lanes with rotation (c, s). */
#define RP_SOFT_POINT(k, c, s, OX, OY)                                                      \
  {                                                                                         \
    const float2 d_ = RP_POISSON_DISK[(k)];                                                 \
    OX = (c) * d_.x - (s) * d_.y;                                                           \
    OY = (s) * d_.x + (c) * d_.y;                                                           \
  }

/* The PCSS filter's taps in the unit disk: a sunflower (Vogel) spiral, tap k of n at radius
 * sqrt((k + 0.5) / n) and angle k times the golden angle (2.39996323 rad), so the n taps sample
 * the disk uniformly by area (every ring of it gets its share) and any few of them spread
 * around it. The Poisson set pushes its points to the rim (mean r^2 0.62 against the uniform
 * disk's 0.5). Tabled for the two counts the light pass builds (6, and
 * LightPass::kPcssTapsWithoutHistory = 16; cos and sin per tap and work-item cost the busy
 * 720x720 frame's shadow_visibility about a quarter more CPU time), computed for others. */
#if RP_PCSS_FILTER_TAPS == 6
#define RP_SOFT_FILTER_TABLE 1
__constant float2 RP_SOFT_FILTER_DISK[6] = {
    (float2)(0.2886751f, 0.0000000f), (float2)(-0.3686844f, 0.3377451f),
    (float2)(0.0564331f, -0.6430256f), (float2)(0.4647029f, 0.6061226f),
    (float2)(-0.8527869f, -0.1508460f), (float2)(0.8078342f, -0.5138780f)};
#elif RP_PCSS_FILTER_TAPS == 16
#define RP_SOFT_FILTER_TABLE 1
__constant float2 RP_SOFT_FILTER_DISK[16] = {
    (float2)(0.1767767f, 0.0000000f), (float2)(-0.2257722f, 0.2068258f),
    (float2)(0.0345581f, -0.3937712f), (float2)(0.2845712f, 0.3711728f),
    (float2)(-0.5222232f, -0.0923739f), (float2)(0.4946954f, -0.3146847f),
    (float2)(-0.1654659f, 0.6155250f), (float2)(-0.3155615f, -0.6075944f),
    (float2)(0.6846422f, 0.2500302f), (float2)(-0.7122561f, 0.2940090f),
    (float2)(0.3433545f, -0.7337286f), (float2)(0.2537302f, 0.8089320f),
    (float2)(-0.7647459f, -0.4431859f), (float2)(0.8971340f, -0.1972324f),
    (float2)(-0.5475069f, 0.7787722f), (float2)(-0.1264868f, -0.9760897f)};
#endif

/* Filter tap k (of RP_PCSS_FILTER_TAPS) rotated by (c, s), the lanes' rotation. */
#ifdef RP_SOFT_FILTER_TABLE
#define RP_SOFT_FILTER_POINT(k, c, s, OX, OY)                                                \
  {                                                                                         \
    const float2 d_ = RP_SOFT_FILTER_DISK[(k)];                                             \
    OX = (c) * d_.x - (s) * d_.y;                                                           \
    OY = (s) * d_.x + (c) * d_.y;                                                           \
  }
#else
#define RP_SOFT_FILTER_POINT(k, c, s, OX, OY)                                                \
  {                                                                                         \
    const float r_ = sqrt(((float)(k) + 0.5f) / (float)RP_PCSS_FILTER_TAPS);                \
    const float a_ = (float)(k) * 2.39996323f;                                              \
    const float x_ = r_ * cos(a_), y_ = r_ * sin(a_);                                        \
    OX = (c) * x_ - (s) * y_;                                                               \
    OY = (s) * x_ + (c) * y_;                                                               \
  }
#endif

/* Fills *out (PoCL does not inline helpers that return structs: an out-pointer). */
/* The receivers' projection: every field of RpShadow8 up to inv0 (what the hard mode's one tap
 * reads) and q's NDC x, y; rp_shadow8_setup adds the receiver planes and the rotations. */
inline void rp_shadow8_project(RpShadow8* out, __global const FrameConstants* restrict frame,
                               float8 px, float8 py, float8 pz, float8 nx, float8 ny, float8 nz,
                               float8 cos_theta, float8* ndx_out, float8* ndy_out) {
  RpShadow8 s;
  const rp_mat4 m = frame->light_view_proj;
  s.isize = (int)frame->shadow_size;
  s.size = (float)s.isize;
  s.near = frame->clip.z;
  s.far = frame->clip.w;
  s.inv_a = 1.0f / s.near;
  s.inv_b = (s.far - s.near) / (s.near * s.far);
  const float8 w0 = m.c[0].w * px + m.c[1].w * py + m.c[2].w * pz + m.c[3].w;
  const float r0 = m.c[0].x * m.c[0].x + m.c[1].x * m.c[1].x + m.c[2].x * m.c[2].x;
  s.texel = fabs(w0) * (2.0f / (s.size * sqrt(r0)));
  const float8 cc = fmax(cos_theta, 1.0e-4f);
  s.tan_theta = fmin(sqrt(fmax(1.0f - cc * cc, 0.0f)) / cc, RP_DIRECT_MAX_SLOPE);
  const float8 off = s.texel * RP_SHADOW_NORMAL_OFFSET;
  const float8 qx = px + nx * off, qy = py + ny * off, qz = pz + nz * off;
  const float8 cx = m.c[0].x * qx + m.c[1].x * qy + m.c[2].x * qz + m.c[3].x;
  const float8 cy = m.c[0].y * qx + m.c[1].y * qy + m.c[2].y * qz + m.c[3].y;
  const float8 cz = m.c[0].z * qx + m.c[1].z * qy + m.c[2].z * qz + m.c[3].z;
  const float8 cw = m.c[0].w * qx + m.c[1].w * qy + m.c[2].w * qz + m.c[3].w;
  const int8 front = cw > 0.0f;
  const float8 iw = 1.0f / select((float8)(1.0f), cw, front);
  const float8 ndx = cx * iw, ndy = cy * iw, ndz = cz * iw;
  s.inside = front & (fabs(ndx) <= 1.0f) & (fabs(ndy) <= 1.0f) & (ndz <= 1.0f) &
             (cos_theta > 0.0f);
  s.sx = (ndx * 0.5f + 0.5f) * s.size;
  s.sy = (0.5f - ndy * 0.5f) * s.size;
  s.zr = cw;
  s.inv0 = 1.0f / fmax(cw - s.texel * RP_SHADOW_DEPTH_BIAS, 1.0e-3f);
  *ndx_out = ndx;
  *ndy_out = ndy;
  *out = s;
}

inline void rp_shadow8_setup(RpShadow8* out, __global const FrameConstants* restrict frame,
                             float8 px, float8 py, float8 pz, float8 nx, float8 ny, float8 nz,
                             float8 cos_theta, uint8 xs, uint8 ys) {
  RpShadow8 s;
  float8 ndx, ndy;
  rp_shadow8_project(&s, frame, px, py, pz, nx, ny, nz, cos_theta, &ndx, &ndy);
  const rp_mat4 m = frame->light_view_proj;
  const float r0 = m.c[0].x * m.c[0].x + m.c[1].x * m.c[1].x + m.c[2].x * m.c[2].x;
  const float r1 = m.c[0].y * m.c[0].y + m.c[1].y * m.c[1].y + m.c[2].y * m.c[2].y;
  /* receiver plane: n.D(u, v) = n.F + u n.R + v n.U */
  const float ir0 = 1.0f / r0, ir1 = 1.0f / r1;
  const float8 n_f = nx * m.c[0].w + ny * m.c[1].w + nz * m.c[2].w;
  const float8 n_r = (nx * m.c[0].x + ny * m.c[1].x + nz * m.c[2].x) * ir0;
  const float8 n_u = (nx * m.c[0].y + ny * m.c[1].y + nz * m.c[2].y) * ir1;
  const float8 n_d = n_f + ndx * n_r + ndy * n_u;
  const float8 n_d_safe = select(n_d, (float8)(-1.0e-6f), fabs(n_d) < 1.0e-6f);
  const float8 gscale = (2.0f / s.size) / n_d_safe;
  const float8 gmax = (float8)(RP_PLANE_MAX_GRADIENT);
  s.gx = fmin(fmax(n_r * gscale, -gmax), gmax);
  s.gy = fmin(fmax(-n_u * gscale, -gmax), gmax);
  s.gx0 = s.inv0 * s.gx;
  s.gy0 = s.inv0 * s.gy;
  /* two rotations per pixel and frame: one of 16 angles each (a table, not sin/cos: vectorizes),
   * a per-pixel start stepping with the frame (by 1 and by 7, both coprime with 16), so that
   * every 16 consecutive frames visit each angle once instead of drawing 16 at random (the
   * accuracy report's 16-frame average: penumbra PSNR at 128x128 25.9 -> 26.2 dB) */
  const uint8 h = rp_hash8_u32(xs ^ rp_hash8_u32(ys));
  const uint f = frame->frame_index;
  const uint8 a0 = ((h >> 28) + f) & 15u, a1 = (((h >> 24) & 15u) + 7u * f) & 15u;
  s.ca = shuffle(RP_SOFT_COS16, a0);
  s.sa = shuffle(RP_SOFT_COS16, (a0 + 12u) & 15u);
  s.cb = shuffle(RP_SOFT_COS16, a1);
  s.sb = shuffle(RP_SOFT_COS16, (a1 + 12u) & 15u);
  *out = s;
}

#if RP_SHADOW_MODE == 2 || RP_SHADOW_MODE == 3
/* The lamp's disk in texels: K = a P00 size / 2, z_e (shared by PCSS and VSSM). */
typedef struct {
  float8 xr, yr;   /* the receiver q relative to the map centre (texels) */
  float8 k_h;      /* K / (z_r - z_e): r(z) = k_h (z_r / z - 1) */
  float8 c_h;      /* z_r / (z_r - z_e): c(z) = x_r c_h (1 - z_e / z) */
  float8 g0, g1;   /* c(z) / u_r - 1 = g0 - g1 / z */
  float8 kz;       /* k_h z_r: r(z) = kz / z - k_h */
  float8 i_near;   /* 1 / the nearest blocker depth searched: min(RP_PCSS_NEAREST,
                      (z_r + z_e) / 2) (a receiver above RP_PCSS_NEAREST still has room) */
  float ze;
} RpLamp8;

inline void rp_lamp8(RpLamp8* out, __global const FrameConstants* restrict frame,
                     const RpShadow8* s) {
  RpLamp8 L;
  const float4 lp = frame->light_pos;
  const rp_mat4 m = frame->light_view_proj;
  L.ze = lp.y - RP_CEILING_Y;
  const float a = sqrt(fmax(lp.w * lp.w - L.ze * L.ze, 0.0f));
  const float p00 = sqrt(m.c[0].x * m.c[0].x + m.c[1].x * m.c[1].x + m.c[2].x * m.c[2].x);
  const float k = a * p00 * s->size * 0.5f;
  const float8 h = 1.0f / fmax(s->zr - L.ze, 1.0e-3f);
  L.k_h = k * h;
  L.c_h = s->zr * h;
  L.xr = s->sx - s->size * 0.5f;
  L.yr = s->sy - s->size * 0.5f;
  L.i_near = 1.0f / fmin((float8)(RP_PCSS_NEAREST), fmax((s->zr + L.ze) * 0.5f, 1.0e-3f));
  L.g0 = L.c_h - 1.0f;
  L.g1 = L.c_h * L.ze;
  L.kz = L.k_h * s->zr;
  *out = L;
}

/* Sizes and offsets of the mip levels (shared/shadow_mips.h), computed once per work-item. */
typedef struct {
  int n[RP_SHADOW_MIP_LEVELS + 1];    /* texels per side of level l (l >= 1) */
  int off[RP_SHADOW_MIP_LEVELS + 1];  /* first texel of level l in the MIN plane */
  int levels;
  int plane;                          /* texels per plane (all levels) */
} RpMipTable;

inline void rp_mip_table(RpMipTable* t, int size) {
  t->levels = (int)rp_shadow_mip_levels((uint)size);
  int n = size, off = 0;
  for (int l = 1; l <= RP_SHADOW_MIP_LEVELS; ++l) {
    n = (n + 1) / 2;
    t->n[l] = n;
    t->off[l] = off;
    if (l <= t->levels) off += n * n;
  }
  t->plane = off;
}

/* Step 1 for the chunk: the MIN mip over the union of the lanes' boxes of the cone between
 * depths 1 / inear and z_r (lanes in `skip` left out), read as a footprint of at most 4x4
 * texels at the first level whose texels are at least a third of the union's extent wide.
 * Returns that min (a lower bound of every lane's own; 0 when the map has no mips, +inf
 * when every lane is skipped). */
inline float rp_pcss_min(__global const float* restrict mips, const RpShadow8* s,
                         const RpLamp8* L, const RpMipTable* t, float8 inear, float8 skip) {
  const float8 r = fmin(fmax(L->k_h * (s->zr * inear - 1.0f), (float8)(0.0f)),
                        (float8)(RP_PCSS_MAX_RADIUS)) + RP_PCSS_MIN_RADIUS;
  const float8 cf = L->c_h * (1.0f - L->ze * inear);
  const float8 mid = (float8)(s->size * 0.5f);
  const float8 cx = L->xr * cf + mid, cy = L->yr * cf + mid;
  /* skipped lanes: an empty box; the rest clamped to the map (the taps clamp their addresses
   * to it too) before any int conversion (lanes outside the frustum may hold any value) */
  const float8 lo = (float8)(0.0f), hi = (float8)(s->size - 1.0f);
  const int8 off = skip > 0.5f;
  const float8 x0 = select(fmin(fmax(fmin(cx, s->sx) - r, lo), hi), hi, off);
  const float8 x1 = select(fmin(fmax(fmax(cx, s->sx) + r, lo), hi), lo, off);
  const float8 y0 = select(fmin(fmax(fmin(cy, s->sy) - r, lo), hi), hi, off);
  const float8 y1 = select(fmin(fmax(fmax(cy, s->sy) + r, lo), hi), lo, off);
  const float4 a0 = fmin(x0.lo, x0.hi), a1 = fmax(x1.lo, x1.hi);
  const float4 b0 = fmin(y0.lo, y0.hi), b1 = fmax(y1.lo, y1.hi);
  const float ux0 = fmin(fmin(a0.x, a0.y), fmin(a0.z, a0.w));
  const float ux1 = fmax(fmax(a1.x, a1.y), fmax(a1.z, a1.w));
  const float uy0 = fmin(fmin(b0.x, b0.y), fmin(b0.z, b0.w));
  const float uy1 = fmax(fmax(b1.x, b1.y), fmax(b1.z, b1.w));
  if (ux1 < ux0 || uy1 < uy0) return 3.0e38f;
  if (t->levels == 0) return 0.0f;
  const float extent = fmax(fmax(ux1 - ux0, uy1 - uy0), 1.0f);
  int level = 1;
  while (level < t->levels && (float)(3 << level) < extent) ++level;
  const float scale = 1.0f / (float)(1 << level);
  const int n = t->n[level];
  const __global float* m = mips + t->off[level];
  const int i0 = min((int)(ux0 * scale), n - 1), i1 = min((int)(ux1 * scale), n - 1);
  const int j0 = min((int)(uy0 * scale), n - 1), j1 = min((int)(uy1 * scale), n - 1);
  float z = 3.0e38f;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) z = fmin(z, m[j * n + i]);
  return z;
}
#endif

#if RP_SHADOW_MODE == 2
/* The lanes of rp_shadow8 are a 4x2 block of pixels (lane k at column k & 3, row k >> 2):
 * RP_SHADOW_SWAP_H / _V / _D give each lane its neighbour in the same row, the same column and
 * the diagonal one, within its 2x2 quad. */
#define RP_SHADOW_SWAP_H ((uint8)(1u, 0u, 3u, 2u, 5u, 4u, 7u, 6u))
#define RP_SHADOW_SWAP_V ((uint8)(4u, 5u, 6u, 7u, 0u, 1u, 2u, 3u))
#define RP_SHADOW_SWAP_D ((uint8)(5u, 4u, 7u, 6u, 1u, 0u, 3u, 2u))

/* 1 where a lane and its partner under `swap` see the same surface, so that their blocker
 * searches may be pooled: both inside, receivers within RP_PCSS_PAIR_TEXELS texels of each
 * other in the map and in depth, normals within acos(0.9). Symmetric: both lanes agree. */
inline float8 rp_pcss_same(const RpShadow8* s, float8 nx, float8 ny, float8 nz, uint8 swap) {
  const float8 lim = (float8)(RP_PCSS_PAIR_TEXELS);
  const float8 texel = fmax(s->texel, shuffle(s->texel, swap));
  const int8 near = (fabs(s->sx - shuffle(s->sx, swap)) < lim) &
                    (fabs(s->sy - shuffle(s->sy, swap)) < lim) &
                    (fabs(s->zr - shuffle(s->zr, swap)) < lim * texel);
  const float8 cosn = nx * shuffle(nx, swap) + ny * shuffle(ny, swap) + nz * shuffle(nz, swap);
  const int8 both = s->inside & shuffle(s->inside, swap);
  return select((float8)(0.0f), (float8)(1.0f), near & both & (cosn > 0.9f));
}

/* 1 where the texel at (tx, ty) blocks the lamp from the receiver: in front of its plane and
 * inside its cone at the texel's own depth. *inv gets the texel's inverse depth. */
inline float8 rp_pcss_blocker(__global const float* restrict shadow, const RpShadow8* s,
                              const RpLamp8* L, float8 tx, float8 ty, float8* inv) {
  const float8 hi = (float8)(s->size - 1.0f), lo = (float8)(0.0f);
  const int8 idx = convert_int8(fmin(fmax(ty, lo), hi)) * s->isize +
                   convert_int8(fmin(fmax(tx, lo), hi));
  const float8 d = rp_shadow_gather8(shadow, idx);
  const float8 raw = s->inv_a - d * s->inv_b;
  /* anything nearer than the search's nearest depth counts as there (nearer
   * than the lamp's disk the cone formulas would mirror) */
  const float8 it = fmin(raw, L->i_near);
  *inv = it;
  const float8 vx = tx - s->sx, vy = ty - s->sy; /* tap - apex (the receiver) */
  /* in front of the receiver plane and of the receiver: 1/z > (1/z_q) max(1 + g . v, 1) */
  const float8 thr = fmax(s->inv0 + s->gx0 * vx + s->gy0 * vy, s->inv0);
  /* the cone's disk at the texel's depth: centre - apex = x_r (c(z) / u_r - 1), radius r */
  const float8 cf1 = L->g0 - L->g1 * it;
  const float8 wx = L->xr * cf1, wy = L->yr * cf1;
  const float8 dx = vx - wx, dy = vy - wy;     /* tap - disk centre */
  const float8 r = L->kz * it - L->k_h;
  const float8 rr = fmax(r, (float8)(RP_PCSS_MIN_RADIUS));
  const float8 front =
      select((float8)(0.0f), (float8)(1.0f), (raw > thr) & (d < 1.0f) & (r > 0.0f));
  /* inside the cone anywhere between the texel's depth and the receiver (a shadow map's
   * occluder is solid behind its front face): the convex hull of the disk (c, rr) and the apex
   * u_r, i.e. the disk or the sector of radius T = sqrt(L^2 - rr^2) (the tangent length; that
   * circle meets the disk's at right angles, so its arc lies inside the disk) around the apex
   * within the tangents' angle */
  const float8 vw = vx * wx + vy * wy, vv = vx * vx + vy * vy;
  const float8 t2 = wx * wx + wy * wy - rr * rr;
  const float8 in_disk = select((float8)(0.0f), (float8)(1.0f), dx * dx + dy * dy < rr * rr);
  const float8 in_sector =
      select((float8)(0.0f), (float8)(1.0f), (vw > 0.0f) & (vw * vw > vv * t2) & (vv < t2));
  return front * fmax(in_disk, in_sector);
}

/* Search tap t of the lanes' classes, offset by `off` (pooled search, step 2): lane class c
 * (0, 1, 0, 1, 2, 3, 2, 3: column parity + 2 row parity) traces tap te = 4 t + ((c + off + t)
 * & 3) of the full set of RP_PCSS_SEARCH_TAPS: even te uniform over the search disk (centre
 * (mx, my), radius rs), odd te on the cone's disk at inverse depth lerp(1 / z_min, 1 / z_r,
 * j / (N / 2 - 1)), j = te / 2; Poisson point (te 16 / N) & 15 rotated by (s->ca, s->sa). Adds
 * the blockers found to the sums. */
inline void rp_pcss_search_tap(__global const float* restrict shadow, const RpShadow8* s,
                               const RpLamp8* L, int t, int off, float8 inear, float8 mx,
                               float8 my, float8 rs, float8* count, float8* sum_inv,
                               float8* imax) {
  const float8 mid = (float8)(s->size * 0.5f);
  const int t0 = 4 * t + ((off + t) & 3), t1 = 4 * t + ((off + t + 1) & 3);
  const int t2 = 4 * t + ((off + t + 2) & 3), t3 = 4 * t + ((off + t + 3) & 3);
  const int8 te = (int8)(t0, t1, t0, t1, t2, t3, t2, t3);
  /* the lanes' Poisson points, then one rotation */
  const float2 q0 = RP_POISSON_DISK[(t0 * 16 / RP_PCSS_SEARCH_TAPS) & 15];
  const float2 q1 = RP_POISSON_DISK[(t1 * 16 / RP_PCSS_SEARCH_TAPS) & 15];
  const float2 q2 = RP_POISSON_DISK[(t2 * 16 / RP_PCSS_SEARCH_TAPS) & 15];
  const float2 q3 = RP_POISSON_DISK[(t3 * 16 / RP_PCSS_SEARCH_TAPS) & 15];
  const float8 dx = (float8)(q0.x, q1.x, q0.x, q1.x, q2.x, q3.x, q2.x, q3.x);
  const float8 dy = (float8)(q0.y, q1.y, q0.y, q1.y, q2.y, q3.y, q2.y, q3.y);
  const float8 ox = s->ca * dx - s->sa * dy, oy = s->sa * dx + s->ca * dy;
  const float8 f = convert_float8(te >> 1) * (1.0f / (float)(RP_PCSS_SEARCH_TAPS / 2 - 1));
  const float8 ik = inear + (1.0f / s->zr - inear) * f;
  const float8 rk = fmin(fmax(L->k_h * (s->zr * ik - 1.0f), (float8)(RP_PCSS_MIN_RADIUS)),
                         (float8)(RP_PCSS_MAX_RADIUS));
  const float8 ck = L->c_h * (1.0f - L->ze * ik);
  const int8 ladder = (te & 1) != 0;
  const float8 cx = select(mx, L->xr * ck + mid, ladder), cy = select(my, L->yr * ck + mid, ladder);
  const float8 r = select(rs, rk, ladder);
  float8 it;
  const float8 b = rp_pcss_blocker(shadow, s, L, cx + ox * r, cy + oy * r, &it);
  *count += b;
  *sum_inv += b * it;
  *imax = fmax(*imax, b * it);
}
#endif

#if RP_SHADOW_MODE == 3
/* Trilinear MEAN / MEAN2 lookup at (x, y) (texel coordinates) over a footprint `width` texels
 * wide, one lane at a time. */
inline float2 rp_vssm_moments(__global const float* restrict mips, const RpMipTable* tb,
                              float x, float y, float width) {
  const int levels = tb->levels;
  /* a bilinear lookup at level l averages over about 2^(l+1) texels (one level coarser, as
   * first written, blurred the tumblers away: no floor shadows in the demo at all) */
  const float lambda = clamp(native_log2(fmax(width, 1.0f)) - 1.0f, 1.0f, (float)levels);
  const int l0 = min((int)lambda, levels);
  const int l1 = min(l0 + 1, levels);
  const float t = lambda - (float)l0;
  float2 m[2];
  for (int k = 0; k < 2; ++k) {
    const int level = k == 0 ? l0 : l1;
    const int n = tb->n[level];
    const float scale = 1.0f / (float)(1 << level);
    const float u = x * scale - 0.5f, v = y * scale - 0.5f;
    const float fu = floor(u), fv = floor(v);
    const float au = u - fu, av = v - fv;
    const int i0 = clamp((int)fu, 0, n - 1), i1 = clamp((int)fu + 1, 0, n - 1);
    const int j0 = clamp((int)fv, 0, n - 1), j1 = clamp((int)fv + 1, 0, n - 1);
    const __global float* mean = mips + tb->plane * RP_SHADOW_MIP_MEAN + tb->off[level];
    const __global float* mean2 = mean + tb->plane;
    const int t00 = j0 * n + i0, t10 = j0 * n + i1, t01 = j1 * n + i0, t11 = j1 * n + i1;
    const float w00 = (1.0f - au) * (1.0f - av), w10 = au * (1.0f - av);
    const float w01 = (1.0f - au) * av, w11 = au * av;
    m[k] = (float2)(w00 * mean[t00] + w10 * mean[t10] + w01 * mean[t01] + w11 * mean[t11],
                    w00 * mean2[t00] + w10 * mean2[t10] + w01 * mean2[t01] + w11 * mean2[t11]);
  }
  return mix(m[0], m[1], t);
}

/* Chebyshev's one-sided bound P(z >= t) for moments (mu, E[z^2]). */
inline float8 rp_vssm_chebyshev(float8 mu, float8 m2, float8 t) {
  const float8 var = fmax(m2 - mu * mu, (float8)(RP_VSSM_MIN_VARIANCE));
  const float8 d = t - mu;
  return select(var / (var + d * d), (float8)(1.0f), t <= mu);
}

/* Moments of every lane over disks centred (cx, cy) with radius r (texels). */
inline void rp_vssm_lookup8(__global const float* restrict mips, const RpShadow8* s,
                            const RpMipTable* tb, float8 cx, float8 cy, float8 r, float8* mu,
                            float8* m2) {
  float xs[8], ys[8], rs[8], a[8], b[8];
  const float8 lo = (float8)(-1.0f), hi = (float8)(s->size + 1.0f);
  vstore8(fmin(fmax(cx, lo), hi), 0, xs); /* clamped before any int conversion */
  vstore8(fmin(fmax(cy, lo), hi), 0, ys);
  vstore8(r, 0, rs);
  for (int i = 0; i < 8; ++i) {
    const float2 v = tb->levels > 0 ? rp_vssm_moments(mips, tb, xs[i], ys[i], 2.0f * rs[i])
                                    : (float2)(s->far, s->far * s->far);
    a[i] = v.x;
    b[i] = v.y;
  }
  *mu = vload8(0, a);
  *m2 = vload8(0, b);
}
#endif

/* The hard mode's one tap (see the header) from a set-up state: 1 lit, 0 shadowed; 1 outside
 * the shadow frustum. Also the pcss checkerboard's check of a filled chunk
 * (kernels/shadow_visibility.cl). */
inline float8 rp_shadow8_hard_tap(__global const float* restrict shadow, const RpShadow8* s) {
  const float8 receiver = s->zr - s->texel * (RP_SHADOW_DEPTH_BIAS + 1.0f * s->tan_theta);
  const float8 hi = (float8)(s->size - 1.0f), lo = (float8)(0.0f);
  const int8 idx = convert_int8(fmin(fmax(s->sy, lo), hi)) * s->isize +
                   convert_int8(fmin(fmax(s->sx, lo), hi));
  const float8 d = rp_shadow_gather8(shadow, idx);
  /* lit iff 1/z_stored <= 1/receiver (both depths positive); an empty texel is lit */
  const float8 inv_tap = s->inv_a - d * s->inv_b;
  const int8 shadowed = s->inside & (d < 1.0f) & (inv_tap * receiver > 1.0f);
  return select((float8)(1.0f), (float8)(0.0f), shadowed);
}

/* rp_shadow8_hard_tap for eight receivers (rp_shadow8's arguments, without the pixels). */
inline float8 rp_shadow8_hard(__global const FrameConstants* restrict frame,
                              __global const float* restrict shadow, float8 px, float8 py,
                              float8 pz, float8 nx, float8 ny, float8 nz, float8 cos_theta) {
  RpShadow8 s;
  float8 ndx, ndy;
  rp_shadow8_project(&s, frame, px, py, pz, nx, ny, nz, cos_theta, &ndx, &ndy);
  if (!any(s.inside)) return (float8)(1.0f);
  return rp_shadow8_hard_tap(shadow, &s);
}

/* Visibility of the lamp from eight receivers (see the header). *mip_lit: 1 when pcss's step 1
 * found every lane lit (nothing in front of any receiver over the union of their cones), else
 * 0. */
inline float8 rp_shadow8(__global const FrameConstants* restrict frame,
                         __global const float* restrict shadow,
                         __global const float* restrict mips, float8 px, float8 py, float8 pz,
                         float8 nx, float8 ny, float8 nz, float8 cos_theta, uint8 xs, uint8 ys,
                         int* mip_lit) {
  *mip_lit = 0;
  RpShadow8 s;
  rp_shadow8_setup(&s, frame, px, py, pz, nx, ny, nz, cos_theta, xs, ys);
  const float8 one = (float8)(1.0f), zero = (float8)(0.0f);
  if (!any(s.inside)) return one;
  const float8 outside = select(one, zero, s.inside);
#if RP_SHADOW_MODE == 0
  (void)mips;
  (void)outside;
  return rp_shadow8_hard_tap(shadow, &s);
#elif RP_SHADOW_MODE == 1
  (void)mips;
  float8 lit = zero;
  for (int t = 0; t < RP_PCF_TAPS; ++t) {
    float8 ox, oy;
    RP_SOFT_POINT((t * 16 / RP_PCF_TAPS) & 15, s.ca, s.sa, ox, oy);
    lit += rp_soft_plane_lit(shadow, &s, s.sx + ox * RP_PCF_RADIUS, s.sy + oy * RP_PCF_RADIUS);
  }
  return fmax(lit * (1.0f / (float)RP_PCF_TAPS), outside);
#else
  RpLamp8 L;
  rp_lamp8(&L, frame, &s);
  /* Step 1, narrowed RP_PCSS_MIN_PASSES times: a blocker at depth z lies in the region for z,
   * which shrinks as z grows, so nothing nearer than the min m over one region means the
   * region for m holds every blocker; its min is then read at a finer level. */
  RpMipTable table;
  rp_mip_table(&table, s.isize);
  float zm = 0.0f;
  float8 inear = L.i_near;
  for (int pass = 0; pass < RP_PCSS_MIN_PASSES; ++pass) {
    zm = fmax(zm, rp_pcss_min(mips, &s, &L, &table, inear, outside));
    if (all((zm >= s.zr) | (s.inside == 0))) {
      *mip_lit = 1;
      return one;
    }
    inear = fmin((float8)(1.0f / zm), L.i_near);
  }
  const float8 zmin = (float8)(zm);
  const float8 done = fmax(outside, select(zero, one, zmin >= s.zr));
  const float8 mid = (float8)(s.size * 0.5f);
  /* The search disk (both modes): centre (mx, my) halfway between c(z_min) and the receiver,
   * radius rs = r(z_min) plus half their distance: it holds the cone's disks at every depth
   * from z_min to z_r. */
  const float8 rb = fmin(fmax(L.k_h * (s.zr * inear - 1.0f), zero), (float8)(RP_PCSS_MAX_RADIUS));
  const float8 cfb = L.c_h * (1.0f - L.ze * inear);
  const float8 bx = L.xr * cfb + mid, by = L.yr * cfb + mid;
  const float8 mx = (bx + s.sx) * 0.5f, my = (by + s.sy) * 0.5f;
  const float8 rs = fmin(rb + 0.5f * sqrt((bx - s.sx) * (bx - s.sx) + (by - s.sy) * (by - s.sy)) +
                             RP_PCSS_MIN_RADIUS,
                         (float8)(RP_PCSS_MAX_RADIUS));
#if RP_SHADOW_MODE == 2
  /* Blocker search (rp_pcss_search_tap: even taps uniform over the search disk, odd taps on
   * the cone's disk at depths from z_min to the receiver, the last within RP_PCSS_MIN_RADIUS
   * of it: contact shadows). Pooled over each 2x2 quad of the block: lane class c (column
   * parity + 2 row parity) traces the N / 4 taps 4 t + ((c + t) & 3), t = 0 .. N / 4 - 1, so
   * a quad's four lanes trace the whole set once, each with its own rotation; a lane then adds
   * the blockers of every quad neighbour that sees the same surface (rp_pcss_same). When some
   * undecided lane of the block pools with fewer than three neighbours (a silhouette, an
   * isolated point), every lane traces another N / 4 (class c + 2's), so that no lane relies
   * on fewer than N / 2 taps and a lane pooled with one neighbour sees the whole set; when one
   * pools with none (the floor beside a tumbler's outline in the picture, whose quad
   * neighbours show the tumbler), every lane traces the other two classes too, so that it
   * sees the whole set alone. (With N / 2 taps such receivers' blocker depths were the
   * noisiest of the penumbra: bench --accuracy --size 360 --spp 512, pcss, floor beside
   * objects' outlines 23.8 -> 25.9 dB, penumbra 31.8 -> 32.2 dB; at 128 30.9 -> 32.0 dB;
   * shadow_visibility's share of the busy 720x720 frame's CPU time 8.18 / 8.41 -> 8.26 /
   * 8.52 %.) */
  {
    /* one search rotation per quad (its top-left pixel's), so that a quad's taps together are
     * the rotated Poisson set, evenly spread, rather than four independently rotated parts */
    const uint8 hq = rp_hash8_u32((xs & ~1u) ^
                                  rp_hash8_u32((ys & ~1u) ^ rp_hash_u32(frame->frame_index)));
    const uint8 aq = hq >> 28;
    s.ca = shuffle(RP_SOFT_COS16, aq);
    s.sa = shuffle(RP_SOFT_COS16, (aq + 12u) & 15u);
  }
  float8 count = zero, sum_inv = zero, imax = zero;
  for (int t = 0; t < RP_PCSS_SEARCH_TAPS / 4; ++t)
    rp_pcss_search_tap(shadow, &s, &L, t, 0, inear, mx, my, rs, &count, &sum_inv, &imax);
  const float8 gh = rp_pcss_same(&s, nx, ny, nz, RP_SHADOW_SWAP_H);
  const float8 gv = rp_pcss_same(&s, nx, ny, nz, RP_SHADOW_SWAP_V);
  const float8 gd = rp_pcss_same(&s, nx, ny, nz, RP_SHADOW_SWAP_D);
  float own_taps = (float)(RP_PCSS_SEARCH_TAPS / 4);
  if (any((gh + gv + gd < 2.5f) & (done < 0.5f))) {
    for (int t = 0; t < RP_PCSS_SEARCH_TAPS / 4; ++t)
      rp_pcss_search_tap(shadow, &s, &L, t, 2, inear, mx, my, rs, &count, &sum_inv, &imax);
    own_taps *= 2.0f;
    if (any((gh + gv + gd < 0.5f) & (done < 0.5f))) {
      for (int t = 0; t < RP_PCSS_SEARCH_TAPS / 4; ++t) {
        rp_pcss_search_tap(shadow, &s, &L, t, 1, inear, mx, my, rs, &count, &sum_inv, &imax);
        rp_pcss_search_tap(shadow, &s, &L, t, 3, inear, mx, my, rs, &count, &sum_inv, &imax);
      }
      own_taps *= 2.0f;
    }
  }
  const float8 taps = own_taps * (1.0f + gh + gv + gd);
  {
    const float8 c0 = count, s0 = sum_inv, m0 = imax;
    count += gh * shuffle(c0, RP_SHADOW_SWAP_H) + gv * shuffle(c0, RP_SHADOW_SWAP_V) +
             gd * shuffle(c0, RP_SHADOW_SWAP_D);
    sum_inv += gh * shuffle(s0, RP_SHADOW_SWAP_H) + gv * shuffle(s0, RP_SHADOW_SWAP_V) +
               gd * shuffle(s0, RP_SHADOW_SWAP_D);
    imax = fmax(fmax(imax, gh * shuffle(m0, RP_SHADOW_SWAP_H)),
                fmax(gv * shuffle(m0, RP_SHADOW_SWAP_V), gd * shuffle(m0, RP_SHADOW_SWAP_D)));
  }
  const float8 none = select(zero, one, count < 0.5f);
  const float8 umbra = select(zero, one, count > taps - 0.5f);
  if (all(fmax(fmax(done, none), umbra) > 0.5f)) return fmax(fmax(done, none), zero);
  /* step 3: halfway between the mean and the nearest blocker, in 1/z */
  const float8 iavg = select(inear, 0.5f * (sum_inv / fmax(count, one) + imax), count > 0.5f);
  const float8 rf = fmin(fmax(L.k_h * (s.zr * iavg - 1.0f), (float8)(RP_PCSS_MIN_RADIUS)),
                         (float8)(RP_PCSS_MAX_RADIUS));
  const float8 cff = L.c_h * (1.0f - L.ze * iavg);
  const float8 fx = L.xr * cff + mid, fy = L.yr * cff + mid;
  float8 occ = zero;
  for (int t = 0; t < RP_PCSS_FILTER_TAPS; ++t) {
    float8 ox, oy;
    RP_SOFT_FILTER_POINT(t, s.cb, s.sb, ox, oy);
    const float8 tx = fx + ox * rf, ty = fy + oy * rf;
    /* the tap's lamp ray between the blocker plane and the receiver (points linear in 1/z,
     * so linear in texels): blocked where a point lies inside a caster's solid, between the
     * nearest and the farthest stored surface on its texel's ray (a thick blocker's body,
     * which the front face alone does not show) */
    float8 thick = zero;
    const float8 hi = (float8)(s.size - 1.0f);
    for (int m = 1; m <= RP_PCSS_MARCH; ++m) {
      const float f = (float)m / (float)(RP_PCSS_MARCH + 1);
      const float8 mx2 = tx + f * (s.sx - tx), my2 = ty + f * (s.sy - ty);
      const int8 idx2 = convert_int8(fmin(fmax(my2, zero), hi)) * s.isize +
                        convert_int8(fmin(fmax(mx2, zero), hi));
      const float8 d2 = rp_shadow_gather8(shadow, idx2);
      const float8 b2 = rp_shadow_gather8(shadow + s.isize * s.isize, idx2);
      const float8 i2 = iavg + f * (1.0f / s.zr - iavg); /* the ray point's inverse depth */
      const float8 inv2 = s.inv_a - d2 * s.inv_b;          /* the nearest surface's */
      const float8 invb = s.inv_a - b2 * s.inv_b;          /* the farthest's */
      const int8 inside = (inv2 > i2) & (i2 * (1.0f + RP_PCSS_BACK_MARGIN * invb) > invb) &
                          (inv2 > s.inv0) & (d2 < 1.0f);
      thick = fmax(thick, select(zero, one, inside));
    }
    occ += fmax(rp_pcss_plane_blocked(shadow, &s, tx, ty, iavg), thick);
  }
  /* (N - occ) / N, not 1 - occ / N: with a tap count that is no power of two, a contracted
   * fma(-occ, 1 / N, 1) gives -3e-8 for occ = N */
  const float8 vis = ((float)RP_PCSS_FILTER_TAPS - occ) * (1.0f / (float)RP_PCSS_FILTER_TAPS);
  /* decided lanes: lit (mip, outside, no blocker found) or umbra (every search tap blocked) */
  return select(select(vis, zero, umbra > 0.5f), one, fmax(done, none) > 0.5f);
#else /* VSSM: over the search disk above */
  /* the receiver plane's depth at a disk's centre, less its own spread over the disk */
  float8 mu, m2;
  rp_vssm_lookup8(mips, &s, &table, mx, my, rs, &mu, &m2);
  const float8 slope = fabs(s.gx) + fabs(s.gy);
  const float8 ts = 1.0f / (s.inv0 * fmin(fmax(1.0f + s.gx * (mx - s.sx) + s.gy * (my - s.sy),
                                               (float8)(0.5f)), (float8)(2.0f)) *
                            (1.0f + slope * rs));
  const float8 p = rp_vssm_chebyshev(mu, m2, ts);
  const float8 blockers = 1.0f - p;
  const float8 zb = fmin(fmax((mu - p * ts) / fmax(blockers, (float8)(1.0e-4f)),
                              1.0f / inear), ts);
  const float8 none = select(zero, one, blockers < 1.0e-3f);
  if (all(fmax(done, none) > 0.5f)) return one;
  const float8 ib = 1.0f / zb;
  const float8 rf = fmin(fmax(L.k_h * (s.zr * ib - 1.0f), (float8)(RP_PCSS_MIN_RADIUS)),
                         (float8)(RP_PCSS_MAX_RADIUS));
  const float8 cff = L.c_h * (1.0f - L.ze * ib);
  const float8 fx = L.xr * cff + mid, fy = L.yr * cff + mid;
  rp_vssm_lookup8(mips, &s, &table, fx, fy, rf, &mu, &m2);
  const float8 tf = 1.0f / (s.inv0 * fmin(fmax(1.0f + s.gx * (fx - s.sx) + s.gy * (fy - s.sy),
                                               (float8)(0.5f)), (float8)(2.0f)) *
                            (1.0f + slope * rf));
  const float8 pv = rp_vssm_chebyshev(mu, m2, tf);
  const float8 vis = clamp((pv - RP_VSSM_BLEED) * (1.0f / (1.0f - RP_VSSM_BLEED)), zero, one);
  return select(vis, one, fmax(done, none) > 0.5f);
#endif
#endif
}

#endif
