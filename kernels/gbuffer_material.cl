/* GBuffer material pass: a file's per-texel material maps (scene/frame_scene.h Material;
 * kernels/shared/types.h Material.normal_texture, metallic_roughness_texture, emission_texture)
 * applied to what gbuffer_resolve wrote, for the pixels whose material has any. Runs only when
 * some material has such a map (the demo has none). Per pixel, with the triangle and
 * barycentrics of the visibility buffer:
 *
 *   normal map: tangent t = model * (interpolated vertex tangent), made orthogonal to the
 *     GBuffer's normal n, bitangent b = w * cross(n, t), n' = normalize(t x s + b y s + n z)
 *     for the map's (x, y, z) = rgb * 2 - 1 and s = the material's normal scale; where
 *     gbuffer_resolve turned n to the side the camera sees (the interpolated vertex normal
 *     points away from the GBuffer's), n' is built on the vertex normal's side and turned;
 *   metallic-roughness: roughness = factor * G, metallic = factor * B, metal at >= 0.5; the
 *     gloss code (shared/brdf_layout.h) rebuilt from them (dielectrics keep the material's f0);
 *   emission: emission.rgb *= the map (sRGB).
 *
 * The maps are sampled bilinearly at level 0 with the texture's wrap modes, texel centres at
 * +0.5, v up: the path tracer's arithmetic (truth/trace_scene.h LinearTexture), so both see the
 * same surface; the base colour keeps gbuffer_resolve's filtered lookup. Spheres and
 * background are left as they are.
 *
 * One work-item per span of RP_SPAN pixels of a row (common/span.h: the CPU's vector width, 1 on
 * GPUs), a 1D range over the spans in row-major order, as gbuffer_resolve: the span is walked
 * per distinct (instance, primitive), whose triangle, material, maps and matrices are loaded
 * once as scalars and interpolated for all lanes as vectors; the lanes' maps are then sampled
 * together (common/span_texture.h) and the normal and gloss code rebuilt as vector arithmetic.
 * (A per-lane loop with scalar maths took 40 of the atrium's 57 ms GBuffer pass at 720x720.)
 */
#include "shared/types.h"
#include "shared/brdf_layout.h"
#include "common/colour.h"
#include "common/math.h"
#include "common/span.h"
#include "common/span_texture.h"

/* The lanes' map of one kind (normal, metallic-roughness or emission): which lanes have one,
 * and its size, first texel and wrap modes per lane (common/span_texture.h's inputs). */
typedef struct {
  rp_spani on;
  rp_spanf w, h;
  rp_spanu offset, wrap;
} GmMap;

inline GmMap gm_map_none(void) {
  GmMap m;
  m.on = (rp_spani)(0);
  m.w = m.h = (rp_spanf)(1.0f);
  m.offset = (rp_spanu)(0u);
  m.wrap = (rp_spanu)(RP_WRAP_REPEAT);
  return m;
}

/* Texture `texture` (RP_TEXTURE_NONE: none) into the lanes of `group`. */
inline void gm_map_select(GmMap* m, __global const TextureInfo* textures, uint texture,
                          rp_spani group) {
  if (texture == RP_TEXTURE_NONE) return;
  __global const TextureInfo* info = textures + texture;
  m->on |= group;
  m->w = select(m->w, (rp_spanf)((float)info->width), group);
  m->h = select(m->h, (rp_spanf)((float)info->height), group);
  m->offset = select(m->offset, (rp_spanu)(info->offset), group);
  m->wrap = select(m->wrap, (rp_spanu)(info->wrap), group);
}

__kernel void gbuffer_material(__global const FrameConstants* frame,
                               __global const uint* ids,
                               __global const float* bary,
                               __global const Instance* instances,
                               __global const Vertex* vertices,
                               __global const float4* tangents,
                               __global const Triangle* triangles,
                               __global const Material* materials,
                               __global const TextureInfo* textures,
                               __global const uint* texels,
                               __global float* normal_depth,
                               __global float* emission) {
  const uint width = frame->width, height = frame->height;
  const uint spans_per_row = (width + RP_SPAN - 1) / RP_SPAN;
  const uint gid = (uint)get_global_id(0);
  const uint y = gid / spans_per_row, x0 = (gid - y * spans_per_row) * RP_SPAN;
  if (y >= height) return;
  const int n = (int)min((uint)RP_SPAN, width - x0);
  const uint pixel = y * width + x0;
  const uint instance_count = frame->instance_count;

  rp_spanu id_x, id_y;
  rp_load_span_pairs_u(ids + 2 * pixel, n, &id_x, &id_y);
  rp_spanf b1, b2;
  rp_load_span_pairs_f(bary + 2 * pixel, n, &b1, &b2);
  const rp_spanf b0 = 1.0f - b1 - b2;

  /* Per lane: the three maps, uv, and what each map's arithmetic takes from the material and
   * the triangle (lanes without that map keep the neutral values). */
  GmMap nm = gm_map_none(), mr = gm_map_none(), em = gm_map_none();
  rp_spanf tu = 0.0f, tv = 0.0f;
  rp_spanf rough_factor = 0.0f, metal_factor = 0.0f;
  rp_spanf f0_code = 0.0f;  /* 256 * quantised f0 of a dielectric, 0 if it has none */
  rp_spanf normal_scale = 0.0f;
  rp_spanf tx = 0.0f, ty = 0.0f, tz = 0.0f, tsign = 1.0f; /* world tangent, bitangent sign */
  rp_spanf vx = 0.0f, vy = 0.0f, vz = 0.0f;               /* world interpolated vertex normal */

  uint lane_x[RP_SPAN], lane_y[RP_SPAN];
  RP_SPAN_TO_ARRAY(id_x, lane_x);
  RP_SPAN_TO_ARRAY(id_y, lane_y);
  rp_spani done = (rp_spani)(0);
  int lane_done[RP_SPAN];
  RP_SPAN_TO_ARRAY(done, lane_done);
  bool have_maps = false;
  for (int lane = 0; lane < n; ++lane) {
    if (lane_done[lane]) continue;
    const uint a = lane_x[lane], p = lane_y[lane];
    const rp_spani group = (id_x == a) & (id_y == p);
    done |= group;
    RP_SPAN_TO_ARRAY(done, lane_done);
    if (a >= instance_count || p >= instances[a].triangle_count) continue;
    __global const Instance* inst = instances + a;
    const Triangle tri = triangles[inst->first_triangle + p];
    __global const Material* mat = materials + tri.w;
    const uint nmi = mat->normal_texture, mri = mat->metallic_roughness_texture;
    const uint emi = mat->emission_texture;
    if (nmi == RP_TEXTURE_NONE && mri == RP_TEXTURE_NONE && emi == RP_TEXTURE_NONE) continue;
    have_maps = true;
    const float4 p0 = vertices[tri.x].position_u, n0 = vertices[tri.x].normal_v;
    const float4 p1 = vertices[tri.y].position_u, n1 = vertices[tri.y].normal_v;
    const float4 p2 = vertices[tri.z].position_u, n2 = vertices[tri.z].normal_v;
    tu = select(tu, p0.w * b0 + p1.w * b1 + p2.w * b2, group);
    tv = select(tv, n0.w * b0 + n1.w * b1 + n2.w * b2, group);
    gm_map_select(&em, textures, emi, group);
    if (mri != RP_TEXTURE_NONE) {
      gm_map_select(&mr, textures, mri, group);
      const float4 factors = mat->factors;
      rough_factor = select(rough_factor, (rp_spanf)(factors.y), group);
      metal_factor = select(metal_factor, (rp_spanf)(factors.z), group);
      const float code =
          factors.w > 0.0f
              ? (float)(256 * clamp((int)(factors.w * RP_GLOSS_F0_SCALE + 0.5f), 1, 255))
              : 0.0f;
      f0_code = select(f0_code, (rp_spanf)(code), group);
    }
    if (nmi != RP_TEXTURE_NONE) {
      gm_map_select(&nm, textures, nmi, group);
      normal_scale = select(normal_scale, (rp_spanf)(mat->factors.x), group);
      const float4 t0 = tangents[tri.x], t1 = tangents[tri.y], t2 = tangents[tri.z];
      const rp_spanf otx = t0.x * b0 + t1.x * b1 + t2.x * b2;
      const rp_spanf oty = t0.y * b0 + t1.y * b1 + t2.y * b2;
      const rp_spanf otz = t0.z * b0 + t1.z * b1 + t2.z * b2;
      const rp_spanf otw = t0.w * b0 + t1.w * b1 + t2.w * b2;
      const rp_mat4 m = inst->model, nmat = inst->normal_matrix;
      tx = select(tx, RP_MAT4_ROW_DIR(m, x, otx, oty, otz), group);
      ty = select(ty, RP_MAT4_ROW_DIR(m, y, otx, oty, otz), group);
      tz = select(tz, RP_MAT4_ROW_DIR(m, z, otx, oty, otz), group);
      tsign = select(tsign, select((rp_spanf)(1.0f), (rp_spanf)(-1.0f), otw < 0.0f), group);
      const rp_spanf onx = n0.x * b0 + n1.x * b1 + n2.x * b2;
      const rp_spanf ony = n0.y * b0 + n1.y * b1 + n2.y * b2;
      const rp_spanf onz = n0.z * b0 + n1.z * b1 + n2.z * b2;
      vx = select(vx, RP_MAT4_ROW_DIR(nmat, x, onx, ony, onz), group);
      vy = select(vy, RP_MAT4_ROW_DIR(nmat, y, onx, ony, onz), group);
      vz = select(vz, RP_MAT4_ROW_DIR(nmat, z, onx, ony, onz), group);
    }
  }
  if (!have_maps) return;

  const bool any_em = rp_span_any(em.on), any_mr = rp_span_any(mr.on);
  if (any_em || any_mr) {
    rp_spanf er, eg, eb, ew;
    rp_load_span_quads_f(emission + 4 * pixel, n, &er, &eg, &eb, &ew);
    if (any_em) {
      rp_spanf mr_, mg_, mb_;
      rp_span_texture_sample_coded(texels, em.on, em.w, em.h, em.offset, em.wrap, tu, tv, n, 1,
                                   &mr_, &mg_, &mb_);
      er = select(er, er * mr_, em.on);
      eg = select(eg, eg * mg_, em.on);
      eb = select(eb, eb * mb_, em.on);
    }
    if (any_mr) {
      rp_spanf unused, mg_, mb_;
      rp_span_texture_sample_coded(texels, mr.on, mr.w, mr.h, mr.offset, mr.wrap, tu, tv, n, 0,
                                   &unused, &mg_, &mb_);
      /* roughness = factor * G, metal at factor * B >= 0.5: the gloss code */
      const rp_spanf roughness = clamp(rough_factor * mg_, 0.0f, 1.0f);
      const rp_spanf r = rp_span_convert_float(rp_span_convert_int(roughness * 255.0f + 0.5f));
      const rp_spanf code = select(select((rp_spanf)(0.0f), r + f0_code, f0_code > 0.0f),
                                   r + (float)RP_GLOSS_METAL, metal_factor * mb_ >= 0.5f);
      ew = select(ew, code, mr.on);
    }
    rp_store_span_quads_f(er, eg, eb, ew, emission + 4 * pixel, n);
  }
  if (!rp_span_any(nm.on)) return;
  rp_spanf sx, sy, sz;
  rp_span_texture_sample_coded(texels, nm.on, nm.w, nm.h, nm.offset, nm.wrap, tu, tv, n, 0, &sx,
                               &sy, &sz);
  sx = sx * 2.0f - 1.0f;
  sy = sy * 2.0f - 1.0f;
  sz = sz * 2.0f - 1.0f;
  rp_spanf nx, ny, nz, depth;
  rp_load_span_quads_f(normal_depth + 4 * pixel, n, &nx, &ny, &nz, &depth);
  /* the side gbuffer_resolve turned the normal to: the interpolated vertex normal's sign; the
   * map applies on the vertex normal's side */
  const rp_spanf turned =
      select((rp_spanf)(1.0f), (rp_spanf)(-1.0f), vx * nx + vy * ny + vz * nz < 0.0f);
  const rp_spanf ux = nx * turned, uy = ny * turned, uz = nz * turned;
  /* tangent made orthogonal to the normal, bitangent w cross(n, t) */
  const rp_spanf tn = ux * tx + uy * ty + uz * tz;
  tx -= ux * tn;
  ty -= uy * tn;
  tz -= uz * tn;
  const rp_spanf len2 = tx * tx + ty * ty + tz * tz;
  const rp_spanf inv_t = rsqrt(fmax(len2, 1.0e-30f));
  tx *= inv_t;
  ty *= inv_t;
  tz *= inv_t;
  const rp_spanf bx = tsign * (uy * tz - uz * ty);
  const rp_spanf by = tsign * (uz * tx - ux * tz);
  const rp_spanf bz = tsign * (ux * ty - uy * tx);
  const rp_spanf kx = sx * normal_scale, ky = sy * normal_scale;
  const rp_spanf px = tx * kx + bx * ky + ux * sz;
  const rp_spanf py = ty * kx + by * ky + uy * sz;
  const rp_spanf pz = tz * kx + bz * ky + uz * sz;
  const rp_spanf np2 = px * px + py * py + pz * pz;
  const rp_spani mapped = nm.on & (len2 > 1.0e-24f) & (np2 > 1.0e-24f);
  const rp_spanf k = rsqrt(fmax(np2, 1.0e-30f)) * turned;
  nx = select(nx, px * k, mapped);
  ny = select(ny, py * k, mapped);
  nz = select(nz, pz * k, mapped);
  rp_store_span_quads_f(nx, ny, nz, depth, normal_depth + 4 * pixel, n);
}
