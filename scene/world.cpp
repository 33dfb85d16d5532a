#include "scene/world.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "scene/demo_scene.h"

namespace rp::scene {

namespace wc = world_constants;

namespace {

constexpr glm::vec3 kUp{0.0f, 1.0f, 0.0f};
// Independent PCG32 streams, so marble spawning does not shift the particles' randomness.
constexpr uint64_t kSpawnStream = 0x9e3779b97f4a7c15ULL;
constexpr uint64_t kParticleStream = 0xd1b54a32d192ed03ULL;

// FNV-1a, 64-bit, over raw bytes.
class Fnv1a {
 public:
  void bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) {
      h_ ^= p[i];
      h_ *= 0x100000001b3ULL;
    }
  }
  template <typename T>
  void value(const T& v) {
    bytes(&v, sizeof v);  // only padding-free scalars and glm vectors/quats of floats
  }
  void body(const RigidBody& b) {
    value(b.p);
    value(b.v);
    value(b.w);
    value(b.q);
  }
  uint64_t get() const { return h_; }

 private:
  uint64_t h_ = 0xcbf29ce484222325ULL;
};

}  // namespace

glm::vec3 glass_colour(float hue) {
  const float h6 = hue * 6.0f;
  const glm::vec3 rgb = glm::clamp(
      glm::abs(glm::mod(glm::vec3(h6, h6 + 4.0f, h6 + 2.0f), 6.0f) - 3.0f) - 1.0f, 0.0f, 1.0f);
  return 0.9f * glm::mix(glm::vec3(1.0f), rgb, 0.75f);
}

World::World(WorldConfig config)
    : config_(config), arena_(Arena::from_light(PointLight{})) {
  if (!(config_.dt > 0.0f) || !std::isfinite(config_.dt)) {
    throw std::invalid_argument("World: dt must be a positive finite number of seconds");
  }
  marbles_on_ = config_.marbles;
  fireball_on_ = config_.fireball;
  reset();
}

void World::reset() {
  spawn_rng_.reseed(config_.seed, kSpawnStream);
  particle_rng_.reseed(config_.seed, kParticleStream);
  tumblers_.clear();
  for (const TumblerPlacement& placement : demo_tumbler_placements()) {
    tumblers_.push_back(physics_.make_body(placement));
  }
  marbles_.clear();
  fireballs_.clear();
  particles_.clear();
  drag_.reset();
  step_count_ = 0;
  frame_count_ = 0;
  if (marbles_on_) spawn_marbles();
  if (fireball_on_) spawn_fireball();
  snapshot_previous();
}

void World::set_marbles(bool on) {
  if (on == marbles_on_) return;
  marbles_on_ = on;
  if (on) {
    spawn_marbles();
  } else {
    marbles_.clear();
  }
}

void World::set_fireball(bool on) {
  if (on == fireball_on_) return;
  fireball_on_ = on;
  if (on) {
    spawn_fireball();
  } else {
    fireballs_.clear();
  }
}

Ball World::make_marble(const glm::vec3& center, const glm::vec3& velocity) {
  Ball ball;
  ball.sphere.body.p = center;
  ball.sphere.body.v = velocity;
  ball.sphere.body.mass = wc::kMarbleMass;
  ball.sphere.radius = wc::kMarbleRadius;
  ball.sphere.gravity = wc::kGravity;
  ball.sphere.reset_energy();
  ball.albedo = glass_colour(spawn_rng_.uniform());
  ball.prev_center = center;
  return ball;
}

Ball World::make_fireball(const glm::vec3& center, const glm::vec3& velocity) const {
  Ball ball;
  ball.sphere.body.p = center;
  ball.sphere.body.v = velocity;
  ball.sphere.body.mass = wc::kFireballMass;
  ball.sphere.radius = wc::kFireballRadius;
  ball.sphere.gravity = 0.0f;
  ball.sphere.reset_energy();
  ball.albedo = wc::kFireballEmission / 20.0f;
  ball.emission = wc::kFireballEmission;
  ball.prev_center = center;
  return ball;
}

void World::add_marble(const glm::vec3& center, const glm::vec3& velocity) {
  marbles_.push_back(make_marble(center, velocity));
}

void World::add_fireball(const glm::vec3& center, const glm::vec3& velocity) {
  fireballs_.push_back(make_fireball(center, velocity));
}

void World::spawn_marbles() {
  const float r = wc::kMarbleRadius;
  const float lim = arena_.half_extent - r - 0.05f;
  for (int i = 0; i < wc::kMarbleCount; ++i) {
    // Rejection sampling with a bounded number of tries: clear of tumblers, the lamp and the
    // marbles placed so far (a crowded box just gets its last candidate).
    glm::vec3 c(0.0f);
    for (int attempt = 0; attempt < 64; ++attempt) {
      c = glm::vec3(spawn_rng_.uniform(-lim, lim), spawn_rng_.uniform(-0.3f, 0.7f),
                    spawn_rng_.uniform(-lim, lim));
      bool clear = glm::length(c - arena_.lamp_center) > arena_.lamp_radius + r + 0.05f;
      for (const RigidBody& t : tumblers_) clear = clear && physics_.sdf(t, c) > r + 0.05f;
      for (const Ball& m : marbles_) clear = clear && glm::length(m.sphere.body.p - c) > 2.5f * r;
      if (clear) break;
    }
    const float azimuth = spawn_rng_.uniform(0.0f, 6.2831853f);
    const float speed = spawn_rng_.uniform(wc::kMarbleSpeedMin, wc::kMarbleSpeedMax);
    const glm::vec3 v(speed * std::cos(azimuth),
                      spawn_rng_.uniform(-wc::kMarbleVerticalSpeed, wc::kMarbleVerticalSpeed),
                      speed * std::sin(azimuth));
    marbles_.push_back(make_marble(c, v));
  }
}

void World::spawn_fireball() {
  const glm::vec3 c(spawn_rng_.uniform(-0.5f, 0.5f), spawn_rng_.uniform(0.1f, 0.5f),
                    spawn_rng_.uniform(-0.5f, 0.5f));
  // A direction with a real vertical part, so it reaches the tumblers and the floor.
  glm::vec3 d = spawn_rng_.unit_vector();
  d.y = std::copysign(std::clamp(std::abs(d.y), 0.3f, 0.7f), d.y);
  fireballs_.push_back(make_fireball(c, glm::normalize(d) * wc::kFireballSpeed));
}

void World::snapshot_previous() {
  prev_tumbler_models_.resize(tumblers_.size());
  for (size_t i = 0; i < tumblers_.size(); ++i) prev_tumbler_models_[i] = tumblers_[i].model_matrix();
  for (Ball& b : marbles_) b.prev_center = b.sphere.body.p;
  for (Ball& b : fireballs_) b.prev_center = b.sphere.body.p;
  particles_.mark_previous();
}

void World::step() {
  snapshot_previous();
  step_impl();
}

void World::advance(int steps) {
  snapshot_previous();
  ++frame_count_;
  for (int i = 0; i < steps; ++i) step_impl();
}

void World::move_held_tumbler(RigidBody& body, float dt) {
  Drag& d = *drag_;
  body.w = glm::vec3(0.0f);
  body.v = glm::vec3(0.0f);
  if (d.mode == DragMode::Translate) {
    if (d.target) {
      glm::vec2 delta = *d.target - glm::vec2(body.p.x, body.p.z);
      const float len = glm::length(delta), max_len = wc::kDragMaxSpeed * dt;
      if (len > max_len) delta *= max_len / len;
      body.v = glm::vec3(delta.x, 0.0f, delta.y) / dt;
    }
    body.p += body.v * dt;
  } else {
    glm::vec3 turn = d.pending_turn;
    const float len = glm::length(turn), max_len = wc::kDragMaxSpin * dt;
    if (len > max_len) turn *= max_len / len;
    // Do not turn beyond the pose where the top sphere lies on the floor.
    const RigidBody before = body;
    body.w = turn / dt;
    physics_.integrate(body, dt);
    if (physics_.tilt(body) > physics_.max_tilt() && physics_.tilt(body) > physics_.tilt(before)) {
      body = before;
      body.w = glm::vec3(0.0f);
      body.v = glm::vec3(0.0f);
      turn = glm::vec3(0.0f);
      d.pending_turn = glm::vec3(0.0f);
    }
    d.pending_turn -= turn;
  }
}

void World::step_impl() {
  const float dt = config_.dt;

  // Tumblers: SPEC's restoring impulse and friction, then the rolling step; the held one
  // follows the mouse instead.
  for (size_t i = 0; i < tumblers_.size(); ++i) {
    RigidBody& body = tumblers_[i];
    if (is_held(i)) {
      move_held_tumbler(body, dt);
      continue;
    }
    physics_.apply_restoring(body, dt);
    physics_.apply_friction(body, dt);
    physics_.integrate(body, dt);
  }
  for (Ball& b : marbles_) b.sphere.step_ballistic(dt);
  for (Ball& b : fireballs_) b.sphere.step_ballistic(dt);

  // Tumbler pairs, then walls last so every tumbler ends the step inside the box.
  for (size_t i = 0; i < tumblers_.size(); ++i) {
    for (size_t j = i + 1; j < tumblers_.size(); ++j) {
      collide_tumblers(tumblers_[i], is_held(i), tumblers_[j], is_held(j), physics_,
                       wc::kTumblerRestitution);
    }
  }
  for (size_t i = 0; i < tumblers_.size(); ++i) {
    collide_tumbler_walls(tumblers_[i], physics_, arena_, wc::kWallRestitution, is_held(i));
  }

  collide_balls();

  for (const Ball& f : fireballs_) {
    particles_.emit_fire(f.sphere.body.p, f.sphere.radius, f.sphere.body.v, dt, particle_rng_);
  }
  particles_.step(dt, particle_rng_);
  ++step_count_;
}

void World::collide_balls() {
  // Fireballs burn the marbles they touch (ash where the marble was, sparks at the contact).
  for (Ball& f : fireballs_) {
    for (size_t m = marbles_.size(); m-- > 0;) {
      const SphereBody& marble = marbles_[m].sphere;
      if (!spheres_touch(f.sphere, marble)) continue;
      const glm::vec3 n = glm::normalize(f.sphere.body.p - marble.body.p +
                                         glm::vec3(0.0f, 1e-6f, 0.0f));
      particles_.emit_sparks(marble.body.p + n * marble.radius, n, particle_rng_);
      particles_.emit_ash(marble.body.p, marble.radius, marble.body.v, particle_rng_);
      marbles_.erase(marbles_.begin() + static_cast<std::ptrdiff_t>(m));
    }
  }
  // Marbles bounce off marbles, fireballs off fireballs (elastic; energy invariants updated).
  for (std::vector<Ball>* group : {&marbles_, &fireballs_}) {
    for (size_t i = 0; i < group->size(); ++i) {
      for (size_t j = i + 1; j < group->size(); ++j) {
        const auto hit = collide_spheres((*group)[i].sphere, (*group)[j].sphere);
        if (hit && hit->impact_speed > 0.0f && group == &fireballs_) {
          particles_.emit_sparks(hit->point, hit->normal, particle_rng_);
        }
      }
    }
  }
  // Tumblers, lamp, walls (last: every sphere ends the step inside the box); then the
  // mechanical energy is restored for every sphere whose height a push-out changed.
  for (std::vector<Ball>* group : {&marbles_, &fireballs_}) {
    const bool fiery = group == &fireballs_;
    for (Ball& ball : *group) {
      SphereBody& s = ball.sphere;
      bool moved = false;
      for (size_t i = 0; i < tumblers_.size(); ++i) {
        const auto hit = collide_sphere_tumbler(s, tumblers_[i], physics_, is_held(i));
        if (!hit) continue;
        moved = true;
        if (fiery && hit->contact.impact_speed > 0.0f) {
          particles_.emit_sparks(hit->contact.point, hit->contact.normal, particle_rng_);
        }
      }
      contacts_.clear();
      moved = collide_sphere_lamp(s, arena_, &contacts_) || moved;
      moved = collide_sphere_walls(s, arena_, &contacts_) || moved;
      if (fiery) {
        for (const Contact& c : contacts_) {
          if (c.impact_speed > 0.0f) particles_.emit_sparks(c.point, c.normal, particle_rng_);
        }
      }
      if (moved) s.restore_energy();
    }
  }
}

bool World::begin_drag(glm::vec3 ray_origin, glm::vec3 ray_dir) {
  end_drag();
  std::vector<glm::mat4> models;
  models.reserve(tumblers_.size());
  for (const RigidBody& b : tumblers_) models.push_back(b.model_matrix());
  const std::optional<PickHit> hit = pick_tumbler(models, physics_.shape(), ray_origin, ray_dir);
  if (!hit) return false;
  Drag d;
  d.index = hit->index;
  d.mode = drag_mode_for(hit->point, physics_.params().floor_y + physics_.shape().b);
  d.plane_y = hit->point.y;
  const RigidBody& body = tumblers_[d.index];
  d.grab_offset = glm::vec2(body.p.x - hit->point.x, body.p.z - hit->point.z);
  drag_ = d;
  // Held: the body stops; its velocity from now on is the mouse's.
  tumblers_[d.index].v = glm::vec3(0.0f);
  tumblers_[d.index].w = glm::vec3(0.0f);
  return true;
}

void World::drag(glm::vec3 ray_origin, glm::vec3 ray_dir, glm::vec2 cursor_delta_pixels) {
  if (!drag_) return;
  Drag& d = *drag_;
  if (d.mode == DragMode::Translate) {
    const float len = glm::length(ray_dir);
    if (!(len > 0.0f)) return;
    const auto on_plane = intersect_horizontal_plane(Ray{ray_origin, ray_dir / len}, d.plane_y);
    if (!on_plane) return;
    // Keep the bottom sphere inside the box (the walls handle a tilted top sphere).
    const float lim = arena_.half_extent - physics_.shape().b;
    d.target = glm::clamp(glm::vec2(on_plane->x, on_plane->z) + d.grab_offset, -lim, lim);
  } else {
    // Screen right tilts the top towards the camera's right, screen down towards the camera:
    // a rotation by angle a about axis (y x dir) moves the axis towards dir.
    const glm::vec3 forward = camera_.target - camera_.position;
    glm::vec3 right = glm::cross(forward, camera_.up);
    right.y = 0.0f;
    right = glm::normalize(right);
    const glm::vec3 towards_camera = glm::normalize(glm::vec3(-forward.x, 0.0f, -forward.z));
    d.pending_turn += wc::kDragRadiansPerPixel *
                      (cursor_delta_pixels.x * glm::cross(kUp, right) +
                       cursor_delta_pixels.y * glm::cross(kUp, towards_camera));
  }
}

void World::end_drag() {
  if (!drag_) return;
  RigidBody& body = tumblers_[drag_->index];
  body.v = glm::vec3(0.0f);
  body.w = glm::vec3(0.0f);
  drag_.reset();
}

std::optional<size_t> World::dragged_tumbler() const {
  if (!drag_) return std::nullopt;
  return drag_->index;
}

std::optional<DragMode> World::drag_mode() const {
  if (!drag_) return std::nullopt;
  return drag_->mode;
}

void World::fill_frame(FrameScene& out) const {
  out.camera = camera_;
  out.prev_camera = camera_;
  out.light = light_;
  out.frame_index = frame_count_;
  out.instances.clear();
  out.spheres.clear();

  add_room_instances(out);
  for (size_t i = 0; i < tumblers_.size(); ++i) {
    MeshInstance t;
    t.mesh = demo::kTumblerMesh;
    t.model = tumblers_[i].model_matrix();
    t.prev_model = prev_tumbler_models_[i];
    t.casts_shadow = true;
    out.instances.push_back(t);
  }

  auto add = [&out](const Ball& b, bool marble) {
    const bool casts_shadow = marble;
    Sphere s;
    if (marble) s.specular = demo::kMarbleSpecular;  // fireballs and particles: matte
    s.center = b.sphere.body.p;
    s.prev_center = b.prev_center;
    s.radius = b.sphere.radius;
    s.albedo = b.albedo;
    s.emission = b.emission;
    s.casts_shadow = casts_shadow;
    out.spheres.push_back(s);
  };
  for (const Ball& b : marbles_) add(b, true);
  for (const Ball& b : fireballs_) add(b, false);
  particles_.append_spheres(out.spheres);
}

uint64_t World::state_hash() const {
  Fnv1a h;
  h.value(step_count_);
  h.value(static_cast<uint8_t>(marbles_on_));
  h.value(static_cast<uint8_t>(fireball_on_));
  h.value(spawn_rng_.state());
  h.value(particle_rng_.state());
  for (const RigidBody& b : tumblers_) h.body(b);
  for (const std::vector<Ball>* group : {&marbles_, &fireballs_}) {
    h.value(static_cast<uint64_t>(group->size()));
    for (const Ball& b : *group) {
      h.body(b.sphere.body);
      h.value(b.sphere.radius);
      h.value(b.sphere.energy);
    }
  }
  h.value(static_cast<uint8_t>(drag_.has_value()));
  if (drag_) {
    h.value(static_cast<uint64_t>(drag_->index));
    h.value(static_cast<uint8_t>(drag_->mode == DragMode::Rotate));
    h.value(drag_->target.value_or(glm::vec2(-1e9f)));
    h.value(drag_->pending_turn);
  }
  h.value(particles_.hash());
  return h.get();
}

}  // namespace rp::scene
