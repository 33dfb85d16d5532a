#include "scene/particles.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace rp::scene {

namespace pc = particle_constants;

namespace {

// Random numbers are drawn in separate statements: the evaluation order of function arguments
// is unspecified in C++, so `vec3(rng.uniform(), rng.uniform(), ...)` could differ by compiler.
glm::vec3 ball(Rng& rng) { return rng.in_unit_ball(); }

glm::vec3 symmetric3(Rng& rng, float half_width) {
  const float x = rng.uniform(-half_width, half_width);
  const float y = rng.uniform(-half_width, half_width);
  const float z = rng.uniform(-half_width, half_width);
  return {x, y, z};
}

glm::vec3 safe_normalize(const glm::vec3& v, const glm::vec3& fallback) {
  const float len2 = glm::dot(v, v);
  return len2 > 1e-12f ? v / std::sqrt(len2) : fallback;
}

// Piecewise-linear colour ramp over the remaining life f: cold (f = 0) -> mid -> hot (f = 1).
glm::vec3 ramp(float f, float f_mid, const glm::vec3& cold, const glm::vec3& mid,
               const glm::vec3& hot) {
  if (f >= f_mid) return glm::mix(mid, hot, (f - f_mid) / (1.0f - f_mid));
  return glm::mix(cold, mid, f / f_mid);
}

// Fire: white-yellow when new, the fireball's orange (1, 0.46, 0.01) at 60 % life, deep
// orange-red at the end.
const glm::vec3 kFireHot{1.0f, 0.92f, 0.6f};
const glm::vec3 kFireMid{1.0f, 0.46f, 0.01f};
const glm::vec3 kFireCold{0.75f, 0.12f, 0.01f};
// Sparks: yellow-white cooling to orange.
const glm::vec3 kSparkHot{1.0f, 0.85f, 0.5f};
const glm::vec3 kSparkCold{1.0f, 0.4f, 0.06f};
// Ash embers: dull orange-red glow; albedo from ember brown to black as they cool.
const glm::vec3 kAshEmber{1.0f, 0.3f, 0.04f};
const glm::vec3 kAshEmberAlbedo{0.35f, 0.12f, 0.05f};

float radius_of(const Particle& p) {
  const float f = p.remaining();
  switch (p.kind) {
    case ParticleKind::Fire:
      return p.base_radius * (pc::kFireMinRadiusFraction + (1.0f - pc::kFireMinRadiusFraction) * f);
    case ParticleKind::Spark:
      return p.base_radius *
             (pc::kSparkMinRadiusFraction + (1.0f - pc::kSparkMinRadiusFraction) * f);
    case ParticleKind::Ash:
      return p.base_radius * (pc::kAshMinRadiusFraction + (1.0f - pc::kAshMinRadiusFraction) * f);
  }
  return p.base_radius;
}

float restitution_of(ParticleKind kind) {
  return kind == ParticleKind::Spark ? pc::kSparkRestitution : 0.0f;  // fire and ash stop
}

// Keeps the whole sphere inside [-1,1]^3: the centre within [-1 + r, 1 - r] on each axis; a
// velocity component pointing into the wall is reflected and scaled by `restitution`.
void contain(glm::vec3& position, glm::vec3& velocity, float radius, float restitution) {
  const float lo = -1.0f + radius, hi = 1.0f - radius;
  for (int axis = 0; axis < 3; ++axis) {
    if (position[axis] < lo) {
      position[axis] = lo;
      if (velocity[axis] < 0.0f) velocity[axis] = -velocity[axis] * restitution;
    } else if (position[axis] > hi) {
      position[axis] = hi;
      if (velocity[axis] > 0.0f) velocity[axis] = -velocity[axis] * restitution;
    }
  }
}

// Placement of a freshly emitted particle: inside the box, not moved yet.
void settle_new(Particle& p) {
  contain(p.position, p.velocity, radius_of(p), restitution_of(p.kind));
  p.prev_position = p.position;
}

constexpr uint64_t kFnvOffset = 1469598103934665603ULL;
constexpr uint64_t kFnvPrime = 1099511628211ULL;

void fnv_bytes(uint64_t& h, const void* data, size_t n) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < n; ++i) {
    h ^= bytes[i];
    h *= kFnvPrime;
  }
}

void fnv_float(uint64_t& h, float v) {
  uint32_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  fnv_bytes(h, &bits, sizeof bits);
}

void fnv_vec3(uint64_t& h, const glm::vec3& v) {
  fnv_float(h, v.x);
  fnv_float(h, v.y);
  fnv_float(h, v.z);
}

}  // namespace

ParticleSystem::ParticleSystem() : slots_(kMaxParticles) {}

Particle& ParticleSystem::push() {
  if (count_ == kMaxParticles) {  // full: the oldest slot becomes the newest
    Particle& slot = slots_[head_];
    head_ = (head_ + 1) % kMaxParticles;
    slot = Particle{};
    return slot;
  }
  Particle& slot = at(count_);
  ++count_;
  slot = Particle{};
  return slot;
}

void ParticleSystem::emit_fire(const glm::vec3& fireball_center, float fireball_radius,
                               const glm::vec3& fireball_velocity, float dt, Rng& rng) {
  if (!(dt > 0.0f)) return;
  fire_carry_ += pc::kFireRate * dt;
  const float whole = std::floor(fire_carry_);
  fire_carry_ -= whole;
  // More than a full buffer in one call would only overwrite itself.
  const size_t n = static_cast<size_t>(std::min(whole, static_cast<float>(kMaxParticles)));
  for (size_t k = 0; k < n; ++k) {
    Particle& p = push();
    p.kind = ParticleKind::Fire;
    // Uniform ball point u mapped to u |u|: distance from the centre rho -> rho^2, so the density
    // grows towards the centre (proportional to 1 / distance^1.5).
    const glm::vec3 u = ball(rng);
    p.position = fireball_center + fireball_radius * glm::length(u) * u;
    const float sideways_x = rng.uniform(-pc::kFireSideways, pc::kFireSideways);
    const float rise = pc::kFireRise * rng.uniform(0.5f, 1.0f);
    const float sideways_z = rng.uniform(-pc::kFireSideways, pc::kFireSideways);
    const glm::vec3 upward{sideways_x, rise, sideways_z};
    p.velocity = glm::mix(upward, fireball_velocity, pc::kFireVelocityBlend);
    p.life = pc::kFireLife;
    p.base_radius = fireball_radius * rng.uniform(pc::kFireRadiusMin, pc::kFireRadiusMax);
    settle_new(p);
  }
}

void ParticleSystem::emit_sparks(const glm::vec3& contact, const glm::vec3& normal, Rng& rng) {
  const glm::vec3 n = safe_normalize(normal, glm::vec3(0.0f, 1.0f, 0.0f));
  for (int k = 0; k < pc::kSparksPerContact; ++k) {
    Particle& p = push();
    p.kind = ParticleKind::Spark;
    p.position = contact + pc::kSparkOffset * ball(rng);
    const glm::vec3 dir = safe_normalize(n + pc::kSparkSpread * ball(rng), n);
    p.velocity = dir * rng.uniform(pc::kSparkSpeedMin, pc::kSparkSpeedMax);
    p.life = pc::kSparkLife * rng.uniform(1.0f - pc::kSparkLifeJitter, 1.0f + pc::kSparkLifeJitter);
    p.base_radius = pc::kSparkRadius * rng.uniform(0.7f, 1.3f);
    settle_new(p);
  }
}

void ParticleSystem::emit_ash(const glm::vec3& marble_center, float marble_radius,
                              const glm::vec3& marble_velocity, Rng& rng) {
  for (int k = 0; k < pc::kAshPerMarble; ++k) {
    Particle& p = push();
    p.kind = ParticleKind::Ash;
    p.position = marble_center + marble_radius * ball(rng);
    p.velocity = pc::kAshVelocityScale * marble_velocity + pc::kAshBurst * ball(rng);
    p.life = pc::kAshLife * rng.uniform(1.0f - pc::kAshLifeJitter, 1.0f + pc::kAshLifeJitter);
    p.base_radius = marble_radius * rng.uniform(pc::kAshRadiusMin, pc::kAshRadiusMax);
    settle_new(p);
  }
}

void ParticleSystem::mark_previous() {
  for (size_t i = 0; i < count_; ++i) at(i).prev_position = at(i).position;
}

void ParticleSystem::step(float dt, Rng& rng) {
  // Stable in-place compaction: survivor i moves to position w <= i, so no slot is read after
  // it was overwritten, and the emission order is kept.
  size_t w = 0;
  for (size_t i = 0; i < count_; ++i) {
    Particle p = at(i);
    p.age += dt;
    if (p.age >= p.life) continue;
    switch (p.kind) {
      case ParticleKind::Fire:  // buoyant: keeps its velocity
        break;
      case ParticleKind::Spark:
        p.velocity.y -= pc::kGravity * dt;
        break;
      case ParticleKind::Ash: {
        glm::vec3 accel = symmetric3(rng, pc::kAshJitter);
        accel.y -= pc::kGravity * pc::kAshGravityScale;
        p.velocity += accel * dt;
        p.velocity *= std::max(0.0f, 1.0f - pc::kAshDrag * dt);
        break;
      }
    }
    p.position += p.velocity * dt;
    contain(p.position, p.velocity, radius_of(p), restitution_of(p.kind));
    at(w++) = p;
  }
  count_ = w;
}

Sphere ParticleSystem::sphere_of(const Particle& p) {
  const float f = p.remaining();
  Sphere s;
  s.center = p.position;
  s.prev_center = p.prev_position;
  s.radius = radius_of(p);
  s.casts_shadow = false;
  switch (p.kind) {
    case ParticleKind::Fire: {
      const glm::vec3 colour = ramp(f, 0.6f, kFireCold, kFireMid, kFireHot);
      s.albedo = colour;
      s.emission = colour * (pc::kFireRadiance * f);
      break;
    }
    case ParticleKind::Spark: {
      const glm::vec3 colour = glm::mix(kSparkCold, kSparkHot, f);
      s.albedo = colour;
      s.emission = colour * (pc::kSparkRadiance * f);
      break;
    }
    case ParticleKind::Ash: {
      // Cooling: full glow above kAshCoolRadius x base, none below kAshBlackRadius x base.
      const float q = s.radius / p.base_radius;
      const float glow =
          glm::clamp((q - pc::kAshBlackRadius) / (pc::kAshCoolRadius - pc::kAshBlackRadius), 0.0f,
                     1.0f);
      s.albedo = glm::mix(glm::vec3(pc::kAshBlackAlbedo), kAshEmberAlbedo, glow);
      s.emission = kAshEmber * (pc::kAshRadiance * f * glow);
      break;
    }
  }
  return s;
}

void ParticleSystem::append_spheres(std::vector<Sphere>& out) const {
  for (size_t i = 0; i < count_; ++i) out.push_back(sphere_of(at(i)));
}

std::vector<Particle> ParticleSystem::live_particles() const {
  std::vector<Particle> out;
  out.reserve(count_);
  for (size_t i = 0; i < count_; ++i) out.push_back(at(i));
  return out;
}

void ParticleSystem::clear() {
  head_ = 0;
  count_ = 0;
  fire_carry_ = 0.0f;
}

uint64_t ParticleSystem::hash() const {
  uint64_t h = kFnvOffset;
  const uint64_t count = count_;
  fnv_bytes(h, &count, sizeof count);
  for (size_t i = 0; i < count_; ++i) {
    const Particle& p = at(i);
    fnv_vec3(h, p.position);
    fnv_vec3(h, p.prev_position);
    fnv_vec3(h, p.velocity);
    fnv_float(h, p.age);
    fnv_float(h, p.life);
    fnv_float(h, p.base_radius);
    const auto kind = static_cast<uint8_t>(p.kind);
    fnv_bytes(h, &kind, sizeof kind);
  }
  fnv_float(h, fire_carry_);
  return h;
}

}  // namespace rp::scene
