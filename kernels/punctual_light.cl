/* Punctual light pass: a loaded scene's directional, point and spot lights
 * (FrameConstants.punctual, common/punctual_light.h) added to the light pass's HDR output.
 * Runs only for frames that have such lights, after the light pass (light.cl: the demo's lamp,
 * indirect light and emission). Per pixel:
 *
 *   hdr += sum over lights of (albedo * w_d + spec) * intensity * cos * attenuation * visibility
 *
 * with the light pass's surface model (common/brdf.h rp_brdf_lamp8 for a point-sized light,
 * widen = 0; matte pixels, gloss code 0: w_d = 1, spec = 0). The shadow of each light is
 * filtered over 3x3 texels of its own map (common/punctual_light.h).
 *
 * Variants (-D): RP_LIGHT_SPLIT=1: also adds the direct light to direct_out and its specular
 * part to specular_out (the light pass's split outputs, which hold the lamp's share already).
 */
#include "shared/types.h"
#include "common/math.h"
#include "common/brdf.h"
#include "common/punctual_light.h"

#ifndef RP_LIGHT_SPLIT
#define RP_LIGHT_SPLIT 0
#endif

__kernel void punctual_light_add(__global const FrameConstants* restrict frame,
                                 __global const float4* restrict albedo_plane,
                                 __global const float4* restrict normal_depth_plane,
                                 __global const float4* restrict position_plane,
                                 __global const float4* restrict emission_plane,
                                 __global const float* restrict shadow,
                                 __global const float4* restrict brdf_table,
#if RP_LIGHT_SPLIT
                                 __global float4* restrict direct_out,
                                 __global float4* restrict specular_out,
#endif
                                 __global float4* restrict hdr) {
  const uint x = (uint)get_global_id(0), y = (uint)get_global_id(1);
  const uint width = frame->width;
  if (x >= width || y >= frame->height) return;
  const uint pixel = y * width + x;
  const float4 pos = position_plane[pixel];
  if (pos.w == 0.0f) return;
  const float3 p = pos.xyz, n = normal_depth_plane[pixel].xyz;
  const float3 albedo = albedo_plane[pixel].xyz;
  const float code = emission_plane[pixel].w;
  const float3 v = normalize(frame->camera_pos.xyz - p);
  float3 direct = (float3)(0.0f), spec_direct = (float3)(0.0f);
  for (uint i = 0; i < frame->punctual_count; ++i) {
    float3 l;
    const float3 k = rp_punctual_direct(frame, shadow, i, p, n, 1, &l);
    if (all(k == 0.0f)) continue;
    if (code == 0.0f) {
      direct += albedo * k;
      continue;
    }
    float8 wr, wg, wb, sr, sg, sb, er, eg, eb;
    rp_brdf_lamp8(brdf_table, (float8)(code), (float8)(albedo.x), (float8)(albedo.y),
                  (float8)(albedo.z), (float8)(n.x), (float8)(n.y), (float8)(n.z),
                  (float8)(v.x), (float8)(v.y), (float8)(v.z), (float8)(l.x), (float8)(l.y),
                  (float8)(l.z), (float8)(0.0f), &wr, &wg, &wb, &sr, &sg, &sb, &er, &eg, &eb);
    const float3 spec = (float3)(sr.s0, sg.s0, sb.s0) * k;
    direct += albedo * (float3)(wr.s0, wg.s0, wb.s0) * k + spec;
    spec_direct += spec;
  }
  hdr[pixel].xyz += direct;
#if RP_LIGHT_SPLIT
  direct_out[pixel].xyz += direct;
  specular_out[pixel].xyz += spec_direct;
#endif
}
