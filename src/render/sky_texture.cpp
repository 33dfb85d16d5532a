#include "render/sky_texture.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "render/sky_cells.h"

namespace rp::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Level {
  int width = 0, height = 0;
  std::vector<double> rgb;  // width * height * 3
};

// Solid angle of a texel row of `height` rows, per unit of azimuth: cos theta0 - cos theta1.
double row_weight(int y, int height) {
  return std::cos(kPi * y / height) - std::cos(kPi * (y + 1) / height);
}

// The 2x2 solid-angle weighted mean of `fine` (an odd last row or column counts once).
Level halve(const Level& fine) {
  Level coarse;
  coarse.width = std::max(fine.width / 2, 1);
  coarse.height = std::max(fine.height / 2, 1);
  coarse.rgb.assign(size_t(coarse.width) * coarse.height * 3, 0.0);
  for (int y = 0; y < coarse.height; ++y) {
    const int y0 = std::min(2 * y, fine.height - 1), y1 = std::min(2 * y + 1, fine.height - 1);
    const double w0 = row_weight(y0, fine.height);
    const double w1 = y1 != y0 ? row_weight(y1, fine.height) : 0.0;
    const double inv = 1.0 / (2.0 * (w0 + w1));
    for (int x = 0; x < coarse.width; ++x) {
      const int x0 = std::min(2 * x, fine.width - 1), x1 = std::min(2 * x + 1, fine.width - 1);
      for (int c = 0; c < 3; ++c) {
        const auto at = [&](int xx, int yy) {
          return fine.rgb[(size_t(yy) * fine.width + xx) * 3 + c];
        };
        coarse.rgb[(size_t(y) * coarse.width + x) * 3 + c] =
            (w0 * (at(x0, y0) + at(x1, y0)) + w1 * (at(x0, y1) + at(x1, y1))) * inv;
      }
    }
  }
  return coarse;
}

// Level 0 of `map`'s chain: the map, halved down to kSkyMaxWidth.
Level first_level(const scene::EnvironmentMap& map) {
  if (map.width <= 0 || map.height <= 0 ||
      map.rgb.size() != size_t(map.width) * size_t(map.height) * 3)
    throw std::invalid_argument("sky texture: " + std::to_string(map.rgb.size()) +
                                " floats for a " + std::to_string(map.width) + "x" +
                                std::to_string(map.height) + " map");
  Level level;
  level.width = map.width;
  level.height = map.height;
  level.rgb.assign(map.rgb.begin(), map.rgb.end());
  while (level.width > kSkyMaxWidth) level = halve(level);
  return level;
}

void append_texels(const Level& level, std::vector<gpu::rp_float4>& texels) {
  for (size_t t = 0; t < size_t(level.width) * level.height; ++t)
    texels.push_back({float(level.rgb[3 * t]), float(level.rgb[3 * t + 1]),
                      float(level.rgb[3 * t + 2]), 0.0f});
}

}  // namespace

std::vector<gpu::rp_float4> build_sky_level0(const scene::EnvironmentMap& map) {
  std::vector<gpu::rp_float4> texels;
  append_texels(first_level(map), texels);
  return texels;
}

SkyTexture build_sky_texture(const scene::EnvironmentMap& map) {
  Level level = first_level(map);

  SkyTexture out;
  out.info.turn = {1.0f, 0.0f, 1.0f, 0.0f};
  out.info.width = uint32_t(level.width);
  out.info.height = uint32_t(level.height);
  Level cell_source;  // the first level at most kSkyCellMapHeight tall
  for (uint32_t l = 0; l < RP_SKY_MAX_LEVELS; ++l) {
    out.info.level_offset[l] = uint32_t(out.texels.size());
    out.info.levels = l + 1;
    append_texels(level, out.texels);
    if (cell_source.height == 0 && level.height <= kSkyCellMapHeight) cell_source = level;
    if (level.height == 1) break;
    level = halve(level);
  }
  out.info.cell_offset = uint32_t(out.texels.size());
  const std::vector<gpu::rp_float4> cells =
      sky_cell_table({cell_source.width, cell_source.height, cell_source.rgb.data()});
  out.texels.insert(out.texels.end(), cells.begin(), cells.end());
  return out;
}

uint64_t sky_level0_texel_count(int width, int height) {
  int w = std::max(width, 1), h = std::max(height, 1);
  while (w > kSkyMaxWidth) {
    w = std::max(w / 2, 1);
    h = std::max(h / 2, 1);
  }
  return uint64_t(w) * uint64_t(h);
}

uint64_t sky_texel_count(int width, int height) {
  int w = std::max(width, 1), h = std::max(height, 1);
  while (w > kSkyMaxWidth) {
    w = std::max(w / 2, 1);
    h = std::max(h / 2, 1);
  }
  uint64_t texels = 0;
  for (uint32_t l = 0; l < RP_SKY_MAX_LEVELS; ++l) {
    texels += uint64_t(w) * uint64_t(h);
    if (h == 1) break;
    w = std::max(w / 2, 1);
    h = std::max(h / 2, 1);
  }
  return texels + uint64_t(RP_SKY_CELL_SIDE) * RP_SKY_CELL_SIDE * 16u;
}

gpu::SkyGpu sky_record(const gpu::SkyGpu& levels, const scene::Environment& environment) {
  if (!environment.enabled()) return gpu::SkyGpu{};
  gpu::SkyGpu info = levels;
  constexpr float kDegree = float(kPi / 180.0);
  info.diffuse_cones = 1;
  info.turn = {std::cos(environment.rotate_deg * kDegree),
               std::sin(environment.rotate_deg * kDegree), environment.strength, 0.0f};
  return info;
}

}  // namespace rp::render
