/* The environment seen directly (the real-time modes' background): every pixel the GBuffer
 * left uncovered (position.w == 0) takes the sky's radiance along its camera ray through the
 * pixel centre (the jittered inverse view-projection the rasterizer used, so the background
 * jitters with the geometry and the TAA resolves both alike), at the map's finest level
 * (common/sky.h). Its alpha stays 0 (background), as the light pass wrote it. Runs only when the
 * frame has an environment (FrameConstants.sky.levels > 0). Host: src/passes/sky_background.h.
 *
 * Eight pixels of a row per work-item: the ray directions and the map coordinates (atan2pi,
 * acospi) in float8 arithmetic, the texel taps lane by lane for the uncovered pixels only; a
 * chunk of eight covered pixels returns after one load. (One pixel per work-item called the
 * scalar atan2 per pixel: 35 ms at 720x720 on the 2-core AVX2 EPYC.) Global size
 * (ceil(width / 8), height) rounded up to the work-group.
 */
#include "shared/types.h"
#include "common/sky.h"

/* x, y, z, w of m * (nx, ny, nz, 1) for the lanes' NDC x (ny, nz the same for every lane). */
#define RP_SKY_POINT8(m, nx, ny, nz, X, Y, Z, W)                                  \
  do {                                                                            \
    X = (m).c[0].x * (nx) + ((m).c[1].x * (ny) + (m).c[2].x * (nz) + (m).c[3].x); \
    Y = (m).c[0].y * (nx) + ((m).c[1].y * (ny) + (m).c[2].y * (nz) + (m).c[3].y); \
    Z = (m).c[0].z * (nx) + ((m).c[1].z * (ny) + (m).c[2].z * (nz) + (m).c[3].z); \
    W = (m).c[0].w * (nx) + ((m).c[1].w * (ny) + (m).c[2].w * (nz) + (m).c[3].w); \
  } while (0)

__kernel void sky_background(__global const FrameConstants* restrict frame,
                             __global const float4* restrict sky,
                             __global const float4* restrict position_plane,
                             __global float4* restrict hdr) {
  const uint x0 = 8u * (uint)get_global_id(0), y = (uint)get_global_id(1);
  const uint width = frame->width;
  if (x0 >= width || y >= frame->height) return;
  const uint lanes = min(8u, width - x0);
  const uint row = y * width + x0;
  bool any_open = false;
  for (uint k = 0; k < lanes; ++k) any_open |= position_plane[row + k].w == 0.0f;
  if (!any_open) return;

  const float8 px = (float8)(0.5f, 1.5f, 2.5f, 3.5f, 4.5f, 5.5f, 6.5f, 7.5f) + (float)x0;
  const float8 ndc_x = px * (2.0f / (float)width) - 1.0f;
  const float ndc_y = 1.0f - ((float)y + 0.5f) * (2.0f / (float)frame->height);
  const rp_mat4 inv = frame->inv_view_proj;
  float8 ax, ay, az, aw, bx, by, bz, bw;
  RP_SKY_POINT8(inv, ndc_x, ndc_y, -1.0f, ax, ay, az, aw);
  RP_SKY_POINT8(inv, ndc_x, ndc_y, 1.0f, bx, by, bz, bw);
  const float8 ia = 1.0f / aw, ib = 1.0f / bw;
  float8 dx = bx * ib - ax * ia, dy = by * ib - ay * ia, dz = bz * ib - az * ia;
  const float8 inv_len = rsqrt(dx * dx + dy * dy + dz * dz);
  dx *= inv_len;
  dy *= inv_len;
  dz *= inv_len;
  /* the map's frame and coordinates (common/sky.h: rp_sky_to_map, rp_sky_radiance) */
  __global const SkyGpu* s = &frame->sky;
  const float4 turn = s->turn;
  const float8 mx = turn.x * dx - turn.y * dz, mz = turn.y * dx + turn.x * dz;
  float8 u = 0.5f * atan2pi(mx, -mz);
  u = select(u, u + 1.0f, u < 0.0f);
  const float8 v = acospi(clamp(dy, -1.0f, 1.0f));
  float us[8], vs[8];
  vstore8(u, 0, us);
  vstore8(v, 0, vs);
  const uint offset = s->level_offset[0], w = s->width, h = s->height;
  for (uint k = 0; k < lanes; ++k) {
    if (position_plane[row + k].w != 0.0f) continue;
    hdr[row + k] =
        (float4)(rp_sky_level(sky, offset, w, h, (float2)(us[k], vs[k])) * turn.z, 0.0f);
  }
}
