// Tumbler dynamics in the World (SPEC.md section 3): rocking back upright, the floor, the walls
// and tumbler-tumbler contacts.
#include <algorithm>
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include "scene/collisions.h"
#include "scene/world.h"

namespace {

using rp::scene::RigidBody;
using rp::scene::TumblerPhysics;
using rp::scene::World;

// Deepest overlap of two tumblers by the four sphere-vs-SDF tests (0 when apart).
float overlap(const TumblerPhysics& ph, const RigidBody& a, const RigidBody& b) {
  const auto& s = ph.shape();
  float o = 0.0f;
  o = std::max(o, s.b - ph.sdf(b, a.p));
  o = std::max(o, s.t - ph.sdf(b, ph.top_center(a)));
  o = std::max(o, s.b - ph.sdf(a, b.p));
  o = std::max(o, s.t - ph.sdf(a, ph.top_center(b)));
  return o;
}

// How far either of the tumbler's spheres reaches out of the box (<= 0 inside).
float outside(const TumblerPhysics& ph, const RigidBody& body) {
  const auto& s = ph.shape();
  const glm::vec3 top = ph.top_center(body);
  float o = -1.0f;
  for (int axis : {0, 2}) {
    o = std::max(o, std::abs(body.p[axis]) + s.b - 1.0f);
    o = std::max(o, std::abs(top[axis]) + s.t - 1.0f);
  }
  o = std::max(o, -1.0f - (top.y - s.t));
  return o;
}

TEST(PhysicsTumbler, ReleasedAt45DegreesRocksAndRestsUprightWithinTenSeconds) {
  World world;
  const TumblerPhysics& ph = world.tumbler_physics();
  RigidBody& body = world.tumbler(0);  // centre tumbler, free to roll along z
  body.q = glm::angleAxis(glm::radians(45.0f), glm::vec3(1.0f, 0.0f, 0.0f)) * body.q;
  ASSERT_NEAR(glm::degrees(ph.tilt(body)), 45.0f, 1e-3f);

  const int steps = static_cast<int>(10.0f / world.config().dt);
  int swings = 0;
  float last_side = 1.0f, rest_since = -1.0f, max_travel = 0.0f;
  const glm::vec3 start = body.p;
  for (int i = 0; i < steps; ++i) {
    world.step();
    const RigidBody& b = world.tumblers()[0];
    const float side = ph.axis(b).z;
    if (side * last_side < 0.0f) ++swings;
    if (side != 0.0f) last_side = side;
    max_travel = std::max(max_travel, glm::length(b.p - start));
    const bool at_rest = b.w == glm::vec3(0.0f) && b.v == glm::vec3(0.0f);
    if (!at_rest) rest_since = -1.0f;
    if (at_rest && rest_since < 0.0f) rest_since = static_cast<float>(world.time());
  }
  const RigidBody& b = world.tumblers()[0];
  std::cout << "[ info ] 45-degree release: " << swings << " swings through upright, at rest from t = "
            << rest_since << " s, final tilt " << glm::degrees(ph.tilt(b))
            << " deg, rolled up to " << max_travel << " m\n";
  EXPECT_LT(glm::degrees(ph.tilt(b)), 2.0f);
  EXPECT_GE(rest_since, 0.0f) << "still moving after 10 s";
  EXPECT_LE(rest_since, 10.0f);
  EXPECT_GE(swings, 6) << "should rock visibly, not creep back";
  EXPECT_GT(max_travel, 0.05f) << "rocking rolls it over the floor";
  // The others were never touched.
  for (size_t i = 1; i < world.tumblers().size(); ++i) {
    EXPECT_EQ(world.tumblers()[i].w, glm::vec3(0.0f));
  }
}

TEST(PhysicsTumbler, FallenOverTumblerLiesOnTheFloorThenRightsItself) {
  World world;
  const TumblerPhysics& ph = world.tumbler_physics();
  RigidBody& body = world.tumbler(0);
  body.q = glm::angleAxis(glm::radians(150.0f), glm::vec3(1.0f, 0.0f, 0.0f)) * body.q;
  world.step();
  const RigidBody& lying = world.tumblers()[0];
  EXPECT_LE(ph.tilt(lying), ph.max_tilt() + 1e-3f);
  EXPECT_GE(ph.top_center(lying).y - ph.shape().t, -1.0f - 1e-4f);
  for (int i = 0; i < static_cast<int>(20.0f / world.config().dt); ++i) world.step();
  EXPECT_LT(glm::degrees(ph.tilt(world.tumblers()[0])), 2.0f);
}

TEST(PhysicsTumbler, WallsKeepFastTumblersInsideAndBounceThem) {
  World world;
  const TumblerPhysics& ph = world.tumbler_physics();
  // Every tumbler rolls at 3 m/s in a different direction (w = y x v / b).
  for (size_t i = 0; i < world.tumblers().size(); ++i) {
    const float a = 1.3f * static_cast<float>(i) + 0.2f;
    const glm::vec3 v(3.0f * std::cos(a), 0.0f, 3.0f * std::sin(a));
    world.tumbler(i).w = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), v) / ph.shape().b;
  }
  float worst_outside = -1.0f, worst_overlap = 0.0f;
  for (int i = 0; i < 2400; ++i) {
    world.step();
    for (size_t a = 0; a < world.tumblers().size(); ++a) {
      worst_outside = std::max(worst_outside, outside(ph, world.tumblers()[a]));
      for (size_t b = a + 1; b < world.tumblers().size(); ++b) {
        worst_overlap = std::max(worst_overlap, overlap(ph, world.tumblers()[a], world.tumblers()[b]));
      }
    }
  }
  std::cout << "[ info ] walls: worst outside " << worst_outside << " m, worst tumbler overlap "
            << worst_overlap << " m\n";
  EXPECT_LE(worst_outside, 1e-5f);
  EXPECT_LE(worst_overlap, 0.02f);
}

// One pair contact, exactly: overlapping upright tumblers approaching each other leave with
// -e times their normal approach speed, equal and opposite impulses, pushed apart.
TEST(PhysicsTumbler, PairContactReversesApproachWithRestitution) {
  const TumblerPhysics ph;
  RigidBody a = ph.make_body({glm::vec2(-0.195f, 0.0f), 0.0f});
  RigidBody b = ph.make_body({glm::vec2(0.195f, 0.0f), 0.3f});
  a.w = glm::vec3(0.0f, 0.0f, -5.0f);  // rolling towards +x at 1 m/s
  b.w = glm::vec3(0.0f, 0.0f, 2.0f);   // towards -x at 0.4 m/s
  ph.enforce_rolling(a);
  ph.enforce_rolling(b);
  const RigidBody a0 = a, b0 = b;
  const float e = 0.5f;
  const auto hit = rp::scene::collide_tumblers(a, false, b, false, ph, e);
  ASSERT_TRUE(hit.has_value());
  const glm::vec3 n = hit->contact.normal, h = hit->contact.point;
  EXPECT_NEAR(n.x, 1.0f, 1e-4f);
  EXPECT_NEAR(h.y, -0.8f, 1e-4f);  // at the centres' height, between them
  EXPECT_NEAR(hit->depth, 0.01f, 1e-4f);
  const float before = glm::dot(a0.point_velocity(h) - b0.point_velocity(h), n);
  const float after = glm::dot(a.point_velocity(h) - b.point_velocity(h), n);
  EXPECT_NEAR(before, 1.4f, 1e-4f);
  EXPECT_NEAR(after, -e * before, 1e-4f);
  // Equal and opposite: the angular momenta about each floor contact change by (h - c) x (-+j).
  const glm::vec3 j = hit->impulse * n;
  const glm::vec3 la = ph.contact_inertia(a0) * (a.w - a0.w);
  const glm::vec3 lb = ph.contact_inertia(b0) * (b.w - b0.w);
  const glm::vec3 ea = glm::cross(h - ph.floor_contact(a0), -j);
  const glm::vec3 eb = glm::cross(h - ph.floor_contact(b0), j);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(la[k], ea[k], 1e-5f);
    EXPECT_NEAR(lb[k], eb[k], 1e-5f);
  }
  EXPECT_NEAR(b.p.x - a.p.x, 0.4f, 1e-5f);  // touching, no longer overlapping
}

TEST(PhysicsTumbler, TumblersRolledIntoEachOtherSeparateWithoutInterpenetrating) {
  World world;
  const TumblerPhysics& ph = world.tumbler_physics();
  // The back pair (-0.42, -0.45) and (0.42, -0.45) roll towards each other at 2 m/s.
  world.tumbler(1).w = glm::vec3(0.0f, 0.0f, -10.0f);
  world.tumbler(2).w = glm::vec3(0.0f, 0.0f, 10.0f);
  float worst = 0.0f, closest = 1e9f;
  for (int i = 0; i < 2400; ++i) {
    world.step();
    const RigidBody& a = world.tumblers()[1];
    const RigidBody& b = world.tumblers()[2];
    worst = std::max(worst, overlap(ph, a, b));
    closest = std::min(closest, glm::length(ph.top_center(a) - ph.top_center(b)));
  }
  std::cout << "[ info ] pair: worst overlap " << worst << " m, closest top centres " << closest
            << " m\n";
  EXPECT_LT(closest, 2.0f * ph.shape().t + 0.01f) << "they should have met";
  EXPECT_LE(worst, 0.02f);
  const RigidBody& a = world.tumblers()[1];
  const RigidBody& b = world.tumblers()[2];
  EXPECT_EQ(overlap(ph, a, b), 0.0f);
  EXPECT_LT(glm::degrees(ph.tilt(a)), 2.0f);
  EXPECT_LT(glm::degrees(ph.tilt(b)), 2.0f);
}

}  // namespace
