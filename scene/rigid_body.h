// Rigid-body state and the free-body operations of SPEC.md section 3: integration with a unit
// quaternion, point velocity, impulse response, model matrix. Units: metres, seconds, kilograms
// (the box spans [-1,1]^3 m). The tumbler's rolling constraint lives in tumbler_physics.h; the
// spheres' exact ballistic step in collisions.h.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace rp::scene {

struct RigidBody {
  glm::vec3 p{0.0f};                         // centre of mass, world space (m)
  glm::vec3 v{0.0f};                         // linear velocity (m/s)
  glm::vec3 w{0.0f};                         // angular velocity, world space (rad/s)
  glm::quat q{1.0f, 0.0f, 0.0f, 0.0f};       // orientation, body -> world (w, x, y, z)
  float mass = 1.0f;                         // kg
  glm::vec3 inertia_local{1.0f};             // principal moments about p, body axes (kg m^2)

  glm::mat3 rotation() const { return glm::mat3_cast(q); }
  // M = [R p; 0 1] (SPEC 3): body -> world.
  glm::mat4 model_matrix() const;
  // v_i = v + w x (x - p) for a world point x rigidly attached to the body.
  glm::vec3 point_velocity(const glm::vec3& x) const { return v + glm::cross(w, x - p); }
  // I_world^-1 = R I_local^-1 R^T.
  glm::mat3 inverse_inertia_world() const;
  glm::mat3 inertia_world() const;

  // Free body (SPEC 3): v += j / m, w += I_world^-1 ((at - p) x j).
  void apply_impulse(const glm::vec3& j, const glm::vec3& at);

  // p += v dt; q += dt/2 (0, w) q, renormalised. (0, w) with the world-frame w multiplies on the
  // left; it equals SPEC's q_w = (0, R^-1 w) multiplied on the right of q.
  void integrate(float dt);
  // Only the orientation part of integrate().
  void integrate_orientation(float dt);
};

// A marble or fireball (SPEC 3 sphere assumptions): the centre's mechanical energy per unit
// mass, |v|^2 / 2 + gravity * p_y, is an invariant of the motion; fireballs have gravity 0.
struct SphereBody {
  RigidBody body;          // p = centre; w only follows rolling on walls (for completeness)
  float radius = 0.05f;    // m
  float gravity = 0.0f;    // downward acceleration, m/s^2
  float energy = 0.0f;     // invariant, J/kg (set by reset_energy())

  float mechanical_energy() const {
    return 0.5f * glm::dot(body.v, body.v) + gravity * body.p.y;
  }
  void reset_energy() { energy = mechanical_energy(); }
  // Exact ballistic step under constant gravity: p += v dt - g dt^2/2 y, v -= g dt y. It keeps
  // the mechanical energy exactly (up to rounding), unlike SPEC's p += v dt (symplectic Euler
  // drifts by ~g dt |v_y| / 2 per unit mass, 0.6 % of a 2 m drop at 240 Hz).
  void step_ballistic(float dt);
  // After a collision moved the centre (changing its height), rescale the speed so the
  // mechanical energy is `energy` again. If the centre was pushed above the height its energy
  // allows, the invariant takes the new, higher value instead.
  void restore_energy();
};

// [a]x, the matrix with [a]x b = a x b.
glm::mat3 cross_matrix(const glm::vec3& a);

}  // namespace rp::scene
