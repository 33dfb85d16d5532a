// The path tracer's environment light (scene/environment.h): radiance by direction, and
// directions sampled in proportion to the map's luminance times sin(theta) (each texel's share
// of the sphere), for next-event estimation combined with the BRDF's own samples by multiple
// importance sampling (power heuristic, truth/sampling.h).
//
// Sampling: a row by the marginal CDF of the rows' weights, a texel in it by the row's CDF, a
// point uniformly inside the texel's (u, v) rectangle. Density over the map's unit square
// p(u, v) = W_texel / W_total * width * height, over solid angle p(dir) = p(u, v) /
// (2 pi^2 sin theta). Radiance is read from the texel without filtering (the same value the
// density was built from, so pdf and radiance agree texel by texel).
#pragma once

#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "scene/environment.h"

namespace rp::truth {

class EnvironmentSampler {
 public:
  explicit EnvironmentSampler(const scene::Environment& environment);

  bool enabled() const { return enabled_; }
  // Radiance arriving from world direction `dir` (unit; strength and rotation applied).
  glm::vec3 radiance(glm::vec3 dir) const;

  // The part of radiance(dir) that the environment's suns took out of the map (map -
  // residual, scene::Environment::residual): what the real-time modes light by directional
  // lights, the path tracer's direct light at the first vertex. 0 without suns.
  glm::vec3 sun_radiance(glm::vec3 dir) const;

  struct Sample {
    glm::vec3 dir{0.0f};       // world, unit
    glm::vec3 radiance{0.0f};  // radiance(dir)
    glm::vec3 sun{0.0f};       // sun_radiance(dir), a part of radiance
    float pdf = 0.0f;          // per unit solid angle
  };
  Sample sample(float u1, float u2) const;
  // The density sample() has at world direction `dir`, per unit solid angle.
  float pdf(glm::vec3 dir) const;

 private:
  size_t texel_of(glm::vec3 map_dir) const;
  glm::vec3 sun_part(size_t texel) const;
  glm::vec3 to_map(glm::vec3 world) const;
  glm::vec3 to_world(glm::vec3 map) const;

  bool enabled_ = false;
  const scene::EnvironmentMap* map_ = nullptr;
  const scene::EnvironmentMap* residual_ = nullptr;  // the map without its suns, or none
  float strength_ = 1.0f;
  float cos_turn_ = 1.0f, sin_turn_ = 0.0f;
  std::vector<float> row_cdf_;    // height entries, inclusive, last = 1
  std::vector<float> texel_cdf_;  // width entries per row, inclusive, last of a row = 1
  std::vector<float> density_;    // per texel: p(u, v) over the unit square
};

// Reads an equirectangular map: OpenEXR (.exr, its R, G, B) or Radiance HDR (.hdr, through
// stb_image). Throws std::runtime_error naming the file and what is wrong (unreadable, not an
// image, non-finite texels, not 2:1); negative texels (a lossy codec's ringing) read as 0.
scene::EnvironmentMap load_environment_map(const std::filesystem::path& path);

}  // namespace rp::truth
