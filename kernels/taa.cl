/* Temporal anti-aliasing resolve (SPEC 6.7). Each work-item resolves 8 consecutive pixels of a
 * row as one float8 per channel (planar in registers, common/taa.h): pixels x0 .. x0+7 with
 * x0 = x_first + 8 * get_global_id(0), row get_global_id(1). The default build takes whole
 * blocks only (x0 + 8 <= width; the range is rounded up to whole work-groups and blocks past
 * that return) and reads and writes them with straight-line vector loads and stores. The
 * RP_TAA_BORDER build resolves the one block per row that crosses the right border
 * (x_first = 8 * (width / 8), or 0 for images narrower than 8): its loads clamp each lane to
 * the last column and it writes only the pixels inside. src/passes/taa.cpp launches the
 * first over the whole blocks and the second over the border column when width % 8 != 0. No
 * atomics, no local memory: every output depends only on the inputs, so runs are bit-identical.
 *
 * Why this shape (PoCL on the CPU, DESIGN.md): per-pixel rgb code is SLP-packed into 2-wide
 * vectors inside the work-item, which stops PoCL's 8-wide vectorization across work-items;
 * explicit float8 code is vector code everywhere. The 8 pixels of a block also share their
 * horizontal neighbours (each input pixel is tone mapped 3 times instead of 5), and when the
 * 8 pixels' history taps are 8 consecutive pixels (still background, an object moving as a
 * whole) the bilinear history is 4 vector loads per channel instead of 32 scalar ones.
 * Bounds branches inside the block's loads and stores cost ~20 %, hence the two builds.
 *
 * Buffers (row-major, top row first; src/render/frame_buffers.h):
 *   hdr_in       float4  linear HDR radiance of this (jittered) frame, w passed through
 *   velocity     float2  pixels, this frame minus previous (+y down), unjittered
 *   depth        float   the visibility buffer's depth, z_ndc * 0.5 + 0.5 (1 where nothing):
 *                        ordered as the view depth, so it picks the nearest surface below (a
 *                        plane of 4 bytes a pixel instead of the GBuffer's 16-byte normal_depth)
 *   history_in   float   previous resolved frame, TONE-MAPPED rgb T(x) = x / (1 + x), as three
 *                        planes of width * height floats: all R, then all G, then all B
 *   history_out  float   this resolved frame, same layout (next frame's history_in)
 *   hdr_out      float4  this resolved frame back in linear HDR: T^-1(history rgb), w of hdr_in
 *
 * Per pixel, on tone-mapped values (common/colour.h):
 *   1. Current colour c = T(hdr_in) at the pixel. The jittered samples are what TAA averages:
 *      pixel p of frame k saw the scene at p - jitter_k, so accumulating them integrates the
 *      pixel footprint. With unjitter = 1, c is instead hdr_in sampled bilinearly at the pixel
 *      centre + jitter (where the unjittered pixel centre landed; the jittered view_proj moves
 *      points by +jitter pixels) - a steadier but softer image.
 *   2. 5-tap cross (centre, left, right, up, down; clamped at borders) in YCoCg: mean m and
 *      standard deviation s; box = m +- gamma * s.
 *   3. Velocity of the nearest surface in the cross (smallest depth; the centre wins ties), so
 *      the silhouettes of moving objects reproject with the object, not the background.
 *   4. History at previous position = pixel centre - velocity, bilinear (clamp to edge). Outside
 *      [0, width] x [0, height], or when history_valid = 0 (reset / resize), history = c.
 *   5. History clipped toward the box centre (rp_taa_clip in common/taa.h), then
 *      out = clamp(hist * history_weight + c * (1 - history_weight), 0, 1).
 * tests/passes/taa_reference.cpp is the same algorithm in plain C++, one pixel at a time.
 */
#include "shared/types.h"
#include "shared/pass_params.h"
#include "common/colour.h"
#include "common/sampling.h"
#include "common/taa.h"

#ifdef RP_TAA_BORDER /* the block crossing the right border: w - x0 < 8 pixels */
#define RP_TAA_LOAD(img, row, R, G, B, A) RP_LOAD_PX8_CLAMPED(img, row, x0, w, R, G, B, A)
#define RP_TAA_LOAD2(img, row, X, Y) RP_LOAD_PX8_FLOAT2_CLAMPED(img, row, x0, w, X, Y)
#define RP_TAA_LOAD1(plane, row, V) RP_LOAD_PLANE8_CLAMPED(plane, row, x0, w, V)
#define RP_TAA_STORE(img, R, G, B, A) RP_STORE_PX8_FIRST(img, row, x0, w - x0, R, G, B, A)
#define RP_TAA_STORE_PLANE(plane, V) RP_STORE_PLANE8_FIRST(plane, row, x0, w - x0, V)
#else
#define RP_TAA_LOAD(img, row, R, G, B, A) RP_LOAD_PX8(img, row, x0, R, G, B, A)
#define RP_TAA_LOAD2(img, row, X, Y) RP_LOAD_PX8_FLOAT2(img, row, x0, X, Y)
#define RP_TAA_LOAD1(plane, row, V) RP_LOAD_PLANE8(plane, row, x0, V)
#define RP_TAA_STORE(img, R, G, B, A) RP_STORE_PX8(img, row, x0, R, G, B, A)
#define RP_TAA_STORE_PLANE(plane, V) RP_STORE_PLANE8(plane, row, x0, V)
#endif

/* Unjittered current sample of lane k: bilinear in HDR at the pixel centre + jitter. */
#define RP_TAA_UNJITTER_LANE(k)                                                            \
  rp_plane_bilinear_clamp(hdr_in, w, h, (float2)(cx.s##k + jitter_x, cy + jitter_y))

/* Adds a neighbour row's tone-mapped YCoCg (as offsets from the centre pixel's, see step 2) to
 * the cross sums and lets it compete for the nearest depth (strict <: earlier candidates win
 * ties). */
#define RP_TAA_ADD_ROW(row_start)                                                          \
  do {                                                                                     \
    float8 r_, g_, b_, a_, d_, vx_, vy_;                                                   \
    RP_TAA_LOAD(hdr_in, row_start, r_, g_, b_, a_);                                        \
    const rp_ycocg8 c_ =                                                                   \
        rp_rgb_to_ycocg8(rp_tone_map8(r_), rp_tone_map8(g_), rp_tone_map8(b_));            \
    const float8 dy_ = c_.y - c0.y, dco_ = c_.co - c0.co, dcg_ = c_.cg - c0.cg;            \
    sum_y += dy_;                                                                          \
    sum_co += dco_;                                                                        \
    sum_cg += dcg_;                                                                        \
    sq_y += dy_ * dy_;                                                                     \
    sq_co += dco_ * dco_;                                                                  \
    sq_cg += dcg_ * dcg_;                                                                  \
    RP_TAA_LOAD1(depth, row_start, d_);                                                    \
    RP_TAA_LOAD2(velocity, row_start, vx_, vy_);                                           \
    const int8 closer_ = d_ < nd;                                                          \
    nd = select(nd, d_, closer_);                                                          \
    vx = select(vx, vx_, closer_);                                                         \
    vy = select(vy, vy_, closer_);                                                         \
  } while (0)

__kernel void taa_resolve(__global const float4* restrict hdr_in,
                          __global const float2* restrict velocity,
                          __global const float* restrict depth,
                          __global const float* restrict history_in,
                          __global float* restrict history_out,
                          __global float4* restrict hdr_out, const TaaParams params) {
  const uint width = params.render_width, height = params.render_height;
  const float jitter_x = params.jitter_x, jitter_y = params.jitter_y; /* this frame's, pixels */
  const float history_weight = params.history_weight, gamma = params.gamma;
  const uint history_valid = params.history_valid, unjitter = params.unjitter;
  const uint x_first = params.x_first;
  const int w = (int)width, h = (int)height;
  const int x0 = (int)x_first + 8 * (int)get_global_id(0), y = (int)get_global_id(1);
#ifdef RP_TAA_BORDER
  if (x0 >= w || y >= h) return;
#else
  if (x0 + 8 > w || y >= h) return;
#endif
  const int row = y * w;
  const int xl = max(x0 - 1, 0), xr = min(x0 + 8, w - 1); /* the block's outer neighbours */
  const float8 cx = convert_float8((int8)(0, 1, 2, 3, 4, 5, 6, 7) + x0) + 0.5f; /* centres */
  const float cy = (float)y + 0.5f;

  /* The pixels themselves: current colour (step 1), centre of the cross, first depth
   * candidate. */
  float8 cr, cg, cb, alpha, nd, vx, vy;
  RP_TAA_LOAD(hdr_in, row, cr, cg, cb, alpha);
  cr = rp_tone_map8(cr);
  cg = rp_tone_map8(cg);
  cb = rp_tone_map8(cb);
  RP_TAA_LOAD1(depth, row, nd);
  RP_TAA_LOAD2(velocity, row, vx, vy);

  /* 2. Cross statistics in YCoCg. Left / right neighbours are the row shifted by one lane,
   * with the block's outer pixels (tone mapped together as one float8) in the end lanes. The
   * sums are of offsets d = v - centre: mean = centre + E[d], variance = E[d^2] - E[d]^2. Same
   * maths as E[v^2] - E[v]^2, but without its cancellation when the neighbours are alike
   * (tests/passes/taa_test.cpp: worst error against the double-precision reference 8e-6 ->
   * 4e-7). */
  const rp_ycocg8 c0 = rp_rgb_to_ycocg8(cr, cg, cb);
  const float8 edges = rp_tone_map8((float8)(hdr_in[row + xl], hdr_in[row + xr]));
  const float3 yl = rp_rgb_to_ycocg(edges.s012), yr = rp_rgb_to_ycocg(edges.s456);
  const float8 ly = rp_shift_right8(c0.y, yl.x) - c0.y;
  const float8 lo = rp_shift_right8(c0.co, yl.y) - c0.co;
  const float8 lg = rp_shift_right8(c0.cg, yl.z) - c0.cg;
  const float8 ry = rp_shift_left8(c0.y, yr.x) - c0.y;
  const float8 ro = rp_shift_left8(c0.co, yr.y) - c0.co;
  const float8 rg = rp_shift_left8(c0.cg, yr.z) - c0.cg;
  float8 sum_y = ly + ry, sum_co = lo + ro, sum_cg = lg + rg;
  float8 sq_y = ly * ly + ry * ry, sq_co = lo * lo + ro * ro, sq_cg = lg * lg + rg * rg;

  /* 3. Nearest surface in the cross (order centre, left, right, up, down; strict <, so the
   * centre wins ties) and its velocity. */
  {
    const float2 vl = velocity[row + xl], vr = velocity[row + xr];
    const float8 dl = rp_shift_right8(nd, depth[row + xl]);
    const float8 dr = rp_shift_left8(nd, depth[row + xr]);
    const float8 vxl = rp_shift_right8(vx, vl.x), vyl = rp_shift_right8(vy, vl.y);
    const float8 vxr = rp_shift_left8(vx, vr.x), vyr = rp_shift_left8(vy, vr.y);
    int8 closer = dl < nd;
    nd = select(nd, dl, closer);
    vx = select(vx, vxl, closer);
    vy = select(vy, vyl, closer);
    closer = dr < nd;
    nd = select(nd, dr, closer);
    vx = select(vx, vxr, closer);
    vy = select(vy, vyr, closer);
  }
  RP_TAA_ADD_ROW(max(y - 1, 0) * w);
  RP_TAA_ADD_ROW(min(y + 1, h - 1) * w);

  if (unjitter != 0u) {
    const float4 s0 = RP_TAA_UNJITTER_LANE(0), s1 = RP_TAA_UNJITTER_LANE(1);
    const float4 s2 = RP_TAA_UNJITTER_LANE(2), s3 = RP_TAA_UNJITTER_LANE(3);
    const float4 s4 = RP_TAA_UNJITTER_LANE(4), s5 = RP_TAA_UNJITTER_LANE(5);
    const float4 s6 = RP_TAA_UNJITTER_LANE(6), s7 = RP_TAA_UNJITTER_LANE(7);
    float8 unused;
    RP_DEINTERLEAVE8((float16)(s0, s1, s2, s3), (float16)(s4, s5, s6, s7), cr, cg, cb, unused);
    cr = rp_tone_map8(cr);
    cg = rp_tone_map8(cg);
    cb = rp_tone_map8(cb);
  }

  /* 4. Reprojected history. */
  float8 rr = cr, rg_ = cg, rb = cb;
  const int plane = w * h; /* floats per history plane */
  if (history_valid != 0u) {
    const float8 oy = sum_y * 0.2f, oo = sum_co * 0.2f, og = sum_cg * 0.2f; /* E[d] */
    const float8 my = c0.y + oy, mo = c0.co + oo, mg = c0.cg + og;             /* means */
    const float8 ey =
        rp_max8(gamma * sqrt(rp_max8(sq_y * 0.2f - oy * oy, 0.0f)), RP_TAA_MIN_EXTENT);
    const float8 eo =
        rp_max8(gamma * sqrt(rp_max8(sq_co * 0.2f - oo * oo, 0.0f)), RP_TAA_MIN_EXTENT);
    const float8 eg =
        rp_max8(gamma * sqrt(rp_max8(sq_cg * 0.2f - og * og, 0.0f)), RP_TAA_MIN_EXTENT);

    const float8 px = cx - vx, py = cy - vy;
    const int8 on_screen = (px >= 0.0f) & (py >= 0.0f) & (px <= (float)w) & (py <= (float)h);
    /* (a NaN position becomes 0 here: the taps stay inside the image) */
    const float8 hx = rp_clamp8(px - 0.5f, 0.0f, (float)(w - 1));
    const float8 hy = rp_clamp8(py - 0.5f, 0.0f, (float)(h - 1));
    const int8 ix0 = convert_int8(hx), iy0 = convert_int8(hy); /* >= 0: truncation = floor */
    const float8 fx = hx - convert_float8(ix0), fy = hy - convert_float8(iy0);
    /* (vector bounds, not min(int8, int): oclgrind 21.10 evaluates that form wrongly) */
    const int8 ix1 = min(ix0 + 1, (int8)(w - 1)), iy1 = min(iy0 + 1, (int8)(h - 1));
    const int8 ia = iy0 * w + ix0, ib = iy0 * w + ix1, ic = iy1 * w + ix0, id = iy1 * w + ix1;
    float8 hr, hg, hb;
    RP_TAA_HISTORY8(history_in, plane, w, hr, hg, hb);
    const rp_ycocg8 hc = rp_rgb_to_ycocg8(hr, hg, hb);

    /* 5. Clip toward the box centre (rp_taa_clip, lane by lane), back to rgb, blend. */
    float8 qy, qo, qg;
    RP_TAA_CLIP8(hc, my, mo, mg, ey, eo, eg, qy, qo, qg);
    const float8 t = qy - qg;
    const float f = history_weight, g = 1.0f - history_weight;
    rr = select(cr, rp_clamp8((t + qo) * f + cr * g, 0.0f, 1.0f), on_screen);
    rg_ = select(cg, rp_clamp8((qy + qg) * f + cg * g, 0.0f, 1.0f), on_screen);
    rb = select(cb, rp_clamp8((t - qo) * f + cb * g, 0.0f, 1.0f), on_screen);
  }
  RP_TAA_STORE_PLANE(history_out, rr);
  RP_TAA_STORE_PLANE(history_out + plane, rg_);
  RP_TAA_STORE_PLANE(history_out + 2 * plane, rb);
  RP_TAA_STORE(hdr_out, rp_tone_map_inverse8(rr), rp_tone_map_inverse8(rg_),
               rp_tone_map_inverse8(rb), alpha);
}
