/* Voxelize pass (SPEC 6.3): mesh triangles of all instances and analytic spheres -> level 0 of
 * the voxel radiance volume (R^3 float4 over [-1,1]^3, layout shared/voxel_layout.h,
 * coordinates and contents common/voxel.h). Host side: src/passes/voxelize.cpp.
 *
 * Per frame, in order:
 *   voxelize_clear      zero the fixed-point sums, overflow bits and the large-triangle count
 *                       (one work-item per voxel)
 *   voxelize_triangles  one work-item per RP_SPAN consecutive instance triangles, one lane
 *                       each (common/span.h: 16 on CPUs, 1 on GPUs): set-up, the small
 *                       triangles' shading and voxels as vector arithmetic across the lanes;
 *                       large triangles are appended to a list instead
 *   voxelize_large      one work-item (CPUs) or several (GPUs) per listed large triangle,
 *                       lanes = RP_SPAN neighbouring voxel columns of its candidate rectangle
 *   voxelize_spheres    one work-item (CPUs) or several (GPUs) per sphere: every voxel it
 *                       overlaps
 *   voxelize_resolve    sums -> level-0 float4 (one work-item per voxel)
 *   (textures are read as the scene's packed RGBA8 sRGB texels, decoded per tap:
 *   common/span_texture.h)
 * The resolution R is a kernel argument (the host checks it against FrameConstants). Which
 * lane or work-item handles which triangle or voxel changes nothing: the sums are integers.
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
 *   oriented like the vertex normals, the texture sampled at p's interpolated uv, trilinear
 *   in the mip level matching the voxel size (vx_texture_level).
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
 * Coated surfaces: "albedo" above is the material's or sphere's albedo times its
 * albedo.w, the layered base's weight 1 - E_spec_avg (shading::voxel_base_weight; 1 without a
 * coat and for metals): the base's diffuse outgoing radiance averaged over the directions the
 * cones look from. The coat's own reflection of the lamp is view dependent and is left out
 * (E_spec(mu_i) of the light, 4-8 % for the demo's coats).
 *
 * Several bounces: with a bounce grid (common/bounce.h, bounce_cells > 0) every radiance
 * above also reflects the light of earlier bounces, L = albedo * (I * direct(p) + E(p, n)) +
 * emission, E the grid's irradiance / pi at the shading point (a sphere smaller than half a
 * voxel: the mean over its cell's six faces).
 *
 * Accumulation (order independent, DESIGN.md): per voxel RP_VOXEL_ACCUM_WORDS (8) uints. Words
 * 0-3: channel c of (L.rgb * a, a) added as round(min(value, RP_VOXEL_MAX_CONTRIB) *
 * 2^RP_VOXEL_FIXED_BITS) with atomic_add; an add that wraps past 2^32 sets bit c of the voxel's
 * overflow word (atomic_or). Words 4-6: the facing coverage along x, y, z (vx_facing_words,
 * vx_facing_words_all; layout in shared/voxel_layout.h), read by the mip builder for level 1.
 * All of it goes through vx_sink; built with -DRP_VOXEL_FRAGMENTS the same contributions are
 * written as a fragment list for the sparse voxel octree instead (shared/svo_layout.h).
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
#include "shared/pass_params.h"
#include "shared/voxel_layout.h"
#include "shared/svo_layout.h"
#include "common/math.h"
#include "common/voxel_resolve.h"
#include "common/colour.h"
#include "common/direct_light.h"
#include "common/voxel.h"
#include "common/span.h"
#include "common/span_texture.h"
#include "common/alpha_mask.h"
#include "common/bounce.h"
#include "common/punctual_light.h"

#if !defined(RP_VOXEL_FIXED_BITS) || !defined(RP_VOXEL_MAX_CONTRIB) || !defined(RP_VOXEL_SATURATED)
#error "voxelize.cl needs -DRP_VOXEL_FIXED_BITS, -DRP_VOXEL_MAX_CONTRIB, -DRP_VOXEL_SATURATED"
#endif
#define RP_VOXEL_FIXED_SCALE ((float)(1u << RP_VOXEL_FIXED_BITS))

/* Shadow lookup for voxels (a cheap soft shadow): the receiver pushed 1 texel along the normal,
 * 4 taps at (+-RP_VOXEL_SHADOW_SPREAD, +-RP_VOXEL_SHADOW_SPREAD) texels around it (visibility
 * 0, 1/4 .. 1: a penumbra about a voxel wide, 3 texels of a 1024 map at the floor against a
 * voxel of 4.4), compared with 1 texel of depth bias plus a slope bias over the taps' reach
 * (the farthest tap's texel lies up to 1.5 sqrt(2) + 0.7 = 2.8 texels away). */
#define RP_VOXEL_SHADOW_NORMAL_OFFSET 1.0f
#define RP_VOXEL_SHADOW_DEPTH_BIAS 1.0f
#define RP_VOXEL_SHADOW_SPREAD 1.5f
#define RP_VOXEL_SHADOW_REACH 2.8f
/* Triangles whose bounding box spans at most this many voxels along every axis are shaded once,
 * at their centroid (most tumbler triangles); larger ones per voxel. */
#define RP_VOXEL_SMALL_TRIANGLE 2.0f
/* Triangles shaded per voxel with at most this many candidate columns are voxelized in
 * voxelize_triangles' lanes (one triangle a lane); larger ones by voxelize_large. */
#define RP_VOXEL_LANE_COLUMNS 16
/* Margin (grid units) added to a column's plane range when picking candidates. */
#define RP_VOXEL_CANDIDATE_MARGIN (1.0f / 1024.0f)

/* ---- scalar helpers (spheres) ---- */

/* Voxel index range [first, last] along one axis touched by the closed interval [lo, hi]
 * (grid units), clipped to [0, R - 1]; empty when first > last. */
inline int2 vx_axis_range(float lo, float hi, int resolution) {
  const float lim = (float)resolution + 1.0f;
  lo = clamp(lo, -1.0f, lim); /* also maps NaN to a bound: no undefined int conversion */
  hi = clamp(hi, -1.0f, lim);
  return (int2)(max((int)ceil(lo) - 1, 0), min((int)floor(hi), resolution - 1));
}

inline uint vx_fixed(float value) {
  return (uint)(fmin(fmax(value, 0.0f), RP_VOXEL_MAX_CONTRIB) * RP_VOXEL_FIXED_SCALE + 0.5f);
}

/* Adds fixed-point contributions q (r*a, g*a, b*a, a) to voxel `voxel` (see the header). */
inline void vx_add_fixed(volatile __global uint* accum, volatile __global uint* overflow,
                         uint voxel, uint4 q) {
  const uint qs[4] = {q.x, q.y, q.z, q.w};
  for (uint c = 0; c < 4u; ++c) {
    if (qs[c] == 0u) continue;
    const uint old = atomic_add(accum + RP_VOXEL_ACCUM_WORDS * voxel + c, qs[c]);
    if (old > 0xFFFFFFFFu - qs[c]) atomic_or(overflow + voxel, 1u << c);
  }
}

/* The facing coverage words (x, y, z) a surface with normal n (any length, not 0) and opacity
 * a adds to its voxel (see "Facing" in the header): per axis i, round(a |n_i| / max|n| * UNIT)
 * in the half of word i that matches the sign of n_i (0: nothing to add). */
inline uint3 vx_facing_words(float3 n, float a) {
  const float3 an = fabs(n);
  const float scale = a * RP_VOXEL_FACING_UNIT / fmax(fmax(an.x, an.y), an.z);
  const float c[3] = {an.x * scale, an.y * scale, an.z * scale};
  const float s[3] = {n.x, n.y, n.z};
  uint w[3];
  for (uint i = 0; i < 3u; ++i) {
    const uint q = (uint)(fmin(c[i], RP_VOXEL_FACING_UNIT) + 0.5f);
    w[i] = s[i] > 0.0f ? q : q << 16;
  }
  return (uint3)(w[0], w[1], w[2]);
}

/* Facing coverage `a` in every direction (spheres: seen alike from everywhere). */
inline uint3 vx_facing_words_all(float a) {
  const uint q = (uint)(fmin(a, 1.0f) * RP_VOXEL_FACING_UNIT + 0.5f);
  return (uint3)(q | (q << 16));
}

#ifdef RP_VOXEL_FRAGMENTS
/* One fragment (shared/svo_layout.h: 5 words, the opacity and the facing words packed into
 * one: exact for the two kinds vx_sink gets, a plane's at opacity 1 and a sphere's). */
inline void vx_fragment_write(volatile __global uint* frag, uint voxel, uint4 q, uint3 f) {
  frag[0] = q.x;
  frag[1] = q.y;
  frag[2] = q.z;
  frag[RP_SVO_FRAGMENT_COVER] = rp_svo_pack_cover(q.w, f.x, f.y, f.z);
  frag[RP_SVO_FRAGMENT_KEY] = voxel;
}

/* Fragment output (the sparse voxel octree, shared/svo_layout.h): instead of adding into the
 * dense sums, every contribution becomes one fragment of RP_SVO_FRAGMENT_WORDS words (the
 * same four fixed-point words, the three facing words packed, the voxel index) appended to
 * `accum`; overflow[0] counts the fragments (also those past the capacity overflow[1]: the
 * host then grows the list and voxelizes again). Which slot a fragment takes is racy; nothing
 * downstream depends on it (svo.cl ORs flags and adds integers). */
inline void vx_sink(volatile __global uint* accum, volatile __global uint* overflow, uint voxel,
                    uint4 q, uint3 f) {
  if ((q.x | q.y | q.z | q.w | f.x | f.y | f.z) == 0u) return;
  const uint slot = atomic_inc(overflow);
  if (slot >= overflow[1]) return;
  vx_fragment_write(accum + RP_SVO_FRAGMENT_WORDS * slot, voxel, q, f);
}
#else
/* Adds fixed-point contributions q and facing words f to voxel `voxel`'s sums. */
inline void vx_sink(volatile __global uint* accum, volatile __global uint* overflow, uint voxel,
                    uint4 q, uint3 f) {
  vx_add_fixed(accum, overflow, voxel, q);
  const uint fs[3] = {f.x, f.y, f.z};
  for (uint i = 0; i < 3u; ++i)
    if (fs[i] != 0u) atomic_add(accum + RP_VOXEL_ACCUM_WORDS * voxel + 4u + i, fs[i]);
}

/* vx_sink for the sums q of several contributions to one voxel (64-bit: their total can pass
 * 2^32, which sets the channel's overflow bit as the separate adds would have). */
inline void vx_add_wide(volatile __global uint* accum, volatile __global uint* overflow,
                        uint voxel, ulong4 q, uint3 f) {
  const ulong qs[4] = {q.x, q.y, q.z, q.w};
  for (uint c = 0; c < 4u; ++c) {
    if (qs[c] == 0ul) continue;
    const uint low = (uint)qs[c];
    bool wrapped = qs[c] > 0xFFFFFFFFul;
    if (low != 0u) {
      const uint old = atomic_add(accum + RP_VOXEL_ACCUM_WORDS * voxel + c, low);
      wrapped = wrapped || old > 0xFFFFFFFFu - low;
    }
    if (wrapped) atomic_or(overflow + voxel, 1u << c);
  }
  const uint fs[3] = {f.x, f.y, f.z};
  for (uint i = 0; i < 3u; ++i)
    if (fs[i] != 0u) atomic_add(accum + RP_VOXEL_ACCUM_WORDS * voxel + 4u + i, fs[i]);
}
#endif

/* Adds (rgb * a, a) and the facing words f to voxel `voxel`. */
inline void vx_accumulate(volatile __global uint* accum, volatile __global uint* overflow,
                          uint voxel, float3 radiance, float a, uint3 f) {
  const float3 premul = radiance * a;
  vx_sink(accum, overflow, voxel,
          (uint4)(vx_fixed(premul.x), vx_fixed(premul.y), vx_fixed(premul.z), vx_fixed(a)), f);
}

/* Direct light at p (normal n) with the 4 shadow taps; rgb radiance before albedo. */
inline float3 vx_direct(__global const FrameConstants* frame, __global const float* shadow,
                        float3 p, float3 n) {
  float cos_theta;
  const float scale = rp_direct_unshadowed(frame->light_pos, p, n, &cos_theta);
  if (scale <= 0.0f) return (float3)(0.0f);
  const RpShadowLookup s =
      rp_shadow_lookup(frame, p, n, cos_theta, RP_VOXEL_SHADOW_NORMAL_OFFSET,
                       RP_VOXEL_SHADOW_DEPTH_BIAS, RP_VOXEL_SHADOW_REACH);
  const float o = RP_VOXEL_SHADOW_SPREAD;
  const float lit = ((rp_shadow_tap(shadow, &s, (float2)(-o, -o)) +
                      rp_shadow_tap(shadow, &s, (float2)(o, -o))) +
                     (rp_shadow_tap(shadow, &s, (float2)(-o, o)) +
                      rp_shadow_tap(shadow, &s, (float2)(o, o)))) * 0.25f;
  return frame->light_intensity.xyz * (scale * lit);
}

/* ---- span arithmetic: one lane per triangle (voxelize_triangles) or per voxel column
 * (voxelize_large); the same IEEE operations in the same order as the scalar formulas.
 * Functions that also read memory take VxVec arguments by pointer: inlined with by-value
 * struct arguments they carry llvm.experimental.noalias.scope.decl, which oclgrind 21.10
 * cannot run. ---- */

typedef struct {
  rp_spanf x, y, z;
} VxVec;

inline VxVec vxv(rp_spanf x, rp_spanf y, rp_spanf z) {
  VxVec r;
  r.x = x;
  r.y = y;
  r.z = z;
  return r;
}
inline VxVec vxv_add(VxVec a, VxVec b) { return vxv(a.x + b.x, a.y + b.y, a.z + b.z); }
inline VxVec vxv_sub(VxVec a, VxVec b) { return vxv(a.x - b.x, a.y - b.y, a.z - b.z); }
inline VxVec vxv_scale(VxVec a, rp_spanf s) { return vxv(a.x * s, a.y * s, a.z * s); }
inline VxVec vxv_mul(VxVec a, VxVec b) { return vxv(a.x * b.x, a.y * b.y, a.z * b.z); }
inline VxVec vxv_fmin(VxVec a, VxVec b) {
  return vxv(fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z));
}
inline VxVec vxv_fmax(VxVec a, VxVec b) {
  return vxv(fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z));
}
inline VxVec vxv_fabs(VxVec a) { return vxv(fabs(a.x), fabs(a.y), fabs(a.z)); }
inline VxVec vxv_select(VxVec a, VxVec b, rp_spani m) {
  return vxv(select(a.x, b.x, m), select(a.y, b.y, m), select(a.z, b.z, m));
}
/* vx_dot / vx_cross of the scalar code */
inline rp_spanf vxv_dot(VxVec a, VxVec b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
inline VxVec vxv_cross(VxVec a, VxVec b) {
  return vxv(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
/* Projections of p on e x X, e x Y, e x Z. */
inline VxVec vxv_edge_projections(VxVec e, VxVec p) {
  return vxv(e.z * p.y - e.y * p.z, e.x * p.z - e.z * p.x, e.y * p.x - e.x * p.y);
}

/* Voxel index range per lane along one axis (vx_axis_range). */
inline void vx_axis_range_span(rp_spanf lo, rp_spanf hi, int resolution, rp_spani* first,
                               rp_spani* last) {
  const float lim = (float)resolution + 1.0f;
  lo = clamp(lo, -1.0f, lim);
  hi = clamp(hi, -1.0f, lim);
  *first = max(rp_span_convert_int(ceil(lo)) - 1, (rp_spani)(0));
  *last = min(rp_span_convert_int(floor(hi)), (rp_spani)(resolution - 1));
}

/* Largest value of v over lanes with m set (lanes < n); `none` when there is no such lane. */
inline int vx_lane_max(rp_spani v, rp_spani m, int n, int none) {
  int lv[RP_SPAN], lm[RP_SPAN];
  RP_SPAN_TO_ARRAY(v, lv);
  RP_SPAN_TO_ARRAY(m, lm);
  int r = none;
  for (int i = 0; i < n; ++i)
    if (lm[i]) r = max(r, lv[i]);
  return r;
}

/* True when some lane < n has m set. */
inline bool vx_lane_any(rp_spani m, int n) {
  int lm[RP_SPAN];
  RP_SPAN_TO_ARRAY(m, lm);
  bool any = false;
  for (int i = 0; i < n; ++i) any |= lm[i] != 0;
  return any;
}

/* ---- the exact triangle / closed box test (Akenine-Moller separating axes), per lane ----
 * Split into a per-triangle set-up and a cheap per-voxel part. The three box-normal axes are
 * the triangle's voxel range per axis (vx_axis_range_span: exact, from floor/ceil of the
 * bounding box), so only voxels inside it are tested; the other ten axes (the triangle normal
 * and the nine edge x box-axis products) compare the triangle's projection interval
 * [pmin, pmax] with the box centre's projection s and the box radius r on the axis: separated
 * when pmin - s > r or pmax - s < -r. Coordinates are grid units relative to the integer grid
 * point `origin` (the first voxel of the range), so they stay small and the voxel centres
 * (i - origin + 0.5) are exact. Axis k = 3 * edge + j is edge x (X, Y, Z)[j]. */
typedef struct {
  VxVec n;           /* triangle normal, cross(B - A, C - B) */
  rp_spanf n_dist;   /* dot(n, A): the plane's projection */
  rp_spanf n_radius; /* the box's radius on n: 0.5 (|n.x| + |n.y| + |n.z|) */
  VxVec e[3];        /* edges B - A, C - B, A - C */
  rp_spanf pmin[9], pmax[9], radius[9];
} VxAxes;

inline void vx_triangle_axes_span(VxVec A, VxVec B, VxVec C, VxAxes* t) {
  t->e[0] = vxv_sub(B, A);
  t->e[1] = vxv_sub(C, B);
  t->e[2] = vxv_sub(A, C);
  t->n = vxv_cross(t->e[0], t->e[1]);
  t->n_dist = vxv_dot(t->n, A);
  t->n_radius = 0.5f * ((fabs(t->n.x) + fabs(t->n.y)) + fabs(t->n.z));
  for (int i = 0; i < 3; ++i) {
    const VxVec e = t->e[i];
    const VxVec pa = vxv_edge_projections(e, A), pb = vxv_edge_projections(e, B),
                pc = vxv_edge_projections(e, C);
    const VxVec lo = vxv_fmin(vxv_fmin(pa, pb), pc), hi = vxv_fmax(vxv_fmax(pa, pb), pc);
    const VxVec ae = vxv_fabs(e);
    t->pmin[3 * i + 0] = lo.x;
    t->pmin[3 * i + 1] = lo.y;
    t->pmin[3 * i + 2] = lo.z;
    t->pmax[3 * i + 0] = hi.x;
    t->pmax[3 * i + 1] = hi.y;
    t->pmax[3 * i + 2] = hi.z;
    t->radius[3 * i + 0] = 0.5f * (ae.z + ae.y);
    t->radius[3 * i + 1] = 0.5f * (ae.z + ae.x);
    t->radius[3 * i + 2] = 0.5f * (ae.y + ae.x);
  }
}

/* Lanes where no axis separates the triangle from the box of centre c (relative to the
 * origin, half size 0.5). The caller has restricted the voxel to the triangle's range. */
inline rp_spani vx_triangle_box_span(const VxAxes* t, const VxVec* cp) {
  const VxVec c = *cp;
  /* Written as "every axis overlaps" (<=, >=) rather than "not (some axis separates)": the
   * two agree for finite values, and oclgrind 21.10 mis-evaluates negated vector masks. */
  rp_spani overlap = fabs(t->n_dist - vxv_dot(t->n, c)) <= t->n_radius;
  for (int i = 0; i < 3; ++i) {
    const VxVec s = vxv_edge_projections(t->e[i], c);
    const int k = 3 * i;
    overlap &= (t->pmin[k] - s.x <= t->radius[k]) & (t->pmax[k] - s.x >= -t->radius[k]);
    overlap &= (t->pmin[k + 1] - s.y <= t->radius[k + 1]) &
               (t->pmax[k + 1] - s.y >= -t->radius[k + 1]);
    overlap &= (t->pmin[k + 2] - s.z <= t->radius[k + 2]) &
               (t->pmax[k + 2] - s.z >= -t->radius[k + 2]);
  }
  return overlap;
}

/* ---- lighting per lane (vx_direct's formulas, common/direct_light.h) ---- */

/* The frame's lamp and shadow-map constants. */
typedef struct {
  float3 light_pos, intensity; /* light_pos: the lamp disk's centre */
  float disk_a2, disk_ze;
  rp_mat4 lvp;      /* light_view_proj */
  float size_f;     /* shadow map texels per side */
  int size;
  float near, far;  /* light clip planes */
  float texel_den;  /* size * |row 0 of lvp|: a texel is 2 |w| / texel_den world units */
  __global const float4* bounce; /* the bounce grid (common/bounce.h) */
  uint bounce_cells;             /* its cells per side; 0: no bounce light (one bounce) */
  __global const FrameConstants* frame; /* a file scene's punctual lights */
} VxLight;

inline VxLight vx_light(__global const FrameConstants* frame, __global const float4* bounce,
                        uint bounce_cells) {
  VxLight L;
  L.bounce = bounce;
  L.bounce_cells = bounce_cells;
  L.frame = frame;
  /* the lamp disk's centre and a^2 (common/direct_light.h, rp_direct_unshadowed) */
  L.light_pos = frame->light_pos.xyz;
  L.disk_a2 = rp_lamp_disk_a2(frame->light_pos);
  L.disk_ze = frame->light_pos.y - RP_CEILING_Y;
  L.intensity = frame->light_intensity.xyz;
  L.lvp = frame->light_view_proj;
  L.size = (int)frame->shadow_size;
  L.size_f = (float)L.size;
  L.near = frame->clip.z;
  L.far = frame->clip.w;
  L.texel_den = (float)L.size * length(rp_mat4_row(L.lvp, 0).xyz);
  return L;
}

/* Row r of M * (p, 1): ((c0 x + c1 y) + c2 z) + c3, as rp_mat4_mul_point. */
#define VX_ROW_POINT(m, row, p) \
  ((((m).c[0].row * (p).x + (m).c[1].row * (p).y) + (m).c[2].row * (p).z) + (m).c[3].row)

/* Direct light (rgb, before albedo) at p with unit normal n for lanes in `active` (< n_lanes),
 * 0 elsewhere: rp_direct_unshadowed, rp_shadow_lookup and vx_direct's 4 rp_shadow_taps. */
inline VxVec vx_direct_span(const VxLight* L, __global const float* shadow, const VxVec* pp,
                            const VxVec* np, rp_spani active, int n_lanes) {
  const VxVec p = *pp, n = *np;
  const VxVec to_light = vxv(L->light_pos.x - p.x, L->light_pos.y - p.y, L->light_pos.z - p.z);
  const rp_spanf dyd = to_light.y - L->disk_ze;
  const rp_spanf d2 = to_light.x * to_light.x + dyd * dyd + to_light.z * to_light.z;
  const rp_spanf inv_d = rsqrt(vxv_dot(to_light, to_light));
  const VxVec l = vxv_scale(to_light, inv_d);
  const rp_spanf c = vxv_dot(n, l);
  const rp_spanf s = clamp(l.y, 0.0f, 1.0f);
  const rp_spanf falloff =
      mad(s, mad(s, (rp_spanf)(0.204f), (rp_spanf)(0.446f)), (rp_spanf)(0.35f));
  const rp_spanf scale = select((rp_spanf)(0.0f), c * falloff / (d2 + L->disk_a2), c > 0.0f);
  const rp_spani lit = active & (scale > 0.0f);

  /* Shadow: receiver pushed one texel along n, compared in linear light depth. */
  const rp_spanf w0 = VX_ROW_POINT(L->lvp, w, p);
  const rp_spanf texel = 2.0f * fabs(w0) / L->texel_den;
  const rp_spanf cc = fmax(c, 1.0e-4f);
  const rp_spanf tan_theta = fmin(sqrt(fmax(1.0f - cc * cc, 0.0f)) / cc, RP_DIRECT_MAX_SLOPE);
  const VxVec q = vxv_add(p, vxv_scale(n, texel * RP_VOXEL_SHADOW_NORMAL_OFFSET));
  const rp_spanf cx = VX_ROW_POINT(L->lvp, x, q), cy = VX_ROW_POINT(L->lvp, y, q);
  const rp_spanf cz = VX_ROW_POINT(L->lvp, z, q), cw = VX_ROW_POINT(L->lvp, w, q);
  const rp_spanf ndc_x = cx / cw, ndc_y = cy / cw, ndc_z = cz / cw;
  const rp_spani inside =
      (cw > 0.0f) & (fabs(ndc_x) <= 1.0f) & (fabs(ndc_y) <= 1.0f) & (ndc_z <= 1.0f);
  const rp_spanf receiver = cw - texel * (RP_VOXEL_SHADOW_DEPTH_BIAS +
                                          RP_VOXEL_SHADOW_REACH * tan_theta);
  const rp_spanf sx = (ndc_x * 0.5f + 0.5f) * L->size_f;
  const rp_spanf sy = (0.5f - ndc_y * 0.5f) * L->size_f;
  /* Clamped before the int conversion (lanes outside the map may hold any value). Integer
   * clamp with span bounds, not scalar ones: oclgrind 21.10 computes garbage for the
   * (vector, scalar, scalar) integer forms of clamp, min and max. */
  const rp_spani last = (rp_spani)(L->size - 1);
  int index[RP_SPAN], tap[RP_SPAN];
  float depth[RP_SPAN];
  RP_SPAN_TO_ARRAY(lit & inside, tap);
  rp_spanf lit_taps = (rp_spanf)(0.0f);
  for (int k = 0; k < 4; ++k) { /* vx_direct's taps, in its order */
    const float ox = (k & 1) ? RP_VOXEL_SHADOW_SPREAD : -RP_VOXEL_SHADOW_SPREAD;
    const float oy = (k & 2) ? RP_VOXEL_SHADOW_SPREAD : -RP_VOXEL_SHADOW_SPREAD;
    const rp_spani tx = clamp(rp_span_convert_int(floor(clamp(sx + ox, -1.0f, L->size_f))),
                              (rp_spani)(0), last);
    const rp_spani ty = clamp(rp_span_convert_int(floor(clamp(sy + oy, -1.0f, L->size_f))),
                              (rp_spani)(0), last);
    RP_SPAN_TO_ARRAY(ty * L->size + tx, index);
    for (int i = 0; i < RP_SPAN; ++i)
      depth[i] = (i < n_lanes && tap[i]) ? shadow[index[i]] : 1.0f;
    const rp_spanf d = RP_SPAN_FROM_ARRAY(depth);
    const rp_spanf z_ndc = d * 2.0f - 1.0f;
    const rp_spanf lin =
        select(2.0f * L->near * L->far / ((L->far + L->near) - z_ndc * (L->far - L->near)),
               (rp_spanf)(3.0e38f), d >= 1.0f);
    lit_taps += select((rp_spanf)(0.0f), (rp_spanf)(1.0f), receiver <= lin);
  }
  const rp_spanf unshadowed = select((rp_spanf)(1.0f), lit_taps * 0.25f, inside);
  const rp_spanf k = select((rp_spanf)(0.0f), scale * unshadowed, lit);
  return vxv(L->intensity.x * k, L->intensity.y * k, L->intensity.z * k);
}

/* ---- per-triangle data and set-up ---- */

/* A triangle's inputs as the lanes see them (world space). */
typedef struct {
  float3 w0, w1, w2;       /* world vertices */
  float3 nsum;             /* normal_matrix * (n0 + n1 + n2): orients the geometric normal */
  float2 uv0, uv1, uv2;
  float3 albedo, emission;
  float tex_w, tex_h;      /* mip level l0's size (texels), 0 without a texture */
  uint tex_offset;         /* its first texel */
  float tex_w1, tex_h1;    /* level l1 = min(l0 + 1, last level) (vx_texture_level) */
  uint tex_offset1;
  float tex_frac;          /* weight of level l1 */
  uint tex_wrap;           /* RP_WRAP_PACK modes (shared/types.h) */
  uint tri;                /* global triangle index (the alpha test reads it) */
  int masked;              /* -1: an alpha-masked material (common/alpha_mask.h), else 0 */
  int valid;               /* an existing triangle of an instance that is voxelized */
} VxTriangle;

/* The mip level matching the voxel (trilinear, per triangle): the footprint of one voxel side
 * s = 2 / R on the triangle's plane in texels, taken along the plane's direction of largest
 * texture stretch (the larger-axis rule of the screen's trilinear filter): with gu, gv the
 * world-space gradients of the texel coordinates (u W, v H) on the plane, the largest squared
 * stretch is the larger eigenvalue of [[gu.gu, gu.gv], [gu.gv, gv.gv]], and
 * lod = log2(s * sqrt(that)), clamped to [0, levels - 1]. Fills r's level fields. */
inline void vx_texture_level(__global const TextureInfo* info, uint resolution, VxTriangle* r) {
  const float3 e1 = r->w1 - r->w0, e2 = r->w2 - r->w0;
  const float d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2);
  const float inv_den = 1.0f / (d00 * d11 - d01 * d01);
  const float3 gb1 = (e1 * d11 - e2 * d01) * inv_den, gb2 = (e2 * d00 - e1 * d01) * inv_den;
  const float tw = (float)info->width, th = (float)info->height;
  const float3 gu = (gb1 * (r->uv1.x - r->uv0.x) + gb2 * (r->uv2.x - r->uv0.x)) * tw;
  const float3 gv = (gb1 * (r->uv1.y - r->uv0.y) + gb2 * (r->uv2.y - r->uv0.y)) * th;
  const float a = dot(gu, gu), b = dot(gu, gv), c = dot(gv, gv);
  const float h = 0.5f * (a - c);
  const float stretch2 = 0.5f * (a + c) + sqrt(h * h + b * b);
  const float voxel = 2.0f / (float)resolution;
  float lod = 0.5f * log2(stretch2 * (voxel * voxel));
  /* NaN (degenerate triangle) -> 0 */
  lod = fmin(fmax(lod, 0.0f), (float)(info->levels - 1u));
  const float l0f = floor(lod);
  const uint l0 = (uint)l0f, l1 = min(l0 + 1u, info->levels - 1u);
  r->tex_w = (float)max(info->width >> l0, 1u);
  r->tex_h = (float)max(info->height >> l0, 1u);
  r->tex_offset = info->level_offset[l0];
  r->tex_w1 = (float)max(info->width >> l1, 1u);
  r->tex_h1 = (float)max(info->height >> l1, 1u);
  r->tex_offset1 = info->level_offset[l1];
  r->tex_frac = lod - l0f;
  r->tex_wrap = info->wrap;
}

/* Triangle number `flat` in the instance-major order of all instances' voxel triangles (each
 * instance's voxel_first_triangle .. + voxel_triangle_count: its mesh's voxel proxy at this
 * resolution, or the mesh; render::GpuScene picks). `hint`: an
 * instance at or before the triangle's (the walk starts there); receives the triangle's. */
inline VxTriangle vx_fetch_triangle(__global const Instance* instances, uint instance_count,
                                    __global const Vertex* vertices,
                                    __global const Triangle* triangles,
                                    __global const Material* materials,
                                    __global const TextureInfo* textures, uint flat,
                                    uint* hint_index, uint* hint_start, uint resolution) {
  VxTriangle r;
  r.valid = 0;
  /* Instances are few (a box, a lamp, the tumblers): a linear walk is cheap. */
  uint inst_index = *hint_index, start = *hint_start;
  while (inst_index < instance_count &&
         flat - start >= instances[inst_index].voxel_triangle_count) {
    start += instances[inst_index].voxel_triangle_count;
    ++inst_index;
  }
  *hint_index = inst_index;
  *hint_start = start;
  if (inst_index >= instance_count) return r;
  __global const Instance* inst = instances + inst_index;
  if (inst->voxelize == 0u) return r;
  const uint tri_index = inst->voxel_first_triangle + (flat - start);
  const Triangle tri = triangles[tri_index];
  __global const Vertex* vtx0 = vertices + tri.x;
  __global const Vertex* vtx1 = vertices + tri.y;
  __global const Vertex* vtx2 = vertices + tri.z;
  /* vx_transform: ((c0 x + c1 y) + c2 z) + c3 */
  const rp_mat4 model = inst->model;
#define VX_TRANSFORM(p) \
  ((((model.c[0].xyz * (p).x + model.c[1].xyz * (p).y) + model.c[2].xyz * (p).z) + model.c[3].xyz))
  const float3 p0 = vtx0->position_u.xyz, p1 = vtx1->position_u.xyz, p2 = vtx2->position_u.xyz;
  r.w0 = VX_TRANSFORM(p0);
  r.w1 = VX_TRANSFORM(p1);
  r.w2 = VX_TRANSFORM(p2);
#undef VX_TRANSFORM
  r.nsum = rp_mat4_mul_dir(inst->normal_matrix,
                           vtx0->normal_v.xyz + vtx1->normal_v.xyz + vtx2->normal_v.xyz);
  r.uv0 = (float2)(vtx0->position_u.w, vtx0->normal_v.w);
  r.uv1 = (float2)(vtx1->position_u.w, vtx1->normal_v.w);
  r.uv2 = (float2)(vtx2->position_u.w, vtx2->normal_v.w);
  __global const Material* mat = materials + tri.w;
  r.albedo = mat->albedo.xyz * mat->albedo.w; /* w: the coat's base weight (see the header) */
  r.emission = mat->emission.xyz;
  r.tex_w = r.tex_h = r.tex_w1 = r.tex_h1 = r.tex_frac = 0.0f;
  r.tex_offset = r.tex_offset1 = 0u;
  r.tex_wrap = RP_WRAP_REPEAT;
  if (mat->texture != RP_TEXTURE_NONE) vx_texture_level(textures + mat->texture, resolution, &r);
  r.tri = tri_index;
  r.masked = RP_MATERIAL_MASKED(*mat) ? -1 : 0;
  r.valid = -1;
  return r;
}

/* Everything the voxel loops need, per lane. */
typedef struct {
  rp_spani valid;           /* a non-degenerate triangle with a non-empty voxel range */
  rp_spani small, large;    /* shaded once at the centroid / per voxel (complementary masks:
                               oclgrind 21.10 mis-evaluates negated vector masks) */
  VxVec w0, e01, e02;       /* world vertex 0 and edges */
  VxVec nw;                 /* unit geometric normal, oriented like the vertex normals */
  rp_spanf d00, d01, d11, inv_denom; /* barycentric projection (large triangles) */
  VxVec uv_u, uv_v;         /* (uv0, uv1, uv2) u and v components */
  VxVec albedo, emission;
  rp_spani textured;
  rp_spanf tex_w, tex_h, tex_w1, tex_h1, tex_frac;
  rp_spanu tex_offset, tex_offset1, tex_wrap;
  rp_spanu tri;             /* global triangle index */
  rp_spani masked;          /* an alpha-masked material */
  rp_spani origin[3];       /* first voxel of the range per axis */
  VxAxes axes;              /* relative to origin */
  rp_spani dom;             /* dominant axis 0, 1, 2 */
  rp_spani ru0, ru1, rv0, rv1, rd0, rd1; /* voxel ranges along u, v, d (d = dominant) */
  rp_spanf n_u, n_v, a_u, a_v, a_d, inv_nd, half_spread;
} VxSetup;

/* Lane arrays of VxTriangle fields -> spans. */
typedef struct {
  float w[9][RP_SPAN];   /* w0.xyz, w1.xyz, w2.xyz */
  float nsum[3][RP_SPAN];
  float uv[6][RP_SPAN];  /* u0, u1, u2, v0, v1, v2 */
  float albedo[3][RP_SPAN], emission[3][RP_SPAN];
  float tex_w[RP_SPAN], tex_h[RP_SPAN], tex_w1[RP_SPAN], tex_h1[RP_SPAN], tex_frac[RP_SPAN];
  uint tex_offset[RP_SPAN], tex_offset1[RP_SPAN], tex_wrap[RP_SPAN], tri[RP_SPAN];
  int masked[RP_SPAN], valid[RP_SPAN];
} VxLanes;

inline void vx_put_lane(VxLanes* L, int i, const VxTriangle* t) {
  L->w[0][i] = t->w0.x; L->w[1][i] = t->w0.y; L->w[2][i] = t->w0.z;
  L->w[3][i] = t->w1.x; L->w[4][i] = t->w1.y; L->w[5][i] = t->w1.z;
  L->w[6][i] = t->w2.x; L->w[7][i] = t->w2.y; L->w[8][i] = t->w2.z;
  L->nsum[0][i] = t->nsum.x; L->nsum[1][i] = t->nsum.y; L->nsum[2][i] = t->nsum.z;
  L->uv[0][i] = t->uv0.x; L->uv[1][i] = t->uv1.x; L->uv[2][i] = t->uv2.x;
  L->uv[3][i] = t->uv0.y; L->uv[4][i] = t->uv1.y; L->uv[5][i] = t->uv2.y;
  L->albedo[0][i] = t->albedo.x; L->albedo[1][i] = t->albedo.y; L->albedo[2][i] = t->albedo.z;
  L->emission[0][i] = t->emission.x; L->emission[1][i] = t->emission.y;
  L->emission[2][i] = t->emission.z;
  L->tex_w[i] = t->tex_w;
  L->tex_h[i] = t->tex_h;
  L->tex_offset[i] = t->tex_offset;
  L->tex_w1[i] = t->tex_w1;
  L->tex_h1[i] = t->tex_h1;
  L->tex_offset1[i] = t->tex_offset1;
  L->tex_frac[i] = t->tex_frac;
  L->tex_wrap[i] = t->tex_wrap;
  L->tri[i] = t->tri;
  L->masked[i] = t->masked;
  L->valid[i] = t->valid;
}

/* An empty lane (no triangle): finite values, invalid. */
inline void vx_put_empty_lane(VxLanes* L, int i) {
  VxTriangle t;
  t.w0 = t.w1 = t.w2 = t.nsum = t.albedo = t.emission = (float3)(0.0f);
  t.uv0 = t.uv1 = t.uv2 = (float2)(0.0f);
  t.tex_w = t.tex_h = t.tex_w1 = t.tex_h1 = t.tex_frac = 0.0f;
  t.tex_offset = t.tex_offset1 = 0u;
  t.tex_wrap = RP_WRAP_REPEAT;
  t.tri = 0u;
  t.masked = 0;
  t.valid = 0;
  vx_put_lane(L, i, &t);
}

#define VX_SPAN(arr) RP_SPAN_FROM_ARRAY(arr)

inline void vx_setup(const VxLanes* L, uint resolution, VxSetup* s) {
  const VxVec w0 = vxv(VX_SPAN(L->w[0]), VX_SPAN(L->w[1]), VX_SPAN(L->w[2]));
  const VxVec w1 = vxv(VX_SPAN(L->w[3]), VX_SPAN(L->w[4]), VX_SPAN(L->w[5]));
  const VxVec w2 = vxv(VX_SPAN(L->w[6]), VX_SPAN(L->w[7]), VX_SPAN(L->w[8]));
  rp_spani valid = VX_SPAN(L->valid) != 0;

  /* Grid positions and the voxel range per axis (the box-normal axes of the exact test). */
  const float half_r = 0.5f * (float)resolution;
  const int R = (int)resolution;
  const VxVec a = vxv((w0.x + 1.0f) * half_r, (w0.y + 1.0f) * half_r, (w0.z + 1.0f) * half_r);
  const VxVec b = vxv((w1.x + 1.0f) * half_r, (w1.y + 1.0f) * half_r, (w1.z + 1.0f) * half_r);
  const VxVec c = vxv((w2.x + 1.0f) * half_r, (w2.y + 1.0f) * half_r, (w2.z + 1.0f) * half_r);
  const VxVec lo = vxv_fmin(vxv_fmin(a, b), c), hi = vxv_fmax(vxv_fmax(a, b), c);
  rp_spani rx0, rx1, ry0, ry1, rz0, rz1;
  vx_axis_range_span(lo.x, hi.x, R, &rx0, &rx1);
  vx_axis_range_span(lo.y, hi.y, R, &ry0, &ry1);
  vx_axis_range_span(lo.z, hi.z, R, &rz0, &rz1);
  valid &= (rx0 <= rx1) & (ry0 <= ry1) & (rz0 <= rz1);
  s->origin[0] = rx0;
  s->origin[1] = ry0;
  s->origin[2] = rz0;
  const VxVec origin_f =
      vxv(rp_span_convert_float(rx0), rp_span_convert_float(ry0), rp_span_convert_float(rz0));
  vx_triangle_axes_span(vxv_sub(a, origin_f), vxv_sub(b, origin_f), vxv_sub(c, origin_f),
                        &s->axes);
  const VxVec n = s->axes.n;
  const VxVec an = vxv_fabs(n);
  valid &= (an.x != 0.0f) | (an.y != 0.0f) | (an.z != 0.0f); /* else degenerate */

  /* Dominant axis d = argmax |n| (ties: x, then y, then z) and the two others u, v. */
  const rp_spani dom0 = (an.x >= an.y) & (an.x >= an.z);
  const rp_spani dom1 = ((an.x < an.y) | (an.x < an.z)) & (an.y >= an.z); /* not dom0 */
  s->dom = select(select((rp_spani)(2), (rp_spani)(1), dom1), (rp_spani)(0), dom0);
#define VX_UVD(x_, y_, z_, u, v, d) \
  u = select(select(x_, z_, dom1), y_, dom0); \
  v = select(select(y_, x_, dom1), z_, dom0); \
  d = select(select(z_, y_, dom1), x_, dom0)
  rp_spanf n_d, a_u, a_v, a_d;
  VX_UVD(n.x, n.y, n.z, s->n_u, s->n_v, n_d);
  VX_UVD(a.x, a.y, a.z, a_u, a_v, a_d);
  VX_UVD(rx0, ry0, rz0, s->ru0, s->rv0, s->rd0);
  VX_UVD(rx1, ry1, rz1, s->ru1, s->rv1, s->rd1);
#undef VX_UVD
  s->a_u = a_u;
  s->a_v = a_v;
  s->a_d = a_d;
  /* Plane: depth(u, v) = a_d - (n_u (u - a_u) + n_v (v - a_v)) / n_d; over a column square of
   * side 1 it varies by +-half_spread around its value at the square's centre. */
  s->inv_nd = 1.0f / n_d;
  s->half_spread =
      0.5f * (fabs(s->n_u) + fabs(s->n_v)) * fabs(s->inv_nd) + RP_VOXEL_CANDIDATE_MARGIN;

  /* Shading set-up (world space). */
  s->w0 = w0;
  s->e01 = vxv_sub(w1, w0);
  s->e02 = vxv_sub(w2, w0);
  VxVec nw = vxv_cross(s->e01, s->e02);
  nw = vxv_scale(nw, rsqrt(vxv_dot(nw, nw)));
  const VxVec nsum = vxv(VX_SPAN(L->nsum[0]), VX_SPAN(L->nsum[1]), VX_SPAN(L->nsum[2]));
  s->nw = vxv_select(nw, vxv(-nw.x, -nw.y, -nw.z), vxv_dot(nw, nsum) < 0.0f);
  s->d00 = vxv_dot(s->e01, s->e01);
  s->d01 = vxv_dot(s->e01, s->e02);
  s->d11 = vxv_dot(s->e02, s->e02);
  s->inv_denom = 1.0f / (s->d00 * s->d11 - s->d01 * s->d01);
  s->uv_u = vxv(VX_SPAN(L->uv[0]), VX_SPAN(L->uv[1]), VX_SPAN(L->uv[2]));
  s->uv_v = vxv(VX_SPAN(L->uv[3]), VX_SPAN(L->uv[4]), VX_SPAN(L->uv[5]));
  s->albedo = vxv(VX_SPAN(L->albedo[0]), VX_SPAN(L->albedo[1]), VX_SPAN(L->albedo[2]));
  s->emission = vxv(VX_SPAN(L->emission[0]), VX_SPAN(L->emission[1]), VX_SPAN(L->emission[2]));
  s->tex_w = VX_SPAN(L->tex_w);
  s->tex_h = VX_SPAN(L->tex_h);
  s->tex_offset = VX_SPAN(L->tex_offset);
  s->tex_w1 = VX_SPAN(L->tex_w1);
  s->tex_h1 = VX_SPAN(L->tex_h1);
  s->tex_offset1 = VX_SPAN(L->tex_offset1);
  s->tex_frac = VX_SPAN(L->tex_frac);
  s->tex_wrap = VX_SPAN(L->tex_wrap);
  s->tri = VX_SPAN(L->tri);
  s->masked = VX_SPAN(L->masked) != 0;
  s->textured = s->tex_w > 0.0f;

  const VxVec extent = vxv_sub(hi, lo);
  const rp_spanf span_max = fmax(fmax(extent.x, extent.y), extent.z);
  s->small = span_max <= RP_VOXEL_SMALL_TRIANGLE;
  s->large = span_max > RP_VOXEL_SMALL_TRIANGLE;
  s->valid = valid;
}

/* Outgoing radiance of surface points p (unit normal nw, barycentrics b1, b2 for the texture
 * coordinates) of the lanes in `active`: albedo * texture(uv) * direct light + emission. */
/* Albedo (material albedo times the texture at barycentrics (b0, b1, b2)) of the lanes in
 * `active`; the material albedo elsewhere. */
inline VxVec vx_albedo_span(const VxSetup* s, __global const uint* texels, rp_spanf b0,
                            rp_spanf b1, rp_spanf b2, rp_spani active, int n_lanes) {
  rp_spanf r = s->albedo.x, g = s->albedo.y, b = s->albedo.z;
  const rp_spani textured = s->textured & active;
  if (vx_lane_any(textured, n_lanes)) {
    const rp_spanf u = (s->uv_u.x * b0 + s->uv_u.y * b1) + s->uv_u.z * b2;
    const rp_spanf v = (s->uv_v.x * b0 + s->uv_v.y * b1) + s->uv_v.z * b2;
    /* trilinear: levels l0 and l1 of the triangle (vx_texture_level), mixed by tex_frac */
    rp_spanf r0, g0, b0_, r1, g1, b1_;
    rp_span_texture_sample(texels, textured, s->tex_w, s->tex_h, s->tex_offset, s->tex_wrap, u, v,
                           n_lanes, &r0, &g0, &b0_);
    rp_span_texture_sample(texels, textured, s->tex_w1, s->tex_h1, s->tex_offset1, s->tex_wrap, u, v,
                           n_lanes, &r1, &g1, &b1_);
    r = select(r, r * mix(r0, r1, s->tex_frac), textured);
    g = select(g, g * mix(g0, g1, s->tex_frac), textured);
    b = select(b, b * mix(b0_, b1_, s->tex_frac), textured);
  }
  return vxv(r, g, b);
}

/* Light that is evaluated lane by lane (scalar per point), at p with unit normal n for lanes
 * in `active` (< n_lanes), 0 elsewhere; rgb:
 *   punctual 0: the bounce grid's light (irradiance / pi; the caller adds it only when
 *     L->bounce_cells != 0); 2: the same, lanes that share their cells together (CPUs);
 *   punctual 1: a file scene's punctual lights, common/punctual_light.h with one bilinear
 *     shadow comparison per light (the voxels average many surface points, as the lamp's four
 *     taps do), but those flagged RP_LIGHT_NOT_IN_VOXELS. */
inline VxVec vx_lane_light_span(const VxLight* L, __global const float* shadow, const VxVec* p,
                                const VxVec* n, rp_spani active, int n_lanes,
                                const int punctual) {
  float px[RP_SPAN], py[RP_SPAN], pz[RP_SPAN], nx[RP_SPAN], ny[RP_SPAN], nz[RP_SPAN];
  float ex[RP_SPAN], ey[RP_SPAN], ez[RP_SPAN];
  int la[RP_SPAN];
#if RP_SPAN > 1
  if (punctual == 2) {
    /* rp_bounce_irradiance's arithmetic for the lanes at once, a group at a time: the lanes
     * that share the 8 cells around them and the faces their normals pick (the static cache
     * is sorted by voxel, so a span holds one to three such groups), each face loaded once
     * per group instead of once per lane: bit for bit the scalar lookup's result. (A moving
     * object's lanes mostly differ: there it cost more than the lane-by-lane lookup.) */
    const uint cells = L->bounce_cells;
    const float gf = (float)cells;
    const rp_spanf gx = clamp((p->x + 1.0f) * (0.5f * gf) - 0.5f, 0.0f, gf - 1.0f);
    const rp_spanf gy = clamp((p->y + 1.0f) * (0.5f * gf) - 0.5f, 0.0f, gf - 1.0f);
    const rp_spanf gz = clamp((p->z + 1.0f) * (0.5f * gf) - 0.5f, 0.0f, gf - 1.0f);
    const rp_spanf flx = floor(gx), fly = floor(gy), flz = floor(gz);
    const rp_spani pos_x = n->x >= 0.0f, pos_y = n->y >= 0.0f, pos_z = n->z >= 0.0f;
    const rp_spanf ux = gx - flx, uy = gy - fly, uz = gz - flz;
    const rp_spanf wx = n->x * n->x, wy = n->y * n->y, wz = n->z * n->z;
    float cx[RP_SPAN], cy[RP_SPAN], cz[RP_SPAN];
    int sx[RP_SPAN], sy[RP_SPAN], sz[RP_SPAN];
    RP_SPAN_TO_ARRAY(flx, cx);
    RP_SPAN_TO_ARRAY(fly, cy);
    RP_SPAN_TO_ARRAY(flz, cz);
    RP_SPAN_TO_ARRAY(pos_x, sx);
    RP_SPAN_TO_ARRAY(pos_y, sy);
    RP_SPAN_TO_ARRAY(pos_z, sz);
    const rp_spanf zero = 0.0f;
    rp_spanf rr = zero, rg = zero, rb = zero;
    rp_spani todo = active & (rp_span_convert_int(RP_LANES) < n_lanes);
    RP_SPAN_TO_ARRAY(todo, la);
    for (int first = 0; first < RP_SPAN; ++first) {
      if (!la[first]) continue;
      const rp_spani group = todo & (flx == cx[first]) & (fly == cy[first]) &
                             (flz == cz[first]) & (pos_x == sx[first]) & (pos_y == sy[first]) &
                             (pos_z == sz[first]);
      todo &= ~group;
      RP_SPAN_TO_ARRAY(todo, la);
      const uint x0 = (uint)cx[first], y0 = (uint)cy[first], z0 = (uint)cz[first];
      const uint x1 = min(x0 + 1u, cells - 1u), y1 = min(y0 + 1u, cells - 1u);
      const uint z1 = min(z0 + 1u, cells - 1u);
      const uint fx = sx[first] ? RP_DIR_POS_X : RP_DIR_NEG_X;
      const uint fy = sy[first] ? RP_DIR_POS_Y : RP_DIR_NEG_Y;
      const uint fz = sz[first] ? RP_DIR_POS_Z : RP_DIR_NEG_Z;
      rp_spanf sr = zero, sg = zero, sb = zero, weight = zero;
      for (uint c = 0; c < 8u; ++c) {
        const uint x = (c & 1u) ? x1 : x0, y = (c & 2u) ? y1 : y0, z = (c & 4u) ? z1 : z0;
        const rp_spanf wc = ((c & 1u) ? ux : 1.0f - ux) * ((c & 2u) ? uy : 1.0f - uy) *
                            ((c & 4u) ? uz : 1.0f - uz);
        __global const float4* cell = L->bounce + 6u * ((z * cells + y) * cells + x);
        const float4 e[3] = {cell[fx], cell[fy], cell[fz]};
        const rp_spanf w3[3] = {wx, wy, wz};
        for (int a = 0; a < 3; ++a) {
          /* as the scalar lookup, whose skipped faces and cells add exactly 0 */
          const rp_spanf v = e[a].w > 0.0f ? wc * w3[a] : zero;
          sr += v * e[a].x;
          sg += v * e[a].y;
          sb += v * e[a].z;
          weight += v;
        }
      }
      const rp_spani lit = group & (weight > 0.0f);
      rr = select(rr, sr / weight, lit);
      rg = select(rg, sg / weight, lit);
      rb = select(rb, sb / weight, lit);
    }
    return vxv(rr, rg, rb);
  }
#endif
  RP_SPAN_TO_ARRAY(p->x, px);
  RP_SPAN_TO_ARRAY(p->y, py);
  RP_SPAN_TO_ARRAY(p->z, pz);
  RP_SPAN_TO_ARRAY(n->x, nx);
  RP_SPAN_TO_ARRAY(n->y, ny);
  RP_SPAN_TO_ARRAY(n->z, nz);
  RP_SPAN_TO_ARRAY(active, la);
  for (int i = 0; i < RP_SPAN; ++i) {
    float3 e = (float3)(0.0f);
    if (i < n_lanes && la[i]) {
      const float3 pl = (float3)(px[i], py[i], pz[i]), nl = (float3)(nx[i], ny[i], nz[i]);
      if (punctual != 1) {
        e = rp_bounce_irradiance(L->bounce, L->bounce_cells, pl, nl);
      } else {
        for (uint k = 0; k < L->frame->punctual_count; ++k) {
          if ((L->frame->punctual[k].flags & RP_LIGHT_NOT_IN_VOXELS) != 0u) continue;
          float3 l;
          e += rp_punctual_direct(L->frame, shadow, k, pl, nl, 0, &l);
        }
      }
    }
    ex[i] = e.x;
    ey[i] = e.y;
    ez[i] = e.z;
  }
  return vxv(RP_SPAN_FROM_ARRAY(ex), RP_SPAN_FROM_ARRAY(ey), RP_SPAN_FROM_ARRAY(ez));
}

/* The bounce grid's light and the punctual lights at p (vx_lane_light_span; macros, not
 * helpers: another inlined struct-returning level leaves noalias intrinsics that oclgrind
 * 21.10 cannot run). */
#define vx_bounce_span(L, p, n, active, n_lanes) \
  vx_lane_light_span((L), 0, (p), (n), (active), (n_lanes), 0)
#define vx_bounce_span_grouped(L, p, n, active, n_lanes) \
  vx_lane_light_span((L), 0, (p), (n), (active), (n_lanes), 2)
#define vx_punctual_span(L, shadow, p, n, active, n_lanes) \
  vx_lane_light_span((L), (shadow), (p), (n), (active), (n_lanes), 1)

/* Outgoing radiance albedo * (direct + bounce light) + emission at points p with unit
 * normals n. */
inline VxVec vx_radiance_span(const VxLight* L, __global const float* shadow,
                              const VxVec* albedo, const VxVec* p, const VxVec* n,
                              const VxVec* emission, rp_spani active, int n_lanes) {
  VxVec light = vx_direct_span(L, shadow, p, n, active, n_lanes);
  if (L->frame->punctual_count != 0u)
    light = vxv_add(light, vx_punctual_span(L, shadow, p, n, active, n_lanes));
  if (L->bounce_cells != 0u) /* the light of earlier bounces (several bounces) */
    light = vxv_add(light, vx_bounce_span(L, p, n, active, n_lanes));
  return vxv(albedo->x * light.x + emission->x, albedo->y * light.y + emission->y,
             albedo->z * light.z + emission->z);
}

/* Outgoing radiance of surface points p (barycentrics b0, b1, b2 for the texture coordinates)
 * of the lanes in `active`: albedo * texture(uv) * direct light + emission. */
inline VxVec vx_shade_span(const VxSetup* s, const VxLight* L, __global const float* shadow,
                           __global const uint* texels, const VxVec* p, rp_spanf b0,
                           rp_spanf b1, rp_spanf b2, rp_spani active, int n_lanes) {
  const VxVec albedo = vx_albedo_span(s, texels, b0, b1, b2, active, n_lanes);
  return vx_radiance_span(L, shadow, &albedo, p, &s->nw, &s->emission, active, n_lanes);
}

#ifndef RP_VOXEL_FRAGMENTS
/* vx_facing_words(n, 1) of every lane (the same arithmetic as vectors), words x, y, z. */
inline void vx_facing_words_span(const VxVec* n, uint* wx, uint* wy, uint* wz) {
  const rp_spanf ax = fabs(n->x), ay = fabs(n->y), az = fabs(n->z);
  const rp_spanf scale = (1.0f * RP_VOXEL_FACING_UNIT) / fmax(fmax(ax, ay), az);
#define VX_FACING_WORD_SPAN(a, s, out)                                                      \
  {                                                                                         \
    const rp_spanu q = rp_span_convert_uint(fmin((a) * scale, RP_VOXEL_FACING_UNIT) + 0.5f); \
    RP_SPAN_TO_ARRAY(select(q << 16, q, (s) > 0.0f), out);                                  \
  }
  VX_FACING_WORD_SPAN(ax, n->x, wx)
  VX_FACING_WORD_SPAN(ay, n->y, wy)
  VX_FACING_WORD_SPAN(az, n->z, wz)
#undef VX_FACING_WORD_SPAN
}
#endif

/* Adds (radiance, opacity 1) to voxel `voxel` of every lane in `hit`. */
inline void vx_accumulate_span(volatile __global uint* accum, volatile __global uint* overflow,
                               rp_spanu voxel, const VxVec* radiance_p, const VxVec* normal_p,
                               rp_spani hit, int n_lanes) {
  const VxVec radiance = *radiance_p;
  int lh[RP_SPAN];
  RP_SPAN_TO_ARRAY(hit, lh);
  uint lv[RP_SPAN], lr[RP_SPAN], lg[RP_SPAN], lb[RP_SPAN];
  /* vx_fixed per channel (radiance * 1.0 = radiance) */
#define VX_FIXED_SPAN(v) \
  rp_span_convert_uint(fmin(fmax((v), 0.0f), RP_VOXEL_MAX_CONTRIB) * RP_VOXEL_FIXED_SCALE + 0.5f)
  RP_SPAN_TO_ARRAY(VX_FIXED_SPAN(radiance.x), lr);
  RP_SPAN_TO_ARRAY(VX_FIXED_SPAN(radiance.y), lg);
  RP_SPAN_TO_ARRAY(VX_FIXED_SPAN(radiance.z), lb);
#undef VX_FIXED_SPAN
  RP_SPAN_TO_ARRAY(voxel, lv);
  const uint one = vx_fixed(1.0f);
#ifdef RP_VOXEL_FRAGMENTS
  float nx[RP_SPAN], ny[RP_SPAN], nz[RP_SPAN];
  RP_SPAN_TO_ARRAY(normal_p->x, nx);
  RP_SPAN_TO_ARRAY(normal_p->y, ny);
  RP_SPAN_TO_ARRAY(normal_p->z, nz);
  /* one slot reservation for the span's fragments (the counter is the pass's hot spot: one
   * atomic per fragment otherwise); every such fragment has opacity one, never all zero */
  uint hits = 0;
  for (int i = 0; i < n_lanes; ++i) hits += lh[i] ? 1u : 0u;
  if (hits == 0u) return;
  uint slot = atomic_add(overflow, hits);
  for (int i = 0; i < n_lanes; ++i) {
    if (!lh[i]) continue;
    if (slot < overflow[1]) {
      vx_fragment_write(accum + RP_SVO_FRAGMENT_WORDS * slot, lv[i],
                        (uint4)(lr[i], lg[i], lb[i], one),
                        vx_facing_words((float3)(nx[i], ny[i], nz[i]), 1.0f));
    }
    ++slot;
  }
#else
  /* Neighbouring lanes of one voxel (the static cache is sorted by voxel) add their sums
   * before one set of atomics: the same words as one atomic per lane (sums mod 2^32, and
   * vx_add_wide flags the total's overflow as the lanes' adds would). The running sums are
   * scalars: a uint3 kept in memory stalled each lane on its reload. */
  uint lf0[RP_SPAN], lf1[RP_SPAN], lf2[RP_SPAN];
  vx_facing_words_span(normal_p, lf0, lf1, lf2);
  uint voxel_run = 0u, f0 = 0u, f1 = 0u, f2 = 0u;
  ulong r_run = 0ul, g_run = 0ul, b_run = 0ul, a_run = 0ul;
  for (int i = 0; i < n_lanes; ++i) {
    if (!lh[i]) continue;
    if (a_run != 0ul && lv[i] != voxel_run) {
      vx_add_wide(accum, overflow, voxel_run, (ulong4)(r_run, g_run, b_run, a_run),
                  (uint3)(f0, f1, f2));
      r_run = g_run = b_run = a_run = 0ul;
      f0 = f1 = f2 = 0u;
    }
    voxel_run = lv[i];
    r_run += lr[i];
    g_run += lg[i];
    b_run += lb[i];
    a_run += one;
    f0 += lf0[i];
    f1 += lf1[i];
    f2 += lf2[i];
  }
  if (a_run != 0ul)
    vx_add_wide(accum, overflow, voxel_run, (ulong4)(r_run, g_run, b_run, a_run),
                (uint3)(f0, f1, f2));
#endif
}

/* The voxel (x, y, z) of lanes at (iu, iv, id) in their (u, v, d) frame. */
inline void vx_uvd_to_xyz(rp_spani dom, rp_spani iu, rp_spani iv, rp_spani id, rp_spani* x,
                          rp_spani* y, rp_spani* z) {
  const rp_spani d0 = dom == 0, d1 = dom == 1;
  *x = select(select(iu, iv, d1), id, d0);
  *y = select(select(iv, id, d1), iu, d0);
  *z = select(select(id, iu, d1), iv, d0);
}

/* The candidates of column (iu, iv) of the lanes in `col`: [first, last] along d. */
inline void vx_column(const VxSetup* s, rp_spani iu, rp_spani iv, int R, rp_spani* first,
                      rp_spani* last) {
  const rp_spanf depth = s->a_d - (s->n_u * ((rp_span_convert_float(iu) + 0.5f) - s->a_u) +
                                   s->n_v * ((rp_span_convert_float(iv) + 0.5f) - s->a_v)) *
                                      s->inv_nd;
  rp_spani c0, c1;
  vx_axis_range_span(depth - s->half_spread, depth + s->half_spread, R, &c0, &c1);
  *first = max(c0, s->rd0);
  *last = min(c1, s->rd1);
}

/* Shading point of voxels (x, y, z) for triangles shaded per voxel: the voxel centre projected
 * onto the plane, barycentrics clamped into the triangle (negative ones set to 0,
 * renormalised; the centroid for a sliver whose sum is not usable). */
inline VxVec vx_voxel_point(const VxSetup* s, uint resolution, rp_spani x, rp_spani y,
                            rp_spani z, rp_spanf* b0_out, rp_spanf* b1_out, rp_spanf* b2_out) {
  const float to_world = 2.0f / (float)resolution;
  const VxVec centre = vxv((rp_span_convert_float(x) + 0.5f) * to_world - 1.0f,
                           (rp_span_convert_float(y) + 0.5f) * to_world - 1.0f,
                           (rp_span_convert_float(z) + 0.5f) * to_world - 1.0f);
  const VxVec q = vxv_sub(centre, vxv_scale(s->nw, vxv_dot(s->nw, vxv_sub(centre, s->w0))));
  const VxVec rel = vxv_sub(q, s->w0);
  const rp_spanf d20 = vxv_dot(rel, s->e01), d21 = vxv_dot(rel, s->e02);
  rp_spanf b1 = fmax((s->d11 * d20 - s->d01 * d21) * s->inv_denom, 0.0f);
  rp_spanf b2 = fmax((s->d00 * d21 - s->d01 * d20) * s->inv_denom, 0.0f);
  rp_spanf b0 = fmax(1.0f - b1 - b2, 0.0f);
  const rp_spanf b_sum = b0 + b1 + b2;
  const rp_spani usable = (b_sum > 0.0f) & (b_sum < 1.0e30f);
  const float third = 1.0f / 3.0f;
  b0 = select((rp_spanf)(third), b0 / b_sum, usable);
  b1 = select((rp_spanf)(third), b1 / b_sum, usable);
  b2 = select((rp_spanf)(third), b2 / b_sum, usable);
  *b0_out = b0;
  *b1_out = b1;
  *b2_out = b2;
  return vxv_add(vxv_add(s->w0, vxv_scale(s->e01, b1)), vxv_scale(s->e02, b2));
}

/* Radiance of the voxels (x, y, z) of the lanes in `hit` for triangles shaded per voxel. */
inline VxVec vx_voxel_radiance(const VxSetup* s, const VxLight* light,
                               __global const float* shadow,
                               __global const uint* texels, uint resolution,
                               rp_spani x, rp_spani y, rp_spani z, rp_spani hit, int n_lanes) {
  rp_spanf b0, b1, b2;
  const VxVec p = vx_voxel_point(s, resolution, x, y, z, &b0, &b1, &b2);
  return vx_shade_span(s, light, shadow, texels, &p, b0, b1, b2, hit, n_lanes);
}

/* Lanes of `hit` on alpha-masked materials keep only solid surface points (barycentrics b1,
 * b2; common/alpha_mask.h): one point per voxel decides, as a ray would at that point, so a
 * cut-out card (leaves) covers about its solid fraction of the voxels it crosses. One test per
 * distinct triangle among the lanes. */
inline rp_spani vx_alpha_keep(const VxSetup* s, __global const Triangle* triangles,
                              __global const Vertex* vertices,
                              __global const Material* materials,
                              __global const TextureInfo* textures,
                              __global const uint* texels, rp_spanf b1, rp_spanf b2,
                              rp_spani hit) {
  const rp_spani masked = hit & s->masked;
  if (!rp_span_any(masked)) return hit;
  rp_spani keep = select(hit, (rp_spani)(0), masked);
  uint tri[RP_SPAN];
  int todo[RP_SPAN];
  RP_SPAN_TO_ARRAY(s->tri, tri);
  RP_SPAN_TO_ARRAY(masked, todo);
  for (int i = 0; i < RP_SPAN; ++i) {
    if (!todo[i]) continue;
    const rp_spani group = masked & (s->tri == tri[i]);
    int g[RP_SPAN];
    RP_SPAN_TO_ARRAY(group, g);
    for (int j = i; j < RP_SPAN; ++j) todo[j] = todo[j] && !g[j];
    keep |= rp_alpha_solid(triangles, vertices, materials, textures, texels, tri[i], b1, b2,
                           group, RP_SPAN);
  }
  return keep;
}

/* vx_alpha_keep at the shading points of voxels (x, y, z) (triangles shaded per voxel). */
inline rp_spani vx_alpha_keep_voxels(const VxSetup* s, __global const Triangle* triangles,
                                     __global const Vertex* vertices,
                                     __global const Material* materials,
                                     __global const TextureInfo* textures,
                                     __global const uint* texels, uint resolution, rp_spani x,
                                     rp_spani y, rp_spani z, rp_spani hit) {
  if (!rp_span_any(hit & s->masked)) return hit;
  rp_spanf b0, b1, b2;
  (void)vx_voxel_point(s, resolution, x, y, z, &b0, &b1, &b2);
  return vx_alpha_keep(s, triangles, vertices, materials, textures, texels, b1, b2, hit);
}

/* ---- the static surface cache (voxelize_cached; host side in src/passes/voxelize.cpp) ----
 * Per-voxel samples of every triangle of the instances that have not moved: everything but
 * the light (point, normal, albedo * texture, emission), so a frame only adds the light and
 * accumulates. A small triangle gives one sample per voxel it touches, all at its centroid with
 * its centroid's albedo (what VX_ACCUMULATE shades once for all its voxels); a triangle shaded
 * per voxel, one at each voxel's point. Built by voxelize_triangles (small and per-voxel lanes)
 * and voxelize_large in the VX_COUNT and VX_RECORD modes (in no particular order); the samples
 * are computed by the same code as in VX_ACCUMULATE and lit by the same functions, and sums
 * are order independent, so the volume is bit-identical with or without the cache. One sample
 * is 5 float4:
 *   (p.xyz, voxel index as bits), (unit normal, bounce.r), (albedo * texture, bounce.g),
 *   (emission, bounce.b), (direct.rgb, 0)
 * bounce = the bounce grid's light at the sample (irradiance / pi) as of the frame that last
 * refreshed it (0 when recorded); direct = the lamp's and the punctual lights' light at the
 * sample (before albedo) as of the last run that computed it.
 * The bounce grid changes slowly (it blends each frame's gather in at 1/32, kernels/bounce.cl),
 * so voxelize_cached may refresh the bounce light of only one in `refresh_stride` samples per
 * run (those whose voxel hashes to `refresh_phase`) and reuse the stored value for the others
 * (the host cycles the phase over the runs; stride 1 refreshes all: exact, and bit-identical
 * to the per-frame path). The direct light is reused whole (`direct_fresh`) when the host
 * knows that the lights and shadow maps are those of the run that stored it (a still scene
 * under still lights): then the stored value is the one the run would compute. */
#define VX_ACCUMULATE 0u /* shade and accumulate the instances that are not cached */
#define VX_COUNT 1u      /* count the samples of cached instances (and list their large
                            triangles: voxelize_triangles) */
#define VX_RECORD 2u     /* write them (cache_count restarts at 0; the large list is kept) */
#define VX_SAMPLE_FLOAT4S 5u

/* Writes (or counts) one cache sample per lane of `hit`: point p, normal, albedo, emission of
 * the lanes, at their voxel. */
inline void vx_write_samples(const VxVec* p, const VxVec* nrm, const VxVec* albedo,
                             const VxVec* emission, rp_spanu voxel, rp_spani hit, uint record,
                             volatile __global uint* cache_count, __global float4* cache,
                             uint cache_capacity) {
  int lh[RP_SPAN];
  RP_SPAN_TO_ARRAY(hit, lh);
  if (record == VX_COUNT) {
    uint hits = 0;
    for (int i = 0; i < RP_SPAN; ++i) hits += lh[i] != 0;
    if (hits != 0u) atomic_add(cache_count, hits);
    return;
  }
  float v[12][RP_SPAN];
  uint lv[RP_SPAN];
  RP_SPAN_TO_ARRAY(p->x, v[0]);
  RP_SPAN_TO_ARRAY(p->y, v[1]);
  RP_SPAN_TO_ARRAY(p->z, v[2]);
  RP_SPAN_TO_ARRAY(nrm->x, v[3]);
  RP_SPAN_TO_ARRAY(nrm->y, v[4]);
  RP_SPAN_TO_ARRAY(nrm->z, v[5]);
  RP_SPAN_TO_ARRAY(albedo->x, v[6]);
  RP_SPAN_TO_ARRAY(albedo->y, v[7]);
  RP_SPAN_TO_ARRAY(albedo->z, v[8]);
  RP_SPAN_TO_ARRAY(emission->x, v[9]);
  RP_SPAN_TO_ARRAY(emission->y, v[10]);
  RP_SPAN_TO_ARRAY(emission->z, v[11]);
  RP_SPAN_TO_ARRAY(voxel, lv);
  for (int i = 0; i < RP_SPAN; ++i) {
    if (!lh[i]) continue;
    const uint slot = atomic_inc(cache_count);
    if (slot >= cache_capacity) continue; /* the host sized it from VX_COUNT: cannot happen */
    __global float4* q = cache + VX_SAMPLE_FLOAT4S * slot;
    q[0] = (float4)(v[0][i], v[1][i], v[2][i], as_float(lv[i]));
    q[1] = (float4)(v[3][i], v[4][i], v[5][i], 0.0f);
    q[2] = (float4)(v[6][i], v[7][i], v[8][i], 0.0f);
    q[3] = (float4)(v[9][i], v[10][i], v[11][i], 0.0f);
    q[4] = (float4)(0.0f);
  }
}

/* The samples of a large triangle's voxels (x, y, z) of the lanes in `hit`. */
inline void vx_record_samples(const VxSetup* s, __global const uint* texels,
                              uint resolution, rp_spani x, rp_spani y, rp_spani z,
                              rp_spanu voxel, rp_spani hit, uint record,
                              volatile __global uint* cache_count, __global float4* cache,
                              uint cache_capacity) {
  if (record == VX_COUNT) {
    vx_write_samples(0, 0, 0, 0, voxel, hit, record, cache_count, cache, cache_capacity);
    return;
  }
  rp_spanf b0, b1, b2;
  const VxVec p = vx_voxel_point(s, resolution, x, y, z, &b0, &b1, &b2);
  const VxVec albedo = vx_albedo_span(s, texels, b0, b1, b2, hit, RP_SPAN);
  vx_write_samples(&p, &s->nw, &albedo, &s->emission, voxel, hit, record, cache_count, cache,
                   cache_capacity);
}

/* ---- kernels ---- */

__kernel void voxelize_clear(__global uint4* accum, __global uint* overflow, uint voxel_count,
                             __global uint* large_count) {
  const uint i = (uint)get_global_id(0);
  if (i == 0u) large_count[0] = 0u;
  if (i >= voxel_count) return;
  accum[2u * i] = (uint4)(0u);
  accum[2u * i + 1u] = (uint4)(0u);
  overflow[i] = 0u;
}

/* record (params.record): VX_ACCUMULATE shades and accumulates the lanes of instances that are
 * not cached (cached_instances[instance] == 0) and lists their large triangles; VX_COUNT and
 * VX_RECORD count or write the cache samples of the cached instances' small and per-voxel
 * triangles, VX_COUNT listing their large triangles for voxelize_large. */
__kernel void voxelize_triangles(__global const FrameConstants* frame,
                                 __global const Instance* instances,
                                 __global const Vertex* vertices,
                                 __global const Triangle* triangles,
                                 __global const Material* materials,
                                 __global const TextureInfo* textures,
                                 __global const uint* texels,
                                 __global const float* shadow,
                                 volatile __global uint* accum,
                                 volatile __global uint* overflow,
                                 volatile __global uint* large_count,
                                 __global uint* large_list,
                                 __global const uint* cached_instances,
                                 volatile __global uint* cache_count, __global float4* cache,
                                 __global const float4* bounce, const VoxelizeParams params) {
  const uint instance_count = params.instance_count, triangle_total = params.triangle_total;
  const uint resolution = params.resolution, bounce_cells = params.bounce_cells;
  const uint record = params.record, cache_capacity = params.cache_capacity;
  const uint first = (uint)get_global_id(0) * RP_SPAN;
  if (first >= triangle_total) return;
  const int n = (int)min((uint)RP_SPAN, triangle_total - first);
  const int R = (int)resolution;

  VxLanes lanes;
  uint hint_index = 0, hint_start = 0;
  for (int i = 0; i < RP_SPAN; ++i) {
    if (i < n) {
      VxTriangle t = vx_fetch_triangle(instances, instance_count, vertices, triangles,
                                       materials, textures, first + (uint)i, &hint_index,
                                       &hint_start, resolution);
      /* this launch's instances only: the cached ones when counting or recording */
      if (t.valid && (cached_instances[hint_index] != 0u) != (record != VX_ACCUMULATE))
        t.valid = 0;
      vx_put_lane(&lanes, i, &t);
    } else {
      vx_put_empty_lane(&lanes, i);
    }
  }
  VxSetup s;
  vx_setup(&lanes, resolution, &s);

  /* Triangles shaded per voxel with at most RP_VOXEL_LANE_COLUMNS candidate columns (thin
   * ones, like a tumbler's cone) stay in their lane; larger ones go to voxelize_large (lanes
   * over their columns). Either way each voxel gets the same value. */
  const rp_spani columns = (s.ru1 - s.ru0 + 1) * (s.rv1 - s.rv0 + 1);
  const rp_spani per_voxel = s.valid & s.large & (columns <= RP_VOXEL_LANE_COLUMNS);
  if (record != VX_RECORD) {
    int lv[RP_SPAN], ls[RP_SPAN], lp[RP_SPAN];
    RP_SPAN_TO_ARRAY(s.valid, lv);
    RP_SPAN_TO_ARRAY(s.small, ls);
    RP_SPAN_TO_ARRAY(per_voxel, lp);
    for (int i = 0; i < n; ++i)
      if (lv[i] && !ls[i] && !lp[i]) large_list[atomic_inc(large_count)] = first + (uint)i;
  }
  const rp_spani small = s.valid & s.small;
  const rp_spani active = small | per_voxel;
  if (!vx_lane_any(active, n)) return;
  const bool any_per_voxel = vx_lane_any(per_voxel, n);

  /* A small triangle is shaded once, at its centroid, for all its voxels. */
  const VxLight light = vx_light(frame, bounce, bounce_cells);
  const float third = 1.0f / 3.0f;
  const VxVec centroid = vxv_add(vxv_add(s.w0, vxv_scale(s.e01, third)), vxv_scale(s.e02, third));
  const VxVec small_albedo = vx_albedo_span(&s, texels, (rp_spanf)(third), (rp_spanf)(third),
                                            (rp_spanf)(third), small, n);
  const VxVec radiance =
      record == VX_ACCUMULATE
          ? vx_radiance_span(&light, shadow, &small_albedo, &centroid, &s.nw, &s.emission,
                             small, n)
          : vxv((rp_spanf)(0.0f), (rp_spanf)(0.0f), (rp_spanf)(0.0f));
  /* alpha masks: a small triangle exists where its centroid does */
  const bool any_masked = vx_lane_any(s.masked & active, n);
  const rp_spani small_kept =
      any_masked ? vx_alpha_keep(&s, triangles, vertices, materials, textures, texels,
                                 (rp_spanf)(third), (rp_spanf)(third), small)
                 : small;

  /* Every column (iu, iv) of the lanes' candidate rectangles, one or two voxels along d each. */
  const int max_du = vx_lane_max(s.ru1 - s.ru0, active, n, 0);
  const int max_dv = vx_lane_max(s.rv1 - s.rv0, active, n, 0);
  for (int kv = 0; kv <= max_dv; ++kv) {
    for (int ku = 0; ku <= max_du; ++ku) {
      const rp_spani iu = s.ru0 + ku, iv = s.rv0 + kv;
      const rp_spani col = active & (iu <= s.ru1) & (iv <= s.rv1);
      rp_spani d_first, d_last;
      vx_column(&s, iu, iv, R, &d_first, &d_last);
      const int max_dd = vx_lane_max(d_last - d_first, col & (d_first <= d_last), n, -1);
      for (int kd = 0; kd <= max_dd; ++kd) {
        const rp_spani id = d_first + kd;
        rp_spani x, y, z;
        vx_uvd_to_xyz(s.dom, iu, iv, id, &x, &y, &z);
        const VxVec centre = vxv(rp_span_convert_float(x - s.origin[0]) + 0.5f,
                                 rp_span_convert_float(y - s.origin[1]) + 0.5f,
                                 rp_span_convert_float(z - s.origin[2]) + 0.5f);
        rp_spani hit = col & (id <= d_last) & vx_triangle_box_span(&s.axes, &centre);
        if (any_masked)
          hit = (hit & small_kept) |
                vx_alpha_keep_voxels(&s, triangles, vertices, materials, textures, texels,
                                     resolution, x, y, z, hit & per_voxel);
        const rp_spanu voxel = rp_span_convert_uint((z * R + y) * R + x);
        if (record != VX_ACCUMULATE) {
          /* the sample: the centroid's (small), the voxel's point (per voxel) */
          VxVec p = centroid, albedo = small_albedo;
          const rp_spani hit_per_voxel = hit & per_voxel;
          if (record == VX_RECORD && any_per_voxel && vx_lane_any(hit_per_voxel, n)) {
            rp_spanf b0, b1, b2;
            const VxVec pv = vx_voxel_point(&s, resolution, x, y, z, &b0, &b1, &b2);
            const VxVec av = vx_albedo_span(&s, texels, b0, b1, b2, hit_per_voxel, n);
            p = vxv_select(p, pv, per_voxel);
            albedo = vxv_select(albedo, av, per_voxel);
          }
          vx_write_samples(&p, &s.nw, &albedo, &s.emission, voxel, hit, record, cache_count,
                           cache, cache_capacity);
          continue;
        }
        VxVec value = radiance;
        if (any_per_voxel && vx_lane_any(hit & per_voxel, n))
          value = vxv_select(radiance,
                             vx_voxel_radiance(&s, &light, shadow, texels, resolution, x,
                                               y, z, hit & per_voxel, n),
                             per_voxel);
        vx_accumulate_span(accum, overflow, voxel, &value, &s.nw, hit, n);
      }
    }
  }
}

/* One large triangle (flat instance-triangle index `flat`): its set-up is computed for every
 * lane (all lanes the same triangle), the lanes then take RP_SPAN neighbouring columns of a
 * row at a time: the work-item's share, groups number `slice` (0 .. slices - 1) of every
 * `slices` consecutive groups. Each voxel is shaded at its centre projected onto the plane,
 * barycentrics clamped into the triangle. */
inline void vx_large_triangle(__global const FrameConstants* frame,
                              __global const Instance* instances, uint instance_count,
                              __global const Vertex* vertices,
                              __global const Triangle* triangles,
                              __global const Material* materials,
                              __global const TextureInfo* textures,
                              __global const uint* texels,
                              __global const float* shadow, uint resolution,
                              volatile __global uint* accum, volatile __global uint* overflow,
                              uint flat, __global const uint* cached_instances, uint record,
                              volatile __global uint* cache_count, __global float4* cache,
                              uint cache_capacity, __global const float4* bounce,
                              uint bounce_cells, uint slice, uint slices) {
  const int R = (int)resolution;
  uint hint_index = 0, hint_start = 0;
  const VxTriangle t = vx_fetch_triangle(instances, instance_count, vertices, triangles,
                                         materials, textures, flat, &hint_index, &hint_start,
                                         resolution);
  /* A cached instance's samples are shaded by voxelize_cached; recording passes handle only
   * cached instances. */
  if (hint_index >= instance_count) return;
  if ((cached_instances[hint_index] != 0u) != (record != VX_ACCUMULATE)) return;
  VxLanes lanes;
  for (int i = 0; i < RP_SPAN; ++i) vx_put_lane(&lanes, i, &t);
  VxSetup s;
  vx_setup(&lanes, resolution, &s);
  /* All lanes hold the same triangle: its ranges as scalars. */
  int ru0[RP_SPAN], ru1[RP_SPAN], rv0[RP_SPAN], rv1[RP_SPAN], valid[RP_SPAN];
  RP_SPAN_TO_ARRAY(s.ru0, ru0);
  RP_SPAN_TO_ARRAY(s.ru1, ru1);
  RP_SPAN_TO_ARRAY(s.rv0, rv0);
  RP_SPAN_TO_ARRAY(s.rv1, rv1);
  RP_SPAN_TO_ARRAY(s.valid, valid);
  if (!valid[0]) return;
  const bool masked = t.masked != 0;
  const VxLight light = vx_light(frame, bounce, bounce_cells);
  const rp_spani lane = rp_span_convert_int(RP_LANES);

  /* The columns of the candidate rectangle numbered row by row (k = (iv - rv0) * width +
   * iu - ru0), RP_SPAN consecutive numbers at a time, so narrow rectangles fill the lanes. */
  const int width = ru1[0] - ru0[0] + 1, columns = width * (rv1[0] - rv0[0] + 1);
  for (int k0 = (int)slice * RP_SPAN; k0 < columns; k0 += (int)slices * RP_SPAN) {
    {  /* (one block: the loop body of the row-by-row layout) */
      const rp_spani k = k0 + lane;
      /* k / width without a per-lane integer division (exact: k, width < 2^12) */
      const rp_spani row =
          rp_span_convert_int((rp_span_convert_float(k) + 0.5f) * (1.0f / (float)width));
      const rp_spani iu = ru0[0] + (k - row * width), iv = rv0[0] + row;
      const rp_spani col = k < columns;
      rp_spani d_first, d_last;
      vx_column(&s, iu, iv, R, &d_first, &d_last);
      const int max_dd = vx_lane_max(d_last - d_first, col & (d_first <= d_last), RP_SPAN, -1);
      for (int kd = 0; kd <= max_dd; ++kd) {
        const rp_spani id = d_first + kd;
        rp_spani x, y, z;
        vx_uvd_to_xyz(s.dom, iu, iv, id, &x, &y, &z);
        const VxVec box = vxv(rp_span_convert_float(x - s.origin[0]) + 0.5f,
                              rp_span_convert_float(y - s.origin[1]) + 0.5f,
                              rp_span_convert_float(z - s.origin[2]) + 0.5f);
        rp_spani hit = col & (id <= d_last) & vx_triangle_box_span(&s.axes, &box);
        if (masked)
          hit = vx_alpha_keep_voxels(&s, triangles, vertices, materials, textures, texels,
                                     resolution, x, y, z, hit);
        if (!vx_lane_any(hit, RP_SPAN)) continue;

        const rp_spanu voxel = rp_span_convert_uint((z * R + y) * R + x);
        if (record == VX_ACCUMULATE) {
          const VxVec radiance = vx_voxel_radiance(&s, &light, shadow, texels,
                                                   resolution, x, y, z, hit, RP_SPAN);
          vx_accumulate_span(accum, overflow, voxel, &radiance, &s.nw, hit, RP_SPAN);
        } else {
          vx_record_samples(&s, texels, resolution, x, y, z, voxel, hit, record,
                            cache_count, cache, cache_capacity);
        }
      }
    }
  }
}


/* The frame's large triangles (listed by voxelize_triangles), by a fixed number of
 * work-items. */
__kernel void voxelize_large(__global const FrameConstants* frame,
                             __global const Instance* instances,
                             __global const Vertex* vertices,
                             __global const Triangle* triangles,
                             __global const Material* materials,
                             __global const TextureInfo* textures,
                             __global const uint* texels,
                             __global const float* shadow,
                             volatile __global uint* accum,
                             volatile __global uint* overflow,
                             __global const uint* large_count,
                             __global const uint* large_list,
                             __global const uint* cached_instances,
                             volatile __global uint* cache_count, __global float4* cache,
                             __global const float4* bounce, const VoxelizeParams params) {
  const uint instance_count = params.instance_count, resolution = params.resolution;
  const uint record = params.record, cache_capacity = params.cache_capacity;
  const uint bounce_cells = params.bounce_cells, slices = params.slices;
  /* A fixed number of work-items strides over the frame's list (its length is only known on
   * the device), `slices` consecutive work-items sharing each triangle's columns (1 on CPUs;
   * on GPUs a wall at 512^3 is 131k columns, far too many for one thread). The global size
   * is a multiple of `slices`. */
  const uint id = (uint)get_global_id(0), slice = id % slices;
  const uint stride = (uint)get_global_size(0) / slices;
  const uint count = large_count[0];
  for (uint entry = id / slices; entry < count; entry += stride)
    vx_large_triangle(frame, instances, instance_count, vertices, triangles, materials, textures,
                      texels, shadow, resolution, accum, overflow, large_list[entry],
                      cached_instances, record, cache_count, cache, cache_capacity, bounce,
                      bounce_cells, slice, slices);
}

/* The frame's light on the cached samples: RP_SPAN samples per work-item. direct_fresh: the
 * samples' stored direct light is this run's (the host's key: lights, shadow maps, instances
 * and spheres unchanged since it was stored); else it is computed and stored. */
__kernel void voxelize_cached(__global const FrameConstants* frame, __global const float* shadow,
                              __global float4* cache, volatile __global uint* accum,
                              volatile __global uint* overflow, __global const float4* bounce,
                              const VoxelizeParams params) {
  const uint samples = params.samples, bounce_cells = params.bounce_cells;
  const uint refresh_stride = params.refresh_stride, refresh_phase = params.refresh_phase;
  const uint direct_fresh = params.direct_fresh;
  const uint first = (uint)get_global_id(0) * RP_SPAN;
  if (first >= samples) return;
  const int n = (int)min((uint)RP_SPAN, samples - first);
  float v[18][RP_SPAN];
  uint lv[RP_SPAN];
  for (int i = 0; i < RP_SPAN; ++i) {
    const uint k = first + (uint)(i < n ? i : 0);
    __global const float4* q = cache + VX_SAMPLE_FLOAT4S * k;
    const float4 q0 = q[0], q1 = q[1], q2 = q[2], q3 = q[3];
    const float4 q4 = direct_fresh ? q[4] : (float4)(0.0f);
    v[0][i] = q0.x;
    v[1][i] = q0.y;
    v[2][i] = q0.z;
    lv[i] = as_uint(q0.w);
    v[3][i] = q1.x;
    v[4][i] = q1.y;
    v[5][i] = q1.z;
    v[6][i] = q2.x;
    v[7][i] = q2.y;
    v[8][i] = q2.z;
    v[9][i] = q3.x;
    v[10][i] = q3.y;
    v[11][i] = q3.z;
    v[12][i] = q1.w;
    v[13][i] = q2.w;
    v[14][i] = q3.w;
    v[15][i] = q4.x;
    v[16][i] = q4.y;
    v[17][i] = q4.z;
  }
  const VxVec p = vxv(VX_SPAN(v[0]), VX_SPAN(v[1]), VX_SPAN(v[2]));
  const VxVec nrm = vxv(VX_SPAN(v[3]), VX_SPAN(v[4]), VX_SPAN(v[5]));
  const VxVec albedo = vxv(VX_SPAN(v[6]), VX_SPAN(v[7]), VX_SPAN(v[8]));
  const VxVec emission = vxv(VX_SPAN(v[9]), VX_SPAN(v[10]), VX_SPAN(v[11]));
  const rp_spani active = rp_span_convert_int(RP_LANES) < n;
  const VxLight light = vx_light(frame, bounce, bounce_cells);
  VxVec direct;
  if (direct_fresh) {
    direct = vxv(VX_SPAN(v[15]), VX_SPAN(v[16]), VX_SPAN(v[17]));
  } else {
    direct = vx_direct_span(&light, shadow, &p, &nrm, active, n);
    if (frame->punctual_count != 0u)
      direct = vxv_add(direct, vx_punctual_span(&light, shadow, &p, &nrm, active, n));
    float dx[RP_SPAN], dy[RP_SPAN], dz[RP_SPAN];
    RP_SPAN_TO_ARRAY(direct.x, dx);
    RP_SPAN_TO_ARRAY(direct.y, dy);
    RP_SPAN_TO_ARRAY(direct.z, dz);
    for (int i = 0; i < n; ++i)
      cache[VX_SAMPLE_FLOAT4S * (first + (uint)i) + 4u] = (float4)(dx[i], dy[i], dz[i], 0.0f);
  }
  VxVec e = vxv(VX_SPAN(v[12]), VX_SPAN(v[13]), VX_SPAN(v[14]));
  if (bounce_cells != 0u) {
    /* Which samples refresh is a hash of their voxel (16 bits, scaled to [0, stride)), not
     * of their slot (the cache is recorded in no particular order): the volume stays the
     * same run to run. */
    const rp_spanu phase = (rp_spanu)(refresh_phase);
    const rp_spanu slot = (((VX_SPAN(lv) * 2654435761u) >> 16) * refresh_stride) >> 16;
    const rp_spani refresh = active & (slot == phase);
    int lr[RP_SPAN];
    RP_SPAN_TO_ARRAY(refresh, lr);
    const VxVec fresh = vx_bounce_span_grouped(&light, &p, &nrm, refresh, n);
    float ex[RP_SPAN], ey[RP_SPAN], ez[RP_SPAN];
    RP_SPAN_TO_ARRAY(fresh.x, ex);
    RP_SPAN_TO_ARRAY(fresh.y, ey);
    RP_SPAN_TO_ARRAY(fresh.z, ez);
    for (int i = 0; i < n; ++i) {
      if (!lr[i]) continue;
      const uint k = first + (uint)i;
      cache[VX_SAMPLE_FLOAT4S * k + 1u].w = ex[i];
      cache[VX_SAMPLE_FLOAT4S * k + 2u].w = ey[i];
      cache[VX_SAMPLE_FLOAT4S * k + 3u].w = ez[i];
    }
    e = vxv(select(e.x, fresh.x, refresh), select(e.y, fresh.y, refresh),
            select(e.z, fresh.z, refresh));
  }
  /* albedo * (direct + bounce) + emission, as vx_radiance_span (written out: a small inlined
   * helper returning a struct leaves noalias intrinsics that oclgrind 21.10 cannot run) */
  VxVec lit = direct;
  if (bounce_cells != 0u) lit = vxv_add(lit, e);
  const VxVec radiance =
      vxv(albedo.x * lit.x + emission.x, albedo.y * lit.y + emission.y,
          albedo.z * lit.z + emission.z);
  vx_accumulate_span(accum, overflow, VX_SPAN(lv), &radiance, &nrm, active, n);
}

__kernel void voxelize_spheres(__global const FrameConstants* frame,
                               __global const Sphere* spheres, __global const float* shadow,
                               volatile __global uint* accum,
                               volatile __global uint* overflow,
                               __global const float4* bounce, const VoxelizeParams params) {
  const uint sphere_count = params.sphere_count, resolution = params.resolution;
  const uint bounce_cells = params.bounce_cells, slices = params.slices;
  /* `slices` consecutive work-items share a sphere's voxel rows (1 on CPUs; on GPUs a marble
   * at 512^3 is thousands of rows, too many for one thread). */
  const uint gid = (uint)get_global_id(0), slice = gid % slices;
  if (gid / slices >= sphere_count) return;
  __global const Sphere* s = spheres + gid / slices;
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
  const float3 albedo = s->albedo.xyz * s->albedo.w, emission = s->emission.xyz;
  const bool small = rg < 0.5f;

  float3 small_radiance = (float3)(0.0f);
  if (small) { /* the sphere's mean radiance: 1/4 of the light at the point facing the lamp */
    const float3 l = normalize(frame->light_pos.xyz - cw);
    const float3 e =
        bounce_cells != 0u ? rp_bounce_mean(bounce, bounce_cells, cw) : (float3)(0.0f);
    small_radiance =
        albedo * (vx_direct(frame, shadow, cw + l * rw, l) * 0.25f + e) + emission;
  }

  /* The rows (j, k) of the bounding box numbered k-major; this work-item's share. */
  const int ny = max(ry.y - ry.x + 1, 0), rows = max(rz.y - rz.x + 1, 0) * ny;
  for (int row = (int)slice; row < rows; row += (int)slices) {
    const int k = rz.x + row / ny, j = ry.x + row % ny;
    const float fk = (float)k;
    const float dz = fmax(fmax(fk - cg.z, cg.z - (fk + 1.0f)), 0.0f);
    const float fz = (fmin(hi.z, fk + 1.0f) - fmax(lo.z, fk)) * inv_extent;
    {
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
          const float3 e = bounce_cells != 0u
                               ? rp_bounce_irradiance(bounce, bounce_cells, cw + n * rw, n)
                               : (float3)(0.0f);
          radiance = albedo * (vx_direct(frame, shadow, cw + n * rw, n) + e) + emission;
        }
        vx_accumulate(accum, overflow, rp_voxel_index(vox, resolution), radiance, a,
                      vx_facing_words_all(a));
      }
    }
  }
}

__kernel void voxelize_resolve(__global const uint4* accum, __global const uint* overflow,
                               __global float4* level0, uint voxel_count) {
  const uint i = (uint)get_global_id(0);
  if (i >= voxel_count) return;
  level0[i] = rp_voxel_resolve(accum[2u * i], overflow[i]);
}
