// The renderer's 8-bit encode on the host, for images made on the host (the path tracer's):
// the same operator and curve as kernels/common/colour.h and kernels/tone_map.cl without the
// dither, so a path-traced PNG and a real-time PNG of the same radiance get the same codes
// (up to the kernels' 7e-6 polynomial sRGB error).
#pragma once

#include <cstdint>
#include <vector>

namespace rp::app {

// One channel: T(x) = x / (1 + x) (negative and NaN -> 0, +inf -> 1, exposure 1), then the exact
// piecewise sRGB encode (12.92 y below 0.0031308, 1.055 y^(1/2.4) - 0.055 above), then rounded
// to the nearest of 0..255.
uint8_t tone_map_code(float radiance);
// The same without the quantisation: T(x) then the exact sRGB encode, in [0, 1) (the accuracy
// report's PSNR is taken on these values).
double tone_map_srgb(double radiance);
// One channel without the tone map: linear [0, 1] (clamped) -> exact sRGB -> nearest code; the
// albedo view's encode.
uint8_t srgb_code(float linear);

// rgb: width * height * 3 linear floats, top row first -> rgba: 4 bytes per pixel, alpha 255.
// `tone_map`: radiance (tone_map_code) or an albedo-like value in [0, 1] (srgb_code).
void encode_rgba8(const std::vector<float>& rgb, bool tone_map, std::vector<uint8_t>& rgba);

}  // namespace rp::app
