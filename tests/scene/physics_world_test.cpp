// The World: determinism (state hash), reset, toggles, the frame it fills, mouse dragging.
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "scene/demo_scene.h"
#include "scene/world.h"

namespace {

using rp::scene::DragMode;
using rp::scene::FrameScene;
using rp::scene::World;
using rp::scene::WorldConfig;

glm::vec3 camera_position() { return rp::scene::Camera{}.position; }
glm::vec3 towards(glm::vec3 p) { return glm::normalize(p - camera_position()); }

// A scripted session: toggles and a drag at fixed steps; returns the hash after `steps`.
uint64_t run_session(uint64_t seed, int steps) {
  World world(WorldConfig{seed, 1.0f / 240.0f, true, true});
  for (int i = 0; i < steps; ++i) {
    if (i == 500) world.begin_drag(camera_position(), towards(glm::vec3(0.0f, -0.6f, 0.2f)));
    if (i > 500 && i < 700) {
      world.drag(camera_position(), towards(glm::vec3(0.0f, -0.6f, 0.2f)), glm::vec2(0.5f, 0.2f));
    }
    if (i == 700) world.end_drag();
    if (i == 2000) world.set_fireball(false);
    if (i == 2500) world.set_fireball(true);
    if (i == 4000) world.set_marbles(false);
    if (i == 4001) world.set_marbles(true);
    world.step();
  }
  return world.state_hash();
}

TEST(PhysicsWorld, SameSeedAndInputsGiveBitIdenticalStateAfter10kSteps) {
  const uint64_t a = run_session(7, 10000);
  const uint64_t b = run_session(7, 10000);
  const uint64_t c = run_session(8, 10000);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(PhysicsWorld, HashFollowsTheStateAndResetRestoresIt) {
  World world(WorldConfig{3, 1.0f / 240.0f, true, false});
  const uint64_t initial = world.state_hash();
  EXPECT_EQ(world.marble_balls().size(), 30u);
  EXPECT_TRUE(world.fireball_balls().empty());
  world.step();
  const uint64_t one = world.state_hash();
  EXPECT_NE(one, initial);
  for (int i = 0; i < 100; ++i) world.step();
  EXPECT_EQ(world.step_count(), 101u);
  world.reset();
  EXPECT_EQ(world.step_count(), 0u);
  EXPECT_EQ(world.state_hash(), initial);
  world.step();
  EXPECT_EQ(world.state_hash(), one);
  // Toggles: marbles off and on again draws new ones from the stream (different positions).
  const glm::vec3 first = world.marble_balls()[0].sphere.body.p;
  world.set_marbles(false);
  EXPECT_TRUE(world.marble_balls().empty());
  EXPECT_FALSE(world.marbles());
  world.set_marbles(true);
  ASSERT_EQ(world.marble_balls().size(), 30u);
  EXPECT_NE(world.marble_balls()[0].sphere.body.p, first);
  world.set_fireball(true);
  EXPECT_EQ(world.fireball_balls().size(), 1u);
  world.set_fireball(true);  // already on: unchanged
  EXPECT_EQ(world.fireball_balls().size(), 1u);
}

TEST(PhysicsWorld, SpawnedMarblesStartClearOfTumblersAndEachOther) {
  World world(WorldConfig{11, 1.0f / 240.0f, true, false});
  const auto& ph = world.tumbler_physics();
  const auto& marbles = world.marble_balls();
  for (size_t i = 0; i < marbles.size(); ++i) {
    const auto& s = marbles[i].sphere;
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::abs(s.body.p[k]) + s.radius, 1.0f);
    for (const auto& t : world.tumblers()) EXPECT_GT(ph.sdf(t, s.body.p), s.radius);
    for (size_t j = 0; j < i; ++j) {
      EXPECT_GT(glm::length(marbles[j].sphere.body.p - s.body.p), 2.0f * s.radius);
    }
    EXPECT_GT(glm::length(s.body.v), 0.1f);
  }
}

TEST(PhysicsWorld, FillFrameHasTheDemoInstancesAndSpheresWithPreviousTransforms) {
  World world(WorldConfig{5, 1.0f / 240.0f, true, true});
  world.tumbler(0).w = glm::vec3(3.0f, 0.0f, 0.0f);  // rocking and rolling
  const glm::mat4 model0 = world.tumblers()[0].model_matrix();
  const glm::vec3 marble0 = world.marble_balls()[0].sphere.body.p;
  world.advance(4);
  FrameScene frame;
  world.fill_frame(frame);
  ASSERT_EQ(frame.instances.size(), 7u);
  EXPECT_EQ(frame.instances[0].mesh, rp::scene::demo::kBoxMesh);
  EXPECT_EQ(frame.instances[1].mesh, rp::scene::demo::kLampMesh);
  EXPECT_FALSE(frame.instances[0].casts_shadow);
  for (size_t i = 2; i < 7; ++i) {
    EXPECT_EQ(frame.instances[i].mesh, rp::scene::demo::kTumblerMesh);
    EXPECT_TRUE(frame.instances[i].casts_shadow);
    EXPECT_EQ(frame.instances[i].model, world.tumblers()[i - 2].model_matrix());
  }
  EXPECT_EQ(frame.instances[2].prev_model, model0);  // before advance()'s four steps
  EXPECT_NE(frame.instances[2].model, model0);
  EXPECT_EQ(frame.instances[3].prev_model, frame.instances[3].model);  // at rest
  const size_t balls = world.marble_balls().size() + world.fireball_balls().size();
  ASSERT_EQ(frame.spheres.size(), balls + world.particles().live_count());
  EXPECT_EQ(frame.spheres[0].prev_center, marble0);
  EXPECT_EQ(frame.spheres[0].center, world.marble_balls()[0].sphere.body.p);
  EXPECT_TRUE(frame.spheres[0].casts_shadow);
  const auto& fire = frame.spheres[world.marble_balls().size()];
  EXPECT_FALSE(fire.casts_shadow);
  EXPECT_NEAR(fire.emission.y / fire.emission.x, 0.46f, 1e-6f);
  EXPECT_NEAR(fire.emission.x, 20.0f, 1e-6f);
  EXPECT_EQ(frame.camera.position, frame.prev_camera.position);
  EXPECT_EQ(frame.frame_index, 1u);
  // The demo's static frame and the world's first frame agree on the tumblers.
  World fresh;
  FrameScene first;
  fresh.fill_frame(first);
  const auto placements = rp::scene::demo_tumbler_placements();
  for (size_t i = 0; i < placements.size(); ++i) {
    const glm::mat4 demo = rp::scene::upright_tumbler_model(rp::scene::TumblerShape{}, placements[i]);
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(first.instances[i + 2].model[c][r], demo[c][r], 1e-6f);
    }
  }
}

TEST(PhysicsWorld, DragBelowTheCentreTranslatesOverTheFloor) {
  World world;
  // Tumbler 0 stands at (0, -0.8, 0.2); aim at its bottom sphere below the centre.
  ASSERT_TRUE(world.begin_drag(camera_position(), towards(glm::vec3(0.0f, -0.9f, 0.2f))));
  EXPECT_EQ(world.dragged_tumbler(), std::optional<size_t>(0));
  EXPECT_EQ(world.drag_mode(), std::optional<DragMode>(DragMode::Translate));
  const glm::quat q0 = world.tumblers()[0].q;
  const glm::vec3 p0 = world.tumblers()[0].p;
  // Move the cursor so its ray meets the grab plane 0.3 further along +x.
  world.drag(camera_position(), towards(glm::vec3(0.3f, -0.9f, 0.2f)), glm::vec2(0.0f));
  world.step();
  EXPECT_GT(world.tumblers()[0].v.x, 0.0f);  // collisions see the motion
  for (int i = 0; i < 120; ++i) world.step();
  const glm::vec3 p1 = world.tumblers()[0].p;
  EXPECT_GT(p1.x - p0.x, 0.25f);
  EXPECT_LT(p1.x - p0.x, 0.35f);
  EXPECT_EQ(world.tumblers()[0].q, q0);  // slides, does not turn
  world.end_drag();
  EXPECT_FALSE(world.dragged_tumbler().has_value());
  EXPECT_EQ(world.tumblers()[0].v, glm::vec3(0.0f));
}

TEST(PhysicsWorld, DragAboveTheCentreTiltsAndRollsThenItRocksBack) {
  World world;
  ASSERT_TRUE(world.begin_drag(camera_position(), towards(glm::vec3(0.0f, -0.6f, 0.2f))));
  EXPECT_EQ(world.drag_mode(), std::optional<DragMode>(DragMode::Rotate));
  const glm::vec3 p0 = world.tumblers()[0].p;
  // 50 pixels to the right: 0.5 rad, the top towards +x, rolling b * 0.5 = 0.1 m along +x.
  world.drag(camera_position(), towards(glm::vec3(0.0f, -0.6f, 0.2f)), glm::vec2(50.0f, 0.0f));
  for (int i = 0; i < 60; ++i) world.step();
  const auto& ph = world.tumbler_physics();
  const auto& body = world.tumblers()[0];
  EXPECT_NEAR(ph.tilt(body), 0.5f, 1e-3f);
  EXPECT_GT(ph.axis(body).x, 0.4f);
  EXPECT_NEAR(body.p.x - p0.x, 0.1f, 1e-3f);
  world.end_drag();
  for (int i = 0; i < 2400; ++i) world.step();
  EXPECT_LT(glm::degrees(ph.tilt(world.tumblers()[0])), 2.0f);
}

TEST(PhysicsWorld, DragMissSelectsNothing) {
  World world;
  EXPECT_FALSE(world.begin_drag(camera_position(), glm::vec3(0.0f, 1.0f, 0.0f)));
  EXPECT_FALSE(world.dragged_tumbler().has_value());
  const uint64_t h = world.state_hash();
  world.drag(camera_position(), glm::vec3(0.0f, 0.0f, -1.0f), glm::vec2(10.0f));
  world.end_drag();
  EXPECT_EQ(world.state_hash(), h);
}

}  // namespace
