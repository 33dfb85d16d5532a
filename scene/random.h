// Seeded, platform-independent random numbers for the simulation (PCG32, O'Neill 2014).
// Only integer arithmetic and exactly specified float conversions, so a seed gives the same
// sequence on every compiler and machine (std:: distributions do not guarantee that).
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace rp::scene {

class Rng {
 public:
  explicit Rng(uint64_t seed = 1, uint64_t stream = 0x5851f42d4c957f2dULL) { reseed(seed, stream); }

  void reseed(uint64_t seed, uint64_t stream = 0x5851f42d4c957f2dULL) {
    state_ = 0;
    inc_ = (stream << 1u) | 1u;
    next_u32();
    state_ += seed;
    next_u32();
  }

  uint32_t next_u32() {
    uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }

  // Uniform in [0, 1): the top 24 bits, exactly representable as float.
  float uniform() { return static_cast<float>(next_u32() >> 8) * (1.0f / 16777216.0f); }
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }

  // Uniform inside the unit ball (rejection sampling: deterministic for a given sequence).
  glm::vec3 in_unit_ball() {
    for (;;) {
      // Separate statements: the order of evaluation of function arguments is unspecified.
      float x = uniform(-1.0f, 1.0f);
      float y = uniform(-1.0f, 1.0f);
      float z = uniform(-1.0f, 1.0f);
      glm::vec3 p(x, y, z);
      if (glm::dot(p, p) <= 1.0f) return p;
    }
  }

  // Uniform on the unit sphere.
  glm::vec3 unit_vector() {
    for (;;) {
      glm::vec3 p = in_unit_ball();
      float d = glm::dot(p, p);
      if (d > 1e-6f) return p / glm::sqrt(d);
    }
  }

  uint64_t state() const { return state_; }

 private:
  uint64_t state_ = 0, inc_ = 1;
};

}  // namespace rp::scene
