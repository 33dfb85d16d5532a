#include "support/image_metrics.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

namespace rp::test {

double psnr_rgb8(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  if (a.size() != b.size() || a.size() % 4 != 0)
    throw std::runtime_error("psnr_rgb8: images differ in size");
  double sum = 0.0;
  size_t count = 0;
  for (size_t i = 0; i < a.size(); i += 4)
    for (size_t c = 0; c < 3; ++c) {
      double d = double(a[i + c]) - double(b[i + c]);
      sum += d * d;
      ++count;
    }
  if (sum == 0.0) return std::numeric_limits<double>::infinity();
  double mse = sum / double(count);
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

Rgba8Image load_png(const std::string& path) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 4);
  if (!data) throw std::runtime_error("cannot read image " + path + ": " + stbi_failure_reason());
  Rgba8Image img{w, h, std::vector<uint8_t>(data, data + size_t(w) * h * 4)};
  stbi_image_free(data);
  return img;
}

void save_png(const std::string& path, const Rgba8Image& image) {
  if (!stbi_write_png(path.c_str(), image.width, image.height, 4, image.rgba.data(),
                      image.width * 4))
    throw std::runtime_error("cannot write image " + path);
}

}  // namespace rp::test
