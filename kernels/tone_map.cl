/* Tone map + sRGB encode + 8-bit quantise (SPEC 6.9): HDR float4 (rgb linear radiance) ->
 * uint RGBA8 per pixel, R in the low byte, A = 255.
 *
 *   out = round(255 * srgb(T(exposure * rgb))),  T(x) = x / (1 + x) per channel
 *
 * (operator, inverse and sRGB curve in common/colour.h). Exposure is fixed at 1.0 for now
 * (RP_EXPOSURE may override it at build time). No dithering yet: round to nearest.
 * One work-item per pixel over the flat pixel index (1D range rounded up, bounds-checked):
 * straight-line scalar code that PoCL vectorizes across work-items.
 */
#include "common/colour.h"

#ifndef RP_EXPOSURE
#define RP_EXPOSURE 1.0f
#endif

__kernel void tone_map_output(__global const float4* hdr, __global uint* rgba8, uint pixel_count) {
  const uint i = (uint)get_global_id(0);
  if (i >= pixel_count) return;
  const float3 c = hdr[i].xyz * RP_EXPOSURE;
  rgba8[i] = rp_pack_rgb8(rp_linear_to_srgb3(rp_tone_map(c)));
}
