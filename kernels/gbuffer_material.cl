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
 * One work-item per RP_SPAN pixels of a row (common/span.h: the CPU's vector width, 1 on GPUs):
 * each lane gathers its pixel's triangle, material and interpolated uv, the lanes' maps are
 * sampled together (common/span_texture.h: per-lane textures, wrap folding and taps as vector
 * arithmetic; the same values as one pixel at a time), and the per-pixel results are then
 * written lane by lane.
 */
#include "shared/types.h"
#include "shared/brdf_layout.h"
#include "common/colour.h"
#include "common/span.h"
#include "common/span_texture.h"

/* Bilinear sample at level 0 of map index[i] for the lanes with has[i] (srgb: decode the codes;
 * else code / 255) at (u, v): rgb into out[3][RP_SPAN]. */
inline void gm_sample_lanes(__global const TextureInfo* textures, __global const uint* texels,
                            const uint* index, const int* has, const float* u, const float* v,
                            int n, int srgb, float out[3][RP_SPAN]) {
  float w[RP_SPAN], h[RP_SPAN];
  uint offset[RP_SPAN], wrap[RP_SPAN];
  int on[RP_SPAN];
  for (int i = 0; i < RP_SPAN; ++i) {
    const bool read = i < n && has[i];
    __global const TextureInfo* info = textures + (read ? index[i] : 0u);
    w[i] = read ? (float)info->width : 1.0f;
    h[i] = read ? (float)info->height : 1.0f;
    offset[i] = read ? info->offset : 0u;
    wrap[i] = read ? info->wrap : RP_WRAP_REPEAT;
    on[i] = read ? -1 : 0;
  }
  rp_spanf r, g, b;
  rp_span_texture_sample_coded(texels, RP_SPAN_FROM_ARRAY(on) != 0, RP_SPAN_FROM_ARRAY(w),
                               RP_SPAN_FROM_ARRAY(h), RP_SPAN_FROM_ARRAY(offset),
                               RP_SPAN_FROM_ARRAY(wrap), RP_SPAN_FROM_ARRAY(u),
                               RP_SPAN_FROM_ARRAY(v), n, srgb, &r, &g, &b);
  RP_SPAN_TO_ARRAY(r, out[0]);
  RP_SPAN_TO_ARRAY(g, out[1]);
  RP_SPAN_TO_ARRAY(b, out[2]);
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
                               __global float4* normal_depth,
                               __global float4* emission) {
  const uint x0 = (uint)get_global_id(0) * RP_SPAN, y = (uint)get_global_id(1);
  const uint width = frame->width;
  if (x0 >= width || y >= frame->height) return;
  const int n = (int)min((uint)RP_SPAN, width - x0);
  /* Per lane: the material, its maps (RP_TEXTURE_NONE: none), uv, the barycentrics. */
  uint mat_index[RP_SPAN], nm[RP_SPAN], mr[RP_SPAN], em[RP_SPAN];
  int has_nm[RP_SPAN], has_mr[RP_SPAN], has_em[RP_SPAN];
  uint tri_x[RP_SPAN], tri_y[RP_SPAN], tri_z[RP_SPAN], inst_index[RP_SPAN];
  float u[RP_SPAN], v[RP_SPAN], b0_[RP_SPAN], b1_[RP_SPAN], b2_[RP_SPAN];
  bool any_nm = false, any_mr = false, any_em = false;
  for (int i = 0; i < RP_SPAN; ++i) {
    has_nm[i] = has_mr[i] = has_em[i] = 0;
    nm[i] = mr[i] = em[i] = mat_index[i] = tri_x[i] = tri_y[i] = tri_z[i] = inst_index[i] = 0u;
    u[i] = v[i] = b0_[i] = b1_[i] = b2_[i] = 0.0f;
    if (i >= n) continue;
    const uint pixel = y * width + x0 + (uint)i;
    const uint a = ids[2 * pixel], p = ids[2 * pixel + 1];
    if (a >= frame->instance_count || p >= instances[a].triangle_count) continue;
    const Triangle tri = triangles[instances[a].first_triangle + p];
    __global const Material* mat = materials + tri.w;
    nm[i] = mat->normal_texture;
    mr[i] = mat->metallic_roughness_texture;
    em[i] = mat->emission_texture;
    has_nm[i] = nm[i] != RP_TEXTURE_NONE;
    has_mr[i] = mr[i] != RP_TEXTURE_NONE;
    has_em[i] = em[i] != RP_TEXTURE_NONE;
    if (!has_nm[i] && !has_mr[i] && !has_em[i]) continue;
    any_nm = any_nm || has_nm[i];
    any_mr = any_mr || has_mr[i];
    any_em = any_em || has_em[i];
    mat_index[i] = tri.w;
    inst_index[i] = a;
    tri_x[i] = tri.x;
    tri_y[i] = tri.y;
    tri_z[i] = tri.z;
    const float b1 = bary[2 * pixel], b2 = bary[2 * pixel + 1], b0 = 1.0f - b1 - b2;
    const float2 uv =
        (float2)(vertices[tri.x].position_u.w, vertices[tri.x].normal_v.w) * b0 +
        (float2)(vertices[tri.y].position_u.w, vertices[tri.y].normal_v.w) * b1 +
        (float2)(vertices[tri.z].position_u.w, vertices[tri.z].normal_v.w) * b2;
    u[i] = uv.x;
    v[i] = uv.y;
    b0_[i] = b0;
    b1_[i] = b1;
    b2_[i] = b2;
  }
  if (!any_nm && !any_mr && !any_em) return;
  float emap[3][RP_SPAN], mrmap[3][RP_SPAN], nmap[3][RP_SPAN];
  if (any_em) gm_sample_lanes(textures, texels, em, has_em, u, v, n, 1, emap);
  if (any_mr) gm_sample_lanes(textures, texels, mr, has_mr, u, v, n, 0, mrmap);
  if (any_nm) gm_sample_lanes(textures, texels, nm, has_nm, u, v, n, 0, nmap);

  for (int i = 0; i < n; ++i) {
    if (!has_nm[i] && !has_mr[i] && !has_em[i]) continue;
    const uint pixel = y * width + x0 + (uint)i;
    __global const Material* mat = materials + mat_index[i];
    float4 e = emission[pixel];
    if (has_em[i]) e.xyz *= (float3)(emap[0][i], emap[1][i], emap[2][i]);
    if (has_mr[i]) {
      const float roughness = clamp(mat->factors.y * mrmap[1][i], 0.0f, 1.0f);
      const bool metal = mat->factors.z * mrmap[2][i] >= 0.5f;
      const float f0 = mat->factors.w;
      const int r = (int)(roughness * 255.0f + 0.5f);
      if (metal)
        e.w = (float)(r + RP_GLOSS_METAL);
      else if (f0 > 0.0f)
        e.w = (float)(r + 256 * clamp((int)(f0 * RP_GLOSS_F0_SCALE + 0.5f), 1, 255));
      else
        e.w = 0.0f;
    }
    emission[pixel] = e;
    if (!has_nm[i]) continue;
    const float b0 = b0_[i], b1 = b1_[i], b2 = b2_[i];
    const float4 t4 = tangents[tri_x[i]] * b0 + tangents[tri_y[i]] * b1 + tangents[tri_z[i]] * b2;
    const rp_mat4 m = instances[inst_index[i]].model;
    float3 t = m.c[0].xyz * t4.x + m.c[1].xyz * t4.y + m.c[2].xyz * t4.z;
    float4 nd = normal_depth[pixel];
    /* the side gbuffer_resolve turned the normal to: the interpolated vertex normal's sign */
    const float3 nv = (vertices[tri_x[i]].normal_v * b0 + vertices[tri_y[i]].normal_v * b1 +
                       vertices[tri_z[i]].normal_v * b2).xyz;
    const rp_mat4 nmat = instances[inst_index[i]].normal_matrix;
    const float3 nw = nmat.c[0].xyz * nv.x + nmat.c[1].xyz * nv.y + nmat.c[2].xyz * nv.z;
    const float turned = dot(nw, nd.xyz) < 0.0f ? -1.0f : 1.0f;
    const float3 nrm = nd.xyz * turned;
    t -= nrm * dot(nrm, t);
    const float len2 = dot(t, t);
    if (len2 > 1.0e-24f) {
      t *= rsqrt(len2);
      const float3 b = (t4.w < 0.0f ? -1.0f : 1.0f) * cross(nrm, t);
      const float3 s = (float3)(nmap[0][i], nmap[1][i], nmap[2][i]) * 2.0f - 1.0f;
      const float scale = mat->factors.x;
      const float3 np = t * (s.x * scale) + b * (s.y * scale) + nrm * s.z;
      if (dot(np, np) > 1.0e-24f) nd.xyz = normalize(np) * turned;
      normal_depth[pixel] = nd;
    }
  }
}
