// The Cornell box walls and the ceiling lamp cap.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include <gtest/gtest.h>

#include "mesh_checks.h"
#include "scene/cornell_box.h"

namespace {

using rp::scene::Mesh;
using rp::scene::testing::face_normal;

constexpr float kPi = std::numbers::pi_v<float>;

rp::scene::BoxMaterialIds distinct_ids() {
  rp::scene::BoxMaterialIds ids;
  ids.floor = 10, ids.ceiling = 11, ids.back = 12, ids.left = 13, ids.right = 14;
  return ids;
}

TEST(CornellBox, FiveWallsOfQuadGrids) {
  const Mesh box = rp::scene::make_cornell_box(distinct_ids(), 8);
  EXPECT_EQ(box.triangles.size(), 5u * 8u * 8u * 2u);
  EXPECT_EQ(box.vertices.size(), 5u * 9u * 9u);
  EXPECT_EQ(rp::scene::make_cornell_box(distinct_ids(), 2).triangles.size(), 5u * 2u * 2u * 2u);
}

TEST(CornellBox, NormalsPointInwardAndWindingIsCounterClockwiseFromInside) {
  const Mesh box = rp::scene::make_cornell_box(distinct_ids(), 4);
  ASSERT_EQ(box.materials.size(), box.triangles.size());
  int per_wall[5] = {0, 0, 0, 0, 0};
  for (size_t i = 0; i < box.triangles.size(); ++i) {
    const glm::uvec3 t = box.triangles[i];
    const rp::scene::Vertex& a = box.vertices[t.x];
    const glm::vec3 centroid =
        (a.position + box.vertices[t.y].position + box.vertices[t.z].position) / 3.0f;
    // Which wall, from the geometry alone, and the inward normal it must have.
    glm::vec3 expected_normal(0.0f);
    uint32_t expected_material = 0;
    if (std::fabs(centroid.y + 1.0f) < 1e-6f) expected_normal = {0, 1, 0}, expected_material = 10;
    else if (std::fabs(centroid.y - 1.0f) < 1e-6f) expected_normal = {0, -1, 0}, expected_material = 11;
    else if (std::fabs(centroid.z + 1.0f) < 1e-6f) expected_normal = {0, 0, 1}, expected_material = 12;
    else if (std::fabs(centroid.x + 1.0f) < 1e-6f) expected_normal = {1, 0, 0}, expected_material = 13;
    else if (std::fabs(centroid.x - 1.0f) < 1e-6f) expected_normal = {-1, 0, 0}, expected_material = 14;
    else FAIL() << "triangle off the box walls (or on the open front)";
    per_wall[expected_material - 10]++;
    EXPECT_EQ(box.materials[i], expected_material);
    for (const uint32_t index : {t.x, t.y, t.z}) {
      EXPECT_EQ(box.vertices[index].normal, expected_normal);
      const glm::vec3 p = box.vertices[index].position;
      EXPECT_LE(glm::length(glm::max(glm::abs(p) - 1.0f, glm::vec3(0.0f))), 0.0f);
    }
    const glm::vec3 fn = face_normal(box, t);
    EXPECT_GT(glm::dot(fn, expected_normal), 0.0f);
    EXPECT_NEAR(glm::length(glm::cross(fn, expected_normal)), 0.0f, 1e-6f);  // flat
    EXPECT_GT(glm::dot(expected_normal, -centroid), 0.0f);  // faces the box centre
  }
  for (const int n : per_wall) EXPECT_EQ(n, 4 * 4 * 2);
}

TEST(CornellBox, FloorUvCoversTheFloorOnce) {
  const Mesh box = rp::scene::make_cornell_box(distinct_ids(), 8);
  for (const rp::scene::Vertex& v : box.vertices) {
    if (v.normal != glm::vec3(0, 1, 0)) continue;
    EXPECT_NEAR(v.uv.x, (v.position.x + 1.0f) * 0.5f, 1e-6f);
    EXPECT_NEAR(v.uv.y, (1.0f - v.position.z) * 0.5f, 1e-6f);
  }
}

// A skylight: the ceiling quads whose centres lie in the rectangle are left out, every other
// quad of the ceiling and of the other walls stays.
TEST(CornellBox, CeilingOpeningLeavesOutTheQuadsInside) {
  rp::scene::CeilingOpening opening;
  opening.min = {-0.5f, -1.0f};
  opening.max = {0.5f, -0.5f};
  const Mesh box = rp::scene::make_cornell_box(distinct_ids(), 8, opening);
  const Mesh closed = rp::scene::make_cornell_box(distinct_ids(), 8);
  // 0.25-wide quads: 4 along x (centres -0.375 .. 0.375) by 2 along z (-0.875, -0.625)
  EXPECT_EQ(box.triangles.size(), closed.triangles.size() - 4u * 2u * 2u);
  size_t ceiling = 0;
  for (size_t i = 0; i < box.triangles.size(); ++i) {
    const glm::uvec3 t = box.triangles[i];
    const glm::vec3 c = (box.vertices[t.x].position + box.vertices[t.y].position +
                         box.vertices[t.z].position) / 3.0f;
    if (box.materials[i] != distinct_ids().ceiling) continue;
    ++ceiling;
    const bool inside = c.x > -0.5f && c.x < 0.5f && c.z > -1.0f && c.z < -0.5f;
    EXPECT_FALSE(inside) << "a ceiling triangle in the opening at " << c.x << ", " << c.z;
  }
  EXPECT_EQ(ceiling, 8u * 8u * 2u - 16u);
}

TEST(LampCap, LiesOnTheSphereBelowTheCeiling) {
  const rp::scene::PointLight light;  // centre (0, 1.1, 0), radius 0.35
  const Mesh cap = rp::scene::make_lamp_cap(light, 5, 3, 1.0f);
  ASSERT_FALSE(cap.triangles.empty());
  for (const uint32_t m : cap.materials) EXPECT_EQ(m, 5u);
  float lowest = 10.0f;
  for (const rp::scene::Vertex& v : cap.vertices) {
    EXPECT_LE(v.position.y, 1.0f);
    EXPECT_NEAR(glm::length(v.position - light.position), light.lamp_radius, 1e-6f);
    EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-6f);
    EXPECT_GT(glm::dot(v.normal, glm::normalize(v.position - light.position)), 0.99999f);
    lowest = std::min(lowest, v.position.y);
  }
  EXPECT_NEAR(lowest, 1.1f - 0.35f, 1e-6f);  // subdivision puts a vertex at the bottom pole
  for (const glm::uvec3& t : cap.triangles) {
    const glm::vec3 centroid = (cap.vertices[t.x].position + cap.vertices[t.y].position +
                                cap.vertices[t.z].position) / 3.0f;
    EXPECT_GT(glm::dot(face_normal(cap, t), centroid - light.position), 0.0f);  // outward
    EXPECT_GT(rp::scene::testing::triangle_area(cap, t), 0.0f);
  }
}

TEST(LampCap, OpenOnlyAlongTheCeilingCircle) {
  const rp::scene::PointLight light;
  const Mesh cap = rp::scene::make_lamp_cap(light, 0, 3, 1.0f);
  // Welding by position must not merge anything: clipped rim vertices are shared by index.
  EXPECT_EQ(rp::scene::testing::count_welded_edges(cap).welded_vertices, cap.vertices.size());
  std::map<std::pair<uint32_t, uint32_t>, int> edges;  // directed, by vertex index
  for (const glm::uvec3& t : cap.triangles) {
    edges[{t.x, t.y}]++, edges[{t.y, t.z}]++, edges[{t.z, t.x}]++;
  }
  const float rim_radius = std::sqrt(0.35f * 0.35f - 0.1f * 0.1f);
  int boundary = 0;
  float boundary_length = 0.0f;
  for (const auto& [edge, n] : edges) {
    EXPECT_EQ(n, 1) << "inconsistent orientation";
    if (edges.count({edge.second, edge.first}) != 0) continue;
    // A boundary edge: only allowed along the ceiling, both ends on the rim circle at y = 1.
    ++boundary;
    const glm::vec3 a = cap.vertices[edge.first].position, b = cap.vertices[edge.second].position;
    for (const glm::vec3 p : {a, b}) {
      EXPECT_EQ(p.y, 1.0f);
      EXPECT_NEAR(glm::length(glm::vec2(p.x, p.z)), rim_radius, 1e-6f);
    }
    boundary_length += glm::length(b - a);
  }
  EXPECT_GT(boundary, 20);
  // The rim polygon goes once round the circle (inscribed: slightly shorter).
  EXPECT_LT(boundary_length, 2.0f * kPi * rim_radius);
  EXPECT_NEAR(boundary_length / (2.0f * kPi * rim_radius), 1.0f, 0.01f);
}

TEST(LampCap, AreaMatchesTheSphericalCap) {
  const rp::scene::PointLight light;
  const Mesh cap = rp::scene::make_lamp_cap(light, 0, 3, 1.0f);
  float area = 0.0f;
  for (const glm::uvec3& t : cap.triangles) area += rp::scene::testing::triangle_area(cap, t);
  // Cap of height h = 0.35 - 0.1 on a sphere of radius 0.35: 2 pi r h.
  const float exact = 2.0f * kPi * 0.35f * 0.25f;
  EXPECT_NEAR(area / exact, 1.0f, 0.02f);
  EXPECT_LT(area, exact);
}

TEST(LampCap, TriangleCountForThreeSubdivisions) {
  const Mesh cap = rp::scene::make_lamp_cap(rp::scene::PointLight{}, 0, 3, 1.0f);
  // 1280 faces on the whole icosphere; the cap is 0.25 / 0.7 of the area, plus clipped pieces.
  EXPECT_GT(cap.triangles.size(), 400u);
  EXPECT_LT(cap.triangles.size(), 600u);
}

}  // namespace
