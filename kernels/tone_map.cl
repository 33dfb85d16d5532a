/* Tone map + sRGB encode + 8-bit quantise (SPEC 6.9): HDR float4 (rgb linear radiance) ->
 * uint RGBA8 per pixel, R in the low byte, A = 255.
 *
 *   out = floor(255 * srgb(T(exposure * rgb)) + d),  T(x) = x / (1 + x) per channel
 *
 * (operator, inverse and sRGB curve in common/colour.h). Exposure is fixed at 1.0 (RP_EXPOSURE
 * may override it at build time). d is the dither: with `dither` = 1 a uniform value in [0, 1)
 * hashed from (byte index i = 4 * pixel + channel, frame), so a smooth gradient's 8-bit codes
 * average to the exact value instead of banding (the noise changes every frame, so TAA / the
 * eye average it too); with `dither` = 0, d = 0.5: round to nearest.
 *
 * One work-item per 16 consecutive pixels (pixel p0 = 16 * get_global_id(0); 1D range rounded
 * up, blocks past the image return), each channel one float16 (planar in registers): explicit
 * vector code that PoCL runs 8 / 16 wide, one vector load of 16 pixels' rgba per 4 and one
 * 16-word store. The last block, when the pixel count is not a multiple of 16, reads its
 * missing pixels as copies of the last pixel and writes only the pixels that exist. Measured at
 * 720x720 on the 2-core PoCL CPU: 1.9x faster than one work-item per output byte (which was
 * 3x faster than per-pixel float3 code); the output is bit-identical to it.
 */
#include "shared/types.h"
#include "shared/pass_params.h"
#include "common/colour.h"
#include "common/random.h"

#ifndef RP_EXPOSURE
#define RP_EXPOSURE 1.0f
#endif

/* rp_hash_u32 (common/random.h) lane by lane. */
inline uint16 rp_hash_u32x16(uint16 v) {
  const uint16 state = v * 747796405u + 2891336453u;
  const uint16 word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

/* 8-bit codes of one channel of 16 pixels; `byte` = each lane's byte index in the output. */
inline uint16 rp_tone_map_codes16(float16 x, uint16 byte, uint frame_hash, uint dither) {
  const float16 d =
      dither != 0u
          ? convert_float16(rp_hash_u32x16(byte ^ frame_hash) >> 8u) * (1.0f / 16777216.0f)
          : (float16)(0.5f);
  const float16 v = rp_linear_to_srgb16(rp_tone_map16(x * RP_EXPOSURE));
  return min(convert_uint16(v * 255.0f + d), (uint16)(255u)); /* (vector bound: see taa.cl) */
}

__kernel void tone_map_output(__global const float* restrict hdr, __global uint* restrict rgba8,
                              const ToneMapParams params) {
  const uint pixel_count = params.pixel_count, dither = params.dither, frame = params.frame;
  const uint p0 = 16u * (uint)get_global_id(0);
  if (p0 >= pixel_count) return;
  const bool whole = p0 + 16u <= pixel_count;
  float16 a, b, c, d; /* rgba of pixels p0 .. p0+3, +4 .. +7, +8 .. +11, +12 .. +15 */
  if (whole) {
    __global const float* f = hdr + 4u * p0;
    a = vload16(0, f);
    b = vload16(1, f);
    c = vload16(2, f);
    d = vload16(3, f);
  } else {
    float t[64];
    for (uint k = 0; k < 16u; ++k) vstore4(vload4(min(p0 + k, pixel_count - 1u), hdr), k, t);
    a = vload16(0, t);
    b = vload16(1, t);
    c = vload16(2, t);
    d = vload16(3, t);
  }
  const uint frame_hash = rp_hash_u32(frame);
  const uint16 byte = 4u * p0 + (uint16)(0u, 4u, 8u, 12u, 16u, 20u, 24u, 28u, 32u, 36u, 40u,
                                         44u, 48u, 52u, 56u, 60u);
  const uint16 r = rp_tone_map_codes16((float16)(a.s048c, b.s048c, c.s048c, d.s048c), byte,
                                       frame_hash, dither);
  const uint16 g = rp_tone_map_codes16((float16)(a.s159d, b.s159d, c.s159d, d.s159d),
                                       byte + 1u, frame_hash, dither);
  const uint16 bl = rp_tone_map_codes16((float16)(a.s26ae, b.s26ae, c.s26ae, d.s26ae),
                                        byte + 2u, frame_hash, dither);
  const uint16 px = r | (g << 8u) | (bl << 16u) | 0xFF000000u;
  if (whole) {
    vstore16(px, 0, rgba8 + p0);
  } else {
    uint t[16];
    vstore16(px, 0, t);
    for (uint k = 0; p0 + k < pixel_count; ++k) rgba8[p0 + k] = t[k];
  }
}
