/* GBuffer resolve (SPEC 6.1): visibility buffer -> per-pixel surface attributes.
 *
 * One work-item per pixel on a 2D range rounded up to the work-group size (bounds-checked).
 * Inputs and outputs are planar, row-major, top row first (src/render/frame_buffers.h):
 *   ids      uint2  (instance, primitive); RP_ID_NONE background, RP_ID_SPHERE_BIT spheres
 *   bary     float2 (b1, b2) perspective-correct, b0 = 1 - b1 - b2
 *   albedo   float4 linear rgb, a = 1 covered / 0 background
 *   normal_depth float4 world unit normal, w linear view depth (-z_view; far plane if background)
 *   position float4 world position, w = 1 covered / 0 background
 *   emission float4 rgb emitted radiance
 *   velocity float2 pixels, this frame minus previous, unjittered, +y down; 0 for background
 */
#include "shared/types.h"
#include "common/math.h"
#include "common/sampling.h"

/* Pixel position of world point p under clip matrix m (w > 0 assumed: visible points). */
inline float2 gbuffer_screen(const rp_mat4 m, float3 p, float2 size) {
  return rp_clip_to_screen(rp_mat4_mul_point(m, p), size);
}

__kernel void gbuffer_resolve(__global const FrameConstants* frame,
                              __global const uint2* ids,
                              __global const float2* bary,
                              __global const Instance* instances,
                              __global const Sphere* spheres,
                              __global const Vertex* vertices,
                              __global const Triangle* triangles,
                              __global const Material* materials,
                              __global const TextureInfo* textures,
                              __global const uint* texels,
                              __global float4* out_albedo,
                              __global float4* out_normal_depth,
                              __global float4* out_position,
                              __global float4* out_emission,
                              __global float2* out_velocity) {
  const uint x = (uint)get_global_id(0), y = (uint)get_global_id(1);
  const uint width = frame->width, height = frame->height;
  if (x >= width || y >= height) return;
  const uint pixel = y * width + x;
  const float2 size = (float2)((float)width, (float)height);

  const uint2 id = ids[pixel];
  const uint sphere_index = id.x & ~RP_ID_SPHERE_BIT;
  const bool is_sphere = id.x != RP_ID_NONE && (id.x & RP_ID_SPHERE_BIT) != 0u &&
                         sphere_index < frame->sphere_count;
  const bool is_mesh = id.x < frame->instance_count && id.y < instances[id.x].triangle_count;

  /* float4 with defined w lanes, not float3: a float3's padding lane is undefined and
   * oclgrind's uninitialised-value check follows it into the stores. w = 1 covered / 0 not. */
  float4 p = (float4)(0.0f), n = (float4)(0.0f), prev_p = (float4)(0.0f);
  float4 albedo = (float4)(0.0f), emission = (float4)(0.0f);

  /* Structs are read through pointers, field by field, rather than copied whole into private
   * memory (only the fields used are loaded). */
  if (is_mesh) {
    __global const Instance* inst = instances + id.x;
    const Triangle tri = triangles[inst->first_triangle + id.y];
    __global const Vertex* v0 = vertices + tri.x;
    __global const Vertex* v1 = vertices + tri.y;
    __global const Vertex* v2 = vertices + tri.z;
    const float2 b = bary[pixel];
    const float b0 = 1.0f - b.x - b.y;
    const float4 pu = v0->position_u * b0 + v1->position_u * b.x + v2->position_u * b.y;
    const float4 nv = v0->normal_v * b0 + v1->normal_v * b.x + v2->normal_v * b.y;
    const float3 p_obj = pu.xyz;
    p = (float4)(rp_mat4_mul_point(inst->model, p_obj).xyz, 1.0f);
    prev_p = (float4)(rp_mat4_mul_point(inst->prev_model, p_obj).xyz, 1.0f);
    n = (float4)(normalize(rp_mat4_mul_dir(inst->normal_matrix, nv.xyz)), 0.0f);

    __global const Material* mat = materials + tri.w;
    albedo = (float4)(mat->albedo.xyz, 1.0f);
    if (mat->texture != RP_TEXTURE_NONE) {
      const float4 t = rp_texture_bilinear(texels, textures + mat->texture, (float2)(pu.w, nv.w));
      albedo.xyz *= t.xyz;
    }
    emission = (float4)(mat->emission.xyz, 0.0f);
  } else if (is_sphere) {
    __global const Sphere* s = spheres + sphere_index;
    /* Camera ray through the pixel centre, unprojected with the jittered matrix the rasterizer
     * used, from the near to the far plane. */
    const float2 ndc = rp_screen_to_ndc((float2)((float)x + 0.5f, (float)y + 0.5f), size);
    const float4 near_h = rp_mat4_mul(frame->inv_view_proj, (float4)(ndc, -1.0f, 1.0f));
    const float4 far_h = rp_mat4_mul(frame->inv_view_proj, (float4)(ndc, 1.0f, 1.0f));
    const float3 origin = near_h.xyz / near_h.w;
    const float3 dir = normalize(far_h.xyz / far_h.w - origin);
    const float3 c = s->center_radius.xyz;
    const float r = s->center_radius.w;
    const float3 oc = origin - c;
    const float bq = dot(oc, dir);
    /* The rasterized silhouette can cover a pixel whose exact ray just misses: clamp the
     * discriminant so such pixels take the closest point along the ray (normal renormalised). */
    const float disc = max(bq * bq - (dot(oc, oc) - r * r), 0.0f);
    const float root = sqrt(disc);
    const float t_near = -bq - root;
    const float t = t_near > 0.0f ? t_near : -bq + root; /* near plane inside the sphere */
    const float3 hit = origin + dir * t;
    p = (float4)(hit, 1.0f);
    n = (float4)(normalize(hit - c), 0.0f);
    prev_p = (float4)(hit - c + s->prev_center.xyz, 1.0f);
    albedo = (float4)(s->albedo.xyz, 1.0f);
    emission = (float4)(s->emission.xyz, 0.0f);
  }

  const bool covered = is_mesh || is_sphere;
  float2 velocity = (float2)(0.0f);
  float depth = frame->clip.y; /* far plane for background */
  if (covered) {
    velocity = gbuffer_screen(frame->view_proj_unjittered, p.xyz, size) -
               gbuffer_screen(frame->prev_view_proj_unjittered, prev_p.xyz, size);
    depth = -rp_mat4_mul_point(frame->view, p.xyz).z;
  }

  out_albedo[pixel] = albedo;
  n.w = depth;
  out_normal_depth[pixel] = n;
  out_position[pixel] = p;
  out_emission[pixel] = emission;
  out_velocity[pixel] = velocity;
}
