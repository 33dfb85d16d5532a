// Random numbers and direction sampling of the path tracer (truth/path_tracer.h). Header-only so
// the tests can check each sampler against its density.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "shading/basis.h"

namespace rp::truth {

inline constexpr float kPi = 3.14159265358979323846f;

// SplitMix64 (Steele, Lea, Flood 2014): a bijective 64-bit mixer; seeds the per-pixel streams.
inline uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// PCG32 (O'Neill 2014, XSH-RR output): 64-bit state, one stream per odd increment. Each pixel
// gets the stream of its index, so what a pixel draws depends only on (seed, pixel).
class Pcg32 {
 public:
  Pcg32(uint64_t seed, uint64_t stream) : inc_((stream << 1) | 1u) {
    next();
    state_ += splitmix64(seed);
    next();
  }
  uint32_t next() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const uint32_t xorshifted = uint32_t(((old >> 18) ^ old) >> 27);
    const uint32_t rot = uint32_t(old >> 59);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  // Uniform in [0, 1): the top 24 bits, so every value is exact in float and below 1.
  float uniform() { return float(next() >> 8) * (1.0f / 16777216.0f); }

 private:
  uint64_t state_ = 0, inc_;
};

// The orthonormal basis around a unit normal (shared with the BRDF).
using Frame = shading::Basis;

// Cosine-weighted direction about n from (u1, u2) in [0,1)^2; density cos(theta) / pi per
// steradian.
inline glm::vec3 sample_cosine_hemisphere(glm::vec3 n, float u1, float u2) {
  const float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
  const float z = std::sqrt(std::max(0.0f, 1.0f - u1));
  return Frame(n).to_world(glm::vec3(r * std::cos(phi), r * std::sin(phi), z));
}

// Uniform direction in the cone about unit axis w whose half angle has 1 - cos = omc (given as
// 1 - cos so small cones keep their precision); density cone_pdf(omc) = 1 / (2 pi omc) per
// steradian.
inline glm::vec3 sample_cone(glm::vec3 w, float omc, float u1, float u2) {
  const float one_minus_cos = u1 * omc;
  const float cos_t = 1.0f - one_minus_cos;
  const float sin_t = std::sqrt(std::max(0.0f, one_minus_cos * (2.0f - one_minus_cos)));
  const float phi = 2.0f * kPi * u2;
  return Frame(w).to_world(glm::vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t));
}
inline float cone_pdf(float omc) { return 1.0f / (2.0f * kPi * omc); }

// 1 - cos of the half angle a sphere of radius r subtends from distance d > r, as
// s2 / (1 + sqrt(1 - s2)) with s2 = (r / d)^2, precise for small far spheres.
inline float sphere_cone_omc(float r, float d) {
  const float s2 = (r * r) / (d * d);
  return s2 / (1.0f + std::sqrt(std::max(0.0f, 1.0f - s2)));
}

// The lamp as an area light (PathTraceSettings::lamp == LampModel::kArea): the part below the
// ceiling plane y = ceiling of the sphere (centre, radius) the lamp cap is cut from
// (scene::make_lamp_cap), emitting with constant radiance (Lambertian). Its light reaches a point
// along the directions whose first meeting with the sphere lies below the ceiling: a ray from
// below the ceiling that met the sphere above it would have passed the ceiling outside the cut
// disc (the box itself never occludes the lamp, as in the point model).
struct LampCap {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
  float ceiling = 1.0f;

  // Distance t > 0 along unit `dir` from `org` to the cap, or -1 when the ray misses the sphere,
  // meets it first above the ceiling or starts inside it.
  float hit(glm::vec3 org, glm::vec3 dir) const {
    const glm::vec3 oc = centre - org;
    const float c = glm::dot(oc, oc) - radius * radius;
    const float b = glm::dot(oc, dir);
    if (c <= 0.0f || b <= 0.0f) return -1.0f;  // inside, or the sphere is behind
    const float disc = b * b - c;
    if (disc < 0.0f) return -1.0f;
    const float t = c / (b + std::sqrt(disc));  // = b - sqrt(disc), without the cancellation
    return org.y + t * dir.y < ceiling ? t : -1.0f;
  }
  // The cap's area projected on a horizontal plane, over pi: the squared radius of its outline
  // seen from far below. With the centre h above the ceiling (0 < h < radius) the outline is the
  // cut circle, radius^2 - h^2 (the sphere's own silhouette lies above the ceiling); with the
  // centre at or below the ceiling it is the equator, radius^2.
  float projected_radius2() const {
    const float h = centre.y - ceiling;
    return h > 0.0f ? radius * radius - h * h : radius * radius;
  }
};

// Power heuristic (beta = 2) weight of a sample drawn with density pa, the other strategy pb.
inline float power_heuristic(float pa, float pb) {
  const float a = pa * pa, b = pb * pb;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

inline float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

}  // namespace rp::truth
