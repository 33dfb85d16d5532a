// How a punctual light (frame_scene.h PunctualLight, glTF KHR_lights_punctual) reaches a
// point: the direction towards it, the distance a shadow ray must cover and the attenuation
// that multiplies its intensity. Shared by the path tracer and the tests of the real-time
// kernels (kernels/common/punctual_light.h does the same arithmetic in OpenCL C).
#pragma once

#include <glm/glm.hpp>

#include "scene/frame_scene.h"

namespace rp::scene {

struct LightSample {
  glm::vec3 l{0.0f};         // unit vector from the point towards the light
  float distance = 0.0f;     // to the light (directional: +infinity-like, 1e30)
  float attenuation = 0.0f;  // direct radiance = albedo * intensity * cos * attenuation
};

// point, spot: 1 / d^2 x glTF's range window clamp(1 - (d / range)^4, 0, 1) (range > 0) x the
// spot's cone t^2, t = clamp((cos a - cos outer) / (cos inner - cos outer), 0, 1) where a is
// the angle between the spot's axis and the direction from the light to p (a hard edge when
// inner >= outer); directional: 1. Zero at the light's own position.
LightSample sample_light(const PunctualLight& light, glm::vec3 p);

}  // namespace rp::scene
