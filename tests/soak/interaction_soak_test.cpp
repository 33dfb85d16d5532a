// 20k-step soak of the simulation under seeded random interaction: drags that
// start on a random point of a random tumbler (rays from the camera eye through it), slow drags
// and flicks (large cursor jumps over a few steps), translate drags (hits below the centre of
// mass) and toggles of marbles, fireball and reset, in a random order. After every step:
// every body and particle is finite, nothing leaves the box [-1,1]^3 and the particle count
// stays within the ring buffer's budget (ParticleSystem::kMaxParticles = 2048). The same script
// run twice gives the same state hash (the soak itself is deterministic for a seed).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "scene/random.h"
#include "scene/world.h"

namespace {

using rp::scene::ParticleSystem;
using rp::scene::Rng;
using rp::scene::World;
using rp::scene::WorldConfig;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// What went wrong, counted over the whole run (first offence described for the failure message).
struct SoakReport {
  long not_finite = 0, sphere_escapes = 0, tumbler_escapes = 0, particle_escapes = 0;
  long over_budget = 0;
  long drags = 0, flicks = 0, translate_drags = 0, misses = 0, toggles = 0, resets = 0;
  size_t most_particles = 0;
  float worst_sphere = -1.0f, worst_particle = -1.0f, worst_tumbler = -1.0f;
  std::string first_problem;
  uint64_t final_hash = 0;

  void note(long& counter, uint64_t step, const std::string& what) {
    if (counter++ == 0 && first_problem.empty()) {
      std::ostringstream s;
      s << "step " << step << ": " << what;
      first_problem = s.str();
    }
  }
};

// Checks one world state after a step (tolerances: the box walls clamp spheres exactly, so 1e-5
// world units is float rounding; tumblers as in physics_soak_test.cpp).
void check_state(const World& world, SoakReport& r) {
  const uint64_t step = world.step_count();
  const auto& ph = world.tumbler_physics();
  const float b = ph.shape().b, t = ph.shape().t;
  for (const auto* group : {&world.marble_balls(), &world.fireball_balls()}) {
    for (const auto& ball : *group) {
      const auto& s = ball.sphere;
      if (!finite(s.body.p) || !finite(s.body.v)) r.note(r.not_finite, step, "sphere not finite");
      for (int k = 0; k < 3; ++k) {
        const float out = std::abs(s.body.p[k]) + s.radius - 1.0f;
        r.worst_sphere = std::max(r.worst_sphere, out);
        if (out > 1e-5f) r.note(r.sphere_escapes, step, "sphere outside the box");
      }
    }
  }
  for (const auto& body : world.tumblers()) {
    if (!finite(body.p) || !finite(body.v) || !finite(body.w) || !std::isfinite(body.q.w) ||
        !std::isfinite(body.q.x) || !std::isfinite(body.q.y) || !std::isfinite(body.q.z)) {
      r.note(r.not_finite, step, "tumbler not finite");
    }
    const glm::vec3 top = ph.top_center(body);
    float out = std::max(std::abs(body.p.x) + b, std::abs(body.p.z) + b);
    out = std::max(out, std::max(std::abs(top.x) + t, std::abs(top.z) + t));
    out = std::max(out - 1.0f, -1.0f - (top.y - t));
    r.worst_tumbler = std::max(r.worst_tumbler, out);
    if (out > 1e-4f) r.note(r.tumbler_escapes, step, "tumbler outside the box");
  }
  const auto& particles = world.particles();
  const size_t n = particles.live_count();
  r.most_particles = std::max(r.most_particles, n);
  if (n > ParticleSystem::kMaxParticles) r.note(r.over_budget, step, "particle count over budget");
  for (const auto& p : particles.live_particles()) {
    if (!finite(p.position) || !finite(p.velocity) || !std::isfinite(p.age)) {
      r.note(r.not_finite, step, "particle not finite");
    }
    // The drawn sphere (radius from the remaining life) stays inside, not only its centre.
    const float out = std::max({std::abs(p.position.x), std::abs(p.position.y),
                                std::abs(p.position.z)}) + ParticleSystem::sphere_of(p).radius - 1.0f;
    r.worst_particle = std::max(r.worst_particle, out);
    if (out > 1e-5f) r.note(r.particle_escapes, step, "particle sphere outside the box");
  }
}

// One scripted session: a plan of random actions from `seed` (its own Rng, separate from the
// world's streams), applied between steps.
SoakReport run_soak(uint64_t seed, int steps) {
  SoakReport r;
  World world(WorldConfig{seed, 1.0f / 240.0f, true, true});
  Rng script(seed ^ 0x9e3779b97f4a7c15ULL, 17);
  const glm::vec3 eye = world.camera().position;
  // The current drag: steps left, per-step cursor delta (pixels) and where the ray aims.
  int drag_steps_left = 0;
  glm::vec2 delta_per_step{0.0f};
  glm::vec3 aim{0.0f};
  glm::vec3 aim_velocity{0.0f};  // world units per step, moves the ray for translate drags
  for (int i = 0; i < steps; ++i) {
    if (drag_steps_left > 0) {
      aim += aim_velocity;
      world.drag(eye, glm::normalize(aim - eye), delta_per_step);
      if (--drag_steps_left == 0) world.end_drag();
    } else if (script.uniform() < 0.03f) {  // ~ every 33 steps (0.14 s) something happens
      const float pick = script.uniform();
      if (pick < 0.7f) {
        // A drag on a random point of a random tumbler: around the body (translate when below
        // the centre of mass) or the head (rotate).
        const size_t k = std::min<size_t>(world.tumblers().size() - 1,
                                          static_cast<size_t>(script.uniform() * 5.0f));
        const auto& body = world.tumblers()[k];
        const bool head = script.uniform() < 0.4f;
        const glm::vec3 centre = head ? world.tumbler_physics().top_center(body) : body.p;
        aim = centre + 0.15f * script.in_unit_ball();
        if (world.begin_drag(eye, glm::normalize(aim - eye))) {
          const bool flick = script.uniform() < 0.3f;
          drag_steps_left = flick ? 1 + static_cast<int>(script.uniform() * 4.0f)
                                  : 10 + static_cast<int>(script.uniform() * 200.0f);
          // Flicks: up to 400 pixels in a few steps; slow drags: up to 3 pixels per step.
          const float per_step = flick ? 400.0f / static_cast<float>(drag_steps_left) : 3.0f;
          delta_per_step = per_step * glm::vec2(script.uniform(-1.0f, 1.0f), script.uniform(-1.0f, 1.0f));
          aim_velocity = (flick ? 0.1f : 0.01f) *
                         glm::vec3(script.uniform(-1.0f, 1.0f), 0.0f, script.uniform(-1.0f, 1.0f));
          ++r.drags;
          if (flick) ++r.flicks;
          if (world.drag_mode() == rp::scene::DragMode::Translate) ++r.translate_drags;
        } else {
          ++r.misses;
        }
      } else if (pick < 0.8f) {
        world.set_marbles(!world.marbles());
        ++r.toggles;
      } else if (pick < 0.88f) {
        world.set_fireball(!world.fireball());
        ++r.toggles;
      } else if (pick < 0.98f) {
        // More fireballs (until the next fireball toggle or reset): more fire, sparks and ash,
        // so the ring buffer fills and the 2048 budget is reached and held.
        for (int f = 0; f < 2; ++f) {
          world.add_fireball(glm::vec3(0.4f * static_cast<float>(f) - 0.2f, 0.5f, 0.0f),
                             1.5f * glm::normalize(script.in_unit_ball() + glm::vec3(0.01f)));
        }
        ++r.toggles;
      } else {
        world.reset();
        ++r.resets;
      }
    }
    world.step();
    check_state(world, r);
  }
  r.final_hash = world.state_hash();
  return r;
}

TEST(InteractionSoak, TwentyThousandRandomStepsStayFiniteInTheBoxAndWithinBudget) {
  constexpr int kSteps = 20000;
  const SoakReport r = run_soak(8, kSteps);
  std::cout << "[ info ] interaction soak: " << kSteps << " steps, " << r.drags << " drags ("
            << r.flicks << " flicks, " << r.translate_drags << " translate), " << r.misses
            << " missed picks, " << r.toggles << " toggles, " << r.resets << " resets; up to "
            << r.most_particles << " particles; worst overshoot: sphere " << r.worst_sphere
            << ", particle " << r.worst_particle << ", tumbler " << r.worst_tumbler << " m\n";
  EXPECT_EQ(r.not_finite, 0) << r.first_problem;
  EXPECT_EQ(r.sphere_escapes, 0) << r.first_problem;
  EXPECT_EQ(r.particle_escapes, 0) << r.first_problem;
  EXPECT_EQ(r.tumbler_escapes, 0) << r.first_problem;
  EXPECT_EQ(r.over_budget, 0) << r.first_problem;
  EXPECT_LE(r.most_particles, ParticleSystem::kMaxParticles);
  // The script really exercised what it claims (else the checks above prove little).
  EXPECT_GT(r.drags, 100);
  EXPECT_GT(r.flicks, 20);
  EXPECT_GT(r.translate_drags, 10);
  EXPECT_GT(r.toggles, 30);
  EXPECT_GT(r.resets, 2);
  EXPECT_EQ(r.most_particles, ParticleSystem::kMaxParticles)
      << "the fireballs should fill the ring buffer (overwriting the oldest) at least once";
}

TEST(InteractionSoak, SameSeedSameScriptSameFinalState) {
  constexpr int kSteps = 3000;
  EXPECT_EQ(run_soak(21, kSteps).final_hash, run_soak(21, kSteps).final_hash);
  EXPECT_NE(run_soak(21, kSteps).final_hash, run_soak(22, kSteps).final_hash);
}

}  // namespace
