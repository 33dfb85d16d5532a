// Fire, sparks and ash (SPEC.md section 5): short-lived particles drawn as small emissive spheres
// whose radius and brightness follow their remaining life.
//
// Memory: one fixed ring buffer of kMaxParticles slots, allocated once in the constructor. The live
// particles occupy `count_` consecutive slots starting at `head_` (mod kMaxParticles), oldest
// first. Emitting into a full buffer overwrites the oldest live particle; step() removes the dead
// ones by a stable in-place compaction. So the live set is always the newest particles in emission
// order, independent of memory addresses, and no step allocates.
//
// Units: world units (the box spans [-1,1]^3), seconds, radiance as in FrameScene (a fireball is
// about (1, 0.46, 0.01) x 20). Every random number comes from the caller's Rng, in a fixed order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/frame_scene.h"
#include "scene/random.h"

namespace rp::scene {

enum class ParticleKind : uint8_t { Fire, Spark, Ash };

// One particle's full state (what hash() covers).
struct Particle {
  glm::vec3 position{0.0f};
  glm::vec3 prev_position{0.0f};  // position at the last mark_previous() (velocity buffer)
  glm::vec3 velocity{0.0f};       // world units per second
  float age = 0.0f;               // seconds since emission
  float life = 1.0f;              // seconds; the particle dies when age >= life
  float base_radius = 0.01f;      // radius at emission (world units)
  ParticleKind kind = ParticleKind::Fire;

  float remaining() const { return glm::clamp(1.0f - age / life, 0.0f, 1.0f); }  // 1 -> 0
};

// Tuning constants (values and reasons next to them; tests read them instead of repeating them).
namespace particle_constants {
inline constexpr float kGravity = 9.81f;            // m/s^2 along -y, like the marbles

// Fire: 400 per second per fireball (SPEC), life 0.45 s (SPEC), so ~180 live per fireball.
inline constexpr float kFireRate = 400.0f;          // particles per second per emit_fire caller
inline constexpr float kFireLife = 0.45f;           // seconds, no jitter (SPEC gives one value)
inline constexpr float kFireRadiusMin = 0.22f;      // initial radius / fireball radius, uniform
inline constexpr float kFireRadiusMax = 0.38f;      //   in [min, max]: blobs that overlap the ball
inline constexpr float kFireRise = 0.55f;           // random upward speed in [0.5, 1] x this
inline constexpr float kFireSideways = 0.12f;       // horizontal jitter speed, per axis (+-)
inline constexpr float kFireVelocityBlend = 0.5f;   // v = mix(random upward, fireball velocity, this)
inline constexpr float kFireRadiance = 20.0f;       // peak radiance scale, like the fireball
inline constexpr float kFireMinRadiusFraction = 0.25f;  // radius = base (0.25 + 0.75 remaining)

// Sparks: a short burst per fireball contact, thrown around the contact normal, falling.
inline constexpr int kSparksPerContact = 24;
inline constexpr float kSparkLife = 1.0f;           // seconds, times [1 - jitter, 1 + jitter]
inline constexpr float kSparkLifeJitter = 0.2f;
inline constexpr float kSparkSpeedMin = 0.8f;       // m/s, uniform in [min, max]
inline constexpr float kSparkSpeedMax = 1.8f;
inline constexpr float kSparkSpread = 0.7f;         // direction = normalize(n + spread * ball)
inline constexpr float kSparkOffset = 0.01f;        // start within this distance of the contact
inline constexpr float kSparkRadius = 0.006f;       // ~2 pixels at 720x720: small
inline constexpr float kSparkRadiance = 30.0f;      // brighter than fire: tiny but visible
inline constexpr float kSparkMinRadiusFraction = 0.5f;  // radius = base (0.5 + 0.5 remaining)
inline constexpr float kSparkRestitution = 0.5f;    // bounce off the walls, losing half the speed

// Ash: a cloud from a burned marble; light flakes: reduced gravity, drag and random gusts.
inline constexpr int kAshPerMarble = 64;
inline constexpr float kAshLife = 1.0f;             // seconds, times [1 - jitter, 1 + jitter]
inline constexpr float kAshLifeJitter = 0.2f;
inline constexpr float kAshVelocityScale = 0.6f;    // initial velocity = this x marble velocity
inline constexpr float kAshBurst = 0.25f;           //   + this x random vector in the unit ball
inline constexpr float kAshGravityScale = 0.15f;    // flakes are buoyed by the hot air
inline constexpr float kAshDrag = 1.5f;             // 1/s, linear drag: they drift, not fly
inline constexpr float kAshJitter = 2.0f;           // m/s^2, random acceleration per step (+-)
inline constexpr float kAshRadiusMin = 0.15f;       // initial radius / marble radius
inline constexpr float kAshRadiusMax = 0.3f;
inline constexpr float kAshMinRadiusFraction = 0.3f;  // radius = base (0.3 + 0.7 remaining)
inline constexpr float kAshCoolRadius = 0.6f;       // below base x this the ember starts to cool
inline constexpr float kAshBlackRadius = 0.45f;     // below base x this it is black: no emission
inline constexpr float kAshRadiance = 8.0f;         // glowing embers, dimmer than fire
inline constexpr float kAshBlackAlbedo = 0.04f;     // albedo of cooled (black) ash
}  // namespace particle_constants

class ParticleSystem {
 public:
  static constexpr size_t kMaxParticles = 2048;

  ParticleSystem();

  // Fire inside the fireball at kFireRate per second: dt x kFireRate particles, the fractional
  // part carried to the next call (one carry shared by all callers, so n fireballs get n x 400/s).
  void emit_fire(const glm::vec3& fireball_center, float fireball_radius,
                 const glm::vec3& fireball_velocity, float dt, Rng& rng);
  // kSparksPerContact sparks at a fireball contact; `normal` points away from the hit surface.
  void emit_sparks(const glm::vec3& contact, const glm::vec3& normal, Rng& rng);
  // kAshPerMarble ash flakes where a marble burned away.
  void emit_ash(const glm::vec3& marble_center, float marble_radius,
                const glm::vec3& marble_velocity, Rng& rng);

  // Ages every particle by dt, drops the dead, integrates the survivors (semi-implicit Euler) and
  // keeps each sphere inside [-1,1]^3 (clamp the centre by the radius, bounce or stop).
  void step(float dt, Rng& rng);

  // Remembers every live particle's position as its "previous" one (the velocity buffer's
  // start point). The world calls it once per rendered frame, before that frame's steps, so
  // motion over several fixed steps shows; particles emitted later start with prev = position.
  void mark_previous();

  // One emissive sphere per live particle, oldest first: centre, prev_center (position at the
  // last mark_previous(), or at emission), radius and emission from the remaining life, casts_shadow = false.
  void append_spheres(std::vector<Sphere>& out) const;
  // The sphere append_spheres() draws for one particle.
  static Sphere sphere_of(const Particle& p);

  size_t live_count() const { return count_; }
  // Copy of the live particles, oldest first (tests and debugging; allocates).
  std::vector<Particle> live_particles() const;
  void clear();

  // FNV-1a (64-bit) over the live particles' exact bits, oldest first, and the fire carry.
  uint64_t hash() const;

 private:
  Particle& push();  // a new slot at the back; overwrites the oldest when full
  Particle& at(size_t i) { return slots_[(head_ + i) % kMaxParticles]; }
  const Particle& at(size_t i) const { return slots_[(head_ + i) % kMaxParticles]; }

  std::vector<Particle> slots_;  // kMaxParticles slots, allocated once
  size_t head_ = 0;              // slot of the oldest live particle
  size_t count_ = 0;             // live particles
  float fire_carry_ = 0.0f;      // fractional fire particles owed, in [0, 1)
};

}  // namespace rp::scene
