// Tumbler dynamics (SPEC.md sections 2 and 3): the inertia tensor from the profile integrals,
// the rolling constraint, the restoring impulse and the floor friction.
//
// Model. The centre of mass is the bottom sphere centre p (SPEC assumption), kept at
// p_y = floor + b; the tumbler rolls on the floor without slipping, v = b (w x y_hat), i.e.
// v_x = -b w_z, v_z = b w_x (SPEC). An impulse j at a point h is answered the way a rolling body
// answers it: the floor's normal and friction impulses act at the contact point c = p - b y_hat,
// so they exert no torque about c, and the angular momentum about c changes by (h - c) x j:
//     I_c dw = (h - c) x j,   I_c = I_world + m b^2 (E - y_hat y_hat^T)  (parallel axes),
//     dv = b (dw x y_hat)     (the rolling constraint).
// This differs from SPEC's w' = w + I^-1 ((h - p) x j) in where the torque is taken: about p, a
// push through the centre of mass (two tumblers touching bottom sphere to bottom sphere, a
// marble hitting the bottom sphere) produced no rotation and hence, with v slaved to w, no
// motion at all. Lift-off is ignored (SPEC: never airborne).
#pragma once

#include <glm/glm.hpp>

#include "scene/demo_scene.h"
#include "scene/rigid_body.h"
#include "scene/tumbler_shape.h"

namespace rp::scene {

// Volume and principal moments of the solid tumbler about the bottom sphere centre (the
// origin of its local space), from the integrals of SPEC 2 (composite Simpson, in double):
//   V = pi int R^2 dy,  rho = m / V,
//   Ixx = Izz = rho pi/4 int (R^4 + 4 y^2 R^2) dy,  Iyy = rho pi/2 int R^4 dy,  y in [-b, y_t + t].
struct TumblerInertia {
  double volume = 0.0;     // m^3
  double density = 0.0;    // kg/m^3
  glm::dvec3 moments{0.0}; // (Ixx, Iyy, Izz), kg m^2
};
// `intervals` Simpson intervals on each of the profile's three smooth pieces (even, >= 2).
TumblerInertia compute_tumbler_inertia(const TumblerShape& shape, double mass,
                                       int intervals = 256);

struct TumblerParams {
  // 0.25 kg: with SPEC's restoring impulse below, the rocking frequency about the floor contact
  // is sqrt(k (arm + b) / I_c) = 8.5 rad/s (period 0.74 s), a toy-like rock that the eye can
  // follow at 60 Hz; marbles (5 g) and the fireball (20 g) nudge it by a few degrees.
  float mass = 0.25f;
  // SPEC's restoring impulse: j = -k dt d at p + (0, arm, 0), d the tumbler's axis. k = 1 N and
  // arm = 1 m are SPEC's numbers; the torque about the floor contact is k (arm + b) sin(tilt).
  float restoring_force = 1.0f;  // k, N
  float restoring_arm = 1.0f;    // m
  // Floor friction mu (SPEC: |w| -= mu g dt / b per step). Coulomb friction takes a fixed
  // amount of swing each half rock and stops the tumbler dead once the restoring torque cannot
  // beat it, at a tilt below mu g I_c / (b k (arm + b)) = 1.6 degrees for mu = 0.04. Released
  // at 45 degrees it rocks ~13 times and is at rest after ~5.3 s (0.03: 6.8 s, 0.06: 3.4 s but
  // up to 2.4 degrees off upright).
  float friction = 0.04f;
  float gravity = 9.81f;         // m/s^2
  float floor_y = -1.0f;         // the box floor
};

// Shape, parameters and the precomputed inertia; stateless operations on a tumbler's RigidBody.
class TumblerPhysics {
 public:
  explicit TumblerPhysics(const TumblerShape& shape = {}, const TumblerParams& params = {});

  const TumblerShape& shape() const { return shape_; }
  const TumblerParams& params() const { return params_; }
  const TumblerInertia& inertia() const { return inertia_; }

  // An upright tumbler at rest at `placement` (same transform as upright_tumbler_model()).
  RigidBody make_body(const TumblerPlacement& placement) const;

  glm::vec3 axis(const RigidBody& body) const;          // d = R y_hat
  glm::vec3 top_center(const RigidBody& body) const;    // p + y_t d
  glm::vec3 floor_contact(const RigidBody& body) const; // c = p - b y_hat
  float tilt(const RigidBody& body) const;              // angle between d and +y, radians
  // Largest tilt before the top sphere touches the floor: cos = (t - b) / y_t (110 degrees).
  float max_tilt() const;

  // World-space SDF of the tumbler's surface and its gradient (outward unit normal).
  float sdf(const RigidBody& body, const glm::vec3& x) const;
  glm::vec3 sdf_gradient(const RigidBody& body, const glm::vec3& x) const;

  // I_c, the inertia about the floor contact point (world axes).
  glm::mat3 contact_inertia(const RigidBody& body) const;
  // K with dv(at) = K j for an impulse j at `at`: K = -[r]x I_c^-1 [r]x, r = at - c.
  glm::mat3 impulse_response(const RigidBody& body, const glm::vec3& at) const;
  // The rolling response above: I_c dw = (at - c) x j, then v from the rolling constraint.
  void apply_impulse(RigidBody& body, const glm::vec3& j, const glm::vec3& at) const;

  // SPEC's restoring impulse for one step of dt.
  void apply_restoring(RigidBody& body, float dt) const;
  // SPEC's friction for one step: |w| -= mu g dt / b (clamped at 0), then v from rolling
  // (so |v| drops by at most mu g dt, SPEC's linear rule).
  void apply_friction(RigidBody& body, float dt) const;
  // p_y = floor + b and v = b (w x y_hat).
  void enforce_rolling(RigidBody& body) const;
  // enforce_rolling, then p += v dt and the quaternion step.
  void integrate(RigidBody& body, float dt) const;

 private:
  TumblerShape shape_;
  TumblerParams params_;
  TumblerInertia inertia_;
};

}  // namespace rp::scene
