/* The specular indirect light's cone, shared by the light pass's reference
 * mode (kernels/light.cl, light_shade: per pixel) and the fast mode's low-resolution trace
 * (kernels/indirect.cl, indirect_trace: one per 4x4 block). OpenCL C only.
 *
 * rp_spec_cone: the radiance arriving along the mirror direction r = reflect(-v, n) of surface
 * point p (unit normal n, gloss code `code`, v the unit direction to the camera), through one
 * cone of the coat's lobe width (common/brdf.h, rp_brdf_spec_cone_tan: the GGX lobe's half
 * width at half maximum, clamped to 0.1 .. 1) from the diffuse cones' apex (one level-0 voxel
 * along n). The coat reflects E_spec(mu_o) times this (split sum: the lobe's integral of the
 * incoming light approximated by the light's mean over the cone times the coat's albedo).
 * The volume is read only through rp_cone_trace_aperture (common/cone_trace.h: origin,
 * direction, aperture), the cone-tracing contract another volume can implement.
 * fine: rp_cone_trace_aperture's mode (1 the reference mode, 0 the fast mode). The sky the cone
 * lets through is added (common/sky.h; `sky`: the frame's environment texels).
 */
#ifndef ROLYPOLY_COMMON_SPEC_CONE_H
#define ROLYPOLY_COMMON_SPEC_CONE_H

#include "shared/types.h"
#include "common/brdf.h"
#include "common/cone_trace.h"

/* The fast mode's narrowest reflection cone (tan of the half-angle; the reference mode's is
 * RP_SPEC_CONE_MIN_TAN): fewer, coarser samples at the indirect pass's low resolution. */
#ifndef RP_SPEC_CONE_MIN_TAN_FAST
#define RP_SPEC_CONE_MIN_TAN_FAST 0.1f
#endif

inline float3 rp_spec_cone(__global const FrameConstants* restrict frame,
                           __global const float4* restrict sky,
                           __global const float4* restrict voxels, uint voxel_resolution,
                           uint voxel_levels, float code, float3 p, float3 n, const int fine) {
  const float3 v = normalize(frame->camera_pos.xyz - p);
  const float3 r = 2.0f * fmax(dot(n, v), 0.0f) * n - v;
  const float tan_half = fmax(rp_brdf_spec_cone_tan(rp_brdf_code_roughness(code)),
                              fine ? 0.0f : RP_SPEC_CONE_MIN_TAN_FAST);
  const float4 cone = rp_cone_trace_aperture(voxels, voxel_resolution, voxel_levels,
                                             rp_cone_apex(p, n, voxel_resolution), r, tan_half,
                                             fine);
  return rp_sky_behind_cone(frame, sky, cone, r, tan_half,
                            fine ? RP_CONE_OPAQUE : RP_CONE_SPEC_OPAQUE_FAST);
}

#endif
