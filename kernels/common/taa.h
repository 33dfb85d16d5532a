/* TAA helpers (OpenCL C only; SPEC 6.7): YCoCg colour space, the history clip, and the
 * 8-pixels-per-work-item (float8, planar) forms kernels/taa.cl uses.
 * tests/passes/taa_test.cpp runs the scalar helpers through a probe kernel against C++
 * references; the float8 forms are checked through the whole pass against the same reference.
 *
 * YCoCg (exactly invertible linear transform, luma Y and two chroma axes):
 *   Y  =  R/4 + G/2 + B/4      R = Y - Cg + Co
 *   Co =  R/2       - B/2      G = Y + Cg
 *   Cg = -R/4 + G/2 - B/4      B = Y - Cg - Co
 * The neighbourhood box is tighter around real colour distributions in YCoCg than in RGB
 * (luma and chroma vary independently), so clipping rejects less valid history.
 */
#ifndef ROLYPOLY_COMMON_TAA_H
#define ROLYPOLY_COMMON_TAA_H

inline float3 rp_rgb_to_ycocg(float3 c) {
  return (float3)(0.25f * c.x + 0.5f * c.y + 0.25f * c.z, 0.5f * c.x - 0.5f * c.z,
                  -0.25f * c.x + 0.5f * c.y - 0.25f * c.z);
}

inline float3 rp_ycocg_to_rgb(float3 c) {
  const float t = c.x - c.z;
  return (float3)(t + c.y, c.x + c.z, t - c.y);
}

/* Smallest box half-extent per channel: keeps the division finite where the neighbourhood is
 * flat in a channel (stddev 0); any history that differs there then clips onto the centre. */
#define RP_TAA_MIN_EXTENT 1.0e-6f

/* Clips `q` to the axis-aligned box centre +- extent (extent >= 0 per channel) along the line
 * from q to the box centre: a point inside (or on) the box is returned unchanged (bit-exact);
 * a point outside moves to where that line crosses the box surface, i.e.
 *   centre + (q - centre) / max_c(|q_c - centre_c| / extent_c).
 * Unlike a per-channel clamp this keeps the history's hue direction relative to the centre. */
inline float3 rp_taa_clip(float3 q, float3 centre, float3 extent) {
  const float3 v = q - centre;
  const float3 e = fmax(extent, (float3)(RP_TAA_MIN_EXTENT));
  const float3 a = fabs(v) / e;
  const float m = fmax(a.x, fmax(a.y, a.z));
  return m > 1.0f ? centre + v / m : q;
}

/* Bilinear history of lane k in plane P: scalar taps at the int8 indices ia, ib (row iy0,
 * columns ix0 and ix0 + 1), ic, id (row iy1), weights fx, fy (float8); the caller names them so. */
#define RP_TAA_HISTORY_LANE(P, k)                                                          \
  mix(mix(P[ia.s##k], P[ib.s##k], fx.s##k), mix(P[ic.s##k], P[id.s##k], fx.s##k), fy.s##k)
#define RP_TAA_HISTORY_LANES(P)                                                            \
  (float8)(RP_TAA_HISTORY_LANE(P, 0), RP_TAA_HISTORY_LANE(P, 1), RP_TAA_HISTORY_LANE(P, 2), \
           RP_TAA_HISTORY_LANE(P, 3), RP_TAA_HISTORY_LANE(P, 4), RP_TAA_HISTORY_LANE(P, 5), \
           RP_TAA_HISTORY_LANE(P, 6), RP_TAA_HISTORY_LANE(P, 7))
/* The same when the lanes' taps are consecutive pixels (ia = ia.s0 + lane, ib = ia + 1,
 * ic = ia + one row, id = ic + 1): four vector loads per plane. */
#define RP_TAA_HISTORY_ROWS(P)                                                             \
  mix(mix(vload8(0, P + ia.s0), vload8(0, P + ia.s0 + 1), fx),                             \
      mix(vload8(0, P + ic.s0), vload8(0, P + ic.s0 + 1), fx), fy)
/* The three tone-mapped history planes (R, G, B, `plane` floats apart from HISTORY) of eight
 * lanes of an image WIDTH wide into HR, HG, HB: four vector loads per plane where the lanes'
 * taps are consecutive pixels of one row (a still view, an object moving as a whole) and not
 * at the right border, scalar taps otherwise. Needs ix0, iy0 and the names above. */
#define RP_TAA_HISTORY8(HISTORY, PLANE, WIDTH, HR, HG, HB)                                 \
  do {                                                                                   \
    __global const float* r_ = (HISTORY);                                                \
    __global const float* g_ = (HISTORY) + (PLANE);                                      \
    __global const float* b_ = (HISTORY) + 2 * (PLANE);                                  \
    if (all(ix0 == ix0.s0 + (int8)(0, 1, 2, 3, 4, 5, 6, 7)) && all(iy0 == iy0.s0) &&     \
        ix0.s0 + 8 <= (WIDTH) - 1) {                                                     \
      HR = RP_TAA_HISTORY_ROWS(r_);                                                      \
      HG = RP_TAA_HISTORY_ROWS(g_);                                                      \
      HB = RP_TAA_HISTORY_ROWS(b_);                                                      \
    } else {                                                                             \
      HR = RP_TAA_HISTORY_LANES(r_);                                                     \
      HG = RP_TAA_HISTORY_LANES(g_);                                                     \
      HB = RP_TAA_HISTORY_LANES(b_);                                                     \
    }                                                                                    \
  } while (0)

/* rp_taa_clip for eight lanes, written as a macro (PoCL does not inline helpers that return
 * structs): the history HC (rp_ycocg8) moved toward the box centre (MY, MO, MG) onto the surface
 * of the box of half-extents (EY, EO, EG) where it lies outside; the result in QY, QO, QG. */
#define RP_TAA_CLIP8(HC, MY, MO, MG, EY, EO, EG, QY, QO, QG)                              \
  do {                                                                                   \
    const float8 dy_ = (HC).y - (MY), dco_ = (HC).co - (MO), dcg_ = (HC).cg - (MG);      \
    const float8 ay_ = fabs(dy_) / (EY), ao_ = fabs(dco_) / (EO), ag_ = fabs(dcg_) / (EG); \
    const float8 m1_ = select(ao_, ay_, ay_ > ao_), m_ = select(ag_, m1_, m1_ > ag_);    \
    const int8 outside_ = m_ > 1.0f;                                                     \
    const float8 s_ = 1.0f / m_;                                                         \
    QY = select((HC).y, (MY) + dy_ * s_, outside_);                                      \
    QO = select((HC).co, (MO) + dco_ * s_, outside_);                                    \
    QG = select((HC).cg, (MG) + dcg_ * s_, outside_);                                    \
  } while (0)

/* ---- Eight pixels at once: one float8 per channel (lane k = pixel x0 + k of a row) ----------
 * PoCL vectorizes straight-line scalar code across work-items, but per-pixel rgb code gets
 * SLP-packed into 2-wide vectors inside the work-item first, which blocks that (measured on
 * this kernel). Explicit float8 code is vector code on every device. Loads and stores are
 * macros: PoCL did not inline a loader function with two paths and paid for the call and its
 * struct-in-memory return (~25 % of the kernel), and straight-line loads and stores without a
 * per-access bounds branch let the register allocator keep more in registers (~20 %), so the
 * whole-block and the border forms are separate macros (kernels/taa.cl builds one or the
 * other). */

/* RGBA of 8 consecutive pixels in two float16 (4 pixels each) -> planes R, G, B, A. */
#define RP_DEINTERLEAVE8(P0, P1, R, G, B, A)                                              \
  do {                                                                                   \
    R = (float8)((P0).s048c, (P1).s048c);                                                \
    G = (float8)((P0).s159d, (P1).s159d);                                                \
    B = (float8)((P0).s26ae, (P1).s26ae);                                                \
    A = (float8)((P0).s37bf, (P1).s37bf);                                                \
  } while (0)

/* Pixels x0 .. x0+7 of the row starting at element `row` of a float4 image, as planes R, G, B,
 * A (float8 lvalues). All 8 pixels must exist (x0 + 8 <= width). */
#define RP_LOAD_PX8(img, row, x0, R, G, B, A)                                             \
  do {                                                                                   \
    __global const float* f_ = (__global const float*)((img) + (row) + (x0));           \
    const float16 p0_ = vload16(0, f_), p1_ = vload16(1, f_);                            \
    RP_DEINTERLEAVE8(p0_, p1_, R, G, B, A);                                              \
  } while (0)

/* The same for a block that would cross the right border (width w): lanes past the last column
 * repeat it (clamp to edge), so nothing outside the image is read. */
#define RP_LOAD_PX8_CLAMPED(img, row, x0, w, R, G, B, A)                                  \
  do {                                                                                   \
    float t_[32];                                                                        \
    for (int k_ = 0; k_ < 8; ++k_) vstore4((img)[(row) + min((x0) + k_, (w) - 1)], k_, t_); \
    const float16 p0_ = vload16(0, t_), p1_ = vload16(1, t_);                            \
    RP_DEINTERLEAVE8(p0_, p1_, R, G, B, A);                                              \
  } while (0)

/* Pixels x0 .. x0+7 of a float2 image row as planes X, Y (all 8 must exist). */
#define RP_LOAD_PX8_FLOAT2(img, row, x0, X, Y)                                            \
  do {                                                                                   \
    const float16 p_ = vload16(0, (__global const float*)((img) + (row) + (x0)));       \
    X = p_.even;                                                                         \
    Y = p_.odd;                                                                          \
  } while (0)

#define RP_LOAD_PX8_FLOAT2_CLAMPED(img, row, x0, w, X, Y)                                 \
  do {                                                                                   \
    float t_[16];                                                                        \
    for (int k_ = 0; k_ < 8; ++k_) vstore2((img)[(row) + min((x0) + k_, (w) - 1)], k_, t_); \
    const float16 p_ = vload16(0, t_);                                                   \
    X = p_.even;                                                                         \
    Y = p_.odd;                                                                          \
  } while (0)

/* Pixels x0 .. x0+7 of a float plane's row (all 8 must exist), and the same for a block that
 * would cross the right border (lanes past the last column repeat it). */
#define RP_LOAD_PLANE8(plane, row, x0, V) V = vload8(0, (plane) + (row) + (x0))
#define RP_LOAD_PLANE8_CLAMPED(plane, row, x0, w, V)                                       \
  do {                                                                                   \
    float t_[8];                                                                         \
    for (int k_ = 0; k_ < 8; ++k_) t_[k_] = (plane)[(row) + min((x0) + k_, (w) - 1)];   \
    V = vload8(0, t_);                                                                   \
  } while (0)

/* Writes planes R, G, B, A to pixels x0 .. x0+7 of a float4 image row. */
#define RP_STORE_PX8(img, row, x0, R, G, B, A)                                            \
  do {                                                                                   \
    const float8 r_ = (R), g_ = (G), b_ = (B), a_ = (A);                                 \
    __global float* f_ = (__global float*)((img) + (row) + (x0));                       \
    vstore16((float16)(r_.s0, g_.s0, b_.s0, a_.s0, r_.s1, g_.s1, b_.s1, a_.s1, r_.s2, g_.s2, \
                       b_.s2, a_.s2, r_.s3, g_.s3, b_.s3, a_.s3),                        \
             0, f_);                                                                     \
    vstore16((float16)(r_.s4, g_.s4, b_.s4, a_.s4, r_.s5, g_.s5, b_.s5, a_.s5, r_.s6, g_.s6, \
                       b_.s6, a_.s6, r_.s7, g_.s7, b_.s7, a_.s7),                        \
             1, f_);                                                                     \
  } while (0)

/* The same for the first n lanes only (0 < n < 8: a block that ends at the image border). */
#define RP_STORE_PX8_FIRST(img, row, x0, n, R, G, B, A)                                   \
  do {                                                                                   \
    float r_[8], g_[8], b_[8], a_[8];                                                    \
    vstore8((R), 0, r_);                                                                 \
    vstore8((G), 0, g_);                                                                 \
    vstore8((B), 0, b_);                                                                 \
    vstore8((A), 0, a_);                                                                 \
    for (int k_ = 0; k_ < (n); ++k_)                                                     \
      (img)[(row) + (x0) + k_] = (float4)(r_[k_], g_[k_], b_[k_], a_[k_]);               \
  } while (0)

/* Writes one float8 to x0 .. x0+7 of a float image row / only its first n lanes. */
#define RP_STORE_PLANE8(plane, row, x0, V) vstore8((V), 0, (plane) + (row) + (x0))
#define RP_STORE_PLANE8_FIRST(plane, row, x0, n, V)                                       \
  do {                                                                                   \
    float t_[8];                                                                         \
    vstore8((V), 0, t_);                                                                 \
    for (int k_ = 0; k_ < (n); ++k_) (plane)[(row) + (x0) + k_] = t_[k_];                \
  } while (0)

/* Lane-wise max / min / clamp to [lo, hi] as compare + select: one instruction each on x86,
 * where OpenCL's fmax / fmin / clamp must also ignore a NaN argument (three). A NaN `a` gives
 * the bound, as fmax(NaN, b) does; bounds are never NaN here. */
inline float8 rp_max8(float8 a, float b) { return select((float8)(b), a, a > b); }
inline float8 rp_min8(float8 a, float b) { return select((float8)(b), a, a < b); }
inline float8 rp_clamp8(float8 a, float lo, float hi) { return rp_min8(rp_max8(a, lo), hi); }

/* YCoCg of 8 pixels. */
typedef struct {
  float8 y, co, cg;
} rp_ycocg8;

inline rp_ycocg8 rp_rgb_to_ycocg8(float8 r, float8 g, float8 b) {
  rp_ycocg8 c;
  c.y = 0.25f * r + 0.5f * g + 0.25f * b;
  c.co = 0.5f * r - 0.5f * b;
  c.cg = -0.25f * r + 0.5f * g - 0.25f * b;
  return c;
}

/* Lane k -> the pixel to its left / right: lane 0's left is `left`, lane 7's right `right`. */
inline float8 rp_shift_right8(float8 v, float left) { return (float8)(left, v.s012, v.s3456); }
inline float8 rp_shift_left8(float8 v, float right) { return (float8)(v.s1234, v.s567, right); }

#endif
