// 1M-step soak of the whole simulation (label "soak", Release: well under 2 minutes on 2 cores):
// 5 tumblers, 30 marbles (respawned whenever the fireball has burned some), a fireball, its
// particles, and a mouse drag now and then. No sphere may ever leave the box, no tumbler leave
// it or fall through the floor, nothing may become NaN.
#include <chrono>
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "scene/world.h"

namespace {

using rp::scene::World;
using rp::scene::WorldConfig;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

TEST(PhysicsSoak, MillionStepsEverythingStaysInTheBox) {
  const auto start = std::chrono::steady_clock::now();
  World world(WorldConfig{2024, 1.0f / 240.0f, true, true});
  const auto& ph = world.tumbler_physics();
  const float b = ph.shape().b, t = ph.shape().t;
  constexpr int kSteps = 1000000;
  long sphere_escapes = 0, tumbler_escapes = 0, not_finite = 0, respawns = 0;
  long sphere_inside_tumbler = 0;
  float worst_sphere = -1.0f, worst_tumbler = -1.0f, worst_sink = 0.0f, top_speed = 0.0f;
  size_t most_particles = 0;
  const glm::vec3 eye = rp::scene::Camera{}.position;
  for (int i = 0; i < kSteps; ++i) {
    // Every 10 s of simulated time, bring the burned marbles back.
    if (i % 2400 == 0 && world.marble_balls().size() < 30) {
      world.set_marbles(false);
      world.set_marbles(true);
      ++respawns;
    }
    // Every ~40 s, tilt one tumbler hard with the mouse for half a second.
    if (i % 9600 == 4800) {
      const int k = (i / 9600) % 5;
      const glm::vec3 p = world.tumblers()[k].p + glm::vec3(0.0f, 0.2f, 0.0f);
      if (world.begin_drag(eye, glm::normalize(p - eye))) {
        world.drag(eye, glm::normalize(p - eye), glm::vec2(k % 2 == 0 ? 120.0f : -90.0f, 60.0f));
      }
    }
    if (i % 9600 == 4920) world.end_drag();
    world.step();
    for (const auto* group : {&world.marble_balls(), &world.fireball_balls()}) {
      for (const auto& ball : *group) {
        const auto& s = ball.sphere;
        if (!finite(s.body.p) || !finite(s.body.v)) ++not_finite;
        top_speed = std::max(top_speed, glm::length(s.body.v));
        for (int k = 0; k < 3; ++k) {
          const float out = std::abs(s.body.p[k]) + s.radius - 1.0f;
          worst_sphere = std::max(worst_sphere, out);
          if (out > 1e-5f) ++sphere_escapes;
        }
        // Squeezed between a wall and a tumbler a sphere may overlap the tumbler for a step,
        // but its centre never gets inside.
        for (const auto& body : world.tumblers()) {
          const float d = ph.sdf(body, s.body.p);
          worst_sink = std::max(worst_sink, s.radius - d);
          if (d <= 0.0f) ++sphere_inside_tumbler;
        }
      }
    }
    for (const auto& body : world.tumblers()) {
      if (!finite(body.p) || !finite(body.w) || !std::isfinite(body.q.w)) ++not_finite;
      const glm::vec3 top = ph.top_center(body);
      float out = std::max(std::abs(body.p.x) + b, std::abs(body.p.z) + b);
      out = std::max(out, std::max(std::abs(top.x) + t, std::abs(top.z) + t));
      out = std::max(out - 1.0f, -1.0f - (top.y - t));
      worst_tumbler = std::max(worst_tumbler, out);
      if (out > 1e-4f || std::abs(body.p.y - (-1.0f + b)) > 1e-6f) ++tumbler_escapes;
    }
    most_particles = std::max(most_particles, world.particles().live_count());
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "[ info ] soak: " << kSteps << " steps (" << world.time() << " s simulated) in "
            << seconds << " s wall; worst sphere overshoot " << worst_sphere
            << " m, worst sphere-tumbler overlap " << worst_sink
            << " m, worst tumbler overshoot " << worst_tumbler << " m; " << respawns
            << " marble respawns; up to " << most_particles << " particles; top sphere speed " << top_speed
            << " m/s\n";
  EXPECT_EQ(not_finite, 0);
  EXPECT_EQ(sphere_escapes, 0);
  EXPECT_EQ(tumbler_escapes, 0);
  EXPECT_EQ(sphere_inside_tumbler, 0);
  // No energy pumping: marbles start with at most 2.1^2/2 + 9.81 x 1.7 = 18.9 J/kg each (launch
  // speed, height above the floor), fireballs 0.72 J/kg; elastic exchanges may pile the energy of
  // all 30 marbles onto one (sqrt(2 x 30 x 18.9) = 33.7 m/s) but never more.
  EXPECT_LT(top_speed, 33.7f);
  EXPECT_GT(respawns, 1) << "the fireball should have burned marbles";
  EXPECT_EQ(world.step_count(), static_cast<uint64_t>(kSteps));
}

}  // namespace
