#include "scene/tumbler_physics.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rp::scene {

namespace {

constexpr glm::vec3 kUp{0.0f, 1.0f, 0.0f};

// The SPEC 2 profile in double (TumblerShape::radius is float; the integrals want more).
struct Profile {
  double b, t, alpha, y_t;
  double radius(double y) const {
    const double ys = b * std::sin(alpha), yc = y_t + t * std::sin(alpha);
    if (y < ys) return std::sqrt(std::max(0.0, b * b - y * y));
    if (y <= yc) return -y * std::tan(alpha) + b / std::cos(alpha);
    const double dy = y - y_t;
    return std::sqrt(std::max(0.0, t * t - dy * dy));
  }
};

// Composite Simpson of f on [lo, hi] with n (even) intervals.
template <typename F>
double simpson(F f, double lo, double hi, int n) {
  const double h = (hi - lo) / n;
  double sum = f(lo) + f(hi);
  for (int i = 1; i < n; ++i) sum += f(lo + i * h) * ((i % 2 == 1) ? 4.0 : 2.0);
  return sum * h / 3.0;
}

}  // namespace

TumblerInertia compute_tumbler_inertia(const TumblerShape& shape, double mass, int intervals) {
  if (intervals < 2 || intervals % 2 != 0 || !(mass > 0.0)) {
    throw std::invalid_argument("compute_tumbler_inertia: need mass > 0 and an even intervals >= 2");
  }
  const Profile pr{shape.b, shape.t, shape.alpha,
                   (double(shape.b) - double(shape.t)) / std::sin(double(shape.alpha))};
  // The profile is smooth on each piece (polynomial in y once squared), so Simpson piecewise
  // converges fast; across the joins it would only be first order.
  const double joins[4] = {-pr.b, pr.b * std::sin(pr.alpha), pr.y_t + pr.t * std::sin(pr.alpha),
                           pr.y_t + pr.t};
  double v = 0.0, ixx = 0.0, iyy = 0.0;
  for (int k = 0; k < 3; ++k) {
    auto r2 = [&](double y) { const double r = pr.radius(y); return r * r; };
    v += simpson(r2, joins[k], joins[k + 1], intervals);
    ixx += simpson([&](double y) { const double s = r2(y); return s * s + 4.0 * y * y * s; },
                   joins[k], joins[k + 1], intervals);
    iyy += simpson([&](double y) { const double s = r2(y); return s * s; }, joins[k],
                   joins[k + 1], intervals);
  }
  constexpr double kPi = std::numbers::pi;
  TumblerInertia out;
  out.volume = kPi * v;
  out.density = mass / out.volume;
  out.moments = glm::dvec3(out.density * kPi / 4.0 * ixx, out.density * kPi / 2.0 * iyy,
                           out.density * kPi / 4.0 * ixx);
  return out;
}

TumblerPhysics::TumblerPhysics(const TumblerShape& shape, const TumblerParams& params)
    : shape_(shape), params_(params), inertia_(compute_tumbler_inertia(shape, params.mass)) {}

RigidBody TumblerPhysics::make_body(const TumblerPlacement& placement) const {
  RigidBody body;
  body.p = glm::vec3(placement.xz.x, params_.floor_y + shape_.b, placement.xz.y);
  body.q = glm::angleAxis(placement.yaw, kUp);
  body.mass = params_.mass;
  body.inertia_local = glm::vec3(inertia_.moments);
  return body;
}

glm::vec3 TumblerPhysics::axis(const RigidBody& body) const { return body.q * kUp; }

glm::vec3 TumblerPhysics::top_center(const RigidBody& body) const {
  return body.p + shape_.y_t * axis(body);
}

glm::vec3 TumblerPhysics::floor_contact(const RigidBody& body) const {
  return body.p - shape_.b * kUp;
}

float TumblerPhysics::tilt(const RigidBody& body) const {
  return std::acos(std::clamp(axis(body).y, -1.0f, 1.0f));
}

float TumblerPhysics::max_tilt() const {
  return std::acos(std::clamp((shape_.t - shape_.b) / shape_.y_t, -1.0f, 1.0f));
}

float TumblerPhysics::sdf(const RigidBody& body, const glm::vec3& x) const {
  return shape_.sdf(glm::conjugate(body.q) * (x - body.p));
}

glm::vec3 TumblerPhysics::sdf_gradient(const RigidBody& body, const glm::vec3& x) const {
  return body.q * shape_.sdf_gradient(glm::conjugate(body.q) * (x - body.p));
}

glm::mat3 TumblerPhysics::contact_inertia(const RigidBody& body) const {
  const float mb2 = body.mass * shape_.b * shape_.b;
  glm::mat3 ic = body.inertia_world();
  ic[0][0] += mb2;  // + m b^2 (E - y y^T): x and z only
  ic[2][2] += mb2;
  return ic;
}

glm::mat3 TumblerPhysics::impulse_response(const RigidBody& body, const glm::vec3& at) const {
  const glm::mat3 rx = cross_matrix(at - floor_contact(body));
  return -(rx * glm::inverse(contact_inertia(body)) * rx);
}

void TumblerPhysics::apply_impulse(RigidBody& body, const glm::vec3& j, const glm::vec3& at) const {
  body.w += glm::inverse(contact_inertia(body)) * glm::cross(at - floor_contact(body), j);
  enforce_rolling(body);
}

void TumblerPhysics::apply_restoring(RigidBody& body, float dt) const {
  const glm::vec3 j = -params_.restoring_force * dt * axis(body);
  apply_impulse(body, j, body.p + glm::vec3(0.0f, params_.restoring_arm, 0.0f));
}

void TumblerPhysics::apply_friction(RigidBody& body, float dt) const {
  const float speed = glm::length(body.w);
  const float slowed = speed - params_.friction * params_.gravity * dt / shape_.b;
  body.w = slowed > 0.0f ? body.w * (slowed / speed) : glm::vec3(0.0f);
  enforce_rolling(body);
}

void TumblerPhysics::enforce_rolling(RigidBody& body) const {
  body.p.y = params_.floor_y + shape_.b;
  body.v = shape_.b * glm::cross(body.w, kUp);
}

void TumblerPhysics::integrate(RigidBody& body, float dt) const {
  enforce_rolling(body);
  body.integrate(dt);
  body.p.y = params_.floor_y + shape_.b;
}

}  // namespace rp::scene
