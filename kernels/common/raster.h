/* Triangle and sphere maths of the compute rasterizer (OpenCL C only; used by visibility.cl).
 * tests/passes/reference_raster.cpp repeats these formulas operation for operation in C++, so
 * a change here must be mirrored there (the tests compare coverage exactly).
 *
 * Edge functions are homogeneous (Olano & Greer): with vertex i in homogeneous pixel space
 * P_i = (x'_i, y'_i, w_i) (shared/raster_types.h) and a pixel centre p = (px, py, 1), the edge
 * opposite vertex i is E_i(p) = det[P_j, P_k, p] for (i, j, k) cyclic. The perspective-correct
 * barycentrics are E_i / (E_0 + E_1 + E_2), the pixel is covered when all E_i have the sign of
 * det[P_0, P_1, P_2], and this holds for vertices behind the eye too, so triangles crossing the
 * near plane need no clipping (the near plane is a per-pixel test z_ndc >= -1).
 *
 * Precision: edges are evaluated in the frame of the tile that holds the pixel (origin
 * (ox, oy), an integer pixel corner), which keeps the products small. Watertightness: two
 * triangles sharing an edge compute its coefficients from the same vertex bits with the same
 * operations in swapped order, which gives exactly negated values (no FMA contraction, see
 * the pragma), so a pixel centre is on exactly one side, and the top-left rule breaks exact
 * zeros. Limit: for a pixel centre within rounding distance (~1e-6 px) of a shared vertex the
 * decisions of the edges meeting there can disagree, so such a pixel may be covered twice or
 * not at all (odds ~1e-12 per vertex and frame). Exact inputs (pixel-aligned orthographic
 * views, power-of-two sizes) are exact, and there the top-left rule settles vertices too. */
#ifndef ROLYPOLY_COMMON_RASTER_H
#define ROLYPOLY_COMMON_RASTER_H

#include "shared/types.h"
#include "shared/raster_types.h"

/* Contracting a*b - c*d into fma() would break the exact antisymmetry the fill rule relies on. */
#pragma OPENCL FP_CONTRACT OFF

/* ((c0 x + c1 y) + c2 z) + c3 w: column-major matrix times vector, in a fixed order. */
inline float4 rp_raster_transform(const rp_mat4 m, float4 p) {
  return ((m.c[0] * p.x + m.c[1] * p.y) + m.c[2] * p.z) + m.c[3] * p.w;
}

/* One triangle set up for one tile frame. Pixel centre (px, py) has frame coordinates
 * (dx, dy) = (px - ox, py - oy); edge i is e_i = e[i].x * dx + (e[i].y * dy + e[i].z), oriented
 * so that covered pixels have every e_i >= 0. Depth: rp_raster_depth. */
typedef struct {
  float4 e[3];
  int4 top_left; /* xyz: -1 if a centre exactly on edge i (e_i == 0) is covered, else 0;
                    w: -1 if the triangle is valid (non-degenerate) in this frame, else 0 */
} RasterEdges;

/* A pixel centre exactly on an edge belongs to the triangle for which the edge is a left edge
 * (inside towards +x) or a top edge (horizontal, inside towards +y, i.e. below). The two
 * triangles sharing an edge see negated (a, b, c), so exactly one of them takes the centre. */
inline int rp_raster_top_left(float a, float b, float c) {
  return (a > 0.0f || (a == 0.0f && (b > 0.0f || (b == 0.0f && c > 0.0f)))) ? -1 : 0;
}

inline RasterEdges rp_raster_edges(float4 v0, float4 v1, float4 v2, float ox, float oy) {
  float x0 = v0.x - ox * v0.w, y0 = v0.y - oy * v0.w, w0 = v0.w;
  float x1 = v1.x - ox * v1.w, y1 = v1.y - oy * v1.w, w1 = v1.w;
  float x2 = v2.x - ox * v2.w, y2 = v2.y - oy * v2.w, w2 = v2.w;
  /* edge i = cross(P_j, P_k) */
  float a0 = y1 * w2 - w1 * y2, b0 = w1 * x2 - x1 * w2, c0 = x1 * y2 - y1 * x2;
  float a1 = y2 * w0 - w2 * y0, b1 = w2 * x0 - x2 * w0, c1 = x2 * y0 - y2 * x0;
  float a2 = y0 * w1 - w0 * y1, b2 = w0 * x1 - x0 * w1, c2 = x0 * y1 - y0 * x1;
  /* det[P0, P1, P2] = sum_i w_i c_i; its sign orients the edges */
  float det = (w0 * c0 + w1 * c1) + w2 * c2;
  float s = det < 0.0f ? -1.0f : 1.0f;
  a0 *= s; b0 *= s; c0 *= s;
  a1 *= s; b1 *= s; c1 *= s;
  a2 *= s; b2 *= s; c2 *= s;
  det *= s;
  RasterEdges r;
  int valid = (det > 0.0f && isfinite(det)) ? -1 : 0;
  if (!valid) { /* covers nothing: all edges 0 and never top-left */
    r.e[0] = r.e[1] = r.e[2] = (float4)(0.0f);
    r.top_left = (int4)(0);
    return r;
  }
  r.e[0] = (float4)(a0, b0, c0, 0.0f);
  r.e[1] = (float4)(a1, b1, c1, 0.0f);
  r.e[2] = (float4)(a2, b2, c2, 0.0f);
  r.top_left = (int4)(rp_raster_top_left(a0, b0, c0), rp_raster_top_left(a1, b1, c1),
                      rp_raster_top_left(a2, b2, c2), valid);
  return r;
}

/* z_ndc at a pixel from its edge values e_i and the vertices' clip z_i and w_i:
 *     z_ndc = (e0 z0 + e1 z1 + e2 z2) / (e0 w0 + e1 w1 + e2 w2)
 * (perspective-correct interpolation of clip z and w; the edges' common orientation sign
 * cancels). The denominator equals det[P0, P1, P2] in exact arithmetic, but dividing by the
 * pixel's own sum keeps the result a convex combination of the vertices' z_ndc even when the
 * edge values carry large rounding errors (triangles seen almost edge-on): a screen-space depth
 * plane with coefficients sum(z_i a_i) / det amplifies those errors by 1 / det (measured: up to
 * 4e-4 off a double-precision reference in tests/passes/embree_visibility_test.cpp). */
#define RP_RASTER_DEPTH(e0, e1, e2, zs, ws)                      \
  ((((e0) * (zs).x + (e1) * (zs).y) + (e2) * (zs).z) /               \
   (((e0) * (ws).x + (e1) * (ws).y) + (e2) * (ws).z))

/* Conservative binning test: false only if some edge is negative over the whole rectangle of
 * centre (cx, cy) and half extents (h, h) in the frame of `t` (an invalid frame never rejects). */
inline bool rp_raster_rect_may_overlap(const RasterEdges t, float cx, float cy, float h) {
  if (!t.top_left.w) return true;
  for (int i = 0; i < 3; ++i) {
    float4 e = t.e[i];
    float most = (e.x * cx + (e.y * cy + e.z)) + (fabs(e.x) + fabs(e.y)) * h;
    if (most < 0.0f) return false;
  }
  return true;
}

#endif
