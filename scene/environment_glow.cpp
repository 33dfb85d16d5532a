#include "scene/environment_glow.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace rp::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

double luminance(const float* rgb) {
  return 0.2126 * double(rgb[0]) + 0.7152 * double(rgb[1]) + 0.0722 * double(rgb[2]);
}

// One grid cell's sums over its glow texels.
struct CellSum {
  glm::dvec3 rgb{0.0};        // radiance x solid angle
  glm::dvec3 direction{0.0};  // luminance x solid angle x the texel's direction
  double lum = 0.0;           // luminance x solid angle
};

}  // namespace

std::shared_ptr<const EnvironmentGlow> find_environment_glow(const EnvironmentMap& map,
                                                             const EnvironmentMap& residual) {
  const int w = map.width, h = map.height;
  const size_t n = size_t(std::max(0, w)) * size_t(std::max(0, h));
  if (residual.width != w || residual.height != h || map.rgb.size() != n * 3 ||
      residual.rgb.size() != n * 3)
    throw std::invalid_argument("environment glow: the residual is not the map's size");
  if (n > size_t(UINT32_MAX))
    throw std::invalid_argument("environment glow: a map of more than 2^32 texels");
  if (n == 0) return nullptr;
  std::vector<double> row_solid_angle(static_cast<size_t>(h));
  double power = 0.0;
  for (int y = 0; y < h; ++y) {
    row_solid_angle[size_t(y)] =
        (2.0 * kPi / w) * (kPi / h) * std::sin(kPi * (double(y) + 0.5) / double(h));
    for (int x = 0; x < w; ++x)
      power += std::max(0.0, luminance(&map.rgb[3 * (size_t(y) * size_t(w) + size_t(x))])) *
               row_solid_angle[size_t(y)];
  }
  const double edge = kGlowEdge * power / (4.0 * kPi);

  // Flood from the suns' patches through bright residual texels.
  std::vector<uint8_t> glow(n, 0);
  std::vector<size_t> stack;
  for (size_t i = 0; i < n; ++i)
    if (map.rgb[3 * i] != residual.rgb[3 * i] || map.rgb[3 * i + 1] != residual.rgb[3 * i + 1] ||
        map.rgb[3 * i + 2] != residual.rgb[3 * i + 2]) {
      glow[i] = 1;
      stack.push_back(i);
    }
  if (stack.empty()) return nullptr;
  while (!stack.empty()) {
    const size_t i = stack.back();
    stack.pop_back();
    const int x = int(i % size_t(w)), y = int(i / size_t(w));
    for (int dy = -1; dy <= 1; ++dy) {
      const int yy = y + dy;
      if (yy < 0 || yy >= h) continue;
      for (int dx = -1; dx <= 1; ++dx) {
        const size_t j = size_t(yy) * size_t(w) + size_t((x + dx + w) % w);
        if (!glow[j] && luminance(&residual.rgb[3 * j]) >= edge) {
          glow[j] = 1;
          stack.push_back(j);
        }
      }
    }
  }

  auto out = std::make_shared<EnvironmentGlow>();
  out->width = w;
  out->height = h;
  for (size_t i = 0; i < n; ++i)
    if (glow[i]) {
      out->texels.push_back(uint32_t(i));
      out->radiance.emplace_back(residual.rgb[3 * i], residual.rgb[3 * i + 1],
                                 residual.rgb[3 * i + 2]);
    }

  // Cells: the finest grid whose glow fits in kMaxGlowCells.
  for (int cells_u = kGlowCells; cells_u >= 2; cells_u /= 2) {
    const int cells_v = cells_u / 2;
    std::vector<CellSum> sums(size_t(cells_u) * size_t(cells_v));
    for (const uint32_t texel : out->texels) {
      const size_t i = texel;
      const int x = int(i % size_t(w)), y = int(i / size_t(w));
      const int cu = std::min(cells_u - 1, int(int64_t(x) * cells_u / w));
      const int cv = std::min(cells_v - 1, int(int64_t(y) * cells_v / h));
      CellSum& s = sums[size_t(cv) * size_t(cells_u) + size_t(cu)];
      const double sa = row_solid_angle[size_t(y)];
      const double lum = std::max(0.0, luminance(&residual.rgb[3 * i])) * sa;
      s.rgb += glm::dvec3(residual.rgb[3 * i], residual.rgb[3 * i + 1], residual.rgb[3 * i + 2]) *
               sa;
      s.lum += lum;
      s.direction += lum * glm::dvec3(environment_direction((float(x) + 0.5f) / float(w),
                                                            (float(y) + 0.5f) / float(h)));
    }
    out->cells.clear();
    for (const CellSum& s : sums) {
      const double length = glm::length(s.direction);
      if (!(s.lum > 0.0) || !(length > 0.0)) continue;
      // the cell's texels' cosine integral on a plane facing it: |sum L w dOmega|, per channel
      // in the luminance's proportion
      out->cells.push_back(
          {glm::vec3(s.direction / length), glm::vec3(s.rgb * (length / s.lum))});
    }
    if (out->cells.size() <= kMaxGlowCells) break;
  }
  if (out->cells.empty()) return nullptr;
  return out;
}

}  // namespace rp::scene
