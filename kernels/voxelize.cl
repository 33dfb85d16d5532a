/* Voxelize pass (SPEC 6.3): mesh triangles of all instances and analytic spheres -> level 0 of
 * the voxel radiance volume (R^3 float4 over [-1,1]^3, layout shared/voxel_layout.h,
 * coordinates and contents common/voxel.h). Host side: src/passes/voxelize.cpp.
 *
 * Per frame, in order:
 *   voxelize_clear      zero the fixed-point sums and overflow bits (one work-item per voxel)
 *   voxelize_triangles  one work-item per instance triangle: every voxel it overlaps
 *   voxelize_spheres    one work-item per sphere: every voxel it overlaps
 *   voxelize_resolve    sums -> level-0 float4 (one work-item per voxel)
 * The resolution R is a kernel argument (the host checks it against FrameConstants).
 *
 * Triangles. The vertices are transformed to world space and then to grid units (voxel (i,j,k)
 * is the closed box [i,i+1]x[j,j+1]x[k,k+1]). Candidates come from the dominant axis
 * d = argmax |n| (ties: x, then y, then z): for each voxel column of the triangle's bounding
 * box in the two other axes, the range along d where the triangle's plane crosses the column
 * (plus a margin of 1/1024 voxel), clipped to the bounding box: one or two voxels a column.
 * Each candidate is decided by the EXACT separating-axis triangle/box test (Akenine-Moller:
 * 3 box normals, the triangle normal, 9 edge x axis products; vx_triangle_box), so thin and
 * slanted triangles leave no gaps and the touched voxels of a connected mesh are 6-connected.
 * Boxes are closed: a triangle lying exactly on a voxel face touches the voxels on both sides.
 * Triangles with a zero normal (degenerate) are skipped.
 *   Radiance: L = albedo * texture(uv) * I * direct(p) + emission at one surface point p,
 *   direct light with ONE shadow-map lookup (common/direct_light.h), the geometric normal
 *   oriented like the vertex normals, the texture sampled bilinearly at p's interpolated uv.
 *   Where p is: a triangle whose bounding box spans at most RP_VOXEL_SMALL_TRIANGLE voxels
 *   along every axis (tumbler triangles up to R = 128) is shaded once at its centroid for all
 *   its voxels (the voxel then averages its triangles, which filters the texture better than
 *   one point per voxel would); a larger one (walls, floor) per voxel at the voxel centre
 *   projected onto its plane, barycentrics clamped into the triangle (negative ones set to 0,
 *   renormalised). Shading is what costs (texture and shadow lookups): this keeps it to one
 *   per small triangle. Opacity 1.
 *
 * Spheres (marbles, fireballs, particles). Voxel boxes overlapping the sphere (squared distance
 * from the centre to the box <= r^2, in grid units). Opacity per voxel, continuous in r:
 *     a = min(1, pi r^2 * fx * fy * fz)       (r in grid units: pi r^2 = projected area of the
 *                                              sphere over a voxel face)
 * where f_axis = (overlap of [c - r, c + r] with the voxel's interval) / min(2r, 1). A sphere
 * smaller than a voxel thus spreads its projected area over the voxels its bounding box
 * straddles (the f's sum to 1 per axis); a sphere at least a voxel wide gives the voxels inside
 * its bounding box min(1, pi r^2), which is 1 from r = 0.57 voxel on. Radiance, plus emission:
 * r >= 0.5 voxel: per voxel, lit at the sphere point facing the voxel centre (normal = from
 * the sphere centre to the voxel centre, +y when they coincide); r < 0.5 voxel: one value for
 * the whole sphere, its mean over all directions = 1/4 of the light at the point facing the
 * lamp (the mean of max(cos, 0) over a sphere; shadow looked up at that point).
 *
 * Accumulation (order independent, DESIGN.md): per voxel four uint sums, channel c of
 * (L.rgb * a, a) added as round(min(value, RP_VOXEL_MAX_CONTRIB) * 2^RP_VOXEL_FIXED_BITS) with
 * atomic_add; an add that wraps past 2^32 sets bit c of the voxel's overflow word (atomic_or).
 * Zero values are not added. Resolve, with S = sums / 2^bits (an overflowed channel reads
 * RP_VOXEL_SATURATED):
 *     level0 = (S.rgb / max(S.a, 1), min(S.a, 1))
 * i.e. rgb = opacity-weighted mean radiance times the clamped opacity (premultiplied): a voxel
 * with one wall triangle gets (L, 1), three triangles (mean L, 1), a tiny particle (L a, a).
 *
 * Exactness: FP contraction is off so every decision and sum can be repeated bit for bit by
 * the C++ reference in tests/passes/voxelize_reference.cpp (mirror any change there).
 * Fixed-point format from the host (src/render/voxel_volume.h): RP_VOXEL_FIXED_BITS,
 * RP_VOXEL_MAX_CONTRIB, RP_VOXEL_SATURATED.
 */
#pragma OPENCL FP_CONTRACT OFF

#include "shared/types.h"
#include "shared/voxel_layout.h"
#include "common/math.h"
#include "common/sampling.h"
#include "common/direct_light.h"
#include "common/voxel.h"

#if !defined(RP_VOXEL_FIXED_BITS) || !defined(RP_VOXEL_MAX_CONTRIB) || !defined(RP_VOXEL_SATURATED)
#error "voxelize.cl needs -DRP_VOXEL_FIXED_BITS, -DRP_VOXEL_MAX_CONTRIB, -DRP_VOXEL_SATURATED"
#endif
#define RP_VOXEL_FIXED_SCALE ((float)(1u << RP_VOXEL_FIXED_BITS))

/* Shadow lookup for voxels: one tap at the receiver, pushed 1 texel along the normal, 1 texel of
 * depth bias plus 1 texel of slope bias (the tap's texel may be ~0.7 texels away). */
#define RP_VOXEL_SHADOW_NORMAL_OFFSET 1.0f
#define RP_VOXEL_SHADOW_DEPTH_BIAS 1.0f
#define RP_VOXEL_SHADOW_REACH 1.0f
/* Triangles whose bounding box spans at most this many voxels along every axis are shaded once,
 * at their centroid (most tumbler triangles); larger ones per voxel. */
#define RP_VOXEL_SMALL_TRIANGLE 2.0f
/* Margin (grid units) added to a column's plane range when picking candidates. */
#define RP_VOXEL_CANDIDATE_MARGIN (1.0f / 1024.0f)

/* ---- exact arithmetic helpers (fixed operation order, mirrored by the C++ reference) ---- */

inline float3 vx_cross(float3 a, float3 b) {
  return (float3)(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
inline float vx_dot(float3 a, float3 b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }

/* ((c0 x + c1 y) + c2 z) + c3: object point -> world, xyz only. */
inline float3 vx_transform(const rp_mat4 m, float3 p) {
  return ((m.c[0].xyz * p.x + m.c[1].xyz * p.y) + m.c[2].xyz * p.z) + m.c[3].xyz;
}

/* The exact triangle / closed box test (Akenine-Moller separating axes), split into a
 * per-triangle set-up and a cheap per-voxel part. The three box-normal axes are the triangle's
 * voxel range per axis (vx_axis_range: exact, from floor/ceil of the bounding box), so only
 * voxels inside it are tested; the other ten axes (the triangle normal and the nine edge x
 * box-axis products) compare the triangle's projection interval [pmin, pmax] with the box
 * centre's projection s and the box radius r on the axis: separated when pmin - s > r or
 * pmax - s < -r. Coordinates are grid units relative to the integer grid point `origin` (the
 * first voxel of the range), so they stay small and the voxel centres (i - origin + 0.5) are
 * exact. Axis k = 3 * edge + j is edge x (X, Y, Z)[j]: e x X = (0, e.z, -e.y),
 * e x Y = (-e.z, 0, e.x), e x Z = (e.y, -e.x, 0). */
typedef struct {
  float3 n;          /* triangle normal, vx_cross(B - A, C - B) */
  float n_dist;      /* vx_dot(n, A): the plane's projection */
  float n_radius;    /* the box's radius on n: 0.5 (|n.x| + |n.y| + |n.z|) */
  float3 e[3];       /* edges B - A, C - B, A - C */
  float pmin[9], pmax[9], radius[9];
} VxTriangleAxes;

/* Projections of p on e x X, e x Y, e x Z. */
inline float3 vx_edge_projections(float3 e, float3 p) {
  return (float3)(e.z * p.y - e.y * p.z, e.x * p.z - e.z * p.x, e.y * p.x - e.x * p.y);
}

/* Set-up for the triangle (A, B, C) given relative to the origin. */
inline VxTriangleAxes vx_triangle_axes(float3 A, float3 B, float3 C) {
  VxTriangleAxes t;
  t.e[0] = B - A;
  t.e[1] = C - B;
  t.e[2] = A - C;
  t.n = vx_cross(t.e[0], t.e[1]);
  t.n_dist = vx_dot(t.n, A);
  t.n_radius = 0.5f * ((fabs(t.n.x) + fabs(t.n.y)) + fabs(t.n.z));
  for (int i = 0; i < 3; ++i) {
    const float3 e = t.e[i];
    const float3 pa = vx_edge_projections(e, A), pb = vx_edge_projections(e, B),
                 pc = vx_edge_projections(e, C);
    const float3 lo = fmin(fmin(pa, pb), pc), hi = fmax(fmax(pa, pb), pc);
    const float3 ae = fabs(e);
    t.pmin[3 * i + 0] = lo.x;
    t.pmin[3 * i + 1] = lo.y;
    t.pmin[3 * i + 2] = lo.z;
    t.pmax[3 * i + 0] = hi.x;
    t.pmax[3 * i + 1] = hi.y;
    t.pmax[3 * i + 2] = hi.z;
    t.radius[3 * i + 0] = 0.5f * (ae.z + ae.y);
    t.radius[3 * i + 1] = 0.5f * (ae.z + ae.x);
    t.radius[3 * i + 2] = 0.5f * (ae.y + ae.x);
  }
  return t;
}

/* True when no axis separates the triangle from the box of centre c (relative to the origin,
 * half size 0.5). The caller has restricted the voxel to the triangle's voxel range. */
inline bool vx_triangle_box(const VxTriangleAxes* t, float3 c) {
  if (fabs(t->n_dist - vx_dot(t->n, c)) > t->n_radius) return false;
  for (int i = 0; i < 3; ++i) {
    const float3 s = vx_edge_projections(t->e[i], c);
    const int k = 3 * i;
    if (t->pmin[k] - s.x > t->radius[k] || t->pmax[k] - s.x < -t->radius[k]) return false;
    if (t->pmin[k + 1] - s.y > t->radius[k + 1] || t->pmax[k + 1] - s.y < -t->radius[k + 1])
      return false;
    if (t->pmin[k + 2] - s.z > t->radius[k + 2] || t->pmax[k + 2] - s.z < -t->radius[k + 2])
      return false;
  }
  return true;
}

/* Voxel index range [first, last] along one axis touched by the closed interval [lo, hi]
 * (grid units), clipped to [0, R - 1]; empty when first > last. */
inline int2 vx_axis_range(float lo, float hi, int resolution) {
  const float lim = (float)resolution + 1.0f;
  lo = clamp(lo, -1.0f, lim); /* also maps NaN to a bound: no undefined int conversion */
  hi = clamp(hi, -1.0f, lim);
  return (int2)(max((int)ceil(lo) - 1, 0), min((int)floor(hi), resolution - 1));
}

/* ---- accumulation ---- */

inline uint vx_fixed(float value) {
  return (uint)(fmin(fmax(value, 0.0f), RP_VOXEL_MAX_CONTRIB) * RP_VOXEL_FIXED_SCALE + 0.5f);
}

/* Adds (rgb * a, a) to voxel `voxel` (see the header). */
inline void vx_accumulate(volatile __global uint* accum, volatile __global uint* overflow,
                          uint voxel, float3 radiance, float a) {
  const float3 premul = radiance * a;
  const uint q[4] = {vx_fixed(premul.x), vx_fixed(premul.y), vx_fixed(premul.z), vx_fixed(a)};
  for (uint c = 0; c < 4u; ++c) {
    if (q[c] == 0u) continue;
    const uint old = atomic_add(accum + 4u * voxel + c, q[c]);
    if (old > 0xFFFFFFFFu - q[c]) atomic_or(overflow + voxel, 1u << c);
  }
}

/* Direct light at p (normal n) with one shadow tap; rgb radiance before albedo. */
inline float3 vx_direct(__global const FrameConstants* frame, __global const float* shadow,
                        float3 p, float3 n) {
  float cos_theta;
  const float scale = rp_direct_unshadowed(frame->light_pos.xyz, p, n, &cos_theta);
  if (scale <= 0.0f) return (float3)(0.0f);
  const RpShadowLookup s =
      rp_shadow_lookup(frame, p, n, cos_theta, RP_VOXEL_SHADOW_NORMAL_OFFSET,
                       RP_VOXEL_SHADOW_DEPTH_BIAS, RP_VOXEL_SHADOW_REACH);
  return frame->light_intensity.xyz * (scale * rp_shadow_tap(shadow, &s, (float2)(0.0f)));
}

/* Outgoing radiance of a triangle's surface point p (unit normal n, texture coordinates uv;
 * texture 0 = untextured): albedo * texture(uv) * direct light + emission. */
inline float3 vx_shade(__global const FrameConstants* frame, __global const float* shadow,
                       __global const uint* texels, __global const TextureInfo* texture,
                       float3 albedo, float3 emission, float3 p, float3 n, float2 uv) {
  if (texture) albedo *= rp_texture_bilinear(texels, texture, uv).xyz;
  return albedo * vx_direct(frame, shadow, p, n) + emission;
}

__kernel void voxelize_clear(__global uint4* accum, __global uint* overflow, uint voxel_count) {
  const uint i = (uint)get_global_id(0);
  if (i >= voxel_count) return;
  accum[i] = (uint4)(0u);
  overflow[i] = 0u;
}

__kernel void voxelize_triangles(__global const FrameConstants* frame,
                                 __global const Instance* instances, uint instance_count,
                                 uint triangle_total,
                                 __global const Vertex* vertices,
                                 __global const Triangle* triangles,
                                 __global const Material* materials,
                                 __global const TextureInfo* textures,
                                 __global const uint* texels,
                                 __global const float* shadow,
                                 uint resolution,
                                 volatile __global uint* accum,
                                 volatile __global uint* overflow) {
  const uint gid = (uint)get_global_id(0);
  if (gid >= triangle_total) return;
  /* Which instance: instances are few (a box, a lamp, the tumblers), a linear walk is cheap. */
  uint t = gid, inst_index = 0;
  while (inst_index < instance_count && t >= instances[inst_index].triangle_count) {
    t -= instances[inst_index].triangle_count;
    ++inst_index;
  }
  if (inst_index >= instance_count) return;
  __global const Instance* inst = instances + inst_index;
  if (inst->voxelize == 0u) return;
  const Triangle tri = triangles[inst->first_triangle + t];
  __global const Vertex* vtx0 = vertices + tri.x;
  __global const Vertex* vtx1 = vertices + tri.y;
  __global const Vertex* vtx2 = vertices + tri.z;

  /* World and grid positions. */
  const rp_mat4 model = inst->model;
  const float3 w0 = vx_transform(model, vtx0->position_u.xyz);
  const float3 w1 = vx_transform(model, vtx1->position_u.xyz);
  const float3 w2 = vx_transform(model, vtx2->position_u.xyz);
  const float half_r = 0.5f * (float)resolution;
  const float3 a = (w0 + 1.0f) * half_r, b = (w1 + 1.0f) * half_r, c = (w2 + 1.0f) * half_r;
  const int R = (int)resolution;

  /* The voxel range per axis (the box-normal axes of the exact test). */
  const float3 lo = fmin(fmin(a, b), c), hi = fmax(fmax(a, b), c);
  const int2 rx = vx_axis_range(lo.x, hi.x, R);
  const int2 ry = vx_axis_range(lo.y, hi.y, R);
  const int2 rz = vx_axis_range(lo.z, hi.z, R);
  if (rx.x > rx.y || ry.x > ry.y || rz.x > rz.y) return;
  const int3 origin = (int3)(rx.x, ry.x, rz.x);
  const float3 origin_f = convert_float3(origin);
  const VxTriangleAxes axes = vx_triangle_axes(a - origin_f, b - origin_f, c - origin_f);
  const float3 n = axes.n;
  const float3 an = fabs(n);
  if (an.x == 0.0f && an.y == 0.0f && an.z == 0.0f) return; /* degenerate */

  /* Dominant axis d and the two others u, v (as component permutations). */
  const int dom = (an.x >= an.y && an.x >= an.z) ? 0 : (an.y >= an.z ? 1 : 2);
  /* In (u, v, d) order: */
  float3 n_uvd, a_uvd;
  int2 ru, rv, rd;
  if (dom == 0) {
    n_uvd = n.yzx; a_uvd = a.yzx; ru = ry; rv = rz; rd = rx;
  } else if (dom == 1) {
    n_uvd = n.zxy; a_uvd = a.zxy; ru = rz; rv = rx; rd = ry;
  } else {
    n_uvd = n; a_uvd = a; ru = rx; rv = ry; rd = rz;
  }
  /* Plane: depth(u, v) = a_d - (n_u (u - a_u) + n_v (v - a_v)) / n_d; over a column square of
   * side 1 it varies by +-half_spread around its value at the square's centre. */
  const float inv_nd = 1.0f / n_uvd.z;
  const float half_spread =
      0.5f * (fabs(n_uvd.x) + fabs(n_uvd.y)) * fabs(inv_nd) + RP_VOXEL_CANDIDATE_MARGIN;

  /* Shading set-up (world space). */
  const float3 e01 = w1 - w0, e02 = w2 - w0;
  float3 nw = normalize(cross(e01, e02));
  const float3 nsum = rp_mat4_mul_dir(inst->normal_matrix, vtx0->normal_v.xyz +
                                                               vtx1->normal_v.xyz +
                                                               vtx2->normal_v.xyz);
  if (dot(nw, nsum) < 0.0f) nw = -nw;
  const float d00 = dot(e01, e01), d01 = dot(e01, e02), d11 = dot(e02, e02);
  const float inv_denom = 1.0f / (d00 * d11 - d01 * d01);
  const float2 uv0 = (float2)(vtx0->position_u.w, vtx0->normal_v.w);
  const float2 uv1 = (float2)(vtx1->position_u.w, vtx1->normal_v.w);
  const float2 uv2 = (float2)(vtx2->position_u.w, vtx2->normal_v.w);
  __global const Material* mat = materials + tri.w;
  const float3 albedo = mat->albedo.xyz;
  const float3 emission = mat->emission.xyz;
  __global const TextureInfo* texture =
      mat->texture == RP_TEXTURE_NONE ? (__global const TextureInfo*)0 : textures + mat->texture;

  /* A small triangle is shaded once, at its centroid, for all its voxels. */
  const float3 extent = hi - lo;
  const bool small = fmax(fmax(extent.x, extent.y), extent.z) <= RP_VOXEL_SMALL_TRIANGLE;
  float3 radiance = (float3)(0.0f);
  if (small) {
    const float third = 1.0f / 3.0f;
    radiance = vx_shade(frame, shadow, texels, texture, albedo, emission,
                        w0 + e01 * third + e02 * third, nw, uv0 * third + uv1 * third + uv2 * third);
  }

  for (int iv = rv.x; iv <= rv.y; ++iv) {
    for (int iu = ru.x; iu <= ru.y; ++iu) {
      const float depth = a_uvd.z - (n_uvd.x * (((float)iu + 0.5f) - a_uvd.x) +
                                     n_uvd.y * (((float)iv + 0.5f) - a_uvd.y)) * inv_nd;
      const int2 col = vx_axis_range(depth - half_spread, depth + half_spread, R);
      const int d_first = max(col.x, rd.x), d_last = min(col.y, rd.y);
      for (int id = d_first; id <= d_last; ++id) {
        const int3 vox = dom == 0 ? (int3)(id, iu, iv) : dom == 1 ? (int3)(iv, id, iu)
                                                                  : (int3)(iu, iv, id);
        if (!vx_triangle_box(&axes, convert_float3(vox - origin) + 0.5f)) continue;

        if (!small) {
          /* Shading point: the voxel centre on the plane, clamped into the triangle. */
          const float3 centre = rp_voxel_center_world(vox, resolution);
          const float3 q = centre - nw * dot(nw, centre - w0);
          const float3 rel = q - w0;
          const float d20 = dot(rel, e01), d21 = dot(rel, e02);
          float b1 = fmax((d11 * d20 - d01 * d21) * inv_denom, 0.0f);
          float b2 = fmax((d00 * d21 - d01 * d20) * inv_denom, 0.0f);
          float b0 = fmax(1.0f - b1 - b2, 0.0f);
          const float b_sum = b0 + b1 + b2;
          if (b_sum > 0.0f && b_sum < 1.0e30f) { /* else (NaN or inf: a sliver) the centroid */
            b0 /= b_sum;
            b1 /= b_sum;
            b2 /= b_sum;
          } else {
            b0 = b1 = b2 = 1.0f / 3.0f;
          }
          radiance = vx_shade(frame, shadow, texels, texture, albedo, emission,
                              w0 + e01 * b1 + e02 * b2, nw, uv0 * b0 + uv1 * b1 + uv2 * b2);
        }
        vx_accumulate(accum, overflow, rp_voxel_index(vox, resolution), radiance, 1.0f);
      }
    }
  }
}

__kernel void voxelize_spheres(__global const FrameConstants* frame,
                               __global const Sphere* spheres, uint sphere_count,
                               __global const float* shadow,
                               uint resolution,
                               volatile __global uint* accum,
                               volatile __global uint* overflow) {
  const uint gid = (uint)get_global_id(0);
  if (gid >= sphere_count) return;
  __global const Sphere* s = spheres + gid;
  const float3 cw = s->center_radius.xyz;
  const float rw = s->center_radius.w;
  if (!(rw > 0.0f)) return;
  const float half_r = 0.5f * (float)resolution;
  const float3 cg = (cw + 1.0f) * half_r;
  const float rg = rw * half_r;
  const float r2 = rg * rg;
  const float3 lo = cg - rg, hi = cg + rg;
  const int R = (int)resolution;
  const int2 rx = vx_axis_range(lo.x, hi.x, R);
  const int2 ry = vx_axis_range(lo.y, hi.y, R);
  const int2 rz = vx_axis_range(lo.z, hi.z, R);
  /* Projected area (voxel faces) and the per-axis normaliser of the bounding-box overlap. */
  const float area = M_PI_F * r2;
  const float inv_extent = 1.0f / fmin(2.0f * rg, 1.0f);
  const float3 albedo = s->albedo.xyz, emission = s->emission.xyz;
  const bool small = rg < 0.5f;

  float3 small_radiance = (float3)(0.0f);
  if (small) { /* the sphere's mean radiance: 1/4 of the light at the point facing the lamp */
    const float3 l = normalize(frame->light_pos.xyz - cw);
    small_radiance = albedo * (vx_direct(frame, shadow, cw + l * rw, l) * 0.25f) + emission;
  }

  for (int k = rz.x; k <= rz.y; ++k) {
    const float fk = (float)k;
    const float dz = fmax(fmax(fk - cg.z, cg.z - (fk + 1.0f)), 0.0f);
    const float fz = (fmin(hi.z, fk + 1.0f) - fmax(lo.z, fk)) * inv_extent;
    for (int j = ry.x; j <= ry.y; ++j) {
      const float fj = (float)j;
      const float dy = fmax(fmax(fj - cg.y, cg.y - (fj + 1.0f)), 0.0f);
      const float fy = (fmin(hi.y, fj + 1.0f) - fmax(lo.y, fj)) * inv_extent;
      for (int i = rx.x; i <= rx.y; ++i) {
        const float fi = (float)i;
        const float dx = fmax(fmax(fi - cg.x, cg.x - (fi + 1.0f)), 0.0f);
        if ((dx * dx + dy * dy) + dz * dz > r2) continue;
        const float fx = (fmin(hi.x, fi + 1.0f) - fmax(lo.x, fi)) * inv_extent;
        const float a = fmin(((area * fx) * fy) * fz, 1.0f);
        if (!(a > 0.0f)) continue;
        const int3 vox = (int3)(i, j, k);
        float3 radiance = small_radiance;
        if (!small) {
          const float3 to_voxel = rp_voxel_center_world(vox, resolution) - cw;
          const float len2 = dot(to_voxel, to_voxel);
          const float3 n = len2 > 0.0f ? to_voxel * rsqrt(len2) : (float3)(0.0f, 1.0f, 0.0f);
          radiance = albedo * vx_direct(frame, shadow, cw + n * rw, n) + emission;
        }
        vx_accumulate(accum, overflow, rp_voxel_index(vox, resolution), radiance, a);
      }
    }
  }
}

__kernel void voxelize_resolve(__global const uint4* accum, __global const uint* overflow,
                               __global float4* level0, uint voxel_count) {
  const uint i = (uint)get_global_id(0);
  if (i >= voxel_count) return;
  float4 sum = convert_float4(accum[i]) * (1.0f / RP_VOXEL_FIXED_SCALE);
  const uint bits = overflow[i];
  if (bits != 0u) {
    if (bits & 1u) sum.x = RP_VOXEL_SATURATED;
    if (bits & 2u) sum.y = RP_VOXEL_SATURATED;
    if (bits & 4u) sum.z = RP_VOXEL_SATURATED;
    if (bits & 8u) sum.w = RP_VOXEL_SATURATED;
  }
  const float inv = 1.0f / fmax(sum.w, 1.0f);
  level0[i] = (float4)(sum.xyz * inv, fmin(sum.w, 1.0f));
}
