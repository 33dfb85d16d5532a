// Image comparison for golden tests.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rp::test {

// PSNR in dB of two RGBA8 images of equal size over the RGB channels (peak 255); +infinity when
// identical.
double psnr_rgb8(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

struct Rgba8Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

// Loads a PNG as RGBA8 (throws std::runtime_error naming the file on failure).
Rgba8Image load_png(const std::string& path);
void save_png(const std::string& path, const Rgba8Image& image);

}  // namespace rp::test
