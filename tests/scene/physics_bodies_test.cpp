// Rigid bodies and tumbler dynamics (SPEC.md sections 2 and 3): inertia against a voxel estimate,
// quaternion integration against the exact rotation, free-body and rolling impulse responses.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include "scene/rigid_body.h"
#include "scene/tumbler_physics.h"
#include "scene/tumbler_shape.h"

namespace {

using rp::scene::RigidBody;
using rp::scene::TumblerPhysics;
using rp::scene::TumblerShape;

void expect_vec_near(const glm::vec3& a, const glm::vec3& b, float tol, const char* what) {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

// Volume and moments by midpoint voxels of the solid {sdf < 0}: an estimate independent of the
// profile integrals (it only uses the SDF's sign).
TEST(PhysicsInertia, MatchesVoxelEstimateWithinOnePercent) {
  const TumblerShape shape;
  const double mass = 0.25;
  const auto inertia = rp::scene::compute_tumbler_inertia(shape, mass);

  const int nx = 160, ny = 240, nz = 160;
  const double x0 = -shape.b, y0 = -shape.b, y1 = shape.y_top();
  const double hx = 2.0 * shape.b / nx, hy = (y1 - y0) / ny, hz = 2.0 * shape.b / nz;
  double volume = 0.0, sxx = 0.0, syy = 0.0, szz = 0.0;  // sums of y^2+z^2, x^2+z^2, x^2+y^2
  for (int k = 0; k < nz; ++k) {
    const double z = x0 + (k + 0.5) * hz;
    for (int j = 0; j < ny; ++j) {
      const double y = y0 + (j + 0.5) * hy;
      for (int i = 0; i < nx; ++i) {
        const double x = x0 + (i + 0.5) * hx;
        if (shape.sdf(glm::vec3(float(x), float(y), float(z))) >= 0.0f) continue;
        volume += 1.0;
        sxx += y * y + z * z;
        syy += x * x + z * z;
        szz += x * x + y * y;
      }
    }
  }
  const double cell = hx * hy * hz;
  volume *= cell;
  const double density = mass / volume;
  EXPECT_NEAR(inertia.volume, volume, 0.01 * volume);
  EXPECT_NEAR(inertia.moments.x, density * sxx * cell, 0.01 * density * sxx * cell);
  EXPECT_NEAR(inertia.moments.y, density * syy * cell, 0.01 * density * syy * cell);
  EXPECT_NEAR(inertia.moments.z, density * szz * cell, 0.01 * density * szz * cell);
  EXPECT_DOUBLE_EQ(inertia.moments.x, inertia.moments.z);
}

// The volume integral against the closed form of its three pieces (ball minus a cap, cone
// frustum, cap of the top sphere); the moments scale with the mass.
TEST(PhysicsInertia, VolumeMatchesClosedFormPieces) {
  const TumblerShape s;
  const double b = s.b, t = s.t, a = s.alpha, yt = (b - t) / std::sin(a);
  const double pi = std::numbers::pi;
  // Bottom: ball of radius b from y = -b to y = b sin a (a sphere cap volume formula).
  auto cap = [pi](double r, double h) { return pi * h * h * (3.0 * r - h) / 3.0; };
  const double bottom = 4.0 / 3.0 * pi * b * b * b - cap(b, b - b * std::sin(a));
  const double top = cap(t, t - t * std::sin(a));
  // Frustum of a cone between the joins: radii b cos a and t cos a.
  const double h = (yt + t * std::sin(a)) - b * std::sin(a);
  const double r0 = b * std::cos(a), r1 = t * std::cos(a);
  const double frustum = pi * h * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0;
  const auto inertia = rp::scene::compute_tumbler_inertia(s, 1.0);
  EXPECT_NEAR(inertia.volume, bottom + top + frustum, 1e-6 * inertia.volume);
  const auto heavy = rp::scene::compute_tumbler_inertia(s, 3.0);
  EXPECT_NEAR(heavy.moments.x, 3.0 * inertia.moments.x, 1e-12);
  EXPECT_THROW(rp::scene::compute_tumbler_inertia(s, 1.0, 3), std::invalid_argument);
}

TEST(PhysicsRigidBody, QuaternionStepFollowsExactRotationAndStaysUnit) {
  RigidBody body;
  body.q = glm::angleAxis(0.3f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)));
  const glm::quat q0 = body.q;
  const glm::vec3 axis = glm::normalize(glm::vec3(-0.4f, 1.0f, 0.7f));
  body.w = 3.0f * axis;  // rad/s, world frame
  const float dt = 1.0f / 240.0f;
  for (int i = 0; i < 240; ++i) body.integrate(dt);
  // After 1 s: rotated by 3 rad about `axis` (world frame: multiplies on the left).
  const glm::quat exact = glm::angleAxis(3.0f, axis) * q0;
  EXPECT_NEAR(glm::length(body.q), 1.0f, 1e-6f);
  const float angle_error = 2.0f * std::acos(std::min(1.0f, std::abs(glm::dot(exact, body.q))));
  EXPECT_LT(angle_error, 1e-3f);
}

TEST(PhysicsRigidBody, ModelMatrixPointVelocityAndFreeImpulse) {
  RigidBody body;
  body.p = glm::vec3(0.1f, -0.2f, 0.3f);
  body.q = glm::angleAxis(0.7f, glm::vec3(0.0f, 0.0f, 1.0f));
  body.mass = 2.0f;
  body.inertia_local = glm::vec3(0.1f, 0.2f, 0.3f);
  const glm::mat4 m = body.model_matrix();
  const glm::vec3 local(0.5f, 0.0f, 0.0f);
  expect_vec_near(glm::vec3(m * glm::vec4(local, 1.0f)),
                  body.p + glm::vec3(0.5f * std::cos(0.7f), 0.5f * std::sin(0.7f), 0.0f), 1e-6f,
                  "model");
  body.w = glm::vec3(0.0f, 0.0f, 2.0f);
  // Spinning about z at 2 rad/s: a point 0.5 along +x of p moves along +y at 1 m/s.
  expect_vec_near(body.point_velocity(body.p + glm::vec3(0.5f, 0.0f, 0.0f)),
                  glm::vec3(0.0f, 1.0f, 0.0f), 1e-6f, "point velocity");

  // Impulse: linear momentum changes by j, angular momentum about p by r x j.
  const RigidBody before = body;
  const glm::vec3 j(0.3f, -0.1f, 0.2f), at = body.p + glm::vec3(0.1f, 0.4f, -0.2f);
  body.apply_impulse(j, at);
  expect_vec_near(body.mass * (body.v - before.v), j, 1e-6f, "linear momentum");
  expect_vec_near(body.inertia_world() * (body.w - before.w), glm::cross(at - body.p, j), 1e-5f,
                  "angular momentum");
}

TEST(PhysicsRigidBody, CrossMatrixIsTheCrossProduct) {
  const glm::vec3 a(0.3f, -1.2f, 2.0f), b(-0.7f, 0.4f, 1.1f);
  expect_vec_near(rp::scene::cross_matrix(a) * b, glm::cross(a, b), 1e-6f, "cross");
}

// The rolling response: angular momentum about the floor contact changes by (h - c) x j, and the
// linear velocity is the rolling one, v = b (w x y) (v_x = -b w_z, v_z = b w_x).
TEST(PhysicsTumbler, RollingImpulseResponse) {
  const TumblerPhysics physics;
  RigidBody body = physics.make_body({glm::vec2(0.1f, -0.2f), 0.4f});
  body.q = glm::angleAxis(0.3f, glm::normalize(glm::vec3(1.0f, 0.0f, 0.5f))) * body.q;
  const glm::vec3 c = physics.floor_contact(body);
  EXPECT_FLOAT_EQ(c.y, -1.0f);
  const glm::vec3 h = body.p + glm::vec3(0.05f, 0.3f, 0.12f), j(-0.02f, 0.01f, 0.03f);
  const RigidBody before = body;
  physics.apply_impulse(body, j, h);
  const glm::vec3 dw = body.w - before.w;
  expect_vec_near(physics.contact_inertia(before) * dw, glm::cross(h - c, j), 1e-6f, "I_c dw");
  EXPECT_FLOAT_EQ(body.v.x, -physics.shape().b * body.w.z);
  EXPECT_FLOAT_EQ(body.v.z, physics.shape().b * body.w.x);
  EXPECT_EQ(body.v.y, 0.0f);
  EXPECT_FLOAT_EQ(body.p.y, -1.0f + physics.shape().b);
  // K predicts the change of the point velocity at h.
  expect_vec_near(physics.impulse_response(before, h) * j,
                  body.point_velocity(h) - before.point_velocity(h), 1e-6f, "K j");
  // A push through the centre of mass still moves a rolling tumbler (about the contact it has a
  // lever arm b), in the pushed direction.
  RigidBody pushed = physics.make_body({glm::vec2(0.0f), 0.0f});
  physics.apply_impulse(pushed, glm::vec3(0.01f, 0.0f, 0.0f), pushed.p);
  EXPECT_GT(pushed.v.x, 0.0f);
  // m v = j m b^2 / (I_xx + m b^2): the floor's friction takes the rest.
  const float m = physics.params().mass, b = physics.shape().b;
  const float ixx = static_cast<float>(physics.inertia().moments.x);
  EXPECT_NEAR(m * pushed.v.x, 0.01f * m * b * b / (ixx + m * b * b), 1e-7f);
}

TEST(PhysicsTumbler, RestoringTurnsTowardsUprightAndFrictionStops) {
  const TumblerPhysics physics;
  RigidBody body = physics.make_body({glm::vec2(0.0f), 0.0f});
  body.q = glm::angleAxis(0.5f, glm::vec3(0.0f, 0.0f, 1.0f));  // top leans towards -x
  const float tilt0 = physics.tilt(body);
  physics.apply_restoring(body, 1.0f / 240.0f);
  EXPECT_LT(body.w.z, 0.0f);  // turning back about -z
  physics.integrate(body, 1.0f / 240.0f);
  EXPECT_LT(physics.tilt(body), tilt0);
  // Friction: |w| drops by mu g dt / b, and to exactly zero below that.
  RigidBody spin = physics.make_body({glm::vec2(0.0f), 0.0f});
  spin.w = glm::vec3(1.0f, 0.0f, 0.0f);
  const float dt = 1.0f / 240.0f;
  const float drop = physics.params().friction * physics.params().gravity * dt / physics.shape().b;
  physics.apply_friction(spin, dt);
  EXPECT_NEAR(spin.w.x, 1.0f - drop, 1e-6f);
  spin.w = glm::vec3(0.5f * drop, 0.0f, 0.0f);
  physics.apply_friction(spin, dt);
  EXPECT_EQ(spin.w, glm::vec3(0.0f));
  EXPECT_EQ(spin.v, glm::vec3(0.0f));
}

TEST(PhysicsTumbler, MaxTiltIsWhereTheTopSphereTouchesTheFloor) {
  const TumblerPhysics physics;
  const TumblerShape& s = physics.shape();
  RigidBody body = physics.make_body({glm::vec2(0.0f), 0.0f});
  body.q = glm::angleAxis(physics.max_tilt(), glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_NEAR(physics.top_center(body).y - s.t, -1.0f, 1e-5f);
  EXPECT_NEAR(glm::degrees(physics.max_tilt()), 110.0f, 1e-3f);  // 90 + alpha
}

}  // namespace
