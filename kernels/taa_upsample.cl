/* Temporal upsampling (the render scale): resolves a jittered frame rendered at rw x rh into
 * the history and the output image at ow x oh >= rw x rh, one output pixel per work-item.
 * kernels/taa.cl is the same-size resolve; this one differs only where the sizes do:
 *
 *   coordinates  continuous, pixel centres at i + 0.5, +y down. Output pixel X's centre in
 *                render pixels is p = (X + 0.5) * rw / ow. The jittered view_proj moved every
 *                point by +jitter render pixels, so render pixel i sampled the scene at
 *                q_i = i + 0.5 - jitter (in render pixels).
 *   0. per render pixel (kernel taa_upsample_box, at the render size): its tone-mapped
 *                colour T(x) = x / (1 + x), and over the 3x3 around it the mean and gamma x
 *                the standard deviation of T in YCoCg and the velocity of the nearest surface
 *                (smallest linear depth). Steps 2 and 3 read them for the render pixel whose
 *                sample is nearest p: computed once per render pixel rather than once per
 *                output pixel (about 1 / scale^2 times).
 *   1. current   the render pixels whose samples may be within reach of the output pixel
 *                centre: the 3x3 around the one nearest p, or at scales below 0.837 (reach
 *                under one render pixel) the 2x2 around p; each sample weighted by w = max(0,
 *                1 - 0.7 d^2)^2, d its distance from the output pixel centre in OUTPUT pixels
 *                (close to a Gaussian of sigma 0.47 output pixels: about the pixel's own
 *                footprint; zero beyond RP_TAAU_REACH). c = sum w T / sum w. Where no sample is
 *                within reach (sum w = 0: at scale 0.5 the nearest can be 1.4 output pixels
 *                away) c is the nearest sample and, with w_max = 0, the history stays as it was.
 *   2. box       step 0's box of the nearest render pixel, mean +- gamma * stddev, grown to
 *                hold c (the 3x3 spans 3 / scale output pixels, so a thin feature's own colour
 *                can lie outside the moments' box).
 *   3. motion    step 0's velocity of the nearest render pixel (render pixels), times ow / rw:
 *                output pixels.
 *   4. history   output-resolution history, bilinear at the output pixel centre - motion;
 *                outside the image, or when history_valid = 0, history = c.
 *   5. blend     history clipped toward the box centre (rp_taa_clip), then
 *                out = hist + (c - hist) * (1 - history_weight) * w_max, where w_max, the
 *                largest sample weight, says how close this frame came to the output pixel: at
 *                scale 0.5 a render pixel covers 2x2 output pixels and most frames' samples
 *                land elsewhere, so each frame only nudges the pixels it actually sampled and
 *                the jitter sequence (GpuScene::update) fills in the rest over the frames.
 *
 * Buffers (row-major, top row first):
 *   hdr_in        float4 rw x rh  linear HDR of this frame (w passed through from the pixel
 *                                 nearest p); read by step 0
 *   velocity      float2 rw x rh  render pixels, this frame minus previous, unjittered; step 0
 *   normal_depth  float4 rw x rh  the GBuffer's (w: linear view depth; far plane where nothing)
 *   colour, box_centre, box_extent  float4 rw x rh  step 0's (taa_upsample_box says how)
 *   history_in    float  ow x oh  previous resolved frame, tone mapped, planes R, G, B
 *   history_out   float  ow x oh  this resolved frame, same layout
 *   hdr_out       float4 ow x oh  this resolved frame in linear HDR
 *   velocity_out  float2 ow x oh  step 3's motion in output pixels (motion blur at output size)
 *   depth_speed   half2  ow x oh  the motion blur's depth/speed plane (common/depth_speed.h)
 *                                 from velocity_out and the linear depth of the render pixel
 *                                 nearest p, for params.blur_half = shutter / 2; not written
 *                                 when blur_half is 0 (no motion blur)
 * Eight output pixels of a row per work-item, one float8 per channel (common/taa.h says why):
 * pixels x0 .. x0+7 with x0 = 8 * get_global_id(0), row get_global_id(1). Every tap of step 1
 * and step 0's values of the nearest render pixel are one float4 load per lane, each lane
 * named (RP_TAAU_GATHER4). On PoCL that beat loading each render row once as a 16-pixel segment
 * and picking every lane's taps from it through private memory: the pass on the busy 720x720
 * frame at scale 0.5 4.7 / 5.5 / 6.4 -> 3.8 / 5.0 / 5.2 ms, at 0.85 11.1 / 9.8 -> 9.0 / 8.0 ms
 * (rounds alternating on a noisy host).
 * tests/passes/taa_upsample_test.cpp holds the same algorithm in plain C++.
 */
#include "shared/types.h"
#include "shared/pass_params.h"
#include "common/colour.h"
#include "common/taa.h"
#include "common/depth_speed.h"

/* A sample's weight from its squared distance from the output pixel centre (output pixels):
 * (1 - d^2 / 1.43)^2 inside 1.2 pixels, 0 beyond; close to a Gaussian of sigma 0.47 (about
 * the pixel's own footprint: 0.57 at 0.5, 0.09 at 1) without exp's cost. */
inline float8 rp_taau_weight(float8 d2) {
  const float8 t = rp_max8(1.0f - 0.7f * d2, 0.0f);
  return t * t;
}
/* The weight's reach, sqrt(1 / 0.7) output pixels: at scales below 1 / RP_TAAU_REACH (0.837)
 * it is under one render pixel, so the samples within reach of p are among the 2x2 around it */
#define RP_TAAU_REACH 1.1952286f

/* Grows the box centre M +- extent E (one channel) to hold the value C. */
#define RP_TAAU_GROW_BOX(M, E, C)                                                         \
  do {                                                                                   \
    const float8 lo_ = fmin((M) - (E), (C)), hi_ = fmax((M) + (E), (C));                   \
    M = 0.5f * (lo_ + hi_);                                                              \
    E = 0.5f * (hi_ - lo_);                                                              \
  } while (0)

/* Columns x0 - 1 .. x0 + 14 of a float4 image row (clamped to 0 .. w - 1) as planes R, G, B, A
 * (float16 lvalues): two 8-pixel loads inside the image, clamped single loads at its borders. */
#define RP_TAAU_LOAD_SEGMENT(img, row, x0, w, R, G, B, A)                                  \
  do {                                                                                   \
    float8 r0_, g0_, b0_, a0_, r1_, g1_, b1_, a1_;                                       \
    if ((x0) >= 1 && (x0) + 15 <= (w)) {                                                 \
      RP_LOAD_PX8(img, row, (x0) - 1, r0_, g0_, b0_, a0_);                               \
      RP_LOAD_PX8(img, row, (x0) + 7, r1_, g1_, b1_, a1_);                               \
    } else {                                                                             \
      float t_[64];                                                                      \
      for (int k_ = 0; k_ < 16; ++k_)                                                    \
        vstore4((img)[(row) + clamp((x0) - 1 + k_, 0, (w) - 1)], k_, t_);                \
      RP_DEINTERLEAVE8(vload16(0, t_), vload16(1, t_), r0_, g0_, b0_, a0_);              \
      RP_DEINTERLEAVE8(vload16(2, t_), vload16(3, t_), r1_, g1_, b1_, a1_);              \
    }                                                                                    \
    R = (float16)(r0_, r1_);                                                             \
    G = (float16)(g0_, g1_);                                                             \
    B = (float16)(b0_, b1_);                                                             \
    A = (float16)(a0_, a1_);                                                             \
  } while (0)

/* The same for a float2 image (velocity) as planes X, Y. */
#define RP_TAAU_LOAD_SEGMENT2(img, row, x0, w, X, Y)                                       \
  do {                                                                                   \
    float t_[32];                                                                        \
    if ((x0) >= 1 && (x0) + 15 <= (w)) {                                                 \
      const __global float* f_ = (const __global float*)((img) + (row) + (x0) - 1);      \
      vstore16(vload16(0, f_), 0, t_);                                                   \
      vstore16(vload16(1, f_), 1, t_);                                                   \
    } else {                                                                             \
      for (int k_ = 0; k_ < 16; ++k_)                                                    \
        vstore2((img)[(row) + clamp((x0) - 1 + k_, 0, (w) - 1)], k_, t_);                \
    }                                                                                    \
    const float16 p0_ = vload16(0, t_), p1_ = vload16(1, t_);                            \
    X = (float16)(p0_.even, p1_.even);                                                   \
    Y = (float16)(p0_.odd, p1_.odd);                                                     \
  } while (0)

/* Lanes 0..7 of a segment loaded from x0 - 1, shifted by dx in {-1, 0, 1}: pixel x0 + k + dx. */
#define RP_TAAU_SHIFT(S, dx) ((dx) < 0 ? (S).s01234567 : (dx) == 0 ? (S).s12345678 : (S).s23456789)

/* Step 0, at the render size: what depends only on the render pixel nearest an output pixel,
 * computed once per render pixel instead of once per output pixel (4x fewer at scale 0.5).
 * Eight render pixels of a row per work-item: x0 = 8 get_global_id(0), row get_global_id(1).
 *   colour      float4 rw x rh  T(r), T(g), T(b) (tone mapped), alpha
 *   box_centre  float4 rw x rh  the 3x3's mean of T in YCoCg, and the x velocity (render
 *                               pixels) of its nearest surface (smallest depth; the first of
 *                               equals in row-major order)
 *   box_extent  float4 rw x rh  gamma x the 3x3's standard deviation of T in YCoCg, and that
 *                               surface's y velocity
 * The 3x3 clamps its columns and rows to the image (edge pixels repeat). */
__kernel void taa_upsample_box(__global const float4* restrict hdr_in,
                               __global const float2* restrict velocity,
                               __global const float4* restrict normal_depth,
                               __global float4* restrict colour,
                               __global float4* restrict box_centre,
                               __global float4* restrict box_extent, const TaaParams params) {
  const int rw = (int)params.render_width, rh = (int)params.render_height;
  const int x0 = 8 * (int)get_global_id(0), y = (int)get_global_id(1);
  if (x0 >= rw || y >= rh) return;
  float8 m1y = 0.0f, m1o = 0.0f, m1g = 0.0f, m2y = 0.0f, m2o = 0.0f, m2g = 0.0f;
  float8 near_depth = INFINITY, nvx = 0.0f, nvy = 0.0f;
  float8 tr = 0.0f, tg = 0.0f, tb = 0.0f, alpha = 0.0f;
  for (int dy = -1; dy <= 1; ++dy) {
    const int row = clamp(y + dy, 0, rh - 1) * rw;
    float16 r, g, b, a, unused0, unused1, unused2, d, vx, vy;
    RP_TAAU_LOAD_SEGMENT(hdr_in, row, x0, rw, r, g, b, a);
    RP_TAAU_LOAD_SEGMENT(normal_depth, row, x0, rw, unused0, unused1, unused2, d);
    RP_TAAU_LOAD_SEGMENT2(velocity, row, x0, rw, vx, vy);
    r = rp_tone_map16(r);
    g = rp_tone_map16(g);
    b = rp_tone_map16(b);
    if (dy == 0) {
      tr = r.s12345678;
      tg = g.s12345678;
      tb = b.s12345678;
      alpha = a.s12345678;
    }
#define RP_TAAU_BOX_TAP(dx)                                                               \
  do {                                                                                   \
    const float8 r_ = RP_TAAU_SHIFT(r, dx), g_ = RP_TAAU_SHIFT(g, dx);                   \
    const float8 b_ = RP_TAAU_SHIFT(b, dx);                                              \
    const float8 ly_ = 0.25f * r_ + 0.5f * g_ + 0.25f * b_, lo_ = 0.5f * r_ - 0.5f * b_; \
    const float8 lg_ = -0.25f * r_ + 0.5f * g_ - 0.25f * b_;                             \
    m1y += ly_;                                                                          \
    m1o += lo_;                                                                          \
    m1g += lg_;                                                                          \
    m2y += ly_ * ly_;                                                                    \
    m2o += lo_ * lo_;                                                                    \
    m2g += lg_ * lg_;                                                                    \
    const float8 d_ = RP_TAAU_SHIFT(d, dx);                                              \
    const int8 closer_ = d_ < near_depth; /* strict: the first of equals wins */         \
    near_depth = select(near_depth, d_, closer_);                                        \
    nvx = select(nvx, RP_TAAU_SHIFT(vx, dx), closer_);                                   \
    nvy = select(nvy, RP_TAAU_SHIFT(vy, dx), closer_);                                   \
  } while (0)
    RP_TAAU_BOX_TAP(-1);
    RP_TAAU_BOX_TAP(0);
    RP_TAAU_BOX_TAP(1);
#undef RP_TAAU_BOX_TAP
  }
  const float ninth = 1.0f / 9.0f, gamma = params.gamma;
  const float8 my = m1y * ninth, mo = m1o * ninth, mg = m1g * ninth;
  const float8 ey = gamma * sqrt(rp_max8(m2y * ninth - my * my, 0.0f));
  const float8 eo = gamma * sqrt(rp_max8(m2o * ninth - mo * mo, 0.0f));
  const float8 eg = gamma * sqrt(rp_max8(m2g * ninth - mg * mg, 0.0f));
  const int row = y * rw;
  if (x0 + 8 <= rw) {
    RP_STORE_PX8(colour, row, x0, tr, tg, tb, alpha);
    RP_STORE_PX8(box_centre, row, x0, my, mo, mg, nvx);
    RP_STORE_PX8(box_extent, row, x0, ey, eo, eg, nvy);
  } else {
    const int n = rw - x0;
    RP_STORE_PX8_FIRST(colour, row, x0, n, tr, tg, tb, alpha);
    RP_STORE_PX8_FIRST(box_centre, row, x0, n, my, mo, mg, nvx);
    RP_STORE_PX8_FIRST(box_extent, row, x0, n, ey, eo, eg, nvy);
  }
}

/* The float4 img[index.sk] of lane k as planes X, Y, Z, W: one load per lane, each lane named
 * (a loop over the lanes through private memory cost the busy 720x720 frame's resolve at scale
 * 0.5 about 1.2 ms more on PoCL: 7.0 against 5.7 ms). */
#define RP_TAAU_GATHER4(img, index, X, Y, Z, W)                                           \
  do {                                                                                   \
    const float4 g0_ = (img)[(index).s0], g1_ = (img)[(index).s1];                       \
    const float4 g2_ = (img)[(index).s2], g3_ = (img)[(index).s3];                       \
    const float4 g4_ = (img)[(index).s4], g5_ = (img)[(index).s5];                       \
    const float4 g6_ = (img)[(index).s6], g7_ = (img)[(index).s7];                       \
    RP_DEINTERLEAVE8((float16)(g0_, g1_, g2_, g3_), (float16)(g4_, g5_, g6_, g7_), X, Y, Z, W); \
  } while (0)

__kernel void taa_upsample(__global const float4* restrict colour,
                           __global const float4* restrict box_centre,
                           __global const float4* restrict box_extent,
                           __global const float4* restrict normal_depth,
                           __global const float* restrict history_in,
                           __global float* restrict history_out,
                           __global float4* restrict hdr_out,
                           __global float2* restrict velocity_out,
                           __global half* restrict depth_speed, const TaaParams params) {
  const uint render_width = params.render_width, render_height = params.render_height;
  const uint out_width = params.out_width, out_height = params.out_height;
  const float jitter_x = params.jitter_x, jitter_y = params.jitter_y;
  const float history_weight = params.history_weight, blur_half = params.blur_half;
  const uint history_valid = params.history_valid;
  const int ow = (int)out_width, oh = (int)out_height;
  const int x0 = 8 * (int)get_global_id(0), oy = (int)get_global_id(1);
  if (x0 >= ow || oy >= oh) return;
  const int rw = (int)render_width, rh = (int)render_height;
  const float sx = (float)rw / (float)ow, sy = (float)rh / (float)oh; /* render px per output px */
  const float inv_sx = (float)ow / (float)rw, inv_sy = (float)oh / (float)rh;
  const int8 lane = (int8)(0, 1, 2, 3, 4, 5, 6, 7);
  const float8 ocx = convert_float8(lane + x0) + 0.5f; /* output pixel centres */
  const float ocy = (float)oy + 0.5f;
  const float8 px = ocx * sx; /* ... in render pixels */
  const float py = ocy * sy;
  /* the render pixel whose sample q_i = i + 0.5 - jitter is nearest p (vector bounds: see
   * DESIGN.md on oclgrind) */
  const int8 last_col = (int8)(rw - 1);
  const int8 cx = clamp(convert_int8(floor(px + jitter_x)), (int8)(0), last_col);
  const int cy = clamp((int)floor(py + jitter_y), 0, rh - 1);
  const int8 nearest = cx + cy * rw;

  /* step 1: the samples within reach, each weighted by its distance from the output pixel */
  int8 bx;
  int by, taps;
  if (sx * RP_TAAU_REACH < 1.0f && sy * RP_TAAU_REACH < 1.0f) {
    bx = convert_int8(floor(px + (jitter_x - 0.5f)));
    by = (int)floor(py + (jitter_y - 0.5f));
    taps = 2;
  } else {
    bx = cx - 1;
    by = cy - 1;
    taps = 3;
  }
  float8 sum_w = 0.0f, max_w = 0.0f, cr = 0.0f, cg = 0.0f, cb = 0.0f;
  for (int dy = 0; dy < taps; ++dy) {
    const int y = clamp(by + dy, 0, rh - 1), row = y * rw;
    const float ddy = ((float)y + 0.5f - jitter_y - py) * inv_sy;
    for (int dx = 0; dx < taps; ++dx) {
      const int8 col = clamp(bx + dx, (int8)(0), last_col);
      const int8 at = col + row;
      float8 r, g, b, unused_a;
      RP_TAAU_GATHER4(colour, at, r, g, b, unused_a);
      /* the sample's distance from the output pixel centre, in output pixels */
      const float8 ddx = (convert_float8(col) + (0.5f - jitter_x) - px) * inv_sx;
      const float8 w = rp_taau_weight(ddx * ddx + ddy * ddy);
      sum_w += w;
      max_w = fmax(max_w, w);
      cr += w * r;
      cg += w * g;
      cb += w * b;
    }
  }
  /* the nearest render pixel's own colour, its box and its nearest surface's velocity (step 0) */
  float8 nr, ng, nb, alpha, my, mo, mg, vx, ey, eo, eg, vy;
  RP_TAAU_GATHER4(colour, nearest, nr, ng, nb, alpha);
  RP_TAAU_GATHER4(box_centre, nearest, my, mo, mg, vx);
  RP_TAAU_GATHER4(box_extent, nearest, ey, eo, eg, vy);
  /* no sample within reach (at scales < 0.7 the nearest can be up to 0.5 / scale * sqrt 2
   * output pixels away): the nearest sample, and max_w = 0 keeps the history as it is */
  const int8 reached = sum_w > 1.0e-6f;
  const float8 inv_w = 1.0f / select((float8)(1.0f), sum_w, reached);
  cr = select(nr, cr * inv_w, reached);
  cg = select(ng, cg * inv_w, reached);
  cb = select(nb, cb * inv_w, reached);
  const float8 mvx = vx * inv_sx, mvy = vy * inv_sy; /* output pixels */

  /* history: bilinear at the reprojected centre, clamped to the image */
  const float8 hx = ocx - mvx, hy = ocy - mvy;
  const int8 use_history = (int8)(history_valid != 0u ? -1 : 0) & (hx >= 0.0f) & (hy >= 0.0f) &
                           (hx <= (float)ow) & (hy <= (float)oh);
  const float8 tx = rp_clamp8(hx - 0.5f, 0.0f, (float)(ow - 1));
  const float8 ty = rp_clamp8(hy - 0.5f, 0.0f, (float)(oh - 1));
  const int8 ix0 = convert_int8(tx), iy0 = convert_int8(ty); /* >= 0: truncation = floor */
  const float8 fx = tx - convert_float8(ix0), fy = ty - convert_float8(iy0);
  const int8 ix1 = min(ix0 + 1, (int8)(ow - 1)), iy1 = min(iy0 + 1, (int8)(oh - 1));
  const int8 ia = iy0 * ow + ix0, ib = iy0 * ow + ix1, ic = iy1 * ow + ix0, id = iy1 * ow + ix1;
  const int plane = ow * oh;
  float8 hr, hg, hb;
  RP_TAA_HISTORY8(history_in, plane, ow, hr, hg, hb);

  /* clip toward the box centre in YCoCg (rp_taa_clip, lane by lane), then blend; the box grown
   * to hold this frame's c (the 3x3 spans 3 / scale output pixels: a thin feature's own colour
   * can lie outside the moments' box) */
  const rp_ycocg8 cc = rp_rgb_to_ycocg8(cr, cg, cb);
  RP_TAAU_GROW_BOX(my, ey, cc.y);
  RP_TAAU_GROW_BOX(mo, eo, cc.co);
  RP_TAAU_GROW_BOX(mg, eg, cc.cg);
  ey = rp_max8(ey, RP_TAA_MIN_EXTENT);
  eo = rp_max8(eo, RP_TAA_MIN_EXTENT);
  eg = rp_max8(eg, RP_TAA_MIN_EXTENT);
  const rp_ycocg8 hc = rp_rgb_to_ycocg8(hr, hg, hb);
  float8 qy, qo, qg;
  RP_TAA_CLIP8(hc, my, mo, mg, ey, eo, eg, qy, qo, qg);
  const float8 t = qy - qg;
  const float8 qr = t + qo, qgreen = qy + qg, qb = t - qo;
  const float8 k = (1.0f - history_weight) * max_w;
  const float8 rr = select(cr, rp_clamp8(qr + (cr - qr) * k, 0.0f, 1.0f), use_history);
  const float8 rg = select(cg, rp_clamp8(qgreen + (cg - qgreen) * k, 0.0f, 1.0f), use_history);
  const float8 rb = select(cb, rp_clamp8(qb + (cb - qb) * k, 0.0f, 1.0f), use_history);

  const int row = oy * ow;
  /* the motion blur's plane: this motion and the nearest render pixel's depth */
  float16 plane_value = 0.0f;
  if (blur_half > 0.0f) {
    const float8 centre_depth =
        (float8)(normal_depth[nearest.s0].w, normal_depth[nearest.s1].w,
                 normal_depth[nearest.s2].w, normal_depth[nearest.s3].w,
                 normal_depth[nearest.s4].w, normal_depth[nearest.s5].w,
                 normal_depth[nearest.s6].w, normal_depth[nearest.s7].w);
    plane_value = rp_mb_depth_speed8(mvx, mvy, centre_depth, blur_half);
  }
  if (x0 + 8 <= ow) {
    RP_STORE_PLANE8(history_out, row, x0, rr);
    RP_STORE_PLANE8(history_out + plane, row, x0, rg);
    RP_STORE_PLANE8(history_out + 2 * plane, row, x0, rb);
    RP_STORE_PX8(hdr_out, row, x0, rp_tone_map_inverse8(rr), rp_tone_map_inverse8(rg),
                 rp_tone_map_inverse8(rb), alpha);
    if (blur_half > 0.0f) vstore_half16(plane_value, 0, depth_speed + 2 * (row + x0));
    vstore16((float16)(mvx.s0, mvy.s0, mvx.s1, mvy.s1, mvx.s2, mvy.s2, mvx.s3, mvy.s3, mvx.s4,
                       mvy.s4, mvx.s5, mvy.s5, mvx.s6, mvy.s6, mvx.s7, mvy.s7),
             0, (__global float*)(velocity_out + row + x0));
  } else {
    const int n = ow - x0;
    RP_STORE_PLANE8_FIRST(history_out, row, x0, n, rr);
    RP_STORE_PLANE8_FIRST(history_out + plane, row, x0, n, rg);
    RP_STORE_PLANE8_FIRST(history_out + 2 * plane, row, x0, n, rb);
    RP_STORE_PX8_FIRST(hdr_out, row, x0, n, rp_tone_map_inverse8(rr), rp_tone_map_inverse8(rg),
                       rp_tone_map_inverse8(rb), alpha);
    float u_[8], v_[8], p_[16];
    vstore8(mvx, 0, u_);
    vstore8(mvy, 0, v_);
    vstore16(plane_value, 0, p_);
    for (int i = 0; i < n; ++i) velocity_out[row + x0 + i] = (float2)(u_[i], v_[i]);
    if (blur_half > 0.0f)
      for (int i = 0; i < 2 * n; ++i) vstore_half(p_[i], 0, depth_speed + 2 * (row + x0) + i);
  }
}
