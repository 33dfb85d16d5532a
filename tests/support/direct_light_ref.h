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

// cos / (d^2 + a^2) * falloff at point p with unit normal n (no albedo, intensity or shadow;
// 0 when the surface faces away): the lamp's disk model of kernels/common/direct_light.h. The
// direction l (cos, falloff) is towards the lamp centre; d is the distance to the emitting
// disk's centre (on the lamp's axis in the ceiling, y = 1) and a the disk's radius
// (sqrt(R^2 - z_e^2), z_e the lamp centre's height above the ceiling): on the disk's axis that
// is the disk's exact projected solid angle a^2 / (a^2 + d^2) over the far field's a^2 / d^2.
inline double direct_factor_ref(const glm::vec3& p, const glm::vec3& n,
                                const scene::PointLight& light) {
  const glm::dvec3 to = glm::dvec3(light.position) - glm::dvec3(p);
  const glm::dvec3 to_disk = glm::dvec3(light.position.x, 1.0, light.position.z) - glm::dvec3(p);
  const double ze = double(light.position.y) - 1.0;
  const double a2 = std::max(double(light.lamp_radius) * light.lamp_radius - ze * ze, 0.0);
  const glm::dvec3 l = glm::normalize(to);
  const double c = glm::dot(glm::dvec3(n), l);
  return c <= 0.0 ? 0.0 : c / (glm::dot(to_disk, to_disk) + a2) * lamp_falloff_ref(l.y);
}

// A shadow map of the lamp's view (light.view_proj(), depth z_ndc * 0.5 + 0.5, rows top to
// bottom) ray cast in double, in the layout of render::ShadowMap::depth: size x size texels of
// the NEAREST occluder (1 = empty), then size x size of the FARTHEST occluder surface (0 =
// none). hit(origin, unit dir) returns the distance to the nearest occluder along the texel
// centre's ray, or < 0 for none; exit(origin, dir), when given, the distance to the farthest
// (without it every occluder is a sheet: farthest = nearest).
inline std::vector<float> shadow_map_ref(
    const scene::PointLight& light, uint32_t size,
    const std::function<double(glm::dvec3, glm::dvec3)>& hit,
    const std::function<double(glm::dvec3, glm::dvec3)>& exit = nullptr) {
  const glm::dmat4 vp(light.view_proj());
  const glm::dmat4 inv = glm::inverse(vp);
  const glm::dvec3 origin(light.position);
  const size_t plane = size_t(size) * size;
  std::vector<float> map(2 * plane, 1.0f);
  std::fill(map.begin() + std::ptrdiff_t(plane), map.end(), 0.0f);
  auto depth = [&](const glm::dvec3& dir, double t) {
    const glm::dvec4 c = vp * glm::dvec4(origin + dir * t, 1.0);
    return float(c.z / c.w * 0.5 + 0.5);
  };
  for (uint32_t ty = 0; ty < size; ++ty)
    for (uint32_t tx = 0; tx < size; ++tx) {
      const double nx = (tx + 0.5) / size * 2.0 - 1.0, ny = 1.0 - (ty + 0.5) / size * 2.0;
      const glm::dvec4 f = inv * glm::dvec4(nx, ny, 1.0, 1.0);
      const glm::dvec3 dir = glm::normalize(glm::dvec3(f) / f.w - origin);
      const double t = hit(origin, dir);
      if (t < 0) continue;
      const size_t i = size_t(ty) * size + tx;
      map[i] = depth(dir, t);
      const double t_far = exit ? exit(origin, dir) : t;
      map[plane + i] = depth(dir, std::max(t_far, t));
    }
  return map;
}

// A one-plane (nearest-only) hand-made map completed with its farthest plane = the nearest
// (sheets), in render::ShadowMap::depth's layout.
inline std::vector<float> with_sheet_back_plane(std::vector<float> nearest) {
  const size_t plane = nearest.size();
  nearest.resize(2 * plane);
  for (size_t i = 0; i < plane; ++i) nearest[plane + i] = nearest[i] < 1.0f ? nearest[i] : 0.0f;
  return nearest;
}

}  // namespace rp::test
