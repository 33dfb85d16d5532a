// Particle system (SPEC.md section 5): budget and recycling, fire rate, lifetimes, gravity,
// ash cooling, containment in the box, determinism.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "scene/particles.h"

namespace {

using rp::scene::Particle;
using rp::scene::ParticleKind;
using rp::scene::ParticleSystem;
using rp::scene::Rng;
using rp::scene::Sphere;
namespace pc = rp::scene::particle_constants;

constexpr float kDt = 1.0f / 120.0f;

std::vector<Sphere> spheres_of(const ParticleSystem& ps) {
  std::vector<Sphere> out;
  ps.append_spheres(out);
  return out;
}

bool same_bits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(Particles, StartsEmpty) {
  ParticleSystem ps;
  EXPECT_EQ(ps.live_count(), 0u);
  EXPECT_TRUE(spheres_of(ps).empty());
}

TEST(Particles, BudgetIsNeverExceededAndTheNewestAreKept) {
  static_assert(ParticleSystem::kMaxParticles % pc::kAshPerMarble == 0);
  ParticleSystem ps;
  Rng rng(7);
  // 100 tiny "marbles" at distinct x, no step: 6400 particles into 2048 slots.
  constexpr int kCalls = 100;
  constexpr float kTinyRadius = 1e-4f;
  auto centre_of = [](int call) { return glm::vec3(-0.9f + 0.018f * static_cast<float>(call), 0.0f, 0.0f); };
  for (int call = 0; call < kCalls; ++call) {
    ps.emit_ash(centre_of(call), kTinyRadius, glm::vec3(0.0f), rng);
    ASSERT_LE(ps.live_count(), ParticleSystem::kMaxParticles);
  }
  ASSERT_EQ(ps.live_count(), ParticleSystem::kMaxParticles);
  // Oldest first: exactly the particles of the last 2048 / 64 = 32 calls, in call order.
  const std::vector<Particle> live = ps.live_particles();
  const int first_kept = kCalls - static_cast<int>(ParticleSystem::kMaxParticles) / pc::kAshPerMarble;
  for (size_t i = 0; i < live.size(); ++i) {
    const int call = first_kept + static_cast<int>(i) / pc::kAshPerMarble;
    ASSERT_LE(glm::length(live[i].position - centre_of(call)), 1.01f * kTinyRadius) << "particle " << i;
    ASSERT_EQ(live[i].kind, ParticleKind::Ash);
  }
  EXPECT_EQ(spheres_of(ps).size(), ParticleSystem::kMaxParticles);
}

TEST(Particles, HeavyEmissionWhileSteppingStaysWithinBudget) {
  ParticleSystem ps;
  Rng rng(11);
  size_t max_seen = 0;
  for (int step = 0; step < 240; ++step) {
    for (int k = 0; k < 5; ++k) {  // five fireballs, each throwing sparks every step
      const glm::vec3 c(-0.6f + 0.3f * static_cast<float>(k), 0.0f, 0.0f);
      ps.emit_fire(c, 0.1f, glm::vec3(0.5f, 0.0f, 0.0f), kDt, rng);
      ps.emit_sparks(c + glm::vec3(0.0f, -0.1f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), rng);
    }
    ps.emit_ash(glm::vec3(0.0f, 0.5f, 0.0f), 0.05f, glm::vec3(1.0f, 0.0f, 0.0f), rng);
    max_seen = std::max(max_seen, ps.live_count());
    ASSERT_LE(ps.live_count(), ParticleSystem::kMaxParticles);
    ps.step(kDt, rng);
    ASSERT_LE(ps.live_count(), ParticleSystem::kMaxParticles);
    ASSERT_EQ(spheres_of(ps).size(), ps.live_count());
  }
  EXPECT_EQ(max_seen, ParticleSystem::kMaxParticles);  // the emission really was heavy
}

// Fire is emitted at 400 per second whatever the step size (fractional carry).
void expect_fire_rate(float dt, int calls, int fireballs) {
  ParticleSystem ps;
  Rng rng(3);
  for (int i = 0; i < calls; ++i) {
    for (int f = 0; f < fireballs; ++f) ps.emit_fire(glm::vec3(0.0f), 0.1f, glm::vec3(0.0f), dt, rng);
  }
  const double expected = 400.0 * fireballs * static_cast<double>(dt) * calls;  // 1 s of emission
  EXPECT_NEAR(static_cast<double>(ps.live_count()), expected, 1.0) << "dt " << dt;
}

TEST(Particles, FireRateIs400PerSecond) {
  expect_fire_rate(1.0f / 120.0f, 120, 1);
  expect_fire_rate(1.0f / 60.0f, 60, 1);
  expect_fire_rate(1.0f / 144.0f, 144, 1);
  expect_fire_rate(1.0f / 1000.0f, 1000, 1);  // 0.4 per call: carried
  expect_fire_rate(1.0f / 120.0f, 120, 2);    // two fireballs: twice as many
}

TEST(Particles, FireLivesExactly045Seconds) {
  ParticleSystem ps;
  Rng rng(5);
  ps.emit_fire(glm::vec3(0.0f), 0.1f, glm::vec3(0.0f), 0.05f, rng);  // 20 particles
  ASSERT_EQ(ps.live_count(), 20u);
  for (const Particle& p : ps.live_particles()) EXPECT_EQ(p.life, 0.45f);
  for (int k = 1; k <= 60; ++k) {
    ps.step(kDt, rng);
    const float t = static_cast<float>(k) * kDt;
    if (t < 0.45f - 1e-3f) {
      ASSERT_EQ(ps.live_count(), 20u) << "t " << t;
    } else if (t > 0.45f + 1e-3f) {
      ASSERT_EQ(ps.live_count(), 0u) << "t " << t;
    }
  }
}

// Sparks and ash live 1 s +- 20 %; each dies within one step of its own life.
void expect_lifetimes_respected(bool sparks) {
  ParticleSystem ps;
  Rng rng(9);
  if (sparks) {
    ps.emit_sparks(glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f), rng);
  } else {
    ps.emit_ash(glm::vec3(0.0f), 0.05f, glm::vec3(0.0f), rng);
  }
  std::vector<float> lives;
  for (const Particle& p : ps.live_particles()) lives.push_back(p.life);
  ASSERT_EQ(lives.size(), sparks ? static_cast<size_t>(pc::kSparksPerContact)
                                 : static_cast<size_t>(pc::kAshPerMarble));
  for (float life : lives) {
    EXPECT_GE(life, 0.8f);
    EXPECT_LE(life, 1.2f);
  }
  EXPECT_GT(*std::max_element(lives.begin(), lives.end()) - *std::min_element(lives.begin(), lives.end()),
            0.05f);  // jittered
  for (int k = 1; k <= 150; ++k) {
    ps.step(kDt, rng);
    const float t = static_cast<float>(k) * kDt;
    const auto surely_alive = std::count_if(lives.begin(), lives.end(), [&](float l) { return l > t + 1e-4f; });
    const auto maybe_alive = std::count_if(lives.begin(), lives.end(), [&](float l) { return l > t - 1e-4f; });
    ASSERT_GE(static_cast<long>(ps.live_count()), static_cast<long>(surely_alive)) << "t " << t;
    ASSERT_LE(static_cast<long>(ps.live_count()), static_cast<long>(maybe_alive)) << "t " << t;
  }
  EXPECT_EQ(ps.live_count(), 0u);
}

TEST(Particles, SparkLifetimesRespected) { expect_lifetimes_respected(true); }
TEST(Particles, AshLifetimesRespected) { expect_lifetimes_respected(false); }

TEST(Particles, SparksFallUnderGravity) {
  ParticleSystem ps;
  Rng rng(13);
  ps.emit_sparks(glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f), rng);
  const std::vector<Particle> before = ps.live_particles();
  for (const Particle& p : before) EXPECT_GT(p.velocity.y, 0.0f);  // thrown along +y normal
  ps.step(kDt, rng);
  const std::vector<Particle> after = ps.live_particles();
  ASSERT_EQ(after.size(), before.size());
  for (size_t i = 0; i < after.size(); ++i) {
    EXPECT_NEAR(after[i].velocity.y, before[i].velocity.y - 9.81f * kDt, 1e-5f);
    EXPECT_EQ(after[i].velocity.x, before[i].velocity.x);
    EXPECT_EQ(after[i].velocity.z, before[i].velocity.z);
    // Semi-implicit Euler: the new velocity moves the particle.
    EXPECT_NEAR(after[i].position.y, before[i].position.y + after[i].velocity.y * kDt, 1e-6f);
  }
  // After 0.5 s every spark moves down (launch speeds are at most 1.8 m/s < g x 0.5 s).
  for (int k = 1; k < 60; ++k) ps.step(kDt, rng);
  for (const Particle& p : ps.live_particles()) EXPECT_LT(p.velocity.y, 0.0f);
}

TEST(Particles, SparksSpreadAroundTheNormal) {
  ParticleSystem ps;
  Rng rng(17);
  const glm::vec3 n = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));
  ps.emit_sparks(glm::vec3(0.0f), n, rng);
  glm::vec3 mean_dir(0.0f);
  float min_cos = 1.0f;
  for (const Particle& p : ps.live_particles()) {
    const glm::vec3 d = glm::normalize(p.velocity);
    mean_dir += d;
    min_cos = std::min(min_cos, glm::dot(d, n));
    EXPECT_LE(glm::length(p.position), pc::kSparkOffset * 1.001f);
  }
  EXPECT_GT(glm::dot(glm::normalize(mean_dir), n), 0.9f);  // centred on the normal
  EXPECT_GT(min_cos, 0.0f);                                 // spread 0.7: never into the surface
  EXPECT_LT(min_cos, 0.99f);                                // but spread, not a beam
}

TEST(Particles, AshDriftsDownAndInheritsTheMarbleVelocity) {
  ParticleSystem ps;
  Rng rng(19);
  const glm::vec3 marble_v(1.0f, 0.0f, 0.0f);
  ps.emit_ash(glm::vec3(0.0f, 0.5f, 0.0f), 0.05f, marble_v, rng);
  glm::vec3 mean_v(0.0f);
  for (const Particle& p : ps.live_particles()) mean_v += p.velocity;
  mean_v /= static_cast<float>(ps.live_count());
  EXPECT_NEAR(mean_v.x, pc::kAshVelocityScale * marble_v.x, 0.1f);  // proportional to the marble's
  EXPECT_NEAR(mean_v.y, 0.0f, 0.1f);

  const std::vector<Particle> before = ps.live_particles();
  constexpr int kSteps = 60;
  for (int k = 0; k < kSteps; ++k) ps.step(kDt, rng);  // 0.5 s (all still alive: life >= 0.8 s)
  const std::vector<Particle> after = ps.live_particles();
  ASSERT_EQ(after.size(), before.size());
  // Without the random gusts, drag alone would scale v_z by (1 - 1.5 dt)^60.
  const float drag_only = std::pow(1.0f - 1.5f * kDt, static_cast<float>(kSteps));
  float mean_dvy = 0.0f;
  int gusted = 0;
  for (size_t i = 0; i < after.size(); ++i) {
    mean_dvy += after[i].velocity.y - before[i].velocity.y;
    if (std::abs(after[i].velocity.z - before[i].velocity.z * drag_only) > 0.02f) ++gusted;
  }
  mean_dvy /= static_cast<float>(after.size());
  // Expected mean change: -0.15 g (1 - e^{-1.5 x 0.5}) / 1.5 = -0.51 m/s (drag and buoyancy),
  // the random gusts average out; allow for them and the drag discretisation.
  EXPECT_LT(mean_dvy, -0.3f);
  EXPECT_GT(mean_dvy, -0.8f);
  EXPECT_GT(gusted, static_cast<int>(after.size()) / 2);  // random jitter makes them drift
}

TEST(Particles, AshCoolsToBlackBelowItsRadiusThreshold) {
  ParticleSystem ps;
  Rng rng(23);
  ps.emit_ash(glm::vec3(0.0f, 0.5f, 0.0f), 0.05f, glm::vec3(0.0f), rng);
  int glowing = 0, black = 0;
  for (int k = 0; k < 150 && ps.live_count() > 0; ++k) {
    const std::vector<Particle> live = ps.live_particles();
    const std::vector<Sphere> spheres = spheres_of(ps);
    ASSERT_EQ(live.size(), spheres.size());
    for (size_t i = 0; i < live.size(); ++i) {
      const Sphere& s = spheres[i];
      const float q = s.radius / live[i].base_radius;
      const float f = live[i].remaining();
      // Radius shrinks from the base radius towards 0.3 x base with the remaining life.
      EXPECT_NEAR(q, 0.3f + 0.7f * f, 1e-5f);
      if (q < 0.45f) {  // below the threshold: black, emits nothing
        EXPECT_EQ(s.emission, glm::vec3(0.0f));
        EXPECT_LE(std::max({s.albedo.x, s.albedo.y, s.albedo.z}), 0.05f);
        ++black;
      } else if (q > 0.6f) {  // above: a glowing ember, orange-red
        EXPECT_GT(s.emission.x, 0.5f);
        EXPECT_GT(s.emission.x, s.emission.y);
        EXPECT_GT(s.emission.y, s.emission.z);
        ++glowing;
      }
      EXPECT_FALSE(s.casts_shadow);
    }
    ps.step(kDt, rng);
  }
  EXPECT_GT(glowing, 0);
  EXPECT_GT(black, 0);
}

TEST(Particles, FireGoesFromWhiteYellowToDeepRedAndFades) {
  ParticleSystem ps;
  Rng rng(29);
  ps.emit_fire(glm::vec3(0.0f), 0.1f, glm::vec3(0.0f), 0.01f, rng);  // 4 particles
  ASSERT_EQ(ps.live_count(), 4u);
  const Sphere fresh = spheres_of(ps)[0];
  // White-yellow: all channels high, blue lowest; bright like the fireball (x 20).
  EXPECT_GT(fresh.emission.x, 15.0f);
  EXPECT_GT(fresh.emission.y / fresh.emission.x, 0.8f);
  EXPECT_GT(fresh.emission.z / fresh.emission.x, 0.4f);
  EXPECT_LE(fresh.emission.x, 20.0f);
  float last_brightness = fresh.emission.x, last_radius = fresh.radius;
  for (int k = 0; k < 50; ++k) {  // to 0.417 s of 0.45
    ps.step(kDt, rng);
    const Sphere s = spheres_of(ps)[0];
    EXPECT_LT(s.emission.x, last_brightness);
    EXPECT_LT(s.radius, last_radius);
    last_brightness = s.emission.x;
    last_radius = s.radius;
  }
  const Sphere old = spheres_of(ps)[0];
  EXPECT_LT(old.emission.y / old.emission.x, 0.3f);  // deep orange-red
  EXPECT_LT(old.emission.z / old.emission.x, 0.05f);
  EXPECT_LT(old.emission.x, 0.1f * fresh.emission.x);
}

TEST(Particles, FireStartsInsideTheFireballDenserNearTheCentre) {
  ParticleSystem ps;
  Rng rng(31);
  const glm::vec3 c(0.2f, -0.3f, 0.1f), v(0.8f, 0.0f, -0.4f);
  const float radius = 0.1f;
  ps.emit_fire(c, radius, v, 1.0f, rng);  // 400 particles
  int inner = 0;
  glm::vec3 mean_v(0.0f);
  for (const Particle& p : ps.live_particles()) {
    const float d = glm::length(p.position - c);
    EXPECT_LE(d, radius * 1.0001f);
    if (d < 0.5f * radius) ++inner;
    mean_v += p.velocity;
  }
  mean_v /= static_cast<float>(ps.live_count());
  // Uniform in the ball would put 1/8 inside half the radius; denser near the centre means more.
  EXPECT_GT(inner, 400 / 4);
  // Velocity blends the fireball's (weight 0.5) with a random upward one (mean 0.41 m/s up).
  EXPECT_NEAR(mean_v.x, 0.5f * v.x, 0.03f);
  EXPECT_NEAR(mean_v.z, 0.5f * v.z, 0.03f);
  EXPECT_NEAR(mean_v.y, 0.5f * 0.75f * pc::kFireRise, 0.03f);
}

TEST(Particles, PrevCenterIsThePositionAtTheLastMark) {
  ParticleSystem ps;
  Rng rng(37);
  ps.emit_sparks(glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f), rng);
  for (const Sphere& s : spheres_of(ps)) EXPECT_TRUE(same_bits(s.center, s.prev_center));
  ps.step(kDt, rng);
  ps.mark_previous();
  const std::vector<Particle> before = ps.live_particles();
  // A rendered frame of three steps: prev stays where the frame started.
  ps.step(kDt, rng);
  ps.step(kDt, rng);
  ps.step(kDt, rng);
  const std::vector<Sphere> spheres = spheres_of(ps);
  ASSERT_EQ(spheres.size(), before.size());
  for (size_t i = 0; i < spheres.size(); ++i) {
    EXPECT_TRUE(same_bits(spheres[i].prev_center, before[i].position));
    EXPECT_FALSE(same_bits(spheres[i].center, before[i].position));
  }
}

// Every sphere (centre +- radius) stays in [-1,1]^3 with emitters at the walls and corners,
// thrown outwards at high speed.
TEST(Particles, StayInsideTheBox) {
  ParticleSystem ps;
  Rng rng(41);
  auto check = [&](int step) {
    for (const Sphere& s : spheres_of(ps)) {
      for (int a = 0; a < 3; ++a) {
        ASSERT_GE(s.center[a] - s.radius, -1.0f) << "step " << step;
        ASSERT_LE(s.center[a] + s.radius, 1.0f) << "step " << step;
        ASSERT_GE(s.prev_center[a], -1.0f);
        ASSERT_LE(s.prev_center[a], 1.0f);
      }
    }
  };
  for (int step = 0; step < 360; ++step) {
    const float sign = (step % 2 == 0) ? 1.0f : -1.0f;
    const glm::vec3 corner = sign * glm::vec3(0.95f, 0.95f, 0.95f);
    ps.emit_fire(corner, 0.12f, sign * glm::vec3(4.0f, 4.0f, 4.0f), kDt, rng);
    ps.emit_sparks(sign * glm::vec3(1.0f, 0.3f, -0.2f), sign * glm::vec3(1.0f, 0.0f, 0.0f), rng);  // outward
    ps.emit_ash(glm::vec3(0.0f, -0.98f, 0.98f), 0.05f, glm::vec3(3.0f, -6.0f, 5.0f), rng);
    check(step);
    ps.step(kDt, rng);
    check(step);
  }
}

uint64_t run_scenario(uint64_t seed) {
  ParticleSystem ps;
  Rng rng(seed);
  for (int step = 0; step < 240; ++step) {
    const float t = static_cast<float>(step) * kDt;
    ps.emit_fire(glm::vec3(0.5f * std::sin(t), 0.0f, 0.0f), 0.1f, glm::vec3(0.5f * std::cos(t), 0.0f, 0.0f),
                 kDt, rng);
    if (step % 30 == 0) ps.emit_sparks(glm::vec3(0.0f, -0.95f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), rng);
    if (step % 50 == 0) ps.emit_ash(glm::vec3(0.3f, 0.2f, 0.0f), 0.05f, glm::vec3(0.0f, 0.0f, 1.0f), rng);
    ps.step(kDt, rng);
  }
  return ps.hash();
}

TEST(Particles, DeterministicForASeed) {
  EXPECT_EQ(run_scenario(1), run_scenario(1));
  EXPECT_EQ(run_scenario(12345), run_scenario(12345));
  EXPECT_NE(run_scenario(1), run_scenario(2));
}

TEST(Particles, HashCoversTheStateAndClearResets) {
  ParticleSystem ps;
  const uint64_t empty = ps.hash();
  Rng rng(43);
  ps.emit_sparks(glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f), rng);
  const uint64_t emitted = ps.hash();
  EXPECT_NE(emitted, empty);
  ps.step(kDt, rng);
  EXPECT_NE(ps.hash(), emitted);
  ps.emit_fire(glm::vec3(0.0f), 0.1f, glm::vec3(0.0f), 0.001f, rng);  // 0.4: only the carry moves
  ps.clear();
  EXPECT_EQ(ps.live_count(), 0u);
  EXPECT_EQ(ps.hash(), empty);
  // A copy evolves exactly like the original (no pointers into the buffer).
  ps.emit_ash(glm::vec3(0.0f), 0.05f, glm::vec3(0.0f), rng);
  ParticleSystem copy = ps;
  Rng rng_a(1), rng_b(1);
  ps.step(kDt, rng_a);
  copy.step(kDt, rng_b);
  EXPECT_EQ(ps.hash(), copy.hash());
}

}  // namespace
