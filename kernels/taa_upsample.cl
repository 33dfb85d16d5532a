/* Temporal upsampling (the render scale): resolves a jittered frame rendered at rw x rh into
 * the history and the output image at ow x oh >= rw x rh, one output pixel per work-item.
 * kernels/taa.cl is the same-size resolve; this one differs only where the sizes do:
 *
 *   coordinates  continuous, pixel centres at i + 0.5, +y down. Output pixel X's centre in
 *                render pixels is p = (X + 0.5) * rw / ow. The jittered view_proj moved every
 *                point by +jitter render pixels, so render pixel i sampled the scene at
 *                q_i = i + 0.5 - jitter (in render pixels).
 *   1. current   the 3x3 render pixels around the one whose sample is nearest p; each sample
 *                weighted by w = max(0, 1 - 0.7 d^2)^2, d its distance from the output pixel
 *                centre in OUTPUT pixels (close to a Gaussian of sigma 0.47 output pixels:
 *                about the pixel's own footprint). c = sum w T(x) / sum w on tone-mapped colour
 *                T(x) = x / (1 + x). Where no sample is within reach (sum w = 0: at scale 0.5
 *                the nearest can be 1.4 output pixels away) c is the nearest sample and, with
 *                w_max = 0, the history stays as it was.
 *   2. box       mean and standard deviation of the 3x3 samples' T in YCoCg; box = mean +-
 *                gamma * stddev, grown to hold c (the 3x3 spans 3 / scale output pixels, so a
 *                thin feature's own colour can lie outside the moments' box).
 *   3. motion    velocity of the nearest surface (smallest linear depth) among the 3x3, in
 *                render pixels, times ow / rw: output pixels.
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
 *                                 nearest p)
 *   velocity      float2 rw x rh  render pixels, this frame minus previous, unjittered
 *   normal_depth  float4 rw x rh  the GBuffer's (w: linear view depth; far plane where nothing)
 *   history_in    float  ow x oh  previous resolved frame, tone mapped, planes R, G, B
 *   history_out   float  ow x oh  this resolved frame, same layout
 *   hdr_out       float4 ow x oh  this resolved frame in linear HDR
 *   velocity_out  float2 ow x oh  step 3's motion in output pixels (motion blur at output size)
 *   depth_out     float4 ow x oh  w: the linear depth of the pixel nearest p (xyz 0)
 * Eight output pixels of a row per work-item, one float8 per channel (common/taa.h says why):
 * pixels x0 .. x0+7 with x0 = 8 * get_global_id(0), row get_global_id(1). Their samples lie
 * in one render row band and at most 11 consecutive render columns, so each of the three
 * render rows is loaded once as a segment of 16 pixels (tone mapped once) and every lane picks
 * its taps from the segment (rp_pick8), not with a gather from global memory per tap.
 * Cost on the 2-core AVX2 EPYC: 13-15 ms at 720x720 output from 360x360 (the same-size
 * resolve: about 4.7 ms at 720), most of it in the 3x3 loop (3.2 ms without it).
 * tests/passes/taa_upsample_reference.cpp is the same algorithm in plain C++.
 */
#include "shared/types.h"
#include "shared/pass_params.h"
#include "common/colour.h"
#include "common/taa.h"

/* A sample's weight from its squared distance from the output pixel centre (output pixels):
 * (1 - d^2 / 1.43)^2 inside 1.2 pixels, 0 beyond; close to a Gaussian of sigma 0.47 (about
 * the pixel's own footprint: 0.57 at 0.5, 0.09 at 1) without exp's cost. */
inline float8 rp_taau_weight(float8 d2) {
  const float8 t = rp_max8(1.0f - 0.7f * d2, 0.0f);
  return t * t;
}
#define RP_TAAU_SEGMENT 16 /* render pixels loaded per row: 8 lanes at scale <= 1 need <= 11 */

/* Grows the box centre M +- extent E (one channel) to hold the value C. */
#define RP_TAAU_GROW_BOX(M, E, C)                                                         \
  do {                                                                                   \
    const float8 lo_ = fmin((M) - (E), (C)), hi_ = fmax((M) + (E), (C));                   \
    M = 0.5f * (lo_ + hi_);                                                              \
    E = 0.5f * (hi_ - lo_);                                                              \
  } while (0)

/* lane k = x[at.sk], through private memory (measured as fast as OpenCL's shuffle() with a
 * run-time mask on PoCL) */
inline float8 rp_pick8(float16 x, uint8 at) {
  float t[16];
  vstore16(x, 0, t);
  return (float8)(t[at.s0], t[at.s1], t[at.s2], t[at.s3], t[at.s4], t[at.s5], t[at.s6], t[at.s7]);
}

__kernel void taa_upsample(__global const float4* restrict hdr_in,
                           __global const float2* restrict velocity,
                           __global const float4* restrict normal_depth,
                           __global const float* restrict history_in,
                           __global float* restrict history_out,
                           __global float4* restrict hdr_out,
                           __global float2* restrict velocity_out,
                           __global float4* restrict depth_out, const TaaParams params) {
  const uint render_width = params.render_width, render_height = params.render_height;
  const uint out_width = params.out_width, out_height = params.out_height;
  const float jitter_x = params.jitter_x, jitter_y = params.jitter_y;
  const float history_weight = params.history_weight, gamma = params.gamma;
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
  const int base = max(cx.s0 - 1, 0); /* the segments' first column */

  float8 sum_w = 0.0f, max_w = 0.0f, cr = 0.0f, cg = 0.0f, cb = 0.0f;
  float8 m1y = 0.0f, m1o = 0.0f, m1g = 0.0f, m2y = 0.0f, m2o = 0.0f, m2g = 0.0f;
  float8 near_depth = INFINITY, alpha = 0.0f, centre_depth = 0.0f;
  float8 nr = 0.0f, ng = 0.0f, nb = 0.0f; /* the nearest sample (tone mapped) */
  int8 near_index = 0; /* the nearest sample's render pixel index */
  for (int dy = -1; dy <= 1; ++dy) {
    const int y = clamp(cy + dy, 0, rh - 1), row = y * rw;
    /* the segment: 16 render pixels from column `base` (clamped to the last column) */
    float8 r0, g0, b0, a0, r1, g1, b1, a1, unused0, unused1, d0, d1;
    if (base + RP_TAAU_SEGMENT <= rw) {
      RP_LOAD_PX8(hdr_in, row, base, r0, g0, b0, a0);
      RP_LOAD_PX8(hdr_in, row, base + 8, r1, g1, b1, a1);
      RP_LOAD_PX8(normal_depth, row, base, unused0, unused1, unused0, d0);
      RP_LOAD_PX8(normal_depth, row, base + 8, unused0, unused1, unused0, d1);
    } else {
      RP_LOAD_PX8_CLAMPED(hdr_in, row, base, rw, r0, g0, b0, a0);
      RP_LOAD_PX8_CLAMPED(hdr_in, row, min(base + 8, rw - 1), rw, r1, g1, b1, a1);
      RP_LOAD_PX8_CLAMPED(normal_depth, row, base, rw, unused0, unused1, unused0, d0);
      RP_LOAD_PX8_CLAMPED(normal_depth, row, min(base + 8, rw - 1), rw, unused0, unused1,
                          unused0, d1);
    }
    const float16 R = rp_tone_map16((float16)(r0, r1)), G = rp_tone_map16((float16)(g0, g1));
    const float16 B = rp_tone_map16((float16)(b0, b1)), D = (float16)(d0, d1);
    if (dy == 0) {
      const uint8 at = convert_uint8(cx - base);
      alpha = rp_pick8((float16)(a0, a1), at);
      centre_depth = rp_pick8(D, at);
    }
    const float ddy = ((float)y + 0.5f - jitter_y - py) * inv_sy;
    for (int dx = -1; dx <= 1; ++dx) {
      const int8 col = clamp(cx + dx, (int8)(0), last_col);
      const uint8 at = convert_uint8(col - base);
      const float8 r = rp_pick8(R, at), g = rp_pick8(G, at), b = rp_pick8(B, at);
      if (dy == 0 && dx == 0) {
        nr = r;
        ng = g;
        nb = b;
      }
      /* the sample's distance from the output pixel centre, in output pixels */
      const float8 ddx = (convert_float8(col) + (0.5f - jitter_x) - px) * inv_sx;
      const float8 w = rp_taau_weight(ddx * ddx + ddy * ddy);
      sum_w += w;
      max_w = fmax(max_w, w);
      cr += w * r;
      cg += w * g;
      cb += w * b;
      const float8 ly = 0.25f * r + 0.5f * g + 0.25f * b, lo = 0.5f * r - 0.5f * b;
      const float8 lg = -0.25f * r + 0.5f * g - 0.25f * b;
      m1y += ly;
      m1o += lo;
      m1g += lg;
      m2y += ly * ly;
      m2o += lo * lo;
      m2g += lg * lg;
      const float8 d = rp_pick8(D, at);
      const int8 closer = d < near_depth; /* strict: the first of equals wins */
      near_depth = select(near_depth, d, closer);
      near_index = select(near_index, col + row, closer);
    }
  }
  /* the nearest sample's velocity, one gather per lane */
  float8 vx, vy;
  {
    float u_[8], v_[8];
    for (int k = 0; k < 8; ++k) {
      const float2 v = velocity[((int*)&near_index)[k]];
      u_[k] = v.x;
      v_[k] = v.y;
    }
    vx = vload8(0, u_);
    vy = vload8(0, v_);
  }
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

  /* clip toward the box centre in YCoCg (rp_taa_clip, lane by lane), then blend */
  const float ninth = 1.0f / 9.0f;
  /* the box: mean +- gamma stddev of the 3x3, grown to hold this frame's c (the 3x3 spans
   * 3 / scale output pixels: a thin feature's own colour can lie outside the moments' box) */
  const rp_ycocg8 cc = rp_rgb_to_ycocg8(cr, cg, cb);
  float8 my = m1y * ninth, mo = m1o * ninth, mg = m1g * ninth;
  float8 ey = gamma * sqrt(rp_max8(m2y * ninth - my * my, 0.0f));
  float8 eo = gamma * sqrt(rp_max8(m2o * ninth - mo * mo, 0.0f));
  float8 eg = gamma * sqrt(rp_max8(m2g * ninth - mg * mg, 0.0f));
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
  const float8 zero = 0.0f;
  if (x0 + 8 <= ow) {
    RP_STORE_PLANE8(history_out, row, x0, rr);
    RP_STORE_PLANE8(history_out + plane, row, x0, rg);
    RP_STORE_PLANE8(history_out + 2 * plane, row, x0, rb);
    RP_STORE_PX8(hdr_out, row, x0, rp_tone_map_inverse8(rr), rp_tone_map_inverse8(rg),
                 rp_tone_map_inverse8(rb), alpha);
    RP_STORE_PX8(depth_out, row, x0, zero, zero, zero, centre_depth);
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
    RP_STORE_PX8_FIRST(depth_out, row, x0, n, zero, zero, zero, centre_depth);
    float u_[8], v_[8];
    vstore8(mvx, 0, u_);
    vstore8(mvy, 0, v_);
    for (int i = 0; i < n; ++i) velocity_out[row + x0 + i] = (float2)(u_[i], v_[i]);
  }
}
