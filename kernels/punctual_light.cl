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
 * Eight pixels of a row per work-item (common/indirect_simd.h loads and stores): the lights'
 * direction, attenuation and 3x3-filtered shadow for the eight lanes at once
 * (common/punctual_light8.h; only the shadow texels are read lane by lane), the surface model
 * (rp_brdf_lamp8) once for the eight lanes, only where a lane has a coat.
 *
 * Variants (-D): RP_LIGHT_SPLIT=1: also adds the direct light to direct_out and its specular
 * part to specular_out (the light pass's split outputs, which hold the lamp's share already).
 */
#include "shared/types.h"
#include "common/math.h"
#include "common/brdf.h"
#include "common/indirect_simd.h"
#include "common/punctual_light8.h"

#ifndef RP_LIGHT_SPLIT
#define RP_LIGHT_SPLIT 0
#endif

__kernel void punctual_light_add(__global const FrameConstants* restrict frame,
                                 __global const float* restrict albedo_plane,
                                 __global const float* restrict normal_depth_plane,
                                 __global const float* restrict position_plane,
                                 __global const float* restrict emission_plane,
                                 __global const float* restrict shadow,
                                 __global const float4* restrict brdf_table,
                                 __global float* restrict direct_out,
                                 __global float* restrict specular_out,
                                 __global float* restrict hdr) {
  const uint x0 = 8u * (uint)get_global_id(0), y = (uint)get_global_id(1);
  const uint width = frame->width;
  if (x0 >= width || y >= frame->height) return;
  const uint lanes = min(8u, width - x0);
  const uint row = 4u * y * width;
  float8 px, py, pz, cov, nx, ny, nz, depth, ar, ag, ab, aw, er, eg, eb, code;
  rp_load8_float4(position_plane, row, x0, lanes, &px, &py, &pz, &cov);
  if (all(cov == 0.0f)) return; /* background only */
  rp_load8_float4(normal_depth_plane, row, x0, lanes, &nx, &ny, &nz, &depth);
  rp_load8_float4(albedo_plane, row, x0, lanes, &ar, &ag, &ab, &aw);
  rp_load8_float4(emission_plane, row, x0, lanes, &er, &eg, &eb, &code);
  const int8 covered = cov != 0.0f;
  const bool coated = any(covered & (code != 0.0f));
  const float3 cam = frame->camera_pos.xyz;
  float8 vx = cam.x - px, vy = cam.y - py, vz = cam.z - pz;
  const float8 inv_v = rsqrt(vx * vx + vy * vy + vz * vz);
  vx *= inv_v;
  vy *= inv_v;
  vz *= inv_v;
  const int8 on = covered & ((int8)(0, 1, 2, 3, 4, 5, 6, 7) < (int)lanes);
  const float8 zero = 0.0f;
  float8 dr = zero, dg = zero, db = zero, sr_sum = zero, sg_sum = zero, sb_sum = zero;
  for (uint i = 0; i < frame->punctual_count; ++i) {
    /* the light's irradiance factor k (rgb) and direction l, eight lanes at once */
    float8 kr, kg, kb, lx, ly, lz;
    if (!rp_punctual_direct8(frame, shadow, i, px, py, pz, nx, ny, nz, on, &kr, &kg, &kb, &lx,
                             &ly, &lz))
      continue;
    if (!coated) { /* matte lanes: w_d = 1, no specular */
      dr += ar * kr;
      dg += ag * kg;
      db += ab * kb;
      continue;
    }
    float8 wr, wg, wb, sr, sg, sb, vr, vg, vb;
    rp_brdf_lamp8(brdf_table, code, ar, ag, ab, nx, ny, nz, vx, vy, vz, lx, ly, lz, zero, &wr,
                  &wg, &wb, &sr, &sg, &sb, &vr, &vg, &vb);
    /* gloss code 0 (matte): w_d = 1, spec = 0, as the per-pixel form had it */
    const int8 matte = code == 0.0f;
    wr = select(wr, (float8)(1.0f), matte);
    wg = select(wg, (float8)(1.0f), matte);
    wb = select(wb, (float8)(1.0f), matte);
    sr = select(sr * kr, zero, matte);
    sg = select(sg * kg, zero, matte);
    sb = select(sb * kb, zero, matte);
    dr += ar * wr * kr + sr;
    dg += ag * wg * kg + sg;
    db += ab * wb * kb + sb;
    sr_sum += sr;
    sg_sum += sg;
    sb_sum += sb;
  }
  /* add to the planes' rgb, alpha kept (rp_store8_float4 writes all four) */
  float8 hr, hg, hb, ha;
  rp_load8_float4(hdr, row, x0, lanes, &hr, &hg, &hb, &ha);
  rp_store8_float4(hdr, row, x0, lanes, hr + select(zero, dr, covered),
                   hg + select(zero, dg, covered), hb + select(zero, db, covered), ha);
#if RP_LIGHT_SPLIT
  rp_load8_float4(direct_out, row, x0, lanes, &hr, &hg, &hb, &ha);
  rp_store8_float4(direct_out, row, x0, lanes, hr + select(zero, dr, covered),
                   hg + select(zero, dg, covered), hb + select(zero, db, covered), ha);
  rp_load8_float4(specular_out, row, x0, lanes, &hr, &hg, &hb, &ha);
  rp_store8_float4(specular_out, row, x0, lanes, hr + select(zero, sr_sum, covered),
                   hg + select(zero, sg_sum, covered), hb + select(zero, sb_sum, covered), ha);
#endif
}
