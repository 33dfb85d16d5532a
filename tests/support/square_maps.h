// Small environment maps for the suns' and glow's tests (scene/environment_suns.h,
// scene/environment_glow.h): 128 x 64 texels, a background with grey squares painted on it.
#pragma once

#include <cmath>
#include <cstdlib>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/environment.h"

namespace rp::test {

// A grey square of radiance `value`, half-size `half` texels, centred on texel (x, y).
struct MapSquare {
  int x, y, half;
  float value;
};

// The map whose texel (x, y) is background(x, y), with `squares` painted on it in order (later
// ones on top).
inline scene::EnvironmentMap square_map(const std::function<glm::vec3(int x, int y)>& background,
                                        const std::vector<MapSquare>& squares) {
  scene::EnvironmentMap map;
  map.width = 128;
  map.height = 64;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      glm::vec3 c = background(x, y);
      for (const MapSquare& s : squares)
        if (std::abs(x - s.x) <= s.half && std::abs(y - s.y) <= s.half) c = glm::vec3(s.value);
      map.rgb.insert(map.rgb.end(), {c.x, c.y, c.z});
    }
  return map;
}

// A texel's solid angle in row y, (2 pi / w)(pi / h) sin theta at its centre (the suns' and the
// glow's own measure).
inline double texel_solid_angle(const scene::EnvironmentMap& map, int y) {
  constexpr double kPi = 3.14159265358979323846;
  return (2.0 * kPi / map.width) * (kPi / map.height) *
         std::sin(kPi * (double(y) + 0.5) / double(map.height));
}

}  // namespace rp::test
