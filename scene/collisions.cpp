#include "scene/collisions.h"

#include <algorithm>
#include <cmath>

namespace rp::scene {

namespace {

constexpr glm::vec3 kUp{0.0f, 1.0f, 0.0f};

// Reflect the velocity along n if it points into the obstacle (v.n < 0). Returns dv
// (|dv| / 2 is the impact speed).
glm::vec3 reflect_into(glm::vec3& v, const glm::vec3& n) {
  const float vn = glm::dot(v, n);
  if (vn >= 0.0f) return glm::vec3(0.0f);
  const glm::vec3 dv = -2.0f * vn * n;
  v += dv;
  return dv;
}

}  // namespace

bool collide_sphere_walls(SphereBody& sphere, const Arena& arena, std::vector<Contact>* contacts) {
  bool moved = false;
  const float h = arena.half_extent, r = sphere.radius;
  glm::vec3& c = sphere.body.p;
  glm::vec3& v = sphere.body.v;
  for (int axis = 0; axis < 3; ++axis) {
    for (const float side : {-1.0f, 1.0f}) {
      const float limit = side * (h - r);  // the centre's bound on this wall
      if (side * (c[axis] - limit) <= 0.0f) continue;
      c[axis] = limit;
      moved = true;
      glm::vec3 n(0.0f);
      n[axis] = -side;  // into the box
      const glm::vec3 dv = reflect_into(v, n);
      // Rolling on the wall: the contact point c - r n is at rest, w = n x v / r.
      sphere.body.w = glm::cross(n, v) / r;
      if (contacts != nullptr) {
        glm::vec3 point = c;
        point[axis] = side * h;
        contacts->push_back({point, n, 0.5f * glm::length(dv)});
      }
    }
  }
  return moved;
}

bool collide_sphere_lamp(SphereBody& sphere, const Arena& arena, std::vector<Contact>* contacts) {
  glm::vec3& c = sphere.body.p;
  const glm::vec3 u = c - arena.lamp_center;
  const float len = glm::length(u);
  const float r = sphere.radius, big_r = arena.lamp_radius;
  if (len >= big_r + r || len <= 1e-6f) return false;
  const float ceiling = arena.half_extent;
  glm::vec3 closest = arena.lamp_center + u * (big_r / len);
  glm::vec3 n = u / len;
  if (closest.y > ceiling) {
    // The nearest point of the full sphere is hidden in the ceiling: the nearest point of the
    // cap is on its rim circle (y = ceiling).
    const float dy = ceiling - arena.lamp_center.y;
    const float rim = std::sqrt(std::max(0.0f, big_r * big_r - dy * dy));
    glm::vec3 radial(u.x, 0.0f, u.z);
    const float rl = glm::length(radial);
    radial = rl > 1e-6f ? radial / rl : glm::vec3(1.0f, 0.0f, 0.0f);
    closest = glm::vec3(arena.lamp_center.x, ceiling, arena.lamp_center.z) + rim * radial;
    const glm::vec3 off = c - closest;
    const float dist = glm::length(off);
    if (dist >= r) return false;
    if (dist > 1e-6f) n = off / dist;
  } else if (len - big_r >= r) {
    return false;
  }
  c = closest + n * r;
  const glm::vec3 dv = reflect_into(sphere.body.v, n);
  if (contacts != nullptr) contacts->push_back({closest, n, 0.5f * glm::length(dv)});
  return true;
}

std::optional<SphereTumblerHit> collide_sphere_tumbler(SphereBody& sphere, RigidBody& tumbler,
                                                       const TumblerPhysics& physics,
                                                       bool kinematic) {
  glm::vec3& c = sphere.body.p;
  const TumblerShape& shape = physics.shape();
  // Bounding sphere of the tumbler around p: radius max(b, y_t + t).
  const float reach = std::max(shape.b, shape.y_top()) + sphere.radius;
  const glm::vec3 off = c - tumbler.p;
  if (glm::dot(off, off) >= reach * reach) return std::nullopt;
  const float d = physics.sdf(tumbler, c);
  if (d >= sphere.radius) return std::nullopt;
  const glm::vec3 n = physics.sdf_gradient(tumbler, c);
  SphereTumblerHit hit;
  hit.contact = {c - d * n, n};
  c += (sphere.radius - d) * n;
  const glm::vec3 dv = reflect_into(sphere.body.v, n);
  hit.contact.impact_speed = 0.5f * glm::length(dv);
  hit.impulse_on_tumbler = -sphere.body.mass * dv;
  if (!kinematic && glm::dot(dv, dv) > 0.0f) {
    physics.apply_impulse(tumbler, hit.impulse_on_tumbler, hit.contact.point);
  }
  return hit;
}

bool spheres_touch(const SphereBody& a, const SphereBody& b) {
  const glm::vec3 d = b.body.p - a.body.p;
  const float rr = a.radius + b.radius;
  return glm::dot(d, d) < rr * rr;
}

std::optional<Contact> collide_spheres(SphereBody& a, SphereBody& b) {
  if (!spheres_touch(a, b)) return std::nullopt;
  glm::vec3 d = b.body.p - a.body.p;
  const float dist = glm::length(d);
  const glm::vec3 n = dist > 1e-6f ? d / dist : glm::vec3(0.0f, 1.0f, 0.0f);
  const float ma = a.body.mass, mb = b.body.mass, inv_sum = 1.0f / (ma + mb);
  const float depth = a.radius + b.radius - dist;
  a.body.p -= n * (depth * mb * inv_sum);
  b.body.p += n * (depth * ma * inv_sum);
  const float approach = glm::dot(a.body.v - b.body.v, n);
  Contact contact{a.body.p + n * a.radius, n, std::max(approach, 0.0f)};
  if (approach > 0.0f) {
    const float j = 2.0f * approach * ma * mb * inv_sum;  // elastic: e = 1
    a.body.v -= (j / ma) * n;
    b.body.v += (j / mb) * n;
  }
  a.reset_energy();
  b.reset_energy();
  return contact;
}

bool collide_tumbler_walls(RigidBody& tumbler, const TumblerPhysics& physics, const Arena& arena,
                           float restitution, bool kinematic) {
  const TumblerShape& shape = physics.shape();
  bool changed = false;

  // Floor: only the top sphere can reach it (the bottom one rests on it by construction).
  const glm::vec3 d = physics.axis(tumbler);
  if (physics.top_center(tumbler).y - shape.t < -arena.half_extent) {
    const glm::vec3 side = glm::cross(d, kUp);  // turning about it moves d towards +y
    const float len = glm::length(side);
    const glm::vec3 a = len > 1e-6f ? side / len : glm::vec3(1.0f, 0.0f, 0.0f);
    const float excess = physics.tilt(tumbler) - physics.max_tilt();
    tumbler.q = glm::normalize(glm::angleAxis(excess, a) * tumbler.q);
    tumbler.w = glm::vec3(0.0f);
    tumbler.v = glm::vec3(0.0f);
    changed = true;
  }

  // Side walls x = +-h and z = +-h; the hull of the two spheres reaches furthest at one of them.
  struct Ball {
    glm::vec3 c;
    float r;
  };
  const Ball balls[2] = {{tumbler.p, shape.b}, {physics.top_center(tumbler), shape.t}};
  glm::vec3 push(0.0f);
  for (const int axis : {0, 2}) {
    for (const float side : {-1.0f, 1.0f}) {
      float depth = 0.0f;
      glm::vec3 point(0.0f);
      for (const Ball& ball : balls) {
        const float pen = side * ball.c[axis] + ball.r - arena.half_extent;
        if (pen > depth) {
          depth = pen;
          point = ball.c;
          point[axis] = side * arena.half_extent;
        }
      }
      if (depth <= 0.0f) continue;
      changed = true;
      glm::vec3 n(0.0f);
      n[axis] = -side;  // into the box
      push[axis] = -side * std::max(std::abs(push[axis]), depth);
      if (kinematic) continue;
      const float vn = glm::dot(tumbler.point_velocity(point), n);
      if (vn >= 0.0f) continue;
      const float k = glm::dot(n, physics.impulse_response(tumbler, point) * n);
      if (k <= 1e-9f) continue;
      physics.apply_impulse(tumbler, n * (-(1.0f + restitution) * vn / k), point);
    }
  }
  tumbler.p += push;
  return changed;
}

std::optional<TumblerPairHit> collide_tumblers(RigidBody& a, bool a_kinematic, RigidBody& b,
                                               bool b_kinematic, const TumblerPhysics& physics,
                                               float restitution) {
  const TumblerShape& shape = physics.shape();
  // Quick reject: the bodies' bounding spheres around p (radius y_t + t).
  const float reach = 2.0f * std::max(shape.b, shape.y_top());
  const glm::vec3 ab = b.p - a.p;
  if (glm::dot(ab, ab) >= reach * reach) return std::nullopt;

  glm::vec3 sum(0.0f);
  int count = 0;
  float depth = 0.0f;
  auto test = [&](const glm::vec3& c, float r, const RigidBody& other) {
    const float d = physics.sdf(other, c);
    if (d >= r) return;
    sum += c - d * physics.sdf_gradient(other, c);
    ++count;
    depth = std::max(depth, r - d);
  };
  test(a.p, shape.b, b);
  test(physics.top_center(a), shape.t, b);
  test(b.p, shape.b, a);
  test(physics.top_center(b), shape.t, a);
  if (count == 0) return std::nullopt;

  TumblerPairHit hit;
  hit.depth = depth;
  const glm::vec3 h = sum / static_cast<float>(count);
  glm::vec3 n = physics.sdf_gradient(a, h) - physics.sdf_gradient(b, h);
  const float len = glm::length(n);
  n = len > 1e-6f ? n / len : glm::normalize(ab + glm::vec3(1e-6f, 0.0f, 0.0f));
  hit.contact = {h, n};

  // Push apart horizontally (tumblers only move in x/z).
  glm::vec3 horizontal(n.x, 0.0f, n.z);
  if (glm::length(horizontal) < 0.2f) horizontal = glm::vec3(ab.x, 0.0f, ab.z);
  const float hl = glm::length(horizontal);
  horizontal = hl > 1e-6f ? horizontal / hl : glm::vec3(1.0f, 0.0f, 0.0f);
  if (!a_kinematic && !b_kinematic) {
    a.p -= horizontal * (0.5f * depth);
    b.p += horizontal * (0.5f * depth);
  } else if (!a_kinematic) {
    a.p -= horizontal * depth;
  } else if (!b_kinematic) {
    b.p += horizontal * depth;
  }

  const float approach = glm::dot(a.point_velocity(h) - b.point_velocity(h), n);
  if (approach <= 0.0f) return hit;
  float k = 0.0f;
  if (!a_kinematic) k += glm::dot(n, physics.impulse_response(a, h) * n);
  if (!b_kinematic) k += glm::dot(n, physics.impulse_response(b, h) * n);
  if (k <= 1e-9f) return hit;
  hit.impulse = (1.0f + restitution) * approach / k;
  if (!a_kinematic) physics.apply_impulse(a, -hit.impulse * n, h);
  if (!b_kinematic) physics.apply_impulse(b, hit.impulse * n, h);
  return hit;
}

}  // namespace rp::scene
