#include "render/texture_mips.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "render/gpu_types.h"

namespace rp::render {
namespace {

// Linear rgba, 4 doubles per texel, rows top to bottom.
using Plane = std::vector<double>;

double decode(uint8_t code) {
  const double c = code / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

uint8_t encode(double linear) {
  const double l = std::clamp(linear, 0.0, 1.0);
  const double s = l <= 0.0031308 ? l * 12.92 : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
  return static_cast<uint8_t>(std::lround(std::clamp(s, 0.0, 1.0) * 255.0));
}

// Linear [0, 1] -> the nearest 8-bit code (alpha, and the rgb of data maps).
uint8_t encode_linear(double a) {
  return static_cast<uint8_t>(std::lround(std::clamp(a, 0.0, 1.0) * 255.0));
}

// The weights of the area box filter from n texels to m = max(1, n / 2) along one axis:
// taps[i] = (first input, weights...) of output i (see the header).
struct AxisTaps {
  uint32_t first;
  std::vector<double> weights;
};

std::vector<AxisTaps> axis_taps(uint32_t n) {
  const uint32_t m = std::max<uint32_t>(1, n / 2);
  std::vector<AxisTaps> taps(m);
  const double s = double(n) / double(m);
  for (uint32_t i = 0; i < m; ++i) {
    const double lo = i * s, hi = (i + 1) * s;
    const uint32_t j0 = static_cast<uint32_t>(std::floor(lo));
    const uint32_t j1 = std::min(n - 1, static_cast<uint32_t>(std::ceil(hi)) - 1);
    taps[i].first = j0;
    for (uint32_t j = j0; j <= j1; ++j)
      taps[i].weights.push_back((std::min(hi, double(j + 1)) - std::max(lo, double(j))) / s);
  }
  return taps;
}

Plane downsample(const Plane& in, uint32_t w, uint32_t h, uint32_t& ow, uint32_t& oh) {
  const std::vector<AxisTaps> tx = axis_taps(w), ty = axis_taps(h);
  ow = static_cast<uint32_t>(tx.size());
  oh = static_cast<uint32_t>(ty.size());
  Plane out(size_t(ow) * oh * 4, 0.0);
  for (uint32_t y = 0; y < oh; ++y)
    for (uint32_t x = 0; x < ow; ++x) {
      double* o = &out[(size_t(y) * ow + x) * 4];
      for (size_t b = 0; b < ty[y].weights.size(); ++b)
        for (size_t a = 0; a < tx[x].weights.size(); ++a) {
          const double wgt = ty[y].weights[b] * tx[x].weights[a];
          const double* p = &in[((ty[y].first + b) * size_t(w) + tx[x].first + a) * 4];
          for (int c = 0; c < 4; ++c) o[c] += wgt * p[c];
        }
    }
  return out;
}

}  // namespace

float srgb8_decode(uint8_t code) { return static_cast<float>(decode(code)); }
uint8_t srgb8_encode(float linear) { return encode(linear); }

uint32_t mip_level_count(uint32_t width, uint32_t height) {
  uint32_t levels = 1;
  for (uint32_t side = std::max(width, height); side > 1; side >>= 1) ++levels;
  return levels;
}

MipChain build_mip_chain(const scene::Texture& t) {
  if (t.width <= 0 || t.height <= 0 || t.rgba.size() != size_t(t.width) * t.height * 4)
    throw std::invalid_argument("texture '" + t.name + "' has inconsistent size");
  uint32_t w = static_cast<uint32_t>(t.width), h = static_cast<uint32_t>(t.height);
  if (mip_level_count(w, h) > RP_TEXTURE_MAX_LEVELS)
    throw std::invalid_argument("texture '" + t.name + "' is larger than " +
                                std::to_string(1u << (RP_TEXTURE_MAX_LEVELS - 1)) +
                                " texels a side");
  MipChain chain;
  const uint32_t levels = mip_level_count(w, h);
  // Colour (sRGB) rgb is filtered as light; data maps' codes (normals, roughness) as the
  // values they stand for, code / 255, which is how the kernels read them.
  const auto to_linear = [&t](uint8_t code) { return t.srgb ? decode(code) : code / 255.0; };
  const auto to_code = [&t](double v) { return t.srgb ? encode(v) : encode_linear(v); };
  Plane linear(t.rgba.size());
  for (size_t i = 0; i < t.rgba.size(); i += 4) {
    for (int c = 0; c < 3; ++c) linear[i + c] = to_linear(t.rgba[i + c]);
    linear[i + 3] = t.rgba[i + 3] / 255.0;
  }
  auto pack = [](uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
    return uint32_t(r) | uint32_t(g) << 8 | uint32_t(b) << 16 | uint32_t(a) << 24;
  };
  for (uint32_t k = 0; k < levels; ++k) {
    chain.levels.push_back({w, h, static_cast<uint32_t>(chain.texels.size())});
    if (k == 0) {  // the texture's own codes, bit for bit
      for (size_t i = 0; i < t.rgba.size(); i += 4)
        chain.texels.push_back(pack(t.rgba[i], t.rgba[i + 1], t.rgba[i + 2], t.rgba[i + 3]));
    } else {
      for (size_t i = 0; i < linear.size(); i += 4)
        chain.texels.push_back(pack(to_code(linear[i]), to_code(linear[i + 1]),
                                    to_code(linear[i + 2]), encode_linear(linear[i + 3])));
    }
    if (k + 1 < levels) {
      uint32_t nw = 0, nh = 0;
      linear = downsample(linear, w, h, nw, nh);
      w = nw;
      h = nh;
    }
  }
  return chain;
}

}  // namespace rp::render
