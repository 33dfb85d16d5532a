// Collision detection and response (SPEC.md section 3): spheres (marbles, fireballs) against
// the box walls, the ceiling lamp and the tumblers; tumblers against the walls, the floor and
// each other; spheres against spheres. Every function resolves one pair in place: it pushes the
// bodies apart and changes velocities. Spheres keep their speed in every sphere response (pure
// reflections); callers restore the height-dependent energy with SphereBody::restore_energy().
#pragma once

#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/frame_scene.h"
#include "scene/rigid_body.h"
#include "scene/tumbler_physics.h"

namespace rp::scene {

// The static world: the box [-h, h]^3 (the open front face is a wall too, invisible) and the
// lamp, the part below the ceiling of a sphere around the point light.
struct Arena {
  float half_extent = 1.0f;
  glm::vec3 lamp_center{0.0f, 1.1f, 0.0f};
  float lamp_radius = 0.35f;
  static Arena from_light(const PointLight& light) {
    return Arena{1.0f, light.position, light.lamp_radius};
  }
};

// Where two bodies touched: the contact point and the unit normal pointing from the obstacle
// towards the body that was tested (for a wall: into the box).
struct Contact {
  glm::vec3 point{0.0f};
  glm::vec3 normal{0.0f};
  // Speed along the normal with which the body hit (m/s); 0 for a mere push-out of a body that
  // was already leaving (e.g. squeezed by a moving tumbler). Fireballs spark only on impacts.
  float impact_speed = 0.0f;
};

// Sphere vs the six box walls: clamp the centre inside, reflect the velocity component that
// points into a wall (no damping) and set w to rolling on that wall. Appends one contact per
// wall touched to `contacts` (if not null). Returns true if the centre moved.
bool collide_sphere_walls(SphereBody& sphere, const Arena& arena, std::vector<Contact>* contacts);

// Sphere vs the lamp cap (sphere of lamp_radius around lamp_center, the part with y below the
// ceiling; its rim circle included): push out along the cap's normal, reflect the velocity.
bool collide_sphere_lamp(SphereBody& sphere, const Arena& arena, std::vector<Contact>* contacts);

// Sphere vs tumbler through the world SDF (SPEC 3): d = SDF(c) < r collides; n = grad SDF(c);
// h = c - d n; push the sphere to distance r along n; if it moves into the tumbler (v.n < 0),
// reflect v along n and apply j = -m dv at h to the tumbler (unless `kinematic`: a tumbler held
// by the mouse is not moved by impacts).
struct SphereTumblerHit {
  Contact contact;                  // normal points from the tumbler to the sphere
  glm::vec3 impulse_on_tumbler{0.0f};  // j = -m_sphere dv_sphere (0 without reflection)
};
std::optional<SphereTumblerHit> collide_sphere_tumbler(SphereBody& sphere, RigidBody& tumbler,
                                                       const TumblerPhysics& physics,
                                                       bool kinematic);

// Overlap test for two spheres.
bool spheres_touch(const SphereBody& a, const SphereBody& b);
// Elastic collision of two spheres: push apart along the centre line (mass weighted), exchange
// momentum along it if approaching (kinetic energy and momentum kept), then reset both spheres'
// energy invariants (their sum is unchanged when both feel the same gravity and the push is
// mass-symmetric). Returns the contact (normal from a to b) if they touched.
std::optional<Contact> collide_spheres(SphereBody& a, SphereBody& b);

// Tumbler vs floor and walls: if the top sphere reaches below the floor, turn the tumbler back
// to the largest tilt that keeps it above the floor and zero v and w (it fell over; the
// restoring impulse rights it slowly). Then test both spheres against the four side walls: push
// p out along the wall normal and, at the deepest contact of each wall, apply the normal
// impulse that reverses the contact point's wall-normal velocity times `restitution` (SPEC's
// "reverse the wall-normal components of linear and angular velocity, optionally damped",
// expressed through the rolling response so v and w stay consistent). Returns true if the
// tumbler was moved or turned.
bool collide_tumbler_walls(RigidBody& tumbler, const TumblerPhysics& physics, const Arena& arena,
                           float restitution, bool kinematic);

// Tumbler vs tumbler by the averaged-contact method (SPEC 3): each tumbler's two spheres are
// tested against the other's SDF (four sphere-vs-tumbler tests); the contact point h is the
// mean of the surface points found, n = normalize(n_a - n_b) from the two SDF gradients at h,
// both taken as pointing from a to b (SPEC's n1 + n2 with n2 = -grad SDF_b). If the point
// velocities approach along n, one normal impulse lambda n (on b; -lambda n on a) with
//     lambda = (1 + e) dv_n / (n^T (K_a + K_b) n)
// makes the relative normal velocity -e dv_n, K the rolling impulse-response matrices
// (tumbler_physics.h). This keeps momentum (equal and opposite impulses), unlike solving
// each body's K^-1 separately, and works with the rolling K (which is singular along r).
// A kinematic (mouse-held) tumbler has K = 0. Both are pushed apart horizontally by the
// deepest overlap (the held one stays put).
struct TumblerPairHit {
  Contact contact;     // point h, normal from a to b
  float depth = 0.0f;  // deepest overlap of the four sphere tests, m
  float impulse = 0.0f;  // lambda, N s (0 when separating)
};
std::optional<TumblerPairHit> collide_tumblers(RigidBody& a, bool a_kinematic, RigidBody& b,
                                               bool b_kinematic, const TumblerPhysics& physics,
                                               float restitution);

}  // namespace rp::scene
