// Axis-aligned boxes as triangle meshes, for the generated test and bench scenes
// (tools/gen_load_scene, tests/app/bench_test_scene.cpp).
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "scene/frame_scene.h"

namespace rp::scene {

// Appends to `m` the box around `center` with half sides `half`: 12 triangles (one quad a face) of material
// `material`, counter-clockwise seen from outside, flat outward normals, texture coordinates
// 0..uv_repeat across each face and a tangent frame per vertex (tangent along the face's u,
// handedness so that w * cross(n, t) follows +v: what a normal map needs). max_cell > 0
// splits each face into a grid of quads no longer than max_cell along either side (per-vertex
// data such as precomputed radiance transfer then has vertices to live on); 0: one quad.
void append_box(Mesh& m, glm::vec3 center, glm::vec3 half, uint32_t material,
                float uv_repeat = 1.0f, float max_cell = 0.0f);

}  // namespace rp::scene
