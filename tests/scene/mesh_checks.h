// Topology and geometry checks shared by the scene mesh tests.
#pragma once

#include <array>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "scene/frame_scene.h"

namespace rp::scene::testing {

// Directed edges counted after welding vertices with bit-identical positions (seam and pole
// duplicates become one point, as a rasterizer sees them).
struct EdgeCounts {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  size_t welded_vertices = 0;
};

inline EdgeCounts count_welded_edges(const Mesh& mesh) {
  std::map<std::tuple<float, float, float>, uint32_t> ids;
  std::vector<uint32_t> weld(mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const glm::vec3 p = mesh.vertices[i].position;
    weld[i] = ids.emplace(std::make_tuple(p.x, p.y, p.z), static_cast<uint32_t>(ids.size()))
                  .first->second;
  }
  EdgeCounts counts;
  counts.welded_vertices = ids.size();
  for (const glm::uvec3& t : mesh.triangles) {
    const std::array<uint32_t, 3> v = {weld[t.x], weld[t.y], weld[t.z]};
    for (int k = 0; k < 3; ++k) counts.directed[{v[k], v[(k + 1) % 3]}]++;
  }
  return counts;
}

// Geometric normal of a triangle (not normalised): counter-clockwise seen from its tip.
inline glm::vec3 face_normal(const Mesh& mesh, const glm::uvec3& t) {
  const glm::vec3 a = mesh.vertices[t.x].position, b = mesh.vertices[t.y].position,
                  c = mesh.vertices[t.z].position;
  return glm::cross(b - a, c - a);
}

inline float triangle_area(const Mesh& mesh, const glm::uvec3& t) {
  return 0.5f * glm::length(face_normal(mesh, t));
}

}  // namespace rp::scene::testing
