/* Debug views (pass "debug_view"): one buffer of the frame shown as the RGBA8 image (uint per
 * pixel, R in the low byte, A = 255: the tone map's output format), in place of the normal
 * chain. One work-item per pixel, 2D range rounded up to the work-group size.
 *
 * How each view maps its data to 8-bit codes (q(v) = round(255 * clamp(v, 0, 1))):
 *   albedo      q(srgb(albedo.rgb)): the colour as the texture shows it; background 0
 *   normal      q(0.5 + 0.5 n) per channel, no sRGB (the code is the value); background black
 *   depth       grey q((depth - near) / (far - near)), linear view depth over the camera's clip
 *               range, no sRGB: near black, far (and background) white
 *   velocity    q(0.5 + 0.5 clamp(v / RP_DEBUG_VELOCITY_RANGE, -1, 1)) in r (x, right) and g
 *               (y, down), b = q(0.5): no motion is mid grey; +-16 pixels saturate
 *   shadow-map  the lamp's depth map stretched over the image (nearest texel, texel row 0 at
 *               the top), grey q((linear light depth - near) / (far - near)) over the light's
 *               clip range, no sRGB; empty texels (1.0) white
 *   radiance    q(srgb(T(rgb))) with T(x) = x / (1 + x): the final image's tone map and encode,
 *               for the light pass's direct, indirect and specular components (HDR float4
 *               input)
 *   voxels      camera rays through one volume of the voxel chain (level, direction), every
 *               voxel a ray crosses composited front to back once (3D DDA, voxel values as
 *               stored), then tone mapped like radiance; rays missing the box are black
 */
#include "shared/types.h"
#include "shared/pass_params.h"
#include "shared/voxel_layout.h"
#ifdef RP_GI_SVO
#include "common/svo.h"
#endif
#include "common/colour.h"
#include "common/math.h"

#ifndef RP_DEBUG_VELOCITY_RANGE
#define RP_DEBUG_VELOCITY_RANGE 16.0f /* pixels of motion that saturate the velocity view */
#endif
/* The voxel view stops a ray once this opaque (the rest cannot change an 8-bit code much). */
#define RP_DEBUG_VOXEL_OPAQUE 0.999f

/* The pixel of this work-item, or false outside the image. */
inline bool debug_pixel(__global const FrameConstants* frame, uint* x, uint* y, uint* pixel) {
  *x = (uint)get_global_id(0);
  *y = (uint)get_global_id(1);
  if (*x >= frame->width || *y >= frame->height) return false;
  *pixel = *y * frame->width + *x;
  return true;
}

/* rgb codes taken as they are (no sRGB). */
inline uint debug_pack_linear(float3 c) { return rp_pack_rgb8(c); }

/* Tone map and sRGB encode of HDR radiance, as the final image does. */
inline uint debug_pack_radiance(float3 c) { return rp_pack_rgb8(rp_linear_to_srgb3(rp_tone_map(c))); }

__kernel void debug_view_albedo(__global const FrameConstants* frame,
                                __global const float4* albedo, __global uint* out) {
  uint x, y, pixel;
  if (!debug_pixel(frame, &x, &y, &pixel)) return;
  out[pixel] = rp_pack_rgb8(rp_linear_to_srgb3(albedo[pixel].xyz));
}

__kernel void debug_view_normal(__global const FrameConstants* frame,
                                __global const float4* normal_depth,
                                __global const float4* position, __global uint* out) {
  uint x, y, pixel;
  if (!debug_pixel(frame, &x, &y, &pixel)) return;
  const float3 n = normal_depth[pixel].xyz;
  out[pixel] = debug_pack_linear(position[pixel].w != 0.0f ? 0.5f + 0.5f * n : (float3)(0.0f));
}

__kernel void debug_view_depth(__global const FrameConstants* frame,
                               __global const float4* normal_depth, __global uint* out) {
  uint x, y, pixel;
  if (!debug_pixel(frame, &x, &y, &pixel)) return;
  const float near = frame->clip.x, far = frame->clip.y;
  const float grey = (normal_depth[pixel].w - near) / (far - near);
  out[pixel] = debug_pack_linear((float3)(grey));
}

__kernel void debug_view_velocity(__global const FrameConstants* frame,
                                  __global const float2* velocity, __global uint* out) {
  uint x, y, pixel;
  if (!debug_pixel(frame, &x, &y, &pixel)) return;
  const float2 v = clamp(velocity[pixel] * (1.0f / RP_DEBUG_VELOCITY_RANGE), -1.0f, 1.0f);
  out[pixel] = debug_pack_linear((float3)(0.5f + 0.5f * v, 0.5f));
}

__kernel void debug_view_shadow_map(__global const FrameConstants* frame,
                                    __global const float* shadow, __global uint* out) {
  uint x, y, pixel;
  if (!debug_pixel(frame, &x, &y, &pixel)) return;
  const uint size = frame->shadow_size;
  /* nearest texel under the pixel: texel = floor(pixel * size / image size), in integers */
  const uint tx = (uint)(((ulong)x * size) / frame->width);
  const uint ty = (uint)(((ulong)y * size) / frame->height);
  const float d = shadow[ty * size + tx];
  const float near = frame->clip.z, far = frame->clip.w;
  const float z_ndc = d * 2.0f - 1.0f;
  const float lin = 2.0f * near * far / ((far + near) - z_ndc * (far - near));
  const float grey = d >= 1.0f ? 1.0f : (lin - near) / (far - near);
  out[pixel] = debug_pack_linear((float3)(grey));
}

__kernel void debug_view_radiance(__global const FrameConstants* frame,
                                  __global const float4* radiance, __global uint* out) {
  uint x, y, pixel;
  if (!debug_pixel(frame, &x, &y, &pixel)) return;
  out[pixel] = debug_pack_radiance(radiance[pixel].xyz);
}

/* voxels: the chain (shared/voxel_layout.h) of voxel_resolution^3 at level 0; level and dir
 * select the volume shown (dir ignored at level 0). */
__kernel void debug_view_voxels(__global const FrameConstants* frame,
                                __global const float4* voxels, __global uint* out,
                                const VoxelViewParams params) {
  const uint voxel_resolution = params.voxel_resolution, level = params.level;
  const uint dir = params.dir;
  uint x, y, pixel;
  if (!debug_pixel(frame, &x, &y, &pixel)) return;

  /* Camera ray through the pixel centre: from the near plane towards the far plane. */
  const float2 size = (float2)((float)frame->width, (float)frame->height);
  const float2 ndc = rp_screen_to_ndc((float2)((float)x + 0.5f, (float)y + 0.5f), size);
  const float4 a = rp_mat4_mul(frame->inv_view_proj, (float4)(ndc, -1.0f, 1.0f));
  const float4 b = rp_mat4_mul(frame->inv_view_proj, (float4)(ndc, 1.0f, 1.0f));
  const float3 origin = a.xyz / a.w;
  const float3 d = normalize(b.xyz / b.w - origin);

  /* Slab test against [-1,1]^3; components below 1e-12 count as 1e-12 (finite t everywhere,
   * no 0 * inf in the boundary distances below). */
  const float3 inv = 1.0f / copysign(fmax(fabs(d), (float3)(1.0e-12f)), d);
  const float3 t_lo = (-1.0f - origin) * inv, t_hi = (1.0f - origin) * inv;
  const float3 t_near = fmin(t_lo, t_hi), t_far = fmax(t_lo, t_hi);
  const float t_enter = fmax(fmax(fmax(t_near.x, t_near.y), t_near.z), 0.0f);
  const float t_exit = fmin(fmin(t_far.x, t_far.y), t_far.z);
  float4 acc = (float4)(0.0f);
  if (t_enter < t_exit) {
    const int n = (int)rp_voxel_level_size(voxel_resolution, level);
#ifndef RP_GI_SVO
    __global const float4* vol = voxels + rp_voxel_offset(voxel_resolution, level, dir);
#endif
    const float cell = 2.0f / (float)n;
    /* Start inside the first voxel: grid position of the entry point, clamped into the grid. */
    const float3 g = ((origin + d * t_enter) + 1.0f) / cell;
    int3 v = clamp(convert_int3(floor(g)), 0, n - 1);
    const int3 step = (int3)(d.x >= 0.0f ? 1 : -1, d.y >= 0.0f ? 1 : -1, d.z >= 0.0f ? 1 : -1);
    /* Ray parameter at the next voxel boundary on each axis, and between boundaries. */
    const float3 next_face = (convert_float3(v + max(step, 0)) * cell - 1.0f);
    float3 t_max = (next_face - origin) * inv;
    const float3 t_delta = fabs(cell * inv);
    for (int i = 0; i < 3 * n; ++i) {
#ifdef RP_GI_SVO /* voxels: the octree (shared/svo_layout.h) */
      const float4 s = rp_svo_fetch(voxels, voxel_resolution, level, dir, v);
#else
      const float4 s = vol[(v.z * n + v.y) * n + v.x];
#endif
      acc.xyz += (1.0f - acc.w) * s.xyz;
      acc.w += (1.0f - acc.w) * s.w;
      if (acc.w >= RP_DEBUG_VOXEL_OPAQUE) break;
      /* advance across the nearest boundary */
      if (t_max.x <= t_max.y && t_max.x <= t_max.z) {
        v.x += step.x;
        t_max.x += t_delta.x;
      } else if (t_max.y <= t_max.z) {
        v.y += step.y;
        t_max.y += t_delta.y;
      } else {
        v.z += step.z;
        t_max.z += t_delta.z;
      }
      if (v.x < 0 || v.y < 0 || v.z < 0 || v.x >= n || v.y >= n || v.z >= n) break;
    }
  }
  out[pixel] = debug_pack_radiance(acc.xyz);
}
