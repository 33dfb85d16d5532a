/* Compute rasterizer: mesh triangles + analytic spheres -> visibility buffer (or, with
 * -DRP_DEPTH_ONLY=1, the shadow map's depth). Host side: src/passes/visibility.cpp.
 *
 * Per view and frame, in order:
 *   visibility_clear    zero the per-tile counts
 *   visibility_setup    one work-item per draw item (triangle items, then sphere items):
 *                       transform, cull, pixel bounds, count the tiles it may touch
 *   visibility_scan     one work-group: exclusive scan of the counts -> tile list ranges
 *   visibility_bin      the same walk as setup, now writing item indices into the tile lists
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

#ifndef RP_DEPTH_ONLY
#define RP_DEPTH_ONLY 0
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

/* Visits every tile an item may touch: the tiles of its bounds, for triangles only those the
 * edge test cannot reject. Setup counts with it, binning fills with it: same tiles both times. */
#define RP_FOR_ITEM_TILES(view, bounds, is_triangle, tri, BODY)                                  \
  do {                                                                                           \
    if ((bounds).x <= (bounds).z && (bounds).y <= (bounds).w) {                                  \
      RasterEdges frame_edges;                                                                   \
      float fox = (float)(bounds).x, foy = (float)(bounds).y;                                    \
      if (is_triangle) frame_edges = rp_raster_edges((tri).v[0], (tri).v[1], (tri).v[2], fox, foy); \
      int tx0 = (bounds).x / RP_TILE, ty0 = (bounds).y / RP_TILE;                                \
      int tx1 = (bounds).z / RP_TILE, ty1 = (bounds).w / RP_TILE;                                \
      for (int ty = ty0; ty <= ty1; ++ty) {                                                      \
        for (int tx = tx0; tx <= tx1; ++tx) {                                                    \
          if (is_triangle &&                                                                     \
              !rp_raster_rect_may_overlap(frame_edges, (float)(tx * RP_TILE) + 0.5f * RP_TILE - fox, \
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

__kernel __attribute__((reqd_work_group_size(RP_ITEM_GROUP, 1, 1)))
void visibility_setup(const RasterView view, __global const uint2* draw_items,
                      __global const Instance* instances, __global const Triangle* triangles,
                      __global const Vertex* vertices, __global const Sphere* spheres,
                      __global RasterTriangle* tris_out, __global int4* bounds_out,
                      __global uint* tile_counts) {
  uint item = get_global_id(0);
  uint triangle_items = view.triangle_items;
  if (item >= triangle_items + view.sphere_count) return;
  float half_w = 0.5f * (float)view.width, half_h = 0.5f * (float)view.height;
  uint tile_count = view.tiles_x * view.tiles_y;

  if (item < triangle_items) {
    uint2 d = draw_items[item];
    __global const Instance* inst = &instances[d.x];
    const rp_mat4 model = inst->model;
    Triangle t = triangles[d.y];
    float4 clip[3];
    uint idx[3] = {t.x, t.y, t.z};
    for (int i = 0; i < 3; ++i) {
      float4 p = vertices[idx[i]].position_u;
      p.w = 1.0f; /* position_u.w holds the texture u */
      clip[i] = rp_raster_transform(view.view_proj, rp_raster_transform(model, p));
    }
    RasterTriangle rt;
    for (int i = 0; i < 3; ++i) rt.v[i] = rp_to_pixel_space(clip[i], half_w, half_h);
    rt.info = (uint4)(d.x, d.y - inst->first_triangle, 0u, 0u);
    int4 bounds = RP_EMPTY_BOUNDS;
#if RP_DEPTH_ONLY
    bool drawn = inst->casts_shadow != 0u;
#else
    bool drawn = true;
#endif
    if (drawn && !rp_outside_frustum(clip, 3)) bounds = rp_triangle_bounds(rt.v, view.width, view.height);
    tris_out[item] = rt;
    bounds_out[item] = bounds;
    RP_FOR_ITEM_TILES(view, bounds, true, rt, { atomic_inc(&tile_counts[tile]); });
  } else {
    Sphere s = spheres[item - triangle_items];
    int4 bounds = RP_EMPTY_BOUNDS;
#if RP_DEPTH_ONLY
    bool drawn = s.center_radius.w > 0.0f && s.prev_center.w != 0.0f; /* casts shadow */
#else
    bool drawn = s.center_radius.w > 0.0f;
#endif
    if (drawn)
      bounds = rp_sphere_bounds(view.view_proj, s.center_radius, half_w, half_h, view.width,
                                view.height);
    bounds_out[item] = bounds;
    RasterTriangle unused;
    RP_FOR_ITEM_TILES(view, bounds, false, unused,
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
void visibility_bin(const RasterView view, __global const RasterTriangle* tris,
                    __global const int4* bounds_in, __global uint* tile_cursor,
                    __global uint* tile_list) {
  uint item = get_global_id(0);
  uint triangle_items = view.triangle_items;
  if (item >= triangle_items + view.sphere_count) return;
  uint tile_count = view.tiles_x * view.tiles_y;
  int4 bounds = bounds_in[item];
  bool is_triangle = item < triangle_items;
  RasterTriangle rt;
  uint region = 0;
  if (is_triangle)
    rt = tris[item];
  else
    region = tile_count;
  RP_FOR_ITEM_TILES(view, bounds, is_triangle, rt, {
    uint slot = atomic_inc(&tile_cursor[region + tile]);
    if (slot < view.list_capacity) tile_list[slot] = item;
  });
}

/* One work-group per tile, RP_GROUP_W x RP_TILE work-items, each owning RP_SPAN pixels of a
 * row. Items of the tile's lists are set up cooperatively in local memory, RP_BATCH at a time;
 * then every work-item tests its pixels against the batch, keeping its best (z_ndc, item) and,
 * for the camera, the winner's ids and edge values (barycentrics = e1, e2 over their sum). */
__kernel __attribute__((reqd_work_group_size(RP_GROUP_W, RP_TILE, 1)))
void visibility_raster(const RasterView view, __global const RasterTriangle* tris,
                       __global const int4* bounds_in, __global const Sphere* spheres,
                       __global const uint* tile_start, __global const uint* tile_end,
                       __global const uint* tile_list, __global float* depth_out,
                       __global uint* ids_out, __global float* bary_out) {
  __local float4 l_e0[RP_BATCH], l_e1[RP_BATCH], l_e2[RP_BATCH];
  __local float4 l_z[RP_BATCH], l_w[RP_BATCH]; /* vertices' clip z and w (RP_RASTER_DEPTH) */
  __local int4 l_box[RP_BATCH];   /* item bounds in tile pixels (x0, y0, x1, y1) */
  __local int4 l_flags[RP_BATCH]; /* top-left bits of edges 0..2, item, instance, primitive */

  uint tile_x = get_group_id(0), tile_y = get_group_id(1);
  uint tile = tile_y * view.tiles_x + tile_x;
  uint tile_count = view.tiles_x * view.tiles_y;
  uint lid = get_local_id(1) * RP_GROUP_W + get_local_id(0);
  int lx0 = (int)get_local_id(0) * RP_SPAN, ly = (int)get_local_id(1);
  int ox = (int)tile_x * RP_TILE, oy = (int)tile_y * RP_TILE;
  float fox = (float)ox, foy = (float)oy;
  rp_spanf dx = ((float)lx0 + 0.5f) + RP_LANES;
  float dy = (float)ly + 0.5f;

  rp_spanf best_z = (rp_spanf)(1.0f);
  rp_spanu best_key = (rp_spanu)(RP_ID_NONE);
#if !RP_DEPTH_ONLY
  rp_spanu best_instance = (rp_spanu)(RP_ID_NONE), best_primitive = (rp_spanu)(RP_ID_NONE);
  rp_spanf best_e1 = (rp_spanf)(0.0f), best_e2 = (rp_spanf)(0.0f), best_sum = (rp_spanf)(1.0f);
#endif

  /* Triangles: the tile's list, or when the list overflowed (its end is past the capacity the
   * binning could fill) every triangle item; the per-row bounds test then skips the ones that
   * miss the tile, so the result is the same, only slower. */
  uint begin = tile_start[tile], end = tile_end[tile];
  bool every_item = end > view.list_capacity;
  if (every_item) {
    begin = 0u;
    end = view.triangle_items;
  }
  for (uint base = begin; base < end; base += RP_BATCH) {
    uint n = min((uint)RP_BATCH, end - base);
    for (uint k = lid; k < n; k += RP_GROUP_SIZE) {
      uint item = every_item ? base + k : tile_list[base + k];
      RasterTriangle t = tris[item];
      RasterEdges r = rp_raster_edges(t.v[0], t.v[1], t.v[2], fox, foy);
      l_e0[k] = r.e[0];
      l_e1[k] = r.e[1];
      l_e2[k] = r.e[2];
      l_z[k] = (float4)(t.v[0].z, t.v[1].z, t.v[2].z, 0.0f);
      l_w[k] = (float4)(t.v[0].w, t.v[1].w, t.v[2].w, 0.0f);
      l_box[k] = r.top_left.w ? bounds_in[item] - (int4)(ox, oy, ox, oy) : RP_EMPTY_BOUNDS;
      l_flags[k] = (int4)((r.top_left.x & 1) | (r.top_left.y & 2) | (r.top_left.z & 4),
                          (int)item, (int)t.info.x, (int)t.info.y);
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint k = 0; k < n; ++k) {
      int4 box = l_box[k];
      if (ly < box.y || ly > box.w || lx0 + (RP_SPAN - 1) < box.x || lx0 > box.z) continue;
      float4 e0 = l_e0[k], e1 = l_e1[k], e2 = l_e2[k], zv = l_z[k], wv = l_w[k];
      int4 flags = l_flags[k];
      uint key = (uint)flags.y;
      int tl0 = -(flags.x & 1), tl1 = -((flags.x >> 1) & 1), tl2 = -((flags.x >> 2) & 1);
      rp_spanf f0 = e0.x * dx + (e0.y * dy + e0.z);
      rp_spanf f1 = e1.x * dx + (e1.y * dy + e1.z);
      rp_spanf f2 = e2.x * dx + (e2.y * dy + e2.z);
      rp_spanf z = RP_RASTER_DEPTH(f0, f1, f2, zv, wv);
      rp_spani in = ((f0 > 0.0f) | ((f0 == 0.0f) & tl0)) & ((f1 > 0.0f) | ((f1 == 0.0f) & tl1)) &
                    ((f2 > 0.0f) | ((f2 == 0.0f) & tl2)) & (z >= -1.0f) &
                    ((z < best_z) | ((z == best_z) & (key < best_key)));
      best_z = select(best_z, z, in);
      best_key = select(best_key, (rp_spanu)(key), in);
#if !RP_DEPTH_ONLY
      best_instance = select(best_instance, (rp_spanu)((uint)flags.z), in);
      best_primitive = select(best_primitive, (rp_spanu)((uint)flags.w), in);
      best_e1 = select(best_e1, f1, in);
      best_e2 = select(best_e2, f2, in);
      best_sum = select(best_sum, (f0 + f1) + f2, in);
#endif
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }

  /* Spheres: exact intersection of the ray through each pixel centre. */
  begin = tile_start[tile_count + tile];
  end = tile_end[tile_count + tile];
  every_item = end > view.list_capacity;
  if (every_item) {
    begin = view.triangle_items;
    end = view.triangle_items + view.sphere_count;
  }
  if (begin < end) {
    const rp_mat4 inv = view.inv_view_proj, vp = view.view_proj;
    rp_spanf nx = ((float)(ox + lx0) + 0.5f + RP_LANES) * (2.0f / (float)view.width) - 1.0f;
    float ny = 1.0f - ((float)(oy + ly) + 0.5f) * (2.0f / (float)view.height);
    /* points on the near (z_ndc = -1) and far (+1) planes, world space */
#define RP_UNPROJECT(comp, zn) \
  (((inv.c[0].comp * nx + inv.c[1].comp * ny) + inv.c[2].comp * (zn)) + inv.c[3].comp)
    rp_spanf near_w = RP_UNPROJECT(w, -1.0f), far_w = RP_UNPROJECT(w, 1.0f);
    rp_spanf ray_ox = RP_UNPROJECT(x, -1.0f) / near_w, ray_oy = RP_UNPROJECT(y, -1.0f) / near_w,
             ray_oz = RP_UNPROJECT(z, -1.0f) / near_w;
    rp_spanf rx = RP_UNPROJECT(x, 1.0f) / far_w - ray_ox, ry = RP_UNPROJECT(y, 1.0f) / far_w - ray_oy,
             rz = RP_UNPROJECT(z, 1.0f) / far_w - ray_oz;
#undef RP_UNPROJECT
    rp_spanf len = sqrt((rx * rx + ry * ry) + rz * rz);
    rx = rx / len;
    ry = ry / len;
    rz = rz / len;
    /* clip z and w along the ray: linear in the ray parameter t */
    rp_spanf z_o = ((vp.c[0].z * ray_ox + vp.c[1].z * ray_oy) + vp.c[2].z * ray_oz) + vp.c[3].z;
    rp_spanf w_o = ((vp.c[0].w * ray_ox + vp.c[1].w * ray_oy) + vp.c[2].w * ray_oz) + vp.c[3].w;
    rp_spanf z_d = (vp.c[0].z * rx + vp.c[1].z * ry) + vp.c[2].z * rz;
    rp_spanf w_d = (vp.c[0].w * rx + vp.c[1].w * ry) + vp.c[2].w * rz;

    for (uint base = begin; base < end; base += RP_BATCH) {
      uint n = min((uint)RP_BATCH, end - base);
      for (uint k = lid; k < n; k += RP_GROUP_SIZE) {
        uint item = every_item ? base + k : tile_list[base + k];
        uint index = item - view.triangle_items;
        float4 cr = spheres[index].center_radius;
        l_e0[k] = (float4)(cr.xyz, cr.w * cr.w);
        l_box[k] = bounds_in[item] - (int4)(ox, oy, ox, oy);
        l_flags[k] = (int4)(0, (int)item, (int)(RP_ID_SPHERE_BIT | index), 0);
      }
      barrier(CLK_LOCAL_MEM_FENCE);
      for (uint k = 0; k < n; ++k) {
        int4 box = l_box[k];
        if (ly < box.y || ly > box.w || lx0 + (RP_SPAN - 1) < box.x || lx0 > box.z) continue;
        float4 s = l_e0[k];
        int4 flags = l_flags[k];
        uint key = (uint)flags.y;
        rp_spanf cx = ray_ox - s.x, cy = ray_oy - s.y, cz = ray_oz - s.z;
        rp_spanf b = (cx * rx + cy * ry) + cz * rz;
        /* r^2 - squared distance of the centre from the ray (accurate for small spheres) */
        rp_spanf px = cx - b * rx, py = cy - b * ry, pz = cz - b * rz;
        rp_spanf disc = s.w - ((px * px + py * py) + pz * pz);
        rp_spanf root = sqrt(fmax(disc, 0.0f));
        rp_spanf t0 = -b - root;
        rp_spanf t = select(-b + root, t0, t0 >= 0.0f);
        rp_spanf z = (z_o + t * z_d) / (w_o + t * w_d);
        rp_spani in = (disc >= 0.0f) & (t >= 0.0f) & (z >= -1.0f) &
                      ((z < best_z) | ((z == best_z) & (key < best_key)));
        best_z = select(best_z, z, in);
        best_key = select(best_key, (rp_spanu)(key), in);
#if !RP_DEPTH_ONLY
        best_instance = select(best_instance, (rp_spanu)((uint)flags.z), in);
        best_primitive = select(best_primitive, (rp_spanu)(0u), in);
        best_e1 = select(best_e1, (rp_spanf)(0.0f), in);
        best_e2 = select(best_e2, (rp_spanf)(0.0f), in);
        best_sum = select(best_sum, (rp_spanf)(1.0f), in);
#endif
      }
      barrier(CLK_LOCAL_MEM_FENCE);
    }
  }

  /* One write per pixel and plane. */
  int y = oy + ly, x0 = ox + lx0;
  if (y < (int)view.height && x0 < (int)view.width) {
    int valid = min(RP_SPAN, (int)view.width - x0);
    size_t row = (size_t)y * view.width + (size_t)x0;
    rp_store_span_f(best_z * 0.5f + 0.5f, depth_out + row, valid);
#if !RP_DEPTH_ONLY
    rp_store_span_pairs_u(best_instance, best_primitive, ids_out + 2 * row, valid);
    rp_store_span_pairs_f(best_e1 / best_sum, best_e2 / best_sum, bary_out + 2 * row, valid);
#else
    (void)ids_out;
    (void)bary_out;
#endif
  }
}
