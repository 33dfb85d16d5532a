#include "scene/punctual_light.h"

#include <algorithm>
#include <cmath>

namespace rp::scene {

LightSample sample_light(const PunctualLight& light, glm::vec3 p) {
  LightSample s;
  if (light.type == LightType::kDirectional) {
    s.l = -light.direction;
    s.distance = 1.0e30f;
    s.attenuation = 1.0f;
    return s;
  }
  const glm::vec3 to_light = light.position - p;
  const float d2 = glm::dot(to_light, to_light);
  if (!(d2 > 0.0f)) return s;
  s.distance = std::sqrt(d2);
  s.l = to_light / s.distance;
  float a = 1.0f / d2;
  if (light.range > 0.0f) {
    const float r = s.distance / light.range;
    a *= std::clamp(1.0f - (r * r) * (r * r), 0.0f, 1.0f);
  }
  if (light.type == LightType::kSpot) {
    const float cos_a = glm::dot(-s.l, light.direction);
    const float cos_outer = std::cos(light.outer_cone), cos_inner = std::cos(light.inner_cone);
    float t;
    if (cos_inner - cos_outer > 1.0e-6f)
      t = std::clamp((cos_a - cos_outer) / (cos_inner - cos_outer), 0.0f, 1.0f);
    else
      t = cos_a >= cos_outer ? 1.0f : 0.0f;
    a *= t * t;
  }
  s.attenuation = a;
  return s;
}

}  // namespace rp::scene
