/* Compute rasterizer: mesh triangles + analytic spheres -> visibility buffer (or, with
 * -DRP_DEPTH_ONLY=1, the shadow map's depth). Host side: src/passes/visibility.cpp.
 *
 * Per view and frame, in order:
 *   visibility_clear    zero the per-tile counts
 *   visibility_setup    one work-item per RP_SPAN triangle items: transform, cull, pixel
 *                       bounds, edges in the bounds' frame (vector code across the lanes)
 *   visibility_setup_spheres  one work-item per sphere item: pixel bounds
 *   visibility_count    one work-item per item: count the tiles it may touch
 *   visibility_scan     one work-group: exclusive scan of the counts -> tile list ranges
 *   visibility_bin      the same walk as count, now writing item indices into the tile lists
 *   visibility_raster   one work-group per RP_RASTER_TILE^2 tile: nearest surface per pixel,
 *                       written once: depth, and (camera) ids and barycentrics
 *
 * Tile list layout: counts/start/cursor hold 2 * tile_count entries, tile t's triangles at
 * [t], its spheres at [tile_count + t]; the scan makes each range contiguous in one list. The
 * list has RasterView.list_capacity entries, sized by the host from earlier frames' totals (the
 * scan's total is read back asynchronously, so no view waits for it): entries past the capacity
 * are dropped by visibility_bin, and a tile whose range was cut rasterizes every item instead
 * (same result, slower; the host grows the list for the next frame).
 *
 * RasterView is passed by value (a kernel argument): nothing is written to the device per view.
 *
 * Determinism: a pixel keeps the smallest (z_ndc, item) pair. Items are ordered by (instance,
 * primitive) with spheres after all triangles, matching the id order (RP_ID_SPHERE_BIT is the
 * top bit), so ties resolve by ids and the order of a tile's list (set by atomics) never
 * matters. Counts use integer atomics only. */

#include "shared/types.h"
#include "shared/raster_types.h"
#include "common/raster.h"
#include "common/span.h"
#include "common/span_texture.h"
#include "common/alpha_mask.h"

#ifndef RP_DEPTH_ONLY
#define RP_DEPTH_ONLY 0
#endif
#ifndef RP_TILE_LAYOUT
#define RP_TILE_LAYOUT 0
#endif

/* Pixels per work-item along x in the raster kernel (RP_SPAN, common/span.h): 1 for GPUs; 8 or
 * 16 on CPUs, where the float8/float16 code maps onto SIMD registers. Results are bit-identical
 * for every span. */
#define RP_TILE RP_RASTER_TILE
#define RP_GROUP_W (RP_TILE / RP_SPAN)
#define RP_GROUP_SIZE (RP_GROUP_W * RP_TILE)
/* Items set up per local-memory batch (each work-item sets up one or more). */
#define RP_BATCH (RP_GROUP_SIZE > 64 ? RP_GROUP_SIZE : 64)
/* Binning: half extent (pixels) of the tile rectangle tested against the edges: the pixel
 * centres span RP_TILE - 1, plus a margin that absorbs rounding differences between frames. */
#define RP_BIN_HALF_EXTENT (0.5f * RP_TILE + 1.0f)
#define RP_SCAN_GROUP 128
#define RP_ITEM_GROUP 64
#define RP_SETUP_GROUP 16 /* work-items (RP_SPAN triangles each) per visibility_setup group */
/* Pixels by which a triangle's bounds are widened before testing whether they hold a pixel
 * centre (visibility_setup): far above the rounding of x / w at any view size. */
#define RP_CENTRE_MARGIN (1.0f / 16.0f)

/* Pixel bounds (x0, y0, x1, y1 inclusive) from bounds of the covered pixel positions, with a
 * one-pixel margin, clamped to the view; x0 > x1 when nothing is on screen. */
inline int4 rp_pixel_bounds(float2 lo, float2 hi, uint width, uint height) {
  float fw = (float)width, fh = (float)height;
  lo = clamp(lo, (float2)(-2.0f), (float2)(fw + 2.0f, fh + 2.0f));
  hi = clamp(hi, (float2)(-2.0f), (float2)(fw + 2.0f, fh + 2.0f));
  int4 b = (int4)((int)floor(lo.x) - 1, (int)floor(lo.y) - 1, (int)floor(hi.x) + 1,
                  (int)floor(hi.y) + 1);
  b = clamp(b, (int4)(0), (int4)((int)width - 1, (int)height - 1, (int)width - 1,
                                  (int)height - 1));
  if (lo.x > hi.x || lo.y > hi.y || hi.x < 0.0f || hi.y < 0.0f || lo.x > fw || lo.y > fh)
    b = (int4)(0, 0, -1, -1);
  return b;
}

#define RP_EMPTY_BOUNDS ((int4)(0, 0, -1, -1))

/* Clip-space (x, y, z, w) -> homogeneous pixel space (x', y', z, w), see RasterTriangle. */
inline float4 rp_to_pixel_space(float4 clip, float half_w, float half_h) {
  return (float4)((clip.x + clip.w) * half_w, (clip.w - clip.y) * half_h, clip.z, clip.w);
}

/* True when all points are outside one frustum plane (then the primitive covers nothing). */
inline bool rp_outside_frustum(const float4* c, int n) {
  int out[6] = {1, 1, 1, 1, 1, 1};
  for (int i = 0; i < n; ++i) {
    out[0] &= c[i].x > c[i].w;
    out[1] &= c[i].x < -c[i].w;
    out[2] &= c[i].y > c[i].w;
    out[3] &= c[i].y < -c[i].w;
    out[4] &= c[i].z > c[i].w;
    out[5] &= c[i].z < -c[i].w;
  }
  return (out[0] | out[1] | out[2] | out[3] | out[4] | out[5]) != 0;
}

/* Pixel bounds of the part of a triangle in front of the near plane (z >= -w): bounds of the
 * near-clipped polygon's projected vertices (Sutherland-Hodgman against one plane). */
inline int4 rp_triangle_bounds(const float4* v, uint width, uint height) {
  float2 lo = (float2)(INFINITY), hi = (float2)(-INFINITY);
  bool unbounded = false;
  for (int i = 0; i < 3; ++i) {
    float4 a = v[i], b = v[(i + 1) % 3];
    float da = a.z + a.w, db = b.z + b.w;
    float4 p[2];
    int n = 0;
    if (da >= 0.0f) p[n++] = a;
    if ((da >= 0.0f) != (db >= 0.0f)) p[n++] = a + (b - a) * (da / (da - db));
    for (int k = 0; k < n; ++k) {
      if (p[k].w > 0.0f) {
        float2 q = p[k].xy / p[k].w;
        lo = fmin(lo, q);
        hi = fmax(hi, q);
      } else {
        unbounded = true; /* only for unusual projections: fall back to the whole view */
      }
    }
  }
  if (unbounded) return (int4)(0, 0, (int)width - 1, (int)height - 1);
  return rp_pixel_bounds(lo, hi, width, height);
}

/* Pixel bounds of a sphere: the projected corners of its bounding cube (all in front of the
 * eye), else the whole view. */
inline int4 rp_sphere_bounds(const rp_mat4 vp, float4 center_radius, float half_w, float half_h,
                             uint width, uint height) {
  float4 corners[8];
  float r = center_radius.w;
  for (int i = 0; i < 8; ++i) {
    float4 p = (float4)(center_radius.x + ((i & 1) ? r : -r), center_radius.y + ((i & 2) ? r : -r),
                        center_radius.z + ((i & 4) ? r : -r), 1.0f);
    corners[i] = rp_raster_transform(vp, p);
  }
  if (rp_outside_frustum(corners, 8)) return RP_EMPTY_BOUNDS;
  float2 lo = (float2)(INFINITY), hi = (float2)(-INFINITY);
  for (int i = 0; i < 8; ++i) {
    if (!(corners[i].w > 0.0f)) return (int4)(0, 0, (int)width - 1, (int)height - 1);
    float4 q = rp_to_pixel_space(corners[i], half_w, half_h);
    lo = fmin(lo, q.xy / q.w);
    hi = fmax(hi, q.xy / q.w);
  }
  return rp_pixel_bounds(lo, hi, width, height);
}

/* Edges that reject nothing (invalid frame): the tile walk of a sphere. */
inline RasterEdges rp_raster_no_edges(void) {
  RasterEdges r;
  r.e[0] = r.e[1] = r.e[2] = (float4)(0.0f);
  r.top_left = (int4)(0);
  return r;
}

/* Visits every tile an item may touch: the tiles of its bounds, for triangles only those the
 * edge test (`edges`: the triangle set up in the frame of its bounds' first pixel) cannot
 * reject. Counting and binning both use it with the same stored edges: same tiles both times. */
#define RP_FOR_ITEM_TILES(view, bounds, is_triangle, edges, BODY)                                \
  do {                                                                                           \
    if ((bounds).x <= (bounds).z && (bounds).y <= (bounds).w) {                                  \
      float fox = (float)(bounds).x, foy = (float)(bounds).y;                                    \
      int tx0 = (bounds).x / RP_TILE, ty0 = (bounds).y / RP_TILE;                                \
      int tx1 = (bounds).z / RP_TILE, ty1 = (bounds).w / RP_TILE;                                \
      for (int ty = ty0; ty <= ty1; ++ty) {                                                      \
        for (int tx = tx0; tx <= tx1; ++tx) {                                                    \
          if (is_triangle &&                                                                     \
              !rp_raster_rect_may_overlap((edges), (float)(tx * RP_TILE) + 0.5f * RP_TILE - fox, \
                                          (float)(ty * RP_TILE) + 0.5f * RP_TILE - foy,          \
                                          RP_BIN_HALF_EXTENT))                                   \
            continue;                                                                            \
          uint tile = (uint)ty * (view).tiles_x + (uint)tx;                                      \
          BODY                                                                                   \
        }                                                                                        \
      }                                                                                          \
    }                                                                                            \
  } while (0)

__kernel void visibility_clear(__global uint* counts, uint n) {
  uint i = get_global_id(0);
  if (i < n) counts[i] = 0u;
}

/* ---- triangle set-up, RP_SPAN triangle items per work-item (one per lane) ----
 * The same operations per lane as the scalar helpers above (rp_raster_transform,
 * rp_to_pixel_space, rp_outside_frustum, rp_triangle_bounds, rp_pixel_bounds, rp_raster_edges),
 * so the same bits. */

/* Lane masks as ints: -1 / 0 (a scalar comparison gives 1). */
#if RP_SPAN == 1
#define RP_MASK_INT(m) (-(m))
#else
#define RP_MASK_INT(m) (m)
#endif

typedef struct {
  rp_spanf x, y, z, w;
} RpLanes4;

/* m * p per lane, ((c0 x + c1 y) + c2 z) + c3 w (rp_raster_transform). */
inline RpLanes4 rp_lanes_transform(const rp_mat4 m, RpLanes4 p) {
  RpLanes4 r;
#define RP_ROW(row) (((m.c[0].row * p.x + m.c[1].row * p.y) + m.c[2].row * p.z) + m.c[3].row * p.w)
  r.x = RP_ROW(x);
  r.y = RP_ROW(y);
  r.z = RP_ROW(z);
  r.w = RP_ROW(w);
#undef RP_ROW
  return r;
}

inline RpLanes4 rp_lanes_select(RpLanes4 a, RpLanes4 b, rp_spani m) {
  RpLanes4 r;
  r.x = select(a.x, b.x, m);
  r.y = select(a.y, b.y, m);
  r.z = select(a.z, b.z, m);
  r.w = select(a.w, b.w, m);
  return r;
}

/* One near-clipped polygon point (rp_triangle_bounds) into the lanes' bounds. */
inline void rp_lanes_bound_point(RpLanes4 q, rp_spani use, rp_spanf* lo_x, rp_spanf* lo_y,
                                 rp_spanf* hi_x, rp_spanf* hi_y, rp_spani* unbounded) {
  const rp_spani in_front = use & (q.w > 0.0f);
  const rp_spanf x = q.x / q.w, y = q.y / q.w;
  *lo_x = select(*lo_x, fmin(*lo_x, x), in_front);
  *lo_y = select(*lo_y, fmin(*lo_y, y), in_front);
  *hi_x = select(*hi_x, fmax(*hi_x, x), in_front);
  *hi_y = select(*hi_y, fmax(*hi_y, y), in_front);
  *unbounded |= use & (q.w <= 0.0f);
}

/* rp_raster_top_left per lane, as -1 / 0. */
#define RP_LANES_TOP_LEFT(a, b, c) \
  RP_MASK_INT(((a) > 0.0f) | (((a) == 0.0f) & (((b) > 0.0f) | (((b) == 0.0f) & ((c) > 0.0f)))))

/* One work-item per RP_SPAN triangle items: transform, cull, pixel bounds, triangle edges in the
 * bounds' frame. Straight vector code: the tile walk and its atomics are visibility_count's. */
__kernel __attribute__((reqd_work_group_size(RP_SETUP_GROUP, 1, 1)))
void visibility_setup(const RasterView view, __global const uint2* draw_items,
                      __global const Instance* instances, __global const Triangle* triangles,
                      __global const Vertex* vertices, __global const Material* materials,
                      __global RasterTriangle* tris_out, __global int4* bounds_out,
                      __global RasterEdges* edges_out) {
  const uint first = (uint)get_global_id(0) * RP_SPAN;
  if (first >= view.triangle_items) return;
  const int n = (int)min((uint)RP_SPAN, view.triangle_items - first);
  const float half_w = 0.5f * (float)view.width, half_h = 0.5f * (float)view.height;

  /* Gather: object positions, instance and primitive per lane (lanes >= n repeat lane 0). */
  float pos[3][3][RP_SPAN];
  uint inst_of[RP_SPAN], prim_of[RP_SPAN], tri_of[RP_SPAN], masked_of[RP_SPAN];
  int drawn_of[RP_SPAN];
#if !RP_DEPTH_ONLY
  int single_of[RP_SPAN]; /* -1: a single-sided material, its back face culled */
#endif
  for (int i = 0; i < RP_SPAN; ++i) {
    const uint2 d = draw_items[first + (uint)(i < n ? i : 0)];
    __global const Instance* inst = &instances[d.x];
    const Triangle t = triangles[d.y];
    const uint idx[3] = {t.x, t.y, t.z};
    for (int k = 0; k < 3; ++k) {
      const float4 p = vertices[idx[k]].position_u;
      pos[k][0][i] = p.x;
      pos[k][1][i] = p.y;
      pos[k][2][i] = p.z;
    }
    inst_of[i] = d.x;
    prim_of[i] = d.y - inst->first_triangle;
    tri_of[i] = d.y;
    masked_of[i] = RP_MATERIAL_MASKED(materials[t.w]) ? 1u : 0u;
#if RP_DEPTH_ONLY
    drawn_of[i] = (inst->casts_shadow & view.caster_mask) != 0u ? -1 : 0;
#else
    drawn_of[i] = -1;
    single_of[i] = RP_MATERIAL_SINGLE_SIDED(materials[t.w]) ? -1 : 0;
#endif
  }
  RpLanes4 obj[3];
  for (int k = 0; k < 3; ++k) {
    obj[k].x = RP_SPAN_FROM_ARRAY(pos[k][0]);
    obj[k].y = RP_SPAN_FROM_ARRAY(pos[k][1]);
    obj[k].z = RP_SPAN_FROM_ARRAY(pos[k][2]);
    obj[k].w = (rp_spanf)(1.0f); /* position_u.w holds the texture u */
  }

  /* World positions through each distinct instance of the span (usually one). */
  const rp_spanu inst_lanes = RP_SPAN_FROM_ARRAY(inst_of);
  RpLanes4 clip[3];
  rp_spani mirrored = (rp_spani)(0); /* lanes whose model matrix has a negative determinant */
  int done[RP_SPAN];
  RP_SPAN_TO_ARRAY((rp_spani)(0), done);
  for (int i = 0; i < RP_SPAN; ++i) {
    if (done[i]) continue;
    const uint instance = inst_of[i];
    const rp_spani group = inst_lanes == instance;
    int g[RP_SPAN];
    RP_SPAN_TO_ARRAY(group, g);
    for (int j = i; j < RP_SPAN; ++j) done[j] |= g[j];
    const rp_mat4 model = instances[instance].model;
    if (dot(model.c[0].xyz, cross(model.c[1].xyz, model.c[2].xyz)) < 0.0f) mirrored |= group;
    for (int k = 0; k < 3; ++k) {
      const RpLanes4 c = rp_lanes_transform(view.view_proj, rp_lanes_transform(model, obj[k]));
      clip[k] = i == 0 ? c : rp_lanes_select(clip[k], c, group);
    }
  }

  /* Homogeneous pixel space (rp_to_pixel_space). */
  RpLanes4 v[3];
  for (int k = 0; k < 3; ++k) {
    v[k].x = (clip[k].x + clip[k].w) * half_w;
    v[k].y = (clip[k].w - clip[k].y) * half_h;
    v[k].z = clip[k].z;
    v[k].w = clip[k].w;
  }

  /* Frustum: all three vertices outside one plane (rp_outside_frustum). */
  rp_spani outside = (rp_spani)(0);
  {
    rp_spani o0 = (rp_spani)(-1), o1 = o0, o2 = o0, o3 = o0, o4 = o0, o5 = o0;
    for (int k = 0; k < 3; ++k) {
      o0 &= clip[k].x > clip[k].w;
      o1 &= clip[k].x < -clip[k].w;
      o2 &= clip[k].y > clip[k].w;
      o3 &= clip[k].y < -clip[k].w;
      o4 &= clip[k].z > clip[k].w;
      o5 &= clip[k].z < -clip[k].w;
    }
    outside = o0 | o1 | o2 | o3 | o4 | o5;
  }

  /* Bounds of the near-clipped polygon (rp_triangle_bounds, rp_pixel_bounds). */
  rp_spanf lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
  rp_spani unbounded = (rp_spani)(0);
  for (int k = 0; k < 3; ++k) {
    const RpLanes4 a = v[k], b = v[(k + 1) % 3];
    const rp_spanf da = a.z + a.w, db = b.z + b.w;
    const rp_spani a_in = da >= 0.0f;
    /* the edge crosses the near plane: (da >= 0) != (db >= 0), written without a negated
     * mask (oclgrind 21.10 mis-evaluates those) */
    const rp_spani crosses = (a_in & (db < 0.0f)) | ((da < 0.0f) & (db >= 0.0f));
    rp_lanes_bound_point(a, a_in, &lo_x, &lo_y, &hi_x, &hi_y, &unbounded);
    const rp_spanf t = da / (da - db);
    RpLanes4 cut;
    cut.x = a.x + (b.x - a.x) * t;
    cut.y = a.y + (b.y - a.y) * t;
    cut.z = a.z + (b.z - a.z) * t;
    cut.w = a.w + (b.w - a.w) * t;
    rp_lanes_bound_point(cut, crosses, &lo_x, &lo_y, &hi_x, &hi_y, &unbounded);
  }
  const float fw = (float)view.width, fh = (float)view.height;
  lo_x = clamp(lo_x, -2.0f, fw + 2.0f);
  lo_y = clamp(lo_y, -2.0f, fh + 2.0f);
  hi_x = clamp(hi_x, -2.0f, fw + 2.0f);
  hi_y = clamp(hi_y, -2.0f, fh + 2.0f);
  /* Integer clamps with span bounds (oclgrind 21.10 mis-evaluates scalar ones). */
  const rp_spani zero = (rp_spani)(0), last_x = (rp_spani)((int)view.width - 1),
                 last_y = (rp_spani)((int)view.height - 1);
  rp_spani bx0 = clamp(rp_span_convert_int(floor(lo_x)) - 1, zero, last_x);
  rp_spani by0 = clamp(rp_span_convert_int(floor(lo_y)) - 1, zero, last_y);
  rp_spani bx1 = clamp(rp_span_convert_int(floor(hi_x)) + 1, zero, last_x);
  rp_spani by1 = clamp(rp_span_convert_int(floor(hi_y)) + 1, zero, last_y);
  /* No pixel centre (i + 0.5) within the bounds, widened by RP_CENTRE_MARGIN against the
   * rounding between these divided coordinates and the homogeneous edge functions: the
   * triangle covers no pixel (most of a far, finely tessellated scene's triangles). */
  const rp_spani between_centres =
      (floor(hi_x - 0.5f + RP_CENTRE_MARGIN) < ceil(lo_x - 0.5f - RP_CENTRE_MARGIN)) |
      (floor(hi_y - 0.5f + RP_CENTRE_MARGIN) < ceil(lo_y - 0.5f - RP_CENTRE_MARGIN));
  const rp_spani off_view = (lo_x > hi_x) | (lo_y > hi_y) | (hi_x < 0.0f) | (hi_y < 0.0f) |
                            (lo_x > fw) | (lo_y > fh) | between_centres;
  bx0 = select(bx0, zero, off_view);
  by0 = select(by0, zero, off_view);
  bx1 = select(bx1, (rp_spani)(-1), off_view);
  by1 = select(by1, (rp_spani)(-1), off_view);
  bx0 = select(bx0, zero, unbounded); /* unusual projections: the whole view */
  by0 = select(by0, zero, unbounded);
  bx1 = select(bx1, last_x, unbounded);
  by1 = select(by1, last_y, unbounded);
  const rp_spani empty = (RP_SPAN_FROM_ARRAY(drawn_of) != -1) | outside;
  bx0 = select(bx0, zero, empty);
  by0 = select(by0, zero, empty);
  bx1 = select(bx1, (rp_spani)(-1), empty);
  by1 = select(by1, (rp_spani)(-1), empty);

  /* Edges in the frame of the bounds' first pixel (rp_raster_edges). */
  const rp_spanf fox = rp_span_convert_float(bx0), foy = rp_span_convert_float(by0);
  rp_spanf x[3], y[3], w[3];
  for (int k = 0; k < 3; ++k) {
    x[k] = v[k].x - fox * v[k].w;
    y[k] = v[k].y - foy * v[k].w;
    w[k] = v[k].w;
  }
  rp_spanf ea[3], eb[3], ec[3];
  for (int k = 0; k < 3; ++k) {
    const int j = (k + 1) % 3, l = (k + 2) % 3;
    ea[k] = y[j] * w[l] - w[j] * y[l];
    eb[k] = w[j] * x[l] - x[j] * w[l];
    ec[k] = x[j] * y[l] - y[j] * x[l];
  }
  rp_spanf det = (w[0] * ec[0] + w[1] * ec[1]) + w[2] * ec[2];
#if !RP_DEPTH_ONLY
  /* Back faces of single-sided materials are not drawn for the camera (glTF doubleSided false).
   * The front face winds counter-clockwise in the object's space; on screen (y down) that is
   * a negative determinant, and a mirroring model matrix swaps it (glTF: the determinant
   * decides the winding). A closed mesh looks the same without its back faces, for less
   * raster work: visibility -17 % on the atrium, -24 % on the busy demo
   * (bench/results/zen3-2core-pocl-atrium-scale.md). */
  {
    /* the determinant in the view's own frame, not the bounds' (the reference's arithmetic) */
    const rp_spanf c0 = v[1].x * v[2].y - v[1].y * v[2].x;
    const rp_spanf c1 = v[2].x * v[0].y - v[2].y * v[0].x;
    const rp_spanf c2 = v[0].x * v[1].y - v[0].y * v[1].x;
    const rp_spanf facing = (v[0].w * c0 + v[1].w * c1) + v[2].w * c2;
    const rp_spani back = select(facing > 0.0f, facing < 0.0f, mirrored) &
                          (RP_SPAN_FROM_ARRAY(single_of) != 0);
    bx0 = select(bx0, zero, back);
    by0 = select(by0, zero, back);
    bx1 = select(bx1, (rp_spani)(-1), back);
    by1 = select(by1, (rp_spani)(-1), back);
  }
#endif
  const rp_spanf sgn = select((rp_spanf)(1.0f), (rp_spanf)(-1.0f), det < 0.0f);
  for (int k = 0; k < 3; ++k) {
    ea[k] *= sgn;
    eb[k] *= sgn;
    ec[k] *= sgn;
  }
  det *= sgn;
  const rp_spani valid = (det > 0.0f) & RP_MASK_INT(isfinite(det));
  int tl[3][RP_SPAN], valid_of[RP_SPAN];
  float ef[3][3][RP_SPAN];
  for (int k = 0; k < 3; ++k) {
    const rp_spani top_left = RP_LANES_TOP_LEFT(ea[k], eb[k], ec[k]);
    RP_SPAN_TO_ARRAY(select((rp_spani)(0), top_left, valid), tl[k]);
    RP_SPAN_TO_ARRAY(select((rp_spanf)(0.0f), ea[k], valid), ef[k][0]);
    RP_SPAN_TO_ARRAY(select((rp_spanf)(0.0f), eb[k], valid), ef[k][1]);
    RP_SPAN_TO_ARRAY(select((rp_spanf)(0.0f), ec[k], valid), ef[k][2]);
  }
  RP_SPAN_TO_ARRAY(RP_MASK_INT(valid), valid_of);

  /* Per-lane stores. */
  float vf[3][4][RP_SPAN];
  for (int k = 0; k < 3; ++k) {
    RP_SPAN_TO_ARRAY(v[k].x, vf[k][0]);
    RP_SPAN_TO_ARRAY(v[k].y, vf[k][1]);
    RP_SPAN_TO_ARRAY(v[k].z, vf[k][2]);
    RP_SPAN_TO_ARRAY(v[k].w, vf[k][3]);
  }
  int b0[RP_SPAN], b1[RP_SPAN], b2[RP_SPAN], b3[RP_SPAN];
  RP_SPAN_TO_ARRAY(bx0, b0);
  RP_SPAN_TO_ARRAY(by0, b1);
  RP_SPAN_TO_ARRAY(bx1, b2);
  RP_SPAN_TO_ARRAY(by1, b3);
  /* An item that draws nothing (empty bounds: culled, off the view, between pixel centres:
   * most of a large scene's) writes its bounds only: every reader tests them before the rest
   * (the raster's fallback over every item reads its record, but its box is empty). On the
   * atrium 128 bytes less per such triangle, visibility 18.4 -> 17.0 ms at 720x720. */
  for (int i = 0; i < n; ++i) {
    bounds_out[first + (uint)i] = (int4)(b0[i], b1[i], b2[i], b3[i]);
    if (b0[i] > b2[i] || b1[i] > b3[i]) continue;
    RasterTriangle rt;
    for (int k = 0; k < 3; ++k)
      rt.v[k] = (float4)(vf[k][0][i], vf[k][1][i], vf[k][2][i], vf[k][3][i]);
    rt.info = (uint4)(inst_of[i], prim_of[i], tri_of[i], masked_of[i]);
    tris_out[first + (uint)i] = rt;
    RasterEdges e;
    for (int k = 0; k < 3; ++k) e.e[k] = (float4)(ef[k][0][i], ef[k][1][i], ef[k][2][i], 0.0f);
    e.top_left = (int4)(tl[0][i], tl[1][i], tl[2][i], valid_of[i]);
    edges_out[first + (uint)i] = e;
  }
}

/* Sphere items (after the triangle items): pixel bounds of the bounding cube. */
__kernel __attribute__((reqd_work_group_size(RP_ITEM_GROUP, 1, 1)))
void visibility_setup_spheres(const RasterView view, __global const Sphere* spheres,
                              __global int4* bounds_out) {
  const uint index = (uint)get_global_id(0);
  if (index >= view.sphere_count) return;
  const float half_w = 0.5f * (float)view.width, half_h = 0.5f * (float)view.height;
  const Sphere s = spheres[index];
  int4 bounds = RP_EMPTY_BOUNDS;
#if RP_DEPTH_ONLY
  const bool drawn = s.center_radius.w > 0.0f && s.prev_center.w != 0.0f; /* casts shadow */
#else
  const bool drawn = s.center_radius.w > 0.0f;
#endif
  if (drawn)
    bounds = rp_sphere_bounds(view.view_proj, s.center_radius, half_w, half_h, view.width,
                              view.height);
  bounds_out[view.triangle_items + index] = bounds;
}

/* Counts every tile each item may touch (triangles at [tile], spheres at [tile_count + tile]). */
__kernel __attribute__((reqd_work_group_size(RP_ITEM_GROUP, 1, 1)))
void visibility_count(const RasterView view, __global const int4* bounds_in,
                      __global const RasterEdges* edges_in, __global uint* tile_counts) {
  uint item = get_global_id(0);
  uint triangle_items = view.triangle_items;
  if (item >= triangle_items + view.sphere_count) return;
  const int4 bounds = bounds_in[item];
  if (bounds.x > bounds.z || bounds.y > bounds.w) return;
  if (item < triangle_items) {
    const RasterEdges edges = edges_in[item];
    RP_FOR_ITEM_TILES(view, bounds, true, edges, { atomic_inc(&tile_counts[tile]); });
  } else {
    const uint tile_count = view.tiles_x * view.tiles_y;
    RP_FOR_ITEM_TILES(view, bounds, false, rp_raster_no_edges(),
                      { atomic_inc(&tile_counts[tile_count + tile]); });
  }
}

/* Exclusive scan of n counts by one work-group: start[i] = cursor[i] = sum of counts[0..i),
 * total[0] = sum of all (read back by the host to size the list). */
__kernel __attribute__((reqd_work_group_size(RP_SCAN_GROUP, 1, 1)))
void visibility_scan(__global const uint* counts, uint n, __global uint* start,
                     __global uint* cursor, __global uint* total) {
  __local uint partial[RP_SCAN_GROUP];
  uint lid = get_local_id(0);
  uint chunk = (n + RP_SCAN_GROUP - 1) / RP_SCAN_GROUP;
  uint begin = min(n, lid * chunk), end = min(n, begin + chunk);
  uint sum = 0;
  for (uint i = begin; i < end; ++i) sum += counts[i];
  partial[lid] = sum;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (lid == 0) {
    uint run = 0;
    for (uint k = 0; k < RP_SCAN_GROUP; ++k) {
      uint c = partial[k];
      partial[k] = run;
      run += c;
    }
    total[0] = run;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  uint run = partial[lid];
  for (uint i = begin; i < end; ++i) {
    start[i] = run;
    cursor[i] = run;
    run += counts[i];
  }
}

__kernel __attribute__((reqd_work_group_size(RP_ITEM_GROUP, 1, 1)))
void visibility_bin(const RasterView view, __global const int4* bounds_in,
                    __global const RasterEdges* edges_in, __global uint* tile_cursor,
                    __global uint* tile_list) {
  uint item = get_global_id(0);
  uint triangle_items = view.triangle_items;
  if (item >= triangle_items + view.sphere_count) return;
  const int4 bounds = bounds_in[item];
  if (bounds.x > bounds.z || bounds.y > bounds.w) return;
  if (item < triangle_items) {
    const RasterEdges edges = edges_in[item];
    RP_FOR_ITEM_TILES(view, bounds, true, edges, {
      uint slot = atomic_inc(&tile_cursor[tile]);
      if (slot < view.list_capacity) tile_list[slot] = item;
    });
  } else {
    const uint tile_count = view.tiles_x * view.tiles_y;
    RP_FOR_ITEM_TILES(view, bounds, false, rp_raster_no_edges(), {
      uint slot = atomic_inc(&tile_cursor[tile_count + tile]);
      if (slot < view.list_capacity) tile_list[slot] = item;
    });
  }
}

/* ---- per-row evaluation, shared by both raster layouts ----
 * The best surface so far of RP_SPAN pixels of a row: smallest (z_ndc, key) and, for the camera,
 * the winner's ids and edge values (barycentrics = e1, e2 over their sum). */
typedef struct {
  rp_spanf z;
  rp_spanu key;
#if RP_DEPTH_ONLY
  rp_spanf z_back; /* the farthest caster surface (z_ndc), -1 where none */
#else
  rp_spanu instance, primitive;
  rp_spanf e1, e2, sum;
#endif
} RasterBest;

inline RasterBest rp_best_init(void) {
  RasterBest b;
  b.z = (rp_spanf)(1.0f);
  b.key = (rp_spanu)(RP_ID_NONE);
#if RP_DEPTH_ONLY
  b.z_back = (rp_spanf)(-1.0f);
#else
  b.instance = b.primitive = (rp_spanu)(RP_ID_NONE);
  b.e1 = b.e2 = (rp_spanf)(0.0f);
  b.sum = (rp_spanf)(1.0f);
#endif
  return b;
}

/* A triangle item set up for a tile: edges, the vertices' clip z and w, bounds in tile pixels
 * (x0, y0, x1, y1), flags (top-left bits of edges 0..2, item, instance, primitive). */
typedef struct {
  float4 e0, e1, e2, z, w;
  int4 box, flags;
} RasterItem;

inline RasterItem rp_item_triangle(__global const RasterTriangle* tris,
                                   __global const int4* bounds_in, uint item, int ox, int oy) {
  RasterTriangle t = tris[item];
  RasterEdges r = rp_raster_edges(t.v[0], t.v[1], t.v[2], (float)ox, (float)oy);
  RasterItem it;
  it.e0 = r.e[0];
  it.e1 = r.e[1];
  it.e2 = r.e[2];
  it.z = (float4)(t.v[0].z, t.v[1].z, t.v[2].z, 0.0f);
  it.w = (float4)(t.v[0].w, t.v[1].w, t.v[2].w, 0.0f);
  it.box = r.top_left.w ? bounds_in[item] - (int4)(ox, oy, ox, oy) : RP_EMPTY_BOUNDS;
  /* flags.x: the top-left bits; for a masked material also bit 3 and, from bit 4, the global
   * triangle index the alpha test reads (up to 2^27 triangles) */
  const int mask_bits = t.info.w != 0u ? (int)(8u | (t.info.z << 4)) : 0;
  it.flags = (int4)((r.top_left.x & 1) | (r.top_left.y & 2) | (r.top_left.z & 4) | mask_bits,
                    (int)item, (int)t.info.x, (int)t.info.y);
  return it;
}

/* A sphere item: e0 = (centre, r^2), box, flags (0, item, sphere id, 0). */
inline RasterItem rp_item_sphere(const RasterView* view, __global const Sphere* spheres,
                                 __global const int4* bounds_in, uint item, int ox, int oy) {
  uint index = item - view->triangle_items;
  float4 cr = spheres[index].center_radius;
  RasterItem it;
  it.e0 = (float4)(cr.xyz, cr.w * cr.w);
  it.e1 = it.e2 = it.z = it.w = (float4)(0.0f);
  it.box = bounds_in[item] - (int4)(ox, oy, ox, oy);
  it.flags = (int4)(0, (int)item, (int)(RP_ID_SPHERE_BIT | index), 0);
  return it;
}

/* True when the item's box misses the span at row ly, columns lx0 .. lx0 + RP_SPAN - 1. */
#define RP_ITEM_MISSES(box, lx0, ly) \
  ((ly) < (box).y || (ly) > (box).w || (lx0) + (RP_SPAN - 1) < (box).x || (lx0) > (box).z)

/* The scene data the alpha test of masked materials reads (common/alpha_mask.h). */
#define RP_MASK_PARAMS                                                                         \
  __global const Triangle *triangles, __global const Vertex *vertices,                       \
      __global const Material *materials, __global const TextureInfo *textures,              \
      __global const uint *texels
#define RP_MASK_ARGS triangles, vertices, materials, textures, texels

/* Tests pixel centres (dx, dy) (tile frame) against triangle item `it`. */
inline void rp_best_triangle(RasterBest* b, const RasterItem* it, rp_spanf dx, float dy,
                             RP_MASK_PARAMS) {
  const float4 e0 = it->e0, e1 = it->e1, e2 = it->e2;
  const int4 flags = it->flags;
  const uint key = (uint)flags.y;
  const int tl0 = -(flags.x & 1), tl1 = -((flags.x >> 1) & 1), tl2 = -((flags.x >> 2) & 1);
  rp_spanf f0 = e0.x * dx + (e0.y * dy + e0.z);
  rp_spanf f1 = e1.x * dx + (e1.y * dy + e1.z);
  rp_spanf f2 = e2.x * dx + (e2.y * dy + e2.z);
  rp_spanf z = RP_RASTER_DEPTH(f0, f1, f2, it->z, it->w);
  rp_spani in = ((f0 > 0.0f) | ((f0 == 0.0f) & tl0)) & ((f1 > 0.0f) | ((f1 == 0.0f) & tl1)) &
                ((f2 > 0.0f) | ((f2 == 0.0f) & tl2)) & (z >= -1.0f);
  if ((flags.x & 8) != 0 && rp_span_any(in)) { /* a masked material: holes where alpha is low */
    const rp_spanf sum = (f0 + f1) + f2;
    in = rp_alpha_solid(RP_MASK_ARGS, (uint)flags.x >> 4, f1 / sum, f2 / sum, in, RP_SPAN);
  }
#if RP_DEPTH_ONLY
  b->z_back = select(b->z_back, fmax(b->z_back, fmin(z, 1.0f)), in);
#endif
  in &= (z < b->z) | ((z == b->z) & (key < b->key));
  b->z = select(b->z, z, in);
  b->key = select(b->key, (rp_spanu)(key), in);
#if !RP_DEPTH_ONLY
  b->instance = select(b->instance, (rp_spanu)((uint)flags.z), in);
  b->primitive = select(b->primitive, (rp_spanu)((uint)flags.w), in);
  b->e1 = select(b->e1, f1, in);
  b->e2 = select(b->e2, f2, in);
  b->sum = select(b->sum, (f0 + f1) + f2, in);
#endif
}

/* Camera rays through RP_SPAN pixel centres of a row: origin on the near plane, unit direction,
 * and clip z and w along the ray (linear in the ray parameter t). */
typedef struct {
  rp_spanf ox, oy, oz, dx, dy, dz, z_o, w_o, z_d, w_d;
} RasterRays;

inline RasterRays rp_row_rays(const RasterView* view, int px0, int py) {
  const rp_mat4 inv = view->inv_view_proj, vp = view->view_proj;
  rp_spanf nx = ((float)px0 + 0.5f + RP_LANES) * (2.0f / (float)view->width) - 1.0f;
  float ny = 1.0f - ((float)py + 0.5f) * (2.0f / (float)view->height);
  /* points on the near (z_ndc = -1) and far (+1) planes, world space */
#define RP_UNPROJECT(comp, zn) \
  (((inv.c[0].comp * nx + inv.c[1].comp * ny) + inv.c[2].comp * (zn)) + inv.c[3].comp)
  rp_spanf near_w = RP_UNPROJECT(w, -1.0f), far_w = RP_UNPROJECT(w, 1.0f);
  RasterRays r;
  r.ox = RP_UNPROJECT(x, -1.0f) / near_w;
  r.oy = RP_UNPROJECT(y, -1.0f) / near_w;
  r.oz = RP_UNPROJECT(z, -1.0f) / near_w;
  rp_spanf rx = RP_UNPROJECT(x, 1.0f) / far_w - r.ox, ry = RP_UNPROJECT(y, 1.0f) / far_w - r.oy,
           rz = RP_UNPROJECT(z, 1.0f) / far_w - r.oz;
#undef RP_UNPROJECT
  rp_spanf len = sqrt((rx * rx + ry * ry) + rz * rz);
  r.dx = rx / len;
  r.dy = ry / len;
  r.dz = rz / len;
  r.z_o = ((vp.c[0].z * r.ox + vp.c[1].z * r.oy) + vp.c[2].z * r.oz) + vp.c[3].z;
  r.w_o = ((vp.c[0].w * r.ox + vp.c[1].w * r.oy) + vp.c[2].w * r.oz) + vp.c[3].w;
  r.z_d = (vp.c[0].z * r.dx + vp.c[1].z * r.dy) + vp.c[2].z * r.dz;
  r.w_d = (vp.c[0].w * r.dx + vp.c[1].w * r.dy) + vp.c[2].w * r.dz;
  return r;
}

/* Exact intersection of the rays with sphere item `it`. */
inline void rp_best_sphere(RasterBest* b, const RasterItem* it, const RasterRays* r) {
  const float4 s = it->e0;
  const uint key = (uint)it->flags.y;
  rp_spanf cx = r->ox - s.x, cy = r->oy - s.y, cz = r->oz - s.z;
  rp_spanf bq = (cx * r->dx + cy * r->dy) + cz * r->dz;
  /* r^2 - squared distance of the centre from the ray (accurate for small spheres) */
  rp_spanf px = cx - bq * r->dx, py = cy - bq * r->dy, pz = cz - bq * r->dz;
  rp_spanf disc = s.w - ((px * px + py * py) + pz * pz);
  rp_spanf root = sqrt(fmax(disc, 0.0f));
  rp_spanf t0 = -bq - root;
  rp_spanf t = select(-bq + root, t0, t0 >= 0.0f);
  rp_spanf z = (r->z_o + t * r->z_d) / (r->w_o + t * r->w_d);
#if RP_DEPTH_ONLY
  /* the far side: the sphere's back (or the near plane's z when the origin is inside) */
  const rp_spanf t1 = -bq + root;
  const rp_spanf z1 = (r->z_o + t1 * r->z_d) / (r->w_o + t1 * r->w_d);
  b->z_back = select(b->z_back, fmax(b->z_back, fmin(z1, 1.0f)),
                     (disc >= 0.0f) & (t1 >= 0.0f) & (z1 >= -1.0f));
#endif
  rp_spani in = (disc >= 0.0f) & (t >= 0.0f) & (z >= -1.0f) &
                ((z < b->z) | ((z == b->z) & (key < b->key)));
  b->z = select(b->z, z, in);
  b->key = select(b->key, (rp_spanu)(key), in);
#if !RP_DEPTH_ONLY
  b->instance = select(b->instance, (rp_spanu)((uint)it->flags.z), in);
  b->primitive = select(b->primitive, (rp_spanu)(0u), in);
  b->e1 = select(b->e1, (rp_spanf)(0.0f), in);
  b->e2 = select(b->e2, (rp_spanf)(0.0f), in);
  b->sum = select(b->sum, (rp_spanf)(1.0f), in);
#endif
}

/* One write per pixel and plane: RP_SPAN pixels from (x0, y). */
inline void rp_best_store(const RasterView* view, const RasterBest* b, int x0, int y,
                          __global float* depth_out, __global uint* ids_out,
                          __global float* bary_out) {
  if (y >= (int)view->height || x0 >= (int)view->width) return;
  int valid = min(RP_SPAN, (int)view->width - x0);
  size_t row = (size_t)y * view->width + (size_t)x0;
  rp_store_span_f(b->z * 0.5f + 0.5f, depth_out + row, valid);
#if !RP_DEPTH_ONLY
  rp_store_span_pairs_u(b->instance, b->primitive, ids_out + 2 * row, valid);
  rp_store_span_pairs_f(b->e1 / b->sum, b->e2 / b->sum, bary_out + 2 * row, valid);
#else
  /* depth-only: the back plane follows the depth plane in the same buffer (ShadowMap::depth) */
  (void)ids_out;
  (void)bary_out;
  rp_store_span_f(b->z_back * 0.5f + 0.5f,
                  depth_out + (size_t)view->width * view->height + row, valid);
#endif
}

/* A tile's list range [*begin, *end) in the region at `region` (0 triangles, tile_count
 * spheres), or, when the list overflowed there (the range ends past the capacity the binning
 * could fill), every item of the kind: the per-row bounds test then skips the ones that miss
 * the tile, so the result is the same, only slower. Returns whether every item is used. */
inline bool rp_tile_range(const RasterView* view, __global const uint* tile_start,
                          __global const uint* tile_end, uint region, uint tile, bool spheres,
                          uint* begin, uint* end) {
  *begin = tile_start[region + tile];
  *end = tile_end[region + tile];
  if (*end <= view->list_capacity) return false;
  *begin = spheres ? view->triangle_items : 0u;
  *end = spheres ? view->triangle_items + view->sphere_count : view->triangle_items;
  return true;
}

#if RP_TILE_LAYOUT
/* CPU layout (-DRP_TILE_LAYOUT=1, RP_SPAN 8 or 16): one work-item per tile, looping over the
 * tile's rows, each row RP_TILE / RP_SPAN spans. No local memory and no barriers: PoCL runs the
 * work-items of a group one after the other, and a barrier would make it save and restore
 * every work-item's state around it. The tile's items are set up RP_TILE_BATCH at a time into
 * private memory; the spans' best surfaces are kept in private memory between batches. Same
 * arithmetic per pixel as the other layout, so the same result bit for bit. */
#if RP_SPAN < 8 || RP_TILE % RP_SPAN != 0
#error "RP_TILE_LAYOUT needs RP_SPAN 8 or 16"
#endif
#define RP_TILE_BATCH 32
#define RP_ROW_SPANS (RP_TILE / RP_SPAN)

__kernel void visibility_raster(const RasterView view, __global const RasterTriangle* tris,
                                __global const int4* bounds_in, __global const Sphere* spheres,
                                __global const uint* tile_start, __global const uint* tile_end,
                                __global const uint* tile_list, __global float* depth_out,
                                __global uint* ids_out, __global float* bary_out,
                                RP_MASK_PARAMS) {
  const uint tile_count = view.tiles_x * view.tiles_y;
  const uint tile = (uint)get_global_id(0);
  if (tile >= tile_count) return;
  const uint tile_y = tile / view.tiles_x, tile_x = tile - tile_y * view.tiles_x;
  const int ox = (int)tile_x * RP_TILE, oy = (int)tile_y * RP_TILE;

  RasterBest spans[RP_TILE * RP_ROW_SPANS]; /* row ly, span sx at [ly * RP_ROW_SPANS + sx] */
  for (int k = 0; k < RP_TILE * RP_ROW_SPANS; ++k) spans[k] = rp_best_init();
  RasterItem items[RP_TILE_BATCH];

  for (int kind = 0; kind < 2; ++kind) { /* triangles, then spheres */
    uint begin, end;
    const bool every_item = rp_tile_range(&view, tile_start, tile_end, kind ? tile_count : 0u,
                                          tile, kind != 0, &begin, &end);
    for (uint base = begin; base < end; base += RP_TILE_BATCH) {
      const uint n = min((uint)RP_TILE_BATCH, end - base);
      int4 reach = (int4)(RP_TILE, RP_TILE, -1, -1); /* union of the batch's boxes */
      for (uint k = 0; k < n; ++k) {
        const uint item = every_item ? base + k : tile_list[base + k];
        items[k] = kind ? rp_item_sphere(&view, spheres, bounds_in, item, ox, oy)
                        : rp_item_triangle(tris, bounds_in, item, ox, oy);
        reach = (int4)(min(reach.xy, items[k].box.xy), max(reach.zw, items[k].box.zw));
      }
      const int first_row = max(reach.y, 0), last_row = min(reach.w, RP_TILE - 1);
      const int first_span = max(reach.x, 0) / RP_SPAN;
      const int last_span = min(reach.z, RP_TILE - 1) / RP_SPAN;
      for (int ly = first_row; ly <= last_row; ++ly) {
        for (int sx = first_span; sx <= last_span; ++sx) {
          const int lx0 = sx * RP_SPAN;
          RasterBest best = spans[ly * RP_ROW_SPANS + sx];
          if (kind == 0) {
            const rp_spanf dx = ((float)lx0 + 0.5f) + RP_LANES;
            const float dy = (float)ly + 0.5f;
            for (uint k = 0; k < n; ++k)
              if (!RP_ITEM_MISSES(items[k].box, lx0, ly))
                rp_best_triangle(&best, &items[k], dx, dy, RP_MASK_ARGS);
          } else {
            const RasterRays rays = rp_row_rays(&view, ox + lx0, oy + ly);
            for (uint k = 0; k < n; ++k)
              if (!RP_ITEM_MISSES(items[k].box, lx0, ly)) rp_best_sphere(&best, &items[k], &rays);
          }
          spans[ly * RP_ROW_SPANS + sx] = best;
        }
      }
    }
  }
  for (int ly = 0; ly < RP_TILE; ++ly)
    for (int sx = 0; sx < RP_ROW_SPANS; ++sx)
      rp_best_store(&view, &spans[ly * RP_ROW_SPANS + sx], ox + sx * RP_SPAN, oy + ly,
                    depth_out, ids_out, bary_out);
}

#else
/* GPU layout: one work-group per tile, RP_GROUP_W x RP_TILE work-items, each owning RP_SPAN
 * pixels of a row. Items of the tile's lists are set up cooperatively in local memory,
 * RP_BATCH at a time; then every work-item tests its pixels against the batch. */
__kernel __attribute__((reqd_work_group_size(RP_GROUP_W, RP_TILE, 1)))
void visibility_raster(const RasterView view, __global const RasterTriangle* tris,
                       __global const int4* bounds_in, __global const Sphere* spheres,
                       __global const uint* tile_start, __global const uint* tile_end,
                       __global const uint* tile_list, __global float* depth_out,
                       __global uint* ids_out, __global float* bary_out, RP_MASK_PARAMS) {
  __local RasterItem l_items[RP_BATCH];

  uint tile_x = get_group_id(0), tile_y = get_group_id(1);
  uint tile = tile_y * view.tiles_x + tile_x;
  uint tile_count = view.tiles_x * view.tiles_y;
  uint lid = get_local_id(1) * RP_GROUP_W + get_local_id(0);
  int lx0 = (int)get_local_id(0) * RP_SPAN, ly = (int)get_local_id(1);
  int ox = (int)tile_x * RP_TILE, oy = (int)tile_y * RP_TILE;
  rp_spanf dx = ((float)lx0 + 0.5f) + RP_LANES;
  float dy = (float)ly + 0.5f;
  RasterBest best = rp_best_init();

  for (int kind = 0; kind < 2; ++kind) { /* triangles, then spheres */
    uint begin, end;
    const bool every_item = rp_tile_range(&view, tile_start, tile_end, kind ? tile_count : 0u,
                                          tile, kind != 0, &begin, &end);
    if (begin >= end) continue; /* uniform across the group */
    RasterRays rays;
    if (kind) rays = rp_row_rays(&view, ox + lx0, oy + ly);
    for (uint base = begin; base < end; base += RP_BATCH) {
      uint n = min((uint)RP_BATCH, end - base);
      for (uint k = lid; k < n; k += RP_GROUP_SIZE) {
        uint item = every_item ? base + k : tile_list[base + k];
        l_items[k] = kind ? rp_item_sphere(&view, spheres, bounds_in, item, ox, oy)
                          : rp_item_triangle(tris, bounds_in, item, ox, oy);
      }
      barrier(CLK_LOCAL_MEM_FENCE);
      for (uint k = 0; k < n; ++k) {
        const RasterItem it = l_items[k];
        if (RP_ITEM_MISSES(it.box, lx0, ly)) continue;
        if (kind)
          rp_best_sphere(&best, &it, &rays);
        else
          rp_best_triangle(&best, &it, dx, dy, RP_MASK_ARGS);
      }
      barrier(CLK_LOCAL_MEM_FENCE);
    }
  }
  rp_best_store(&view, &best, ox + lx0, oy + ly, depth_out, ids_out, bary_out);
}
#endif
