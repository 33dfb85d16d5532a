/* The environment seen directly (the real-time modes' background): every pixel the GBuffer
 * left uncovered (position.w == 0) takes the sky's radiance along its camera ray through the
 * pixel centre (the jittered inverse view-projection the rasterizer used, so the background
 * jitters with the geometry and the TAA resolves both alike), at the map's finest level
 * (common/sky.h). Its alpha stays 0 (background), as the light pass wrote it. Runs only when the
 * frame has an environment (FrameConstants.sky.levels > 0). Host: src/passes/sky_background.h.
 *
 * One work-item per pixel of the render size; global size (width, height) rounded up.
 */
#include "shared/types.h"
#include "common/math.h"
#include "common/sky.h"

__kernel void sky_background(__global const FrameConstants* restrict frame,
                             __global const float4* restrict sky,
                             __global const float4* restrict position_plane,
                             __global float4* restrict hdr) {
  const uint x = (uint)get_global_id(0), y = (uint)get_global_id(1);
  if (x >= frame->width || y >= frame->height) return;
  const uint pixel = y * frame->width + x;
  if (position_plane[pixel].w != 0.0f) return;
  const float2 size = (float2)((float)frame->width, (float)frame->height);
  const float2 ndc = rp_screen_to_ndc((float2)((float)x + 0.5f, (float)y + 0.5f), size);
  const float4 a = rp_mat4_mul(frame->inv_view_proj, (float4)(ndc, -1.0f, 1.0f));
  const float4 b = rp_mat4_mul(frame->inv_view_proj, (float4)(ndc, 1.0f, 1.0f));
  const float3 d = normalize(b.xyz / b.w - a.xyz / a.w);
  hdr[pixel] = (float4)(rp_sky_radiance(frame, sky, d, 0.0f), 0.0f);
}
