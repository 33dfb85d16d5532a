// C++ reference of the light pass's unshadowed direct factor (kernels/common/direct_light.h),
// in double, for the light and soft-shadow tests.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

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

}  // namespace rp::test
