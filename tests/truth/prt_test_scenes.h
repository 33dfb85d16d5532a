// Small scenes of the PRT tests (prt_transfer_test.cpp, prt_cache_test.cpp): gridded quads, an
// open-topped box, a UV sphere; every one a single mesh drawn by one identity instance unless a
// test adds more.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "scene/frame_scene.h"

namespace rp::truth::prt_test {

// Appends an n x n grid over the parallelogram o + s u + t v (s, t in [0, 1]), facing
// cross(u, v), with material `material`.
inline void add_grid(scene::Mesh& m, glm::vec3 o, glm::vec3 u, glm::vec3 v, uint32_t n,
                     uint32_t material = 0) {
  const glm::vec3 normal = glm::normalize(glm::cross(u, v));
  const uint32_t base = uint32_t(m.vertices.size());
  for (uint32_t j = 0; j <= n; ++j)
    for (uint32_t i = 0; i <= n; ++i) {
      const float s = float(i) / float(n), t = float(j) / float(n);
      m.vertices.push_back({o + s * u + t * v, normal, glm::vec2(s, t)});
    }
  for (uint32_t j = 0; j < n; ++j)
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t a = base + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.triangles.push_back({a, b, d});
      m.triangles.push_back({a, d, c});
      m.materials.insert(m.materials.end(), {material, material});
    }
}

// Assets of one mesh (built by `fill`) and one material of `albedo`; the frame draws it once.
template <class Fill>
scene::SceneAssets one_mesh_assets(glm::vec3 albedo, Fill fill) {
  scene::SceneAssets assets;
  scene::Material mat;
  mat.name = "white";
  mat.albedo = albedo;
  assets.materials.push_back(mat);
  scene::Mesh m;
  m.name = "prt_test";
  fill(m);
  assets.meshes.push_back(std::move(m));
  return assets;
}

inline scene::FrameScene one_instance_frame() {
  scene::FrameScene frame;
  frame.instances.push_back(scene::MeshInstance{});
  return frame;
}

// A square floor [-1, 1]^2 at y = 0 facing +y, n x n cells.
inline void floor_grid(scene::Mesh& m, uint32_t n = 4) {
  add_grid(m, {-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, n);
}

// The box [-1, 1] x [0, 2] x [-1, 1] without its top: floor and four walls facing inwards.
inline void open_box(scene::Mesh& m, uint32_t n = 6) {
  add_grid(m, {-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, n);   // floor, +y
  add_grid(m, {-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, n);   // back, +z
  add_grid(m, {1, 0, 1}, {-2, 0, 0}, {0, 2, 0}, n);    // front, -z
  add_grid(m, {-1, 0, 1}, {0, 0, -2}, {0, 2, 0}, n);   // left, +x
  add_grid(m, {1, 0, -1}, {0, 0, 2}, {0, 2, 0}, n);    // right, -x
}

// A UV sphere of radius r about the origin, vertex normals radial (outwards).
inline void uv_sphere(scene::Mesh& m, float r = 0.5f, uint32_t rings = 12,
                      uint32_t segments = 24) {
  const float pi = 3.14159265358979f;
  for (uint32_t j = 0; j <= rings; ++j)
    for (uint32_t i = 0; i <= segments; ++i) {
      const float theta = pi * float(j) / float(rings);
      const float phi = 2.0f * pi * float(i) / float(segments);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                        -std::sin(theta) * std::sin(phi));
      m.vertices.push_back({r * n, n, glm::vec2(0.0f)});
    }
  for (uint32_t j = 0; j < rings; ++j)
    for (uint32_t i = 0; i < segments; ++i) {
      const uint32_t a = j * (segments + 1) + i, b = a + 1, c = a + segments + 1, d = c + 1;
      if (j > 0) m.triangles.push_back({a, c, b});
      if (j + 1 < rings) m.triangles.push_back({b, c, d});
    }
  m.materials.assign(m.triangles.size(), 0u);
}

}  // namespace rp::truth::prt_test
