// The Cornell box (SPEC.md section 1) and the ceiling lamp, as meshes in world space (their
// instances use the identity model matrix).
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "scene/frame_scene.h"

namespace rp::scene {

// Linear (not sRGB) diffuse albedos of the walls, and the lamp's emitted radiance.
namespace box_colors {
inline constexpr glm::vec3 kWhite{0.75f, 0.75f, 0.72f};   // ceiling and back wall, slightly warm
inline constexpr glm::vec3 kOrange{0.80f, 0.35f, 0.05f};  // left wall (x = -1)
inline constexpr glm::vec3 kSkyBlue{0.15f, 0.45f, 0.80f}; // right wall (x = +1)
inline constexpr glm::vec3 kFloorTint{1.0f, 1.0f, 1.0f};  // floor: multiplies the wood texture
inline constexpr glm::vec3 kLampEmission{12.0f, 11.0f, 9.0f};  // warm white radiance
}  // namespace box_colors

// Material index (into SceneAssets::materials) for each face of the box.
struct BoxMaterialIds {
  uint32_t floor = 0, ceiling = 0, back = 0, left = 0, right = 0;
};

// The box [-1,1]^3 without its front face (z = +1, towards the camera): floor, ceiling, back,
// left and right walls, each a grid of quads_per_side x quads_per_side quads (two triangles
// each) so no triangle gets huge on screen. Normals point into the box; triangles are
// counter-clockwise seen from inside. Each wall has its own vertices (flat normals).
// UVs: floor u = (x + 1) / 2, v = (1 - z) / 2 (v = 1 at the back wall), so the wood texture
// covers the floor once, upright as seen from the camera; other walls use their grid coordinates.
//
// opening: a skylight, the rectangle [min.x, max.x] x [min.y, max.y] of the ceiling in world x
// and z; the ceiling quads whose centres lie inside it are left out (none by default: min > max).
struct CeilingOpening {
  glm::vec2 min{1.0f}, max{-1.0f};
};
Mesh make_cornell_box(const BoxMaterialIds& materials, int quads_per_side = 8,
                      const CeilingOpening& opening = {});

// The visible part of the lamp: an icosphere (icosahedron subdivided `subdivisions` times, each
// step splitting a triangle into four) of radius light.lamp_radius around light.position, cut at
// the ceiling plane y = ceiling_y and keeping the part below it. Triangles crossing the plane
// are clipped; the new vertices lie exactly on the circle where the sphere meets the plane, so
// the cap is on the sphere everywhere and meets the ceiling without a gap. Normals point away
// from the lamp centre (into the box), counter-clockwise seen from outside the sphere.
Mesh make_lamp_cap(const PointLight& light, uint32_t material, int subdivisions = 3,
                   float ceiling_y = 1.0f);

}  // namespace rp::scene
