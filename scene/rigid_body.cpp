#include "scene/rigid_body.h"

#include <cmath>

namespace rp::scene {

glm::mat4 RigidBody::model_matrix() const {
  glm::mat4 m(rotation());
  m[3] = glm::vec4(p, 1.0f);
  return m;
}

glm::mat3 RigidBody::inverse_inertia_world() const {
  const glm::mat3 r = rotation();
  const glm::mat3 inv_local(glm::vec3(1.0f / inertia_local.x, 0.0f, 0.0f),
                            glm::vec3(0.0f, 1.0f / inertia_local.y, 0.0f),
                            glm::vec3(0.0f, 0.0f, 1.0f / inertia_local.z));
  return r * inv_local * glm::transpose(r);
}

glm::mat3 RigidBody::inertia_world() const {
  const glm::mat3 r = rotation();
  const glm::mat3 local(glm::vec3(inertia_local.x, 0.0f, 0.0f),
                        glm::vec3(0.0f, inertia_local.y, 0.0f),
                        glm::vec3(0.0f, 0.0f, inertia_local.z));
  return r * local * glm::transpose(r);
}

void RigidBody::apply_impulse(const glm::vec3& j, const glm::vec3& at) {
  v += j / mass;
  w += inverse_inertia_world() * glm::cross(at - p, j);
}

void RigidBody::integrate_orientation(float dt) {
  // dq/dt = 1/2 (0, w) q  (w in world space). Explicit Euler on the quaternion, then
  // renormalise: second-order error per step, and the norm never drifts.
  const glm::quat omega(0.0f, w.x, w.y, w.z);
  const glm::quat dq = omega * q;
  q = glm::normalize(glm::quat(q.w + 0.5f * dt * dq.w, q.x + 0.5f * dt * dq.x,
                               q.y + 0.5f * dt * dq.y, q.z + 0.5f * dt * dq.z));
}

void RigidBody::integrate(float dt) {
  p += v * dt;
  integrate_orientation(dt);
}

void SphereBody::step_ballistic(float dt) {
  body.p += body.v * dt;
  body.p.y -= 0.5f * gravity * dt * dt;
  body.v.y -= gravity * dt;
  body.integrate_orientation(dt);
}

void SphereBody::restore_energy() {
  const float speed2 = glm::dot(body.v, body.v);
  const float target2 = 2.0f * (energy - gravity * body.p.y);
  if (target2 > 0.0f && speed2 > 1e-12f) {
    body.v *= std::sqrt(target2 / speed2);
  } else {
    reset_energy();
  }
}

glm::mat3 cross_matrix(const glm::vec3& a) {
  // Column-major: columns are [a]x e_x, [a]x e_y, [a]x e_z.
  return glm::mat3(glm::vec3(0.0f, a.z, -a.y), glm::vec3(-a.z, 0.0f, a.x),
                   glm::vec3(a.y, -a.x, 0.0f));
}

}  // namespace rp::scene
