#include "scene/environment_suns.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace rp::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

float luminance(const float* rgb) {
  return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2];
}

// One patch found by the flood fill: its texels and what taking it out gives.
struct Patch {
  std::vector<size_t> texels;
  glm::dvec3 weighted_direction{0.0};
  double excess = 0.0, solid_angle = 0.0;  // luminance x sr, sr
};

}  // namespace

EnvironmentSuns find_environment_suns(const EnvironmentMap& map, int max_suns) {
  EnvironmentSuns out;
  const int w = map.width, h = map.height;
  if (max_suns <= 0 || w <= 0 || h <= 0 || map.rgb.size() != size_t(w) * size_t(h) * 3)
    return out;
  std::vector<double> row_solid_angle(static_cast<size_t>(h));
  std::vector<float> lum(size_t(w) * size_t(h));
  double power = 0.0;
  for (int y = 0; y < h; ++y) {
    row_solid_angle[size_t(y)] =
        (2.0 * kPi / w) * (kPi / h) * std::sin(kPi * (double(y) + 0.5) / double(h));
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      lum[i] = std::max(0.0f, luminance(&map.rgb[3 * i]));
      power += double(lum[i]) * row_solid_angle[size_t(y)];
    }
  }
  const double mean = power / (4.0 * kPi);
  if (!(mean > 0.0)) return out;
  const float edge = float(kSunEdge * mean), peak = float(kSunPeak * mean);

  // Texels brightest first: each unvisited one above the peak level seeds a patch.
  std::vector<size_t> order;
  for (size_t i = 0; i < lum.size(); ++i)
    if (lum[i] >= peak) order.push_back(i);
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return lum[a] != lum[b] ? lum[a] > lum[b] : a < b; });
  std::vector<uint8_t> visited(lum.size(), 0);
  std::vector<Patch> patches;
  std::vector<size_t> stack;
  for (const size_t seed : order) {
    if (visited[seed]) continue;
    Patch patch;
    visited[seed] = 1;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      patch.texels.push_back(i);
      const int x = int(i % size_t(w)), y = int(i / size_t(w));
      for (int dy = -1; dy <= 1; ++dy) {
        const int yy = y + dy;
        if (yy < 0 || yy >= h) continue;
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = (x + dx + w) % w;
          const size_t j = size_t(yy) * size_t(w) + size_t(xx);
          if (!visited[j] && lum[j] >= edge) {
            visited[j] = 1;
            stack.push_back(j);
          }
        }
      }
    }
    for (const size_t i : patch.texels) {
      const int x = int(i % size_t(w)), y = int(i / size_t(w));
      const double sa = row_solid_angle[size_t(y)];
      const double excess = (double(lum[i]) - double(edge)) * sa;
      patch.excess += excess;
      patch.solid_angle += sa;
      patch.weighted_direction += excess * glm::dvec3(environment_direction(
                                               (float(x) + 0.5f) / float(w),
                                               (float(y) + 0.5f) / float(h)));
    }
    if (patch.excess >= kSunMinShare * power && patch.solid_angle <= kSunMaxSolidAngle)
      patches.push_back(std::move(patch));
  }
  std::stable_sort(patches.begin(), patches.end(),
                   [](const Patch& a, const Patch& b) { return a.excess > b.excess; });
  if (patches.size() > size_t(max_suns)) patches.resize(size_t(max_suns));
  if (patches.empty()) return out;

  auto residual = std::make_shared<EnvironmentMap>(map);
  for (const Patch& patch : patches) {
    for (const size_t i : patch.texels) {
      const float keep = edge / lum[i];
      for (size_t c = 0; c < 3; ++c) residual->rgb[3 * i + c] = map.rgb[3 * i + c] * keep;
    }
    EnvironmentSun sun;
    // The light is what the map loses, texel by texel, as float: map - residual.
    glm::dvec3 irradiance(0.0);
    for (const size_t i : patch.texels) {
      const double sa = row_solid_angle[i / size_t(w)];
      for (size_t c = 0; c < 3; ++c)
        irradiance[int(c)] += double(map.rgb[3 * i + c] - residual->rgb[3 * i + c]) * sa;
    }
    sun.irradiance = glm::vec3(irradiance);
    sun.direction = glm::vec3(glm::normalize(patch.weighted_direction));
    sun.solid_angle = float(patch.solid_angle);
    sun.share = float(patch.excess / power);
    out.suns.push_back(sun);
  }
  out.residual = std::move(residual);
  return out;
}

PunctualLight environment_sun_light(const EnvironmentSun& sun, int index, float rotate_deg,
                                    float strength) {
  const glm::vec3 towards = environment_to_world(sun.direction, rotate_deg);
  PunctualLight light;
  light.name = "environment sun " + std::to_string(index + 1);
  light.type = LightType::kDirectional;
  light.direction = -towards;  // the way the light travels
  light.intensity = sun.irradiance * (strength / float(kPi));
  light.in_environment = true;
  return light;
}

}  // namespace rp::scene
