#include "app/host_tone_map.h"

#include <algorithm>
#include <cmath>

namespace rp::app {
namespace {

// Exact sRGB encode in double precision (the kernels' polynomial is within 7e-6 of it).
double srgb_encode(double y) {
  y = std::clamp(y, 0.0, 1.0);
  return y <= 0.0031308 ? 12.92 * y : 1.055 * std::pow(y, 1.0 / 2.4) - 0.055;
}

uint8_t quantize(double v) {
  // floor(v * 255 + 0.5) as rp_quantize8; v is in [0, 1] here.
  return static_cast<uint8_t>(std::min(255.0, std::floor(std::clamp(v, 0.0, 1.0) * 255.0 + 0.5)));
}

}  // namespace

uint8_t tone_map_code(float radiance) {
  // As rp_tone_map1: fmax(x, 0) turns NaN into 0; the cap keeps inf / inf out.
  float x = radiance > 0.0f ? radiance : 0.0f;
  x = std::min(x, 1.0e30f);
  return quantize(srgb_encode(double(x / (1.0f + x))));
}

double tone_map_srgb(double radiance) {
  const double x = radiance > 0.0 ? std::min(radiance, 1.0e30) : 0.0;
  return srgb_encode(x / (1.0 + x));
}

uint8_t srgb_code(float linear) {
  return quantize(srgb_encode(linear > 0.0f ? double(linear) : 0.0));
}

void encode_rgba8(const std::vector<float>& rgb, bool tone_map, std::vector<uint8_t>& rgba) {
  const size_t n = rgb.size() / 3;
  rgba.resize(n * 4);
  for (size_t i = 0; i < n; ++i) {
    for (size_t c = 0; c < 3; ++c)
      rgba[4 * i + c] = tone_map ? tone_map_code(rgb[3 * i + c]) : srgb_code(rgb[3 * i + c]);
    rgba[4 * i + 3] = 255;
  }
}

}  // namespace rp::app
