/* Pixel spans (OpenCL C only): RP_SPAN consecutive pixels of a row handled by one work-item as
 * one vector (float16, ...), the form PoCL maps onto SIMD registers on CPUs (it does not
 * vectorize a loop over work-items that contains loops or gathers). RP_SPAN = 1 gives plain
 * scalar per-pixel code for GPUs. Used by visibility.cl and gbuffer.cl.
 *
 *   rp_spanf / rp_spani / rp_spanu   float / int / uint vector of RP_SPAN lanes
 *   RP_LANES                         (0, 1, 2, ...) as rp_spanf
 * Loads and stores take n = the number of valid lanes (a span at the right edge of the image may
 * be partial); lanes >= n are not touched in memory and load as 0. Interleaved planes (uint2,
 * float2, float4 per pixel) are (de)interleaved with constant shuffles for spans 8 and 16. */
#ifndef ROLYPOLY_COMMON_SPAN_H
#define ROLYPOLY_COMMON_SPAN_H

#ifndef RP_SPAN
#define RP_SPAN 1
#endif

#define RP_CAT_(a, b) a##b
#define RP_CAT(a, b) RP_CAT_(a, b)

#if RP_SPAN == 1
typedef float rp_spanf;
typedef int rp_spani;
typedef uint rp_spanu;
#define RP_LANES 0.0f
#elif RP_SPAN == 4
typedef float4 rp_spanf;
typedef int4 rp_spani;
typedef uint4 rp_spanu;
#define RP_LANES ((float4)(0.0f, 1.0f, 2.0f, 3.0f))
#elif RP_SPAN == 8
typedef float8 rp_spanf;
typedef int8 rp_spani;
typedef uint8 rp_spanu;
#define RP_LANES ((float8)(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f))
#elif RP_SPAN == 16
typedef float16 rp_spanf;
typedef int16 rp_spani;
typedef uint16 rp_spanu;
#define RP_LANES \
  ((float16)(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f, 8.0f, 9.0f, 10.0f, 11.0f, 12.0f, \
             13.0f, 14.0f, 15.0f))
#else
#error "RP_SPAN must be 1, 4, 8 or 16"
#endif

/* convert_int / convert_uint / convert_float of a span. */
#if RP_SPAN == 1
#define rp_span_convert_int(v) convert_int(v)
#define rp_span_convert_uint(v) convert_uint(v)
#define rp_span_convert_float(v) convert_float(v)
#else
#define rp_span_convert_int(v) RP_CAT(convert_int, RP_SPAN)(v)
#define rp_span_convert_uint(v) RP_CAT(convert_uint, RP_SPAN)(v)
#define rp_span_convert_float(v) RP_CAT(convert_float, RP_SPAN)(v)
#endif

/* True when some lane of mask m (from a comparison or logical operator) is set. */
#if RP_SPAN == 1
#define rp_span_any(m) ((m) != 0)
#else
#define rp_span_any(m) (any(m) != 0)
#endif

/* Span <-> private array of RP_SPAN scalars. */
#if RP_SPAN == 1
#define RP_SPAN_TO_ARRAY(v, arr) ((arr)[0] = (v))
#define RP_SPAN_FROM_ARRAY(arr) ((arr)[0])
#else
#define RP_SPAN_TO_ARRAY(v, arr) RP_CAT(vstore, RP_SPAN)((v), 0, (arr))
#define RP_SPAN_FROM_ARRAY(arr) RP_CAT(vload, RP_SPAN)(0, (arr))
#endif

/* Shuffle masks: interleave two spans (first half / second half of the result) and take the
 * even / odd elements of two spans. */
#if RP_SPAN == 16
#define RP_ZIP_LO ((uint16)(0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23))
#define RP_ZIP_HI ((uint16)(8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15, 31))
#define RP_ZIP2_LO ((uint16)(0, 1, 16, 17, 2, 3, 18, 19, 4, 5, 20, 21, 6, 7, 22, 23))
#define RP_ZIP2_HI ((uint16)(8, 9, 24, 25, 10, 11, 26, 27, 12, 13, 28, 29, 14, 15, 30, 31))
#define RP_EVEN ((uint16)(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30))
#define RP_ODD ((uint16)(1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31))
#define RP_SPAN_SHUFFLES 1
#elif RP_SPAN == 8
#define RP_ZIP_LO ((uint8)(0, 8, 1, 9, 2, 10, 3, 11))
#define RP_ZIP_HI ((uint8)(4, 12, 5, 13, 6, 14, 7, 15))
#define RP_ZIP2_LO ((uint8)(0, 1, 8, 9, 2, 3, 10, 11))
#define RP_ZIP2_HI ((uint8)(4, 5, 12, 13, 6, 7, 14, 15))
#define RP_EVEN ((uint8)(0, 2, 4, 6, 8, 10, 12, 14))
#define RP_ODD ((uint8)(1, 3, 5, 7, 9, 11, 13, 15))
#define RP_SPAN_SHUFFLES 1
#else
#define RP_SPAN_SHUFFLES 0
#endif

/* p[i] for lanes i < n, 0 beyond. */
inline rp_spanf rp_load_span_f(__global const float* p, int n) {
#if RP_SPAN == 1
  (void)n;
  return p[0];
#else
  if (n >= RP_SPAN) return RP_CAT(vload, RP_SPAN)(0, p);
  float lanes[RP_SPAN];
  for (int i = 0; i < RP_SPAN; ++i) lanes[i] = i < n ? p[i] : 0.0f;
  return RP_SPAN_FROM_ARRAY(lanes);
#endif
}

/* Writes the first n lanes. */
inline void rp_store_span_f(rp_spanf v, __global float* p, int n) {
#if RP_SPAN == 1
  (void)n;
  p[0] = v;
#else
  if (n >= RP_SPAN) {
    RP_CAT(vstore, RP_SPAN)(v, 0, p);
  } else {
    float lanes[RP_SPAN];
    RP_SPAN_TO_ARRAY(v, lanes);
    for (int i = 0; i < n; ++i) p[i] = lanes[i];
  }
#endif
}

/* Pairs (uint2 / float2 per pixel): a[i] = p[2i], b[i] = p[2i + 1] for lanes i < n, 0 beyond. */
#define RP_DEFINE_LOAD_PAIRS(name, scalar, span_type)                                       \
  inline void name(__global const scalar* p, int n, span_type* a, span_type* b) {           \
    if (RP_SPAN_SHUFFLES && n >= RP_SPAN) {                                                  \
      RP_LOAD_PAIRS_FULL(span_type, p, a, b);                                                \
      return;                                                                                \
    }                                                                                        \
    scalar la[RP_SPAN], lb[RP_SPAN];                                                         \
    for (int i = 0; i < RP_SPAN; ++i) {                                                      \
      la[i] = i < n ? p[2 * i] : (scalar)0;                                                  \
      lb[i] = i < n ? p[2 * i + 1] : (scalar)0;                                              \
    }                                                                                        \
    *a = RP_SPAN_FROM_ARRAY(la);                                                             \
    *b = RP_SPAN_FROM_ARRAY(lb);                                                             \
  }
#if RP_SPAN_SHUFFLES
/* The vector type is named, not taken as __typeof__(*a): NVIDIA's compiler keeps the
   pointer's address space in that type and refuses it on a local variable. */
#define RP_LOAD_PAIRS_FULL(span_type, p, a, b)                             \
  do {                                                                     \
    span_type lo = RP_CAT(vload, RP_SPAN)(0, (p));                         \
    span_type hi = RP_CAT(vload, RP_SPAN)(1, (p));                         \
    *(a) = shuffle2(lo, hi, RP_EVEN);                                      \
    *(b) = shuffle2(lo, hi, RP_ODD);                                       \
  } while (0)
#else
#define RP_LOAD_PAIRS_FULL(span_type, p, a, b) ((void)0)
#endif
RP_DEFINE_LOAD_PAIRS(rp_load_span_pairs_u, uint, rp_spanu)
RP_DEFINE_LOAD_PAIRS(rp_load_span_pairs_f, float, rp_spanf)

/* Pairs out: p[2i] = a[i], p[2i + 1] = b[i] for lanes i < n. */
#define RP_DEFINE_STORE_PAIRS(name, scalar, span_type)                          \
  inline void name(span_type a, span_type b, __global scalar* p, int n) {       \
    if (RP_SPAN_SHUFFLES && n >= RP_SPAN) {                                     \
      RP_STORE_PAIRS_FULL(a, b, p);                                             \
      return;                                                                   \
    }                                                                           \
    scalar la[RP_SPAN], lb[RP_SPAN];                                            \
    RP_SPAN_TO_ARRAY(a, la);                                                    \
    RP_SPAN_TO_ARRAY(b, lb);                                                    \
    for (int i = 0; i < n; ++i) {                                               \
      p[2 * i] = la[i];                                                         \
      p[2 * i + 1] = lb[i];                                                     \
    }                                                                           \
  }
#if RP_SPAN_SHUFFLES
#define RP_STORE_PAIRS_FULL(a, b, p)                                 \
  do {                                                               \
    RP_CAT(vstore, RP_SPAN)(shuffle2((a), (b), RP_ZIP_LO), 0, (p));  \
    RP_CAT(vstore, RP_SPAN)(shuffle2((a), (b), RP_ZIP_HI), 1, (p));  \
  } while (0)
#else
#define RP_STORE_PAIRS_FULL(a, b, p) ((void)0)
#endif
RP_DEFINE_STORE_PAIRS(rp_store_span_pairs_u, uint, rp_spanu)
RP_DEFINE_STORE_PAIRS(rp_store_span_pairs_f, float, rp_spanf)

/* The x, y, z lanes of RP_SPAN float4s in a private array: (*x)[i] = q[i].x, ... */
inline void rp_span_from_float4s(const float4* q, rp_spanf* x, rp_spanf* y, rp_spanf* z) {
#if RP_SPAN_SHUFFLES
  const float* f = (const float*)q;
  /* a_k = the k-th quarter of the interleaved xyzw stream */
  const rp_spanf a0 = RP_CAT(vload, RP_SPAN)(0, f), a1 = RP_CAT(vload, RP_SPAN)(1, f);
  const rp_spanf a2 = RP_CAT(vload, RP_SPAN)(2, f), a3 = RP_CAT(vload, RP_SPAN)(3, f);
  const rp_spanf xz_lo = shuffle2(a0, a1, RP_EVEN), yw_lo = shuffle2(a0, a1, RP_ODD);
  const rp_spanf xz_hi = shuffle2(a2, a3, RP_EVEN), yw_hi = shuffle2(a2, a3, RP_ODD);
  *x = shuffle2(xz_lo, xz_hi, RP_EVEN);
  *z = shuffle2(xz_lo, xz_hi, RP_ODD);
  *y = shuffle2(yw_lo, yw_hi, RP_EVEN);
#elif RP_SPAN == 1
  *x = q[0].x;
  *y = q[0].y;
  *z = q[0].z;
#else
  float lx[RP_SPAN], ly[RP_SPAN], lz[RP_SPAN];
  for (int i = 0; i < RP_SPAN; ++i) {
    lx[i] = q[i].x;
    ly[i] = q[i].y;
    lz[i] = q[i].z;
  }
  *x = RP_SPAN_FROM_ARRAY(lx);
  *y = RP_SPAN_FROM_ARRAY(ly);
  *z = RP_SPAN_FROM_ARRAY(lz);
#endif
}

/* Quads (float4 per pixel) in: a[i] = p[4i], b[i] = p[4i + 1], c[i] = p[4i + 2],
 * d[i] = p[4i + 3] for lanes i < n, 0 beyond. */
inline void rp_load_span_quads_f(__global const float* p, int n, rp_spanf* a, rp_spanf* b,
                                 rp_spanf* c, rp_spanf* d) {
#if RP_SPAN_SHUFFLES
  if (n >= RP_SPAN) {
    /* q_k = the k-th quarter of the interleaved abcd stream */
    const rp_spanf q0 = RP_CAT(vload, RP_SPAN)(0, p), q1 = RP_CAT(vload, RP_SPAN)(1, p);
    const rp_spanf q2 = RP_CAT(vload, RP_SPAN)(2, p), q3 = RP_CAT(vload, RP_SPAN)(3, p);
    const rp_spanf ac_lo = shuffle2(q0, q1, RP_EVEN), bd_lo = shuffle2(q0, q1, RP_ODD);
    const rp_spanf ac_hi = shuffle2(q2, q3, RP_EVEN), bd_hi = shuffle2(q2, q3, RP_ODD);
    *a = shuffle2(ac_lo, ac_hi, RP_EVEN);
    *c = shuffle2(ac_lo, ac_hi, RP_ODD);
    *b = shuffle2(bd_lo, bd_hi, RP_EVEN);
    *d = shuffle2(bd_lo, bd_hi, RP_ODD);
    return;
  }
#endif
#if RP_SPAN == 1
  (void)n;
  const float4 q = vload4(0, p);
  *a = q.x;
  *b = q.y;
  *c = q.z;
  *d = q.w;
#else
  float la[RP_SPAN], lb[RP_SPAN], lc[RP_SPAN], ld[RP_SPAN];
  for (int i = 0; i < RP_SPAN; ++i) {
    const float4 q = i < n ? vload4(i, p) : (float4)(0.0f);
    la[i] = q.x;
    lb[i] = q.y;
    lc[i] = q.z;
    ld[i] = q.w;
  }
  *a = RP_SPAN_FROM_ARRAY(la);
  *b = RP_SPAN_FROM_ARRAY(lb);
  *c = RP_SPAN_FROM_ARRAY(lc);
  *d = RP_SPAN_FROM_ARRAY(ld);
#endif
}

/* Quads (float4 per pixel): p[4i + 0..3] = (a[i], b[i], c[i], d[i]) for lanes i < n. */
inline void rp_store_span_quads_f(rp_spanf a, rp_spanf b, rp_spanf c, rp_spanf d,
                                  __global float* p, int n) {
#if RP_SPAN_SHUFFLES
  if (n >= RP_SPAN) {
    const rp_spanf ab_lo = shuffle2(a, b, RP_ZIP_LO), ab_hi = shuffle2(a, b, RP_ZIP_HI);
    const rp_spanf cd_lo = shuffle2(c, d, RP_ZIP_LO), cd_hi = shuffle2(c, d, RP_ZIP_HI);
    RP_CAT(vstore, RP_SPAN)(shuffle2(ab_lo, cd_lo, RP_ZIP2_LO), 0, p);
    RP_CAT(vstore, RP_SPAN)(shuffle2(ab_lo, cd_lo, RP_ZIP2_HI), 1, p);
    RP_CAT(vstore, RP_SPAN)(shuffle2(ab_hi, cd_hi, RP_ZIP2_LO), 2, p);
    RP_CAT(vstore, RP_SPAN)(shuffle2(ab_hi, cd_hi, RP_ZIP2_HI), 3, p);
    return;
  }
#endif
#if RP_SPAN == 1
  (void)n;
  vstore4((float4)(a, b, c, d), 0, p);
#else
  float la[RP_SPAN], lb[RP_SPAN], lc[RP_SPAN], ld[RP_SPAN];
  RP_SPAN_TO_ARRAY(a, la);
  RP_SPAN_TO_ARRAY(b, lb);
  RP_SPAN_TO_ARRAY(c, lc);
  RP_SPAN_TO_ARRAY(d, ld);
  for (int i = 0; i < n; ++i) vstore4((float4)(la[i], lb[i], lc[i], ld[i]), i, p);
#endif
}

#endif
