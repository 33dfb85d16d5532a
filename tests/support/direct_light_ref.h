// C++ reference of the light pass's unshadowed direct factor (kernels/common/direct_light.h),
// in double, for the light and soft-shadow tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/frame_scene.h"

namespace rp::test {

// The documented falloff: visible projected area of the lamp cap relative to straight below,
// s = l.y (the sine of the lamp's elevation seen from the point).
inline double lamp_falloff_ref(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return 0.35 + s * (0.446 + 0.204 * s);
}

// cos / d^2 * falloff at point p with unit normal n, lamp centre `light` (no albedo, intensity
// or shadow); 0 when the surface faces away.
inline double direct_factor_ref(const glm::vec3& p, const glm::vec3& n, const glm::vec3& light) {
  const glm::dvec3 to = glm::dvec3(light) - glm::dvec3(p);
  const double d2 = glm::dot(to, to);
  const glm::dvec3 l = to / std::sqrt(d2);
  const double c = glm::dot(glm::dvec3(n), l);
  return c <= 0.0 ? 0.0 : c / d2 * lamp_falloff_ref(l.y);
}

// A size x size shadow map of the lamp's view (light.view_proj(), depth z_ndc * 0.5 + 0.5, rows
// top to bottom, 1 = empty) ray cast in double: hit(origin, unit dir) returns the distance to
// the nearest occluder along the texel centre's ray, or < 0 for none.
inline std::vector<float> shadow_map_ref(
    const scene::PointLight& light, uint32_t size,
    const std::function<double(glm::dvec3, glm::dvec3)>& hit) {
  const glm::dmat4 vp(light.view_proj());
  const glm::dmat4 inv = glm::inverse(vp);
  const glm::dvec3 origin(light.position);
  std::vector<float> map(size_t(size) * size, 1.0f);
  for (uint32_t ty = 0; ty < size; ++ty)
    for (uint32_t tx = 0; tx < size; ++tx) {
      const double nx = (tx + 0.5) / size * 2.0 - 1.0, ny = 1.0 - (ty + 0.5) / size * 2.0;
      const glm::dvec4 f = inv * glm::dvec4(nx, ny, 1.0, 1.0);
      const glm::dvec3 dir = glm::normalize(glm::dvec3(f) / f.w - origin);
      const double t = hit(origin, dir);
      if (t < 0) continue;
      const glm::dvec4 c = vp * glm::dvec4(origin + dir * t, 1.0);
      map[size_t(ty) * size + tx] = float(c.z / c.w * 0.5 + 0.5);
    }
  return map;
}

}  // namespace rp::test
