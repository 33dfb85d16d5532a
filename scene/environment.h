// An environment light: radiance arriving from infinitely far away, given as an
// equirectangular map (sky or studio HDR), with a strength and a turn about the vertical axis.
//
// Map layout: linear RGB, 3 floats per texel, rows top to bottom. Row v (0 at the top edge,
// 1 at the bottom) is the polar angle theta = pi v from +y (the world's up: the demo's floor
// is y = -1); column u is the azimuth phi = 2 pi u measured from -z towards +x, so the map's
// centre (u = 0.5) lies towards +z and its left and right edges towards -z:
//   dir = (sin theta sin phi, cos theta, -sin theta cos phi).
// rotate_deg turns the environment about +y (counter-clockwise seen from above).
#pragma once

#include <cmath>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

namespace rp::scene {

struct EnvironmentMap {
  int width = 0, height = 0;
  std::vector<float> rgb;  // width * height * 3, linear radiance
};

struct EnvironmentGlow;  // scene/environment_glow.h

struct Environment {
  std::shared_ptr<const EnvironmentMap> map;  // nullptr: no environment light
  float strength = 1.0f;                      // multiplies the map's radiance
  float rotate_deg = 0.0f;                    // turn about +y
  // The map without its suns (scene/environment_suns.h), or nullptr when none were taken out.
  // The real-time modes gather this one (cones, PRT) and light by the suns as the frame's
  // directional lights marked in_environment; the background shows `map`, and the path tracer
  // samples `map` whole and counts map - residual at the first vertex as direct light.
  std::shared_ptr<const EnvironmentMap> residual;
  // The residual's glow around the suns (scene/environment_glow.h), or nullptr: part of the
  // residual for every mode but PRT, which traces it apart from the band-limited sky.
  std::shared_ptr<const EnvironmentGlow> glow;
  bool enabled() const { return map != nullptr && map->width > 0 && map->height > 0; }
  // What the real-time modes gather: the residual where suns were taken out, else the map.
  const std::shared_ptr<const EnvironmentMap>& gathered_map() const {
    return residual ? residual : map;
  }
};

// Unit direction (in the map's frame) of map coordinates (u, v) in [0, 1]^2.
inline glm::vec3 environment_direction(float u, float v) {
  constexpr float kPi = 3.14159265358979f;
  const float theta = kPi * v, phi = 2.0f * kPi * u;
  const float s = std::sin(theta);
  return {s * std::sin(phi), std::cos(theta), -s * std::cos(phi)};
}

// Map coordinates (u in [0, 1), v in [0, 1]) of unit direction `d` in the map's frame.
inline glm::vec2 environment_uv(glm::vec3 d) {
  constexpr float kPi = 3.14159265358979f;
  float u = std::atan2(d.x, -d.z) / (2.0f * kPi);
  if (u < 0.0f) u += 1.0f;
  if (u >= 1.0f) u -= 1.0f;
  const float v = std::acos(std::fmax(-1.0f, std::fmin(1.0f, d.y))) / kPi;
  return {u, v};
}

// World direction of map-frame direction `d` for a map turned by `rotate_deg` about +y
// (truth::EnvironmentSampler::to_world's turn).
inline glm::vec3 environment_to_world(glm::vec3 d, float rotate_deg) {
  const float a = rotate_deg * 0.0174532925f, c = std::cos(a), s = std::sin(a);
  return {c * d.x + s * d.z, d.y, -s * d.x + c * d.z};
}

}  // namespace rp::scene
