/* Precomputed radiance transfer, shading (seeds 002/003): the sky's irradiance at every pixel
 * from per-vertex transfer vectors (computed on the host: src/truth/prt_transfer.h) and the
 * environment's spherical-harmonic coefficients (src/shading/spherical_harmonics.h), as the
 * dot product
 *     E_c(x) = sum_i T_{c,i}(x) L_{c,i},
 * with x's T interpolated over the pixel's triangle with the visibility buffer's barycentrics
 * (computed as E per vertex, then interpolated: the same sum). Host side:
 * src/passes/prt_sky.h.
 *
 * Inputs:
 *   ids, bary       the visibility buffer (render/frame_buffers.h): (instance, primitive) and
 *                   the barycentrics (b1, b2) of the triangle's 2nd and 3rd vertex
 *   transfer        floats, vertex-major: vertex v, channel c, coefficient i at
 *                   (v * channels + c) * count + i (channels 1: grey, the same T for r, g, b;
 *                   3: RGB)
 *   vertex_offset   int per instance: the PRT vertex of the shared vertex buffer's vertex g is
 *                   g + vertex_offset[instance]; RP_PRT_NO_TRANSFER: the instance has none
 *   env             float4 per coefficient (count of them): rgb L_i / pi, turned and scaled
 *                   for this frame on the host
 *   shadowed        params.suns only: the shadowed transfer the interreflected one started
 *                   from, grey, vertex v's coefficient i at v * count + i
 *   sun_env         params.suns only: as env, for the suns alone: the environment's (the map
 *                   minus its residual: scene/environment_suns.h) and the directional lights'
 *                   (pi I Y(w_light)), which env holds too. Their first vertex is lit with
 *                   shadow maps, so E = T . env - T_shadowed . sun_env: the suns' bounces stay
 *                   with the transfer, their direct light does not
 *   sun_bounce      params.traced_suns only: per vertex v and traced sun j, the rgb irradiance
 *                   its light reaches v with after 1..N bounces, per unit irradiance of the
 *                   sun, at (v * traced_suns + j) * 3 (src/truth/prt_transfer.h)
 *   sun_i           params.traced_suns only: float4 per traced sun, rgb = its intensity I (the
 *                   lights' units: pi I is the irradiance it gives a surface facing it), so
 *                   the sun adds I * sun_bounce to E / pi. env then holds the residual alone:
 *                   E = T . L(residual) + sum_j pi I_j sun_bounce_j
 *   glow            params.glow_scale > 0 only: per vertex the rgb irradiance of the glow
 *                   around the map's suns at strength 1, traced (first vertex and bounces) at
 *                   v * 3; env then leaves the glow out, and E / pi gains glow_scale * glow
 * Output: float4 per pixel, rgb = E / pi (the light pass's D, irradiance over pi: albedo times
 * it is the Lambertian radiance), a = 1 where a transfer was found, 0 elsewhere (background,
 * spheres, instances without transfer). Two kernels: prt_vertex_irradiance dots every vertex's
 * transfer with the coefficients once a frame, prt_shade interpolates the result per pixel.
 */
#include "shared/types.h"
#include "shared/pass_params.h"

#define RP_PRT_NO_TRANSFER ((int)0x80000000)

/* Per PRT vertex: E / pi of its transfer (float4: rgb, a unused). One vertex per work-item;
 * vertex_count of them. Dotting per vertex and interpolating the result per pixel is the same
 * sum as interpolating the transfer (both are linear), and reads 3 float4 a pixel instead of
 * 3 x channels x count floats. */
__kernel void prt_vertex_irradiance(__global const float* restrict transfer,
                                    __global const float4* restrict env,
                                    __global const float* restrict shadowed,
                                    __global const float4* restrict sun_env,
                                    __global const float* restrict sun_bounce,
                                    __global const float4* restrict sun_i,
                                    __global const float* restrict glow,
                                    __global float4* restrict vertex_e,
                                    const PrtVertexParams params) {
  const uint vertex_count = params.vertex_count, channels = params.channels;
  const uint count = params.coefficients;
  const uint v = (uint)get_global_id(0);
  if (v >= vertex_count) return;
  __global const float* t = transfer + v * channels * count;
  float3 e = (float3)(0.0f);
  if (channels == 1u) {
    for (uint i = 0; i < count; ++i) e += t[i] * env[i].xyz;
  } else {
    for (uint i = 0; i < count; ++i) {
      const float4 l = env[i];
      e.x += t[i] * l.x;
      e.y += t[count + i] * l.y;
      e.z += t[2u * count + i] * l.z;
    }
  }
  if (params.suns != 0u) {
    __global const float* t0 = shadowed + v * count;
    for (uint i = 0; i < count; ++i) e -= t0[i] * sun_env[i].xyz;
  }
  const uint traced = params.traced_suns;
  __global const float* b = sun_bounce + v * traced * 3u;
  for (uint j = 0; j < traced; ++j)
    e += (float3)(b[3u * j], b[3u * j + 1u], b[3u * j + 2u]) * sun_i[j].xyz;
  if (params.glow_scale > 0.0f)
    e += params.glow_scale * (float3)(glow[3u * v], glow[3u * v + 1u], glow[3u * v + 2u]);
  vertex_e[v] = (float4)(e, 0.0f);
}

/* Per pixel: the vertices' E / pi interpolated by the visibility buffer's barycentrics. */
__kernel void prt_shade(__global const FrameConstants* restrict frame,
                        __global const uint2* restrict ids,
                        __global const float2* restrict bary,
                        __global const Instance* restrict instances,
                        __global const Triangle* restrict triangles,
                        __global const float4* restrict vertex_e,
                        __global const int* restrict vertex_offset,
                        const uint offset_count,
                        __global float4* restrict out) {
  const uint x = (uint)get_global_id(0), y = (uint)get_global_id(1);
  const uint width = frame->width;
  if (x >= width || y >= frame->height) return;
  const uint pixel = y * width + x;
  const uint2 id = ids[pixel];
  if (id.x == RP_ID_NONE || (id.x & RP_ID_SPHERE_BIT) != 0u || id.x >= offset_count ||
      id.x >= frame->instance_count || id.y >= instances[id.x].triangle_count) {
    out[pixel] = (float4)(0.0f);
    return;
  }
  const int offset = vertex_offset[id.x];
  if (offset == RP_PRT_NO_TRANSFER) {
    out[pixel] = (float4)(0.0f);
    return;
  }
  const Triangle tri = triangles[instances[id.x].first_triangle + id.y];
  const float2 b = bary[pixel];
  const float b0 = 1.0f - b.x - b.y;
  const float3 e = b0 * vertex_e[(int)tri.x + offset].xyz +
                   b.x * vertex_e[(int)tri.y + offset].xyz +
                   b.y * vertex_e[(int)tri.z + offset].xyz;
  /* a negative sum (ringing of a band-limited sky, or a shadowed transfer's noise) is no light */
  out[pixel] = (float4)(fmax(e, 0.0f), 1.0f);
}
