#include "scene/cornell_box.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

namespace rp::scene {

namespace {

// Appends a planar grid of n x n quads spanning origin + s * edge_u + t * edge_v, s,t in [0,1].
// cross(edge_u, edge_v) must point along `normal`: then (p00, p10, p11) is counter-clockwise
// seen from the side the normal points to.
// Quads whose centre `keep` rejects are left out (their vertices stay, unused).
template <class Keep>
void add_wall(Mesh& mesh, glm::vec3 origin, glm::vec3 edge_u, glm::vec3 edge_v, glm::vec3 normal,
              uint32_t material, int n, Keep keep) {
  const uint32_t base = static_cast<uint32_t>(mesh.vertices.size());
  const float inv_n = 1.0f / static_cast<float>(n);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const float s = static_cast<float>(i) * inv_n, t = static_cast<float>(j) * inv_n;
      mesh.vertices.push_back({origin + s * edge_u + t * edge_v, normal, glm::vec2(s, t)});
    }
  }
  const uint32_t row = static_cast<uint32_t>(n) + 1;
  for (uint32_t j = 0; j < static_cast<uint32_t>(n); ++j) {
    for (uint32_t i = 0; i < static_cast<uint32_t>(n); ++i) {
      const uint32_t p00 = base + j * row + i, p10 = p00 + 1, p01 = p00 + row, p11 = p01 + 1;
      const float s = (static_cast<float>(i) + 0.5f) * inv_n;
      const float t = (static_cast<float>(j) + 0.5f) * inv_n;
      if (!keep(origin + s * edge_u + t * edge_v)) continue;
      mesh.triangles.push_back({p00, p10, p11});
      mesh.triangles.push_back({p00, p11, p01});
      mesh.materials.push_back(material);
      mesh.materials.push_back(material);
    }
  }
}

// Unit icosphere: vertices on the unit sphere, faces counter-clockwise seen from outside.
struct UnitSphereMesh {
  std::vector<glm::vec3> points;
  std::vector<glm::uvec3> faces;
};

UnitSphereMesh make_unit_icosphere(int subdivisions) {
  const float g = (1.0f + std::sqrt(5.0f)) / 2.0f;  // golden ratio
  UnitSphereMesh m;
  const std::array<glm::vec3, 12> corners = {{{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                                              {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                                              {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}}};
  for (const glm::vec3& c : corners) m.points.push_back(glm::normalize(c));
  m.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9},  {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6},  {3, 6, 8},
             {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  // Make the outward orientation a property of the code, not of the table above.
  for (glm::uvec3& f : m.faces) {
    const glm::vec3 a = m.points[f.x], b = m.points[f.y], c = m.points[f.z];
    if (glm::dot(glm::cross(b - a, c - a), a + b + c) < 0.0f) std::swap(f.y, f.z);
  }
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;  // edge (lo, hi) -> vertex
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoints.find(key);
      if (it != midpoints.end()) return it->second;
      const uint32_t index = static_cast<uint32_t>(m.points.size());
      m.points.push_back(glm::normalize(m.points[key.first] + m.points[key.second]));
      midpoints.emplace(key, index);
      return index;
    };
    std::vector<glm::uvec3> finer;
    finer.reserve(m.faces.size() * 4);
    for (const glm::uvec3& f : m.faces) {
      const uint32_t ab = midpoint(f.x, f.y), bc = midpoint(f.y, f.z), ca = midpoint(f.z, f.x);
      finer.push_back({f.x, ab, ca});
      finer.push_back({ab, f.y, bc});
      finer.push_back({ca, bc, f.z});
      finer.push_back({ab, bc, ca});
    }
    m.faces = std::move(finer);
  }
  return m;
}

}  // namespace

Mesh make_cornell_box(const BoxMaterialIds& materials, int quads_per_side,
                      const CeilingOpening& opening) {
  if (quads_per_side < 1) throw std::invalid_argument("make_cornell_box: quads_per_side < 1");
  Mesh mesh;
  mesh.name = "cornell_box";
  const int n = quads_per_side;
  const auto all = [](glm::vec3) { return true; };
  const auto outside_opening = [&opening](glm::vec3 c) {
    return !(c.x >= opening.min.x && c.x <= opening.max.x && c.z >= opening.min.y &&
             c.z <= opening.max.y);
  };
  // Floor first so its grid (s, t) is the wood UV: s = (x + 1) / 2, t = (1 - z) / 2.
  add_wall(mesh, {-1, -1, 1}, {2, 0, 0}, {0, 0, -2}, {0, 1, 0}, materials.floor, n, all);
  add_wall(mesh, {-1, 1, -1}, {2, 0, 0}, {0, 0, 2}, {0, -1, 0}, materials.ceiling, n,
           outside_opening);
  add_wall(mesh, {-1, -1, -1}, {2, 0, 0}, {0, 2, 0}, {0, 0, 1}, materials.back, n, all);
  add_wall(mesh, {-1, -1, 1}, {0, 0, -2}, {0, 2, 0}, {1, 0, 0}, materials.left, n, all);
  add_wall(mesh, {1, -1, -1}, {0, 0, 2}, {0, 2, 0}, {-1, 0, 0}, materials.right, n, all);
  return mesh;
}

Mesh make_lamp_cap(const PointLight& light, uint32_t material, int subdivisions, float ceiling_y) {
  if (subdivisions < 0 || subdivisions > 6) {
    throw std::invalid_argument("make_lamp_cap: subdivisions must be in [0, 6]");
  }
  const glm::vec3 centre = light.position;
  const float radius = light.lamp_radius;
  const float cut = ceiling_y - centre.y;  // plane height relative to the centre
  if (cut <= -radius) throw std::invalid_argument("make_lamp_cap: the lamp lies above the ceiling");
  // Radius of the circle where the sphere meets the plane (0 if the plane misses the sphere).
  const float rim_radius = std::sqrt(std::max(0.0f, radius * radius - cut * cut));

  const UnitSphereMesh sphere = make_unit_icosphere(subdivisions);
  Mesh mesh;
  mesh.name = "lamp_cap";
  auto add_vertex = [&](glm::vec3 p) {
    mesh.vertices.push_back({p, glm::normalize(p - centre), glm::vec2(0.0f)});
    return static_cast<uint32_t>(mesh.vertices.size() - 1);
  };

  // Sphere vertices below the plane keep their position; the others get no mesh vertex.
  constexpr uint32_t kOutside = 0xFFFFFFFFu;
  std::vector<uint32_t> kept(sphere.points.size(), kOutside);
  for (size_t i = 0; i < sphere.points.size(); ++i) {
    const glm::vec3 p = centre + radius * sphere.points[i];
    if (p.y <= ceiling_y) kept[i] = add_vertex(p);
  }
  // One rim vertex per crossing edge, shared by the two triangles on that edge: the chord's
  // crossing point pushed radially onto the rim circle (exactly y = ceiling_y, on the sphere).
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> rim;
  auto rim_vertex = [&](uint32_t a, uint32_t b) {
    const auto key = std::minmax(a, b);
    const auto it = rim.find(key);
    if (it != rim.end()) return it->second;
    const glm::vec3 pa = radius * sphere.points[key.first], pb = radius * sphere.points[key.second];
    const float f = (cut - pa.y) / (pb.y - pa.y);
    const glm::vec3 q = pa + f * (pb - pa);
    const glm::vec2 dir = glm::normalize(glm::vec2(q.x, q.z));
    const uint32_t index =
        add_vertex(centre + glm::vec3(rim_radius * dir.x, cut, rim_radius * dir.y));
    rim.emplace(key, index);
    return index;
  };

  for (const glm::uvec3& f : sphere.faces) {
    const std::array<uint32_t, 3> v = {f.x, f.y, f.z};
    // Clip the triangle against the plane (Sutherland-Hodgman, one plane): at most 4 corners,
    // in the triangle's order, so the orientation is kept.
    std::array<uint32_t, 4> poly{};
    int count = 0;
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = v[k], b = v[(k + 1) % 3];
      const bool a_in = kept[a] != kOutside, b_in = kept[b] != kOutside;
      if (a_in) poly[count++] = kept[a];
      if (a_in != b_in) poly[count++] = rim_vertex(a, b);
    }
    for (int k = 1; k + 1 < count; ++k) {
      mesh.triangles.push_back({poly[0], poly[k], poly[k + 1]});
    }
  }
  mesh.materials.assign(mesh.triangles.size(), material);
  return mesh;
}

}  // namespace rp::scene
