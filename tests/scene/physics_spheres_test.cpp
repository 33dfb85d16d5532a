// Marbles and fireballs (SPEC.md section 3): energy kept, walls, lamp, tumblers, each other.
#include <algorithm>
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include "scene/collisions.h"
#include "scene/world.h"

namespace {

using rp::scene::Arena;
using rp::scene::Contact;
using rp::scene::RigidBody;
using rp::scene::SphereBody;
using rp::scene::TumblerPhysics;
using rp::scene::World;

SphereBody marble(glm::vec3 c, glm::vec3 v, float r = 0.04f, float g = 9.81f, float m = 0.005f) {
  SphereBody s;
  s.body.p = c;
  s.body.v = v;
  s.body.mass = m;
  s.radius = r;
  s.gravity = g;
  s.reset_energy();
  return s;
}

// Mechanical energy of the centre, 1/2 m v^2 + m g h, computed here from the state.
double energy(const SphereBody& s) {
  const glm::dvec3 v(s.body.v);
  return 0.5 * s.body.mass * glm::dot(v, v) + s.body.mass * 9.81 * (double(s.body.p.y) + 1.0);
}

TEST(PhysicsSpheres, BouncingMarbleKeepsItsEnergyFor100kSteps) {
  World world;  // five tumblers in the way
  world.add_marble(glm::vec3(0.3f, 0.6f, -0.1f), glm::vec3(1.1f, 0.4f, 0.7f));
  const double e0 = energy(world.marble_balls()[0].sphere);
  double worst = 0.0;
  int tumbler_hits = 0;
  for (int i = 0; i < 100000; ++i) {
    const glm::vec3 w_before = world.tumblers()[0].w + world.tumblers()[1].w +
                               world.tumblers()[2].w + world.tumblers()[3].w + world.tumblers()[4].w;
    world.step();
    const glm::vec3 w_after = world.tumblers()[0].w + world.tumblers()[1].w +
                              world.tumblers()[2].w + world.tumblers()[3].w + world.tumblers()[4].w;
    if (w_before == glm::vec3(0.0f) && w_after != glm::vec3(0.0f)) ++tumbler_hits;
    worst = std::max(worst, std::abs(energy(world.marble_balls()[0].sphere) - e0) / e0);
  }
  std::cout << "[ info ] 100k steps: worst relative energy error " << worst << ", " << tumbler_hits
            << " tumbler hits from rest\n";
  EXPECT_LT(worst, 1e-3);
  EXPECT_GT(tumbler_hits, 0) << "the marble should have met the tumblers";
}

// Thirty marbles bouncing off each other, the tumblers, the lamp and the walls: elastic exchanges
// move energy between marbles, the sum stays.
TEST(PhysicsSpheres, ThirtyMarblesKeepTheirTotalEnergy) {
  World world(rp::scene::WorldConfig{4, 1.0f / 240.0f, true, false});
  auto total = [&world] {
    double e = 0.0;
    for (const auto& m : world.marble_balls()) e += energy(m.sphere);
    return e;
  };
  const double e0 = total();
  double worst = 0.0;
  for (int i = 0; i < 24000; ++i) {
    world.step();
    if (i % 24 == 0) worst = std::max(worst, std::abs(total() - e0) / e0);
  }
  ASSERT_EQ(world.marble_balls().size(), 30u);
  std::cout << "[ info ] 30 marbles, 24k steps: worst relative total energy error " << worst << "\n";
  EXPECT_LT(worst, 1e-3);
}

TEST(PhysicsSpheres, WallsReflectWithoutLossAndSetRolling) {
  const Arena arena;
  SphereBody s = marble(glm::vec3(0.97f, 0.0f, 0.0f), glm::vec3(2.0f, 0.5f, -1.0f), 0.04f, 0.0f);
  std::vector<Contact> contacts;
  ASSERT_TRUE(rp::scene::collide_sphere_walls(s, arena, &contacts));
  EXPECT_FLOAT_EQ(s.body.p.x, 0.96f);
  EXPECT_EQ(s.body.v, glm::vec3(-2.0f, 0.5f, -1.0f));
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].normal, glm::vec3(-1.0f, 0.0f, 0.0f));
  EXPECT_FLOAT_EQ(contacts[0].point.x, 1.0f);
  // Rolling on the wall: the contact point (c + r x) does not slide.
  const glm::vec3 slip = s.body.point_velocity(s.body.p + glm::vec3(0.04f, 0.0f, 0.0f));
  EXPECT_NEAR(slip.y, 0.0f, 1e-6f);
  EXPECT_NEAR(slip.z, 0.0f, 1e-6f);
  // A corner: two walls at once.
  SphereBody c = marble(glm::vec3(-0.99f, -0.99f, 0.0f), glm::vec3(-1.0f, -1.0f, 0.0f));
  contacts.clear();
  rp::scene::collide_sphere_walls(c, arena, &contacts);
  EXPECT_EQ(contacts.size(), 2u);
  EXPECT_EQ(c.body.v, glm::vec3(1.0f, 1.0f, 0.0f));
}

TEST(PhysicsSpheres, LampCapReflectsAlongItsNormal) {
  const Arena arena;  // lamp sphere (0, 1.1, 0), radius 0.35, cut at the ceiling y = 1
  // Straight up under the lamp: hits the cap's lowest point (y = 0.75) and falls back.
  SphereBody s = marble(glm::vec3(0.0f, 0.72f, 0.0f), glm::vec3(0.0f, 2.0f, 0.0f));
  std::vector<Contact> contacts;
  ASSERT_TRUE(rp::scene::collide_sphere_lamp(s, arena, &contacts));
  EXPECT_NEAR(s.body.p.y, 0.75f - 0.04f, 1e-6f);
  EXPECT_NEAR(s.body.v.y, -2.0f, 1e-6f);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR(contacts[0].normal.y, -1.0f, 1e-6f);
  // Beside the rim, a centre that went above the ceiling band this step (walls clamp it later):
  // the nearest point of the full sphere is inside the ceiling, that of the cap is on its rim.
  const float rim = std::sqrt(0.35f * 0.35f - 0.1f * 0.1f);
  SphereBody r = marble(glm::vec3(0.36f, 0.995f, 0.0f), glm::vec3(-1.0f, 0.0f, 0.0f));
  ASSERT_TRUE(rp::scene::collide_sphere_lamp(r, arena, nullptr));
  EXPECT_NEAR(glm::length(r.body.p - glm::vec3(rim, 1.0f, 0.0f)), 0.04f, 1e-5f);
  EXPECT_GT(r.body.v.x, 0.0f);
  // Far away: nothing.
  SphereBody f = marble(glm::vec3(0.8f, 0.9f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_FALSE(rp::scene::collide_sphere_lamp(f, arena, nullptr));
}

// SPEC 3: the sphere is reflected along n; the tumbler receives j = -m dv at the contact point;
// together they keep the momentum of the exchange: m dv + j = 0, and the tumbler's angular
// momentum about its floor contact changes by (h - c) x j.
TEST(PhysicsSpheres, SphereHittingATumblerTransfersMomentum) {
  const TumblerPhysics ph;
  RigidBody t = ph.make_body({glm::vec2(0.0f), 0.0f});
  // Aim at the cone from the side, moving down-left.
  SphereBody s = marble(glm::vec3(0.16f, -0.6f, 0.02f), glm::vec3(-2.0f, -0.5f, 0.3f));
  const float d = ph.sdf(t, s.body.p);
  ASSERT_LT(d, s.radius);
  const RigidBody t0 = t;
  const SphereBody s0 = s;
  const auto hit = rp::scene::collide_sphere_tumbler(s, t, ph, false);
  ASSERT_TRUE(hit.has_value());
  const glm::vec3 n = hit->contact.normal, h = hit->contact.point;
  EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
  EXPECT_NEAR(ph.sdf(t0, h), 0.0f, 1e-5f);  // h on the tumbler surface
  EXPECT_NEAR(ph.sdf(t0, s.body.p), s.radius, 1e-5f);  // pushed out to touching
  EXPECT_NEAR(glm::length(s.body.v), glm::length(s0.body.v), 1e-5f);  // speed kept
  EXPECT_GT(glm::dot(s.body.v, n), 0.0f);  // now leaving
  const glm::vec3 sphere_dp = s.body.mass * (s.body.v - s0.body.v);
  const glm::vec3 j = hit->impulse_on_tumbler;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(sphere_dp[k] + j[k], 0.0f, 1e-7f);
  const glm::vec3 dl = ph.contact_inertia(t0) * (t.w - t0.w);
  const glm::vec3 expected = glm::cross(h - ph.floor_contact(t0), j);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(dl[k], expected[k], 1e-7f);
  EXPECT_LT(t.v.x, 0.0f);  // knocked the way the marble was going
  // A held (kinematic) tumbler reflects the sphere but is not moved.
  RigidBody held = t0;
  SphereBody s2 = s0;
  ASSERT_TRUE(rp::scene::collide_sphere_tumbler(s2, held, ph, true).has_value());
  EXPECT_EQ(held.w, t0.w);
}

TEST(PhysicsSpheres, SphereSphereIsElastic) {
  SphereBody a = marble(glm::vec3(0.0f, 0.0f, 0.0f), glm::vec3(1.0f, 0.2f, 0.0f));
  SphereBody b = marble(glm::vec3(0.07f, 0.02f, 0.0f), glm::vec3(-0.5f, 0.0f, 0.3f), 0.04f, 9.81f,
                        0.01f);
  const glm::vec3 p0 = a.body.mass * a.body.v + b.body.mass * b.body.v;
  const float k0 = 0.5f * a.body.mass * glm::dot(a.body.v, a.body.v) +
                   0.5f * b.body.mass * glm::dot(b.body.v, b.body.v);
  const float e0 = a.body.mass * a.energy + b.body.mass * b.energy;
  ASSERT_TRUE(rp::scene::collide_spheres(a, b).has_value());
  const glm::vec3 p1 = a.body.mass * a.body.v + b.body.mass * b.body.v;
  const float k1 = 0.5f * a.body.mass * glm::dot(a.body.v, a.body.v) +
                   0.5f * b.body.mass * glm::dot(b.body.v, b.body.v);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(p0[k], p1[k], 1e-7f);
  EXPECT_NEAR(k0, k1, 1e-7f);
  EXPECT_NEAR(glm::length(b.body.p - a.body.p), 0.08f, 1e-6f);
  // Mass-weighted push: the centre of mass did not move vertically, so the summed invariant is kept.
  EXPECT_NEAR(a.body.mass * a.energy + b.body.mass * b.energy, e0, 1e-7f);
  EXPECT_GT(glm::dot(b.body.v - a.body.v, glm::normalize(glm::vec3(0.07f, 0.02f, 0.0f))), 0.0f);
}

TEST(PhysicsSpheres, FireballKeepsItsSpeedAndBurnsMarbles) {
  World world;
  world.add_fireball(glm::vec3(-0.5f, 0.3f, 0.0f), glm::vec3(1.2f, 0.0f, 0.0f));
  // Dropped so that it falls through the fireball's path when the fireball passes (0.25 s).
  world.add_marble(glm::vec3(-0.2f, 0.6f, 0.0f), glm::vec3(0.0f, 0.0f, 0.0f));
  ASSERT_EQ(world.marble_balls().size(), 1u);
  bool burned = false;
  size_t burst = 0;  // particles the burning step added
  for (int i = 0; i < 2400; ++i) {
    const size_t before = world.particles().live_count();
    world.step();
    const auto& f = world.fireball_balls()[0].sphere;
    ASSERT_NEAR(glm::length(f.body.v), 1.2f, 1e-4f);
    EXPECT_EQ(f.body.v.y, 0.0f);  // no gravity
    if (!burned && world.marble_balls().empty()) {
      burned = true;
      burst = world.particles().live_count() - before;
    }
  }
  EXPECT_TRUE(burned);
  // Ash and sparks on top of this step's fire (at most 2 particles at 400/s and 240 Hz).
  namespace pc = rp::scene::particle_constants;
  EXPECT_GE(burst, static_cast<size_t>(pc::kAshPerMarble + pc::kSparksPerContact));
  // Afterwards the fire alone: ~400/s x 0.45 s = 180, plus wall sparks.
  EXPECT_GT(world.particles().live_count(), 100u);  // fire keeps burning
  EXPECT_LT(world.particles().live_count(), 400u);
}

}  // namespace
