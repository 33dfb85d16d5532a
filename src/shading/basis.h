// An orthonormal basis (t, b, n) around a unit normal n, n as local z (Duff et al. 2017,
// branchless): shared by the BRDF (src/shading) and the path tracer's samplers (src/truth).
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace rp::shading {

struct Basis {
  glm::vec3 t, b, n;
  explicit Basis(glm::vec3 normal) : n(normal) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float bb = n.x * n.y * a;
    t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * bb, -sign * n.x);
    b = glm::vec3(bb, sign + n.y * n.y * a, -n.y);
  }
  glm::vec3 to_local(glm::vec3 v) const { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
  glm::vec3 to_world(glm::vec3 v) const { return v.x * t + v.y * b + v.z * n; }
};

}  // namespace rp::shading
