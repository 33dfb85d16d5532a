// The simulated world (SPEC.md sections 3-5): five tumblers, marbles (key S),
// fireballs (key F) and their particles, advanced by a fixed time step, deterministic for a
// seed and a sequence of calls. It produces the FrameScene the renderer draws.
//
// Frame loop of an app: for each displayed frame, apply that frame's input (set_marbles,
// begin_drag, ...), then advance(n) with n fixed steps (wall-clock time only decides n), then
// fill_frame(). advance(n) records the transforms before its n steps as the "previous" ones, so
// the velocity buffer sees one frame's motion; step() records them before its single step.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/collisions.h"
#include "scene/frame_scene.h"
#include "scene/particles.h"
#include "scene/picking.h"
#include "scene/random.h"
#include "scene/rigid_body.h"
#include "scene/tumbler_physics.h"

namespace rp::scene {

struct WorldConfig {
  uint64_t seed = 1;
  // 240 Hz: a marble falling the whole box (6.3 m/s) moves 0.026 m per step, well under its
  // radius (0.04), so it never passes a tumbler's medial surface (the SDF push-out then always
  // picks the near side); a rock (0.74 s) gets ~180 steps; a 60 Hz display takes 4 steps per frame.
  float dt = 1.0f / 240.0f;
  bool marbles = false;
  bool fireball = false;
};

// Values and the reasons for them (tumbler mass and friction are in TumblerParams).
namespace world_constants {
inline constexpr int kMarbleCount = 30;            // SPEC
inline constexpr float kMarbleRadius = 0.04f;      // m: 8 cm marbles beside 60 cm tumblers
inline constexpr float kMarbleMass = 0.005f;       // kg: a fast marble (5 m/s) tips a 0.25 kg
                                                   // tumbler by ~8 degrees: visible, not wild
inline constexpr float kMarbleSpeedMin = 0.6f;     // m/s, horizontal launch speed range
inline constexpr float kMarbleSpeedMax = 1.8f;
inline constexpr float kMarbleVerticalSpeed = 1.0f;  // m/s, launch v_y in [-this, this]
inline constexpr float kGravity = 9.81f;           // m/s^2, marbles only
inline constexpr float kFireballRadius = 0.1f;     // m: as big as a tumbler's top sphere
inline constexpr float kFireballMass = 0.02f;      // kg: knocks a tumbler by a few degrees
// m/s, constant (no gravity, no losses): crosses the box in ~1.3 s; among 30 marbles its mean
// free path is 1 / (30/8 m^3 x pi (0.1 + 0.04)^2) = 4.3 m, so at first one burns every ~3 s.
inline constexpr float kFireballSpeed = 1.5f;
inline constexpr glm::vec3 kFireballEmission{20.0f, 9.2f, 0.2f};  // (1, 0.46, 0.01) x 20
// Tumblers are hollow plastic: they bounce off each other and the walls with half their
// approach speed.
inline constexpr float kTumblerRestitution = 0.5f;
inline constexpr float kWallRestitution = 0.5f;
// Mouse: a 100-pixel drag tilts a tumbler by 1 rad; the held tumbler moves at most 4 m/s and
// turns at most 12 rad/s towards where the cursor puts it, so a cursor jump cannot tunnel it
// through another tumbler in one step.
inline constexpr float kDragRadiansPerPixel = 0.01f;
inline constexpr float kDragMaxSpeed = 4.0f;
inline constexpr float kDragMaxSpin = 12.0f;
}  // namespace world_constants

// A marble's saturated "glass" colour from a hue in [0, 1): HSV with s = 0.75, v = 0.9, linear
// RGB (the spawned marbles' albedo; the accuracy report's marble frame uses it too).
glm::vec3 glass_colour(float hue);

// A marble or fireball with what the renderer needs.
struct Ball {
  SphereBody sphere;
  glm::vec3 albedo{0.8f};
  glm::vec3 emission{0.0f};
  glm::vec3 prev_center{0.0f};  // centre at the last advance()/step() start
};

class World {
 public:
  explicit World(WorldConfig config = {});

  // Back to the initial state for the same seed: tumblers upright at the demo placements, step
  // counter 0, random streams re-seeded, particles cleared; marbles and the fireball are
  // respawned if they are on now (as a World built with these toggles would be).
  void reset();
  // One fixed step of config().dt (previous transforms = before this step).
  void step();
  // n fixed steps (previous transforms = before the first of them).
  void advance(int steps);
  uint64_t step_count() const { return step_count_; }
  double time() const { return static_cast<double>(step_count_) * config_.dt; }
  const WorldConfig& config() const { return config_; }

  // Key S: 30 marbles from the seeded random stream (positions clear of tumblers and each
  // other), gravity, energy kept forever. Off removes them all.
  void set_marbles(bool on);
  bool marbles() const { return marbles_on_; }
  // Key F: one fireball (no gravity, constant speed, emissive, burns marbles). Off removes it.
  void set_fireball(bool on);
  bool fireball() const { return fireball_on_; }
  // Extra bodies at a given state (tests; also a hook for more fireballs).
  void add_marble(const glm::vec3& center, const glm::vec3& velocity);
  void add_fireball(const glm::vec3& center, const glm::vec3& velocity);

  // Mouse (SPEC 4). begin_drag picks the nearest tumbler along the ray (false on a miss); a hit
  // below the centre of mass (y < -1 + b) translates it over the floor following the cursor
  // ray's crossing with the plane y = hit.y, else cursor motion tilts it about the camera's
  // horizontal axes (right: towards +x on screen, down: towards the camera), rolling it by the
  // matching distance. The held tumbler is kinematic: it moves where the mouse says (the
  // motion is applied by the next steps, at most kDragMaxSpeed/kDragMaxSpin), pushes other
  // bodies with its velocity and is not pushed back. end_drag releases it at rest.
  bool begin_drag(glm::vec3 ray_origin, glm::vec3 ray_dir);
  void drag(glm::vec3 ray_origin, glm::vec3 ray_dir, glm::vec2 cursor_delta_pixels);
  void end_drag();
  std::optional<size_t> dragged_tumbler() const;
  std::optional<DragMode> drag_mode() const;

  // Box and lamp (identity model, no shadows), the five tumblers (demo::kTumblerMesh, model and
  // previous model), marbles (shadow casting), fireballs (emissive, no shadow), particles;
  // default camera and light with prev_camera = camera. frame_index = number of advance() calls.
  void fill_frame(FrameScene& out) const;

  // FNV-1a (64-bit) over the exact bits of every body's state, the toggles, the drag, the
  // random streams, the step counter and the particle system's hash.
  uint64_t state_hash() const;

  // Read access (tests, debugging) and the tumblers for test set-ups.
  const std::vector<RigidBody>& tumblers() const { return tumblers_; }
  RigidBody& tumbler(size_t i) { return tumblers_.at(i); }
  const std::vector<Ball>& marble_balls() const { return marbles_; }
  const std::vector<Ball>& fireball_balls() const { return fireballs_; }
  const ParticleSystem& particles() const { return particles_; }
  ParticleSystem& particles() { return particles_; }
  Rng& particle_rng() { return particle_rng_; }
  const TumblerPhysics& tumbler_physics() const { return physics_; }
  const Arena& arena() const { return arena_; }
  const Camera& camera() const { return camera_; }

 private:
  struct Drag {
    size_t index = 0;
    DragMode mode = DragMode::Translate;
    float plane_y = 0.0f;
    glm::vec2 grab_offset{0.0f};  // tumbler p.xz - hit point.xz at the grab
    std::optional<glm::vec2> target;  // translate: where p.xz should go
    glm::vec3 pending_turn{0.0f};     // rotate: rotation vector still to apply (rad)
  };

  void step_impl();
  void snapshot_previous();
  void spawn_marbles();
  void spawn_fireball();
  Ball make_marble(const glm::vec3& center, const glm::vec3& velocity);
  Ball make_fireball(const glm::vec3& center, const glm::vec3& velocity) const;
  void move_held_tumbler(RigidBody& body, float dt);
  void collide_balls();
  bool is_held(size_t tumbler_index) const { return drag_ && drag_->index == tumbler_index; }

  WorldConfig config_;
  TumblerPhysics physics_;
  Arena arena_;
  Camera camera_;
  PointLight light_;
  Rng spawn_rng_;     // marbles and fireballs: positions, velocities, colours
  Rng particle_rng_;  // everything the particle system draws
  std::vector<RigidBody> tumblers_;
  std::vector<glm::mat4> prev_tumbler_models_;
  std::vector<Ball> marbles_;
  std::vector<Ball> fireballs_;
  ParticleSystem particles_;
  bool marbles_on_ = false;
  bool fireball_on_ = false;
  std::optional<Drag> drag_;
  uint64_t step_count_ = 0;
  uint32_t frame_count_ = 0;
  std::vector<Contact> contacts_;  // scratch, reused every step
};

}  // namespace rp::scene
