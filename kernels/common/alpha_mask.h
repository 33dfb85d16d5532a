/* Alpha masks (glTF alphaMode MASK; scene/frame_scene.h AlphaMode::kMask): a surface point whose
 * alpha (the material's base colour alpha factor times its base colour texture's alpha, sampled
 * bilinearly at level 0 with the texture's wrap modes) is below the cutoff does not exist. The
 * rule and the sampling are the path tracer's (src/truth/trace_scene.cpp TraceAssets::solid), so
 * the rasterizer, its shadow maps and the truth cut the same holes. Needs shared/types.h and
 * common/span_texture.h. */
#ifndef ROLYPOLY_COMMON_ALPHA_MASK_H
#define ROLYPOLY_COMMON_ALPHA_MASK_H

/* Which lanes of `lanes` are solid at barycentrics (b1, b2) (perspective-correct weights of
 * the triangle's 2nd and 3rd vertex) of triangle `triangle` (global index) of a masked
 * material. Lanes not in `lanes` or >= n come back as they were (0). */
inline rp_spani rp_alpha_solid(__global const Triangle* triangles,
                               __global const Vertex* vertices,
                               __global const Material* materials,
                               __global const TextureInfo* textures,
                               __global const uint* texels, uint triangle, rp_spanf b1,
                               rp_spanf b2, rp_spani lanes, int n) {
  const Triangle tri = triangles[triangle];
  __global const Material* m = materials + tri.w;
  rp_spanf alpha = (rp_spanf)(m->coverage.x);
  if (m->texture != RP_TEXTURE_NONE) {
    const float u0 = vertices[tri.x].position_u.w, v0 = vertices[tri.x].normal_v.w;
    const float u1 = vertices[tri.y].position_u.w, v1 = vertices[tri.y].normal_v.w;
    const float u2 = vertices[tri.z].position_u.w, v2 = vertices[tri.z].normal_v.w;
    const rp_spanf b0 = (1.0f - b1) - b2;
    const rp_spanf u = (b0 * u0 + b1 * u1) + b2 * u2;
    const rp_spanf v = (b0 * v0 + b1 * v1) + b2 * v2;
    __global const TextureInfo* info = textures + m->texture;
    alpha *= rp_span_texture_alpha(texels, lanes, (rp_spanf)((float)info->width),
                                   (rp_spanf)((float)info->height), (rp_spanu)(info->offset),
                                   (rp_spanu)(info->wrap), u, v, n);
  }
  return lanes & (alpha >= m->coverage.y);
}

#endif
