/* Tone map + sRGB encode + 8-bit quantise (SPEC 6.9): HDR float4 (rgb linear radiance) ->
 * uint RGBA8 per pixel, R in the low byte, A = 255.
 *
 *   out = floor(255 * srgb(T(exposure * rgb)) + d),  T(x) = x / (1 + x) per channel
 *
 * (operator, inverse and sRGB curve in common/colour.h). Exposure is fixed at 1.0 (RP_EXPOSURE
 * may override it at build time). d is the dither: with `dither` = 1 a uniform value in [0, 1)
 * hashed from (byte index, frame), so a smooth gradient's 8-bit codes average to the exact
 * value instead of banding (the noise changes every frame, so TAA / the eye average it too);
 * with `dither` = 0, d = 0.5: round to nearest.
 *
 * One work-item per output BYTE over the flat index i = 4 * pixel + channel (1D range rounded
 * up, bounds-checked): float i of the HDR buffer becomes byte i of the RGBA8 buffer (R in the
 * low byte of each uint on the little-endian devices OpenCL runs on). Straight-line scalar code
 * with unit-stride loads and stores is what PoCL vectorizes across work-items; a per-pixel
 * float3 version is SLP-vectorized inside the work-item instead, which blocks that and measured
 * ~3x slower.
 */
#include "common/colour.h"
#include "common/random.h"

#ifndef RP_EXPOSURE
#define RP_EXPOSURE 1.0f
#endif

__kernel void tone_map_output(__global const float* restrict hdr, __global uchar* restrict rgba8,
                              uint byte_count, uint dither, uint frame) {
  const uint i = (uint)get_global_id(0);
  if (i >= byte_count) return;
  const float d = dither != 0u ? rp_hash_to_unit(rp_hash_u32(i ^ rp_hash_u32(frame))) : 0.5f;
  const float v = clamp(rp_linear_to_srgb(rp_tone_map1(hdr[i] * RP_EXPOSURE)), 0.0f, 1.0f);
  const uint code = min((uint)(v * 255.0f + d), 255u);
  rgba8[i] = (uchar)((i & 3u) == 3u ? 255u : code);
}
