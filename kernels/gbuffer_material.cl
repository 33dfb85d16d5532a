/* GBuffer material pass: a file's per-texel material maps (scene/frame_scene.h Material;
 * kernels/shared/types.h Material.normal_texture, metallic_roughness_texture, emission_texture)
 * applied to what gbuffer_resolve wrote, for the pixels whose material has any. Runs only when
 * some material has such a map (the demo has none). Per pixel, with the triangle and
 * barycentrics of the visibility buffer:
 *
 *   normal map: tangent t = model * (interpolated vertex tangent), made orthogonal to the
 *     GBuffer's normal n, bitangent b = w * cross(n, t), n' = normalize(t x s + b y s + n z)
 *     for the map's (x, y, z) = rgb * 2 - 1 and s = the material's normal scale;
 *   metallic-roughness: roughness = factor * G, metallic = factor * B, metal at >= 0.5; the
 *     gloss code (shared/brdf_layout.h) rebuilt from them (dielectrics keep the material's f0);
 *   emission: emission.rgb *= the map (sRGB).
 *
 * The maps are sampled bilinearly at level 0 with the texture's wrap modes, texel centres at +0.5, v
 * up: the path tracer's arithmetic (truth/trace_scene.h LinearTexture), so both see the same
 * surface; the base colour keeps gbuffer_resolve's filtered lookup. Spheres and background
 * are left as they are. One work-item per pixel.
 */
#include "shared/types.h"
#include "shared/brdf_layout.h"
#include "common/colour.h"

/* Texel column (or row) c (an integer held in float) and c + 1 folded into [0, n) by wrap
 * mode `mode` (RP_WRAP_*): the path tracer's rules (common/span_texture.h rp_span_wrap_taps
 * for spans). */
inline void gm_fold(float c, int n, uint mode, int* i0, int* i1) {
  if (mode == RP_WRAP_CLAMP) {
    const int k = (int)clamp(c, -1.0f, (float)n);
    *i0 = clamp(k, 0, n - 1);
    *i1 = clamp(k + 1, 0, n - 1);
    return;
  }
  const int period = mode == RP_WRAP_MIRROR ? 2 * n : n;
  int m = (int)(c - floor(c / (float)period) * (float)period);
  if (m >= period) m -= period;
  if (m < 0) m += period;
  const int m1 = m + 1 == period ? 0 : m + 1;
  *i0 = m < n ? m : period - 1 - m;
  *i1 = m1 < n ? m1 : period - 1 - m1;
}

/* Bilinear texel of texture `info` at uv: linear bytes / 255 (srgb 0) or sRGB decoded
 * (srgb 1); rgb. */
inline float3 gm_sample(__global const TextureInfo* info, __global const uint* texels, float2 uv,
                        int srgb) {
  const int w = (int)info->width, h = (int)info->height;
  const float x = uv.x * (float)w - 0.5f, y = (1.0f - uv.y) * (float)h - 0.5f;
  const float fx0 = floor(x), fy0 = floor(y);
  const float fx = x - fx0, fy = y - fy0;
  int x0, x1, y0, y1;
  gm_fold(fx0, w, RP_WRAP_U(info->wrap), &x0, &x1);
  gm_fold(fy0, h, RP_WRAP_V(info->wrap), &y0, &y1);
  const uint base = info->offset;
  const uint t[4] = {texels[base + (uint)(y0 * w + x0)], texels[base + (uint)(y0 * w + x1)],
                     texels[base + (uint)(y1 * w + x0)], texels[base + (uint)(y1 * w + x1)]};
  float3 c[4];
  for (int k = 0; k < 4; ++k)
    c[k] = srgb ? rp_unpack_rgba8_srgb(t[k]).xyz
                : (float3)((float)(t[k] & 255u), (float)((t[k] >> 8) & 255u),
                           (float)((t[k] >> 16) & 255u)) * (1.0f / 255.0f);
  return mix(mix(c[0], c[1], fx), mix(c[2], c[3], fx), fy);
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
  const uint x = (uint)get_global_id(0), y = (uint)get_global_id(1);
  if (x >= frame->width || y >= frame->height) return;
  const uint pixel = y * frame->width + x;
  const uint a = ids[2 * pixel], p = ids[2 * pixel + 1];
  if (a >= frame->instance_count || p >= instances[a].triangle_count) return;
  __global const Instance* inst = instances + a;
  const Triangle tri = triangles[inst->first_triangle + p];
  __global const Material* mat = materials + tri.w;
  const uint normal_map = mat->normal_texture, mr_map = mat->metallic_roughness_texture;
  const uint emission_map = mat->emission_texture;
  if (normal_map == RP_TEXTURE_NONE && mr_map == RP_TEXTURE_NONE &&
      emission_map == RP_TEXTURE_NONE)
    return;
  const float b1 = bary[2 * pixel], b2 = bary[2 * pixel + 1], b0 = 1.0f - b1 - b2;
  const float2 uv = (float2)(vertices[tri.x].position_u.w, vertices[tri.x].normal_v.w) * b0 +
                    (float2)(vertices[tri.y].position_u.w, vertices[tri.y].normal_v.w) * b1 +
                    (float2)(vertices[tri.z].position_u.w, vertices[tri.z].normal_v.w) * b2;
  float4 e = emission[pixel];
  if (emission_map != RP_TEXTURE_NONE)
    e.xyz *= gm_sample(textures + emission_map, texels, uv, 1);
  if (mr_map != RP_TEXTURE_NONE) {
    const float3 mr = gm_sample(textures + mr_map, texels, uv, 0);
    const float roughness = clamp(mat->factors.y * mr.y, 0.0f, 1.0f);
    const bool metal = mat->factors.z * mr.z >= 0.5f;
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
  if (normal_map != RP_TEXTURE_NONE) {
    const float4 t4 = tangents[tri.x] * b0 + tangents[tri.y] * b1 + tangents[tri.z] * b2;
    const rp_mat4 m = inst->model;
    float3 t = m.c[0].xyz * t4.x + m.c[1].xyz * t4.y + m.c[2].xyz * t4.z;
    float4 nd = normal_depth[pixel];
    const float3 n = nd.xyz;
    t -= n * dot(n, t);
    const float len2 = dot(t, t);
    if (len2 > 1.0e-24f) {
      t *= rsqrt(len2);
      const float3 b = (t4.w < 0.0f ? -1.0f : 1.0f) * cross(n, t);
      const float3 s = gm_sample(textures + normal_map, texels, uv, 0) * 2.0f - 1.0f;
      const float scale = mat->factors.x;
      const float3 np = t * (s.x * scale) + b * (s.y * scale) + n * s.z;
      if (dot(np, np) > 1.0e-24f) nd.xyz = normalize(np);
      normal_depth[pixel] = nd;
    }
  }
}
