// The tumbler triangle mesh: closed, consistently wound outwards, on the analytic surface.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "mesh_checks.h"
#include "scene/tumbler_shape.h"

namespace {

using rp::scene::Mesh;
using rp::scene::TumblerMeshParams;
using rp::scene::TumblerShape;
using rp::scene::testing::count_welded_edges;
using rp::scene::testing::face_normal;

constexpr double kPi = std::numbers::pi;

TEST(TumblerMesh, TriangleCountFollowsTheParameters) {
  const TumblerShape s;
  const Mesh mesh = make_tumbler_mesh(s, TumblerMeshParams{}, 7);
  // 48 segments, 12 + 4 + 8 rings: two pole fans of 48 plus 22 bands of 96.
  EXPECT_EQ(mesh.triangles.size(), 2u * 48u + 22u * 96u);
  EXPECT_EQ(mesh.triangles.size(), 2208u);
  ASSERT_EQ(mesh.materials.size(), mesh.triangles.size());
  for (const uint32_t m : mesh.materials) EXPECT_EQ(m, 7u);
  EXPECT_EQ(make_tumbler_mesh(s, {8, 3, 1, 2}, 0).triangles.size(), 2u * 8u * 5u);
}

TEST(TumblerMesh, ClosedAndConsistentlyOriented) {
  for (const TumblerMeshParams params : {TumblerMeshParams{}, TumblerMeshParams{5, 1, 1, 1}}) {
    const Mesh mesh = make_tumbler_mesh(TumblerShape{}, params, 0);
    const auto counts = count_welded_edges(mesh);
    for (const auto& [edge, n] : counts.directed) {
      EXPECT_EQ(n, 1) << "directed edge used twice";
      const auto reverse = counts.directed.find({edge.second, edge.first});
      ASSERT_NE(reverse, counts.directed.end()) << "boundary edge: the mesh has a hole";
      EXPECT_EQ(reverse->second, 1);
    }
    // A closed genus-0 surface: V - E + F = 2 (E = directed edges / 2).
    const long v = static_cast<long>(counts.welded_vertices);
    const long e = static_cast<long>(counts.directed.size()) / 2;
    const long f = static_cast<long>(mesh.triangles.size());
    EXPECT_EQ(v - e + f, 2);
    // Expected welded vertex count: two poles plus one ring of `segments` per non-pole ring.
    const int rings = params.bottom_rings + params.cone_rings + params.top_rings - 1;
    EXPECT_EQ(v, 2 + rings * params.segments);
  }
}

TEST(TumblerMesh, NoDegenerateTriangles) {
  const Mesh mesh = make_tumbler_mesh(TumblerShape{}, TumblerMeshParams{}, 0);
  for (const glm::uvec3& t : mesh.triangles) {
    // The smallest triangles are at the top pole: about (2 pi t / 48) * (70 deg / 8) / 2.
    EXPECT_GT(rp::scene::testing::triangle_area(mesh, t), 1e-5f);
  }
}

TEST(TumblerMesh, VerticesOnSurfaceWithOutwardUnitNormals) {
  const TumblerShape s;
  const Mesh mesh = make_tumbler_mesh(s, TumblerMeshParams{}, 0);
  for (const rp::scene::Vertex& v : mesh.vertices) {
    const glm::vec3 p = v.position;
    const float r = std::sqrt(p.x * p.x + p.z * p.z);
    // Squared radii: at the poles sqrt() would magnify float rounding.
    const float profile = s.radius(p.y);
    EXPECT_NEAR(r * r, profile * profile, 1e-6f);
    EXPECT_NEAR(s.sdf(p), 0.0f, 2e-6f);
    EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
    EXPECT_GT(glm::dot(v.normal, s.sdf_gradient(p)), 0.99999f);
  }
  // Geometric winding agrees with the vertex normals (counter-clockwise seen from outside).
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::vec3 n = mesh.vertices[t.x].normal + mesh.vertices[t.y].normal +
                        mesh.vertices[t.z].normal;
    EXPECT_GT(glm::dot(face_normal(mesh, t), n), 0.0f);
  }
}

double mesh_volume(const Mesh& mesh) {
  double volume = 0.0;  // divergence theorem: sum of signed tetrahedra to the origin
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 a = mesh.vertices[t.x].position, b = mesh.vertices[t.y].position,
                     c = mesh.vertices[t.z].position;
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return volume;
}

TEST(TumblerMesh, VolumeMatchesTheSolidOfRevolution) {
  const TumblerShape s;
  // pi * integral R^2 dy in closed form: bottom sphere segment + cone frustum + top segment.
  const double b = 0.2, t = 0.1, a = kPi / 9.0, yt = 0.1 / std::sin(a);
  const double y0 = b * std::sin(a), y1 = yt + t * std::sin(a), r0 = b * std::cos(a),
               r1 = t * std::cos(a), st = t * std::sin(a);
  const double bottom = kPi * (b * b * (y0 + b) - (y0 * y0 * y0 + b * b * b) / 3.0);
  const double cone = kPi * (y1 - y0) / 3.0 * (r0 * r0 + r0 * r1 + r1 * r1);
  const double top = kPi * (t * t * (t - st) - (t * t * t - st * st * st) / 3.0);
  const double exact = bottom + cone + top;
  // The mesh is inscribed: slightly smaller; the deficit shrinks with the square of the
  // resolution (0.64 % at the default, 4x finer gives 16x less).
  const double coarse = mesh_volume(make_tumbler_mesh(s, TumblerMeshParams{}, 0));
  const double fine = mesh_volume(make_tumbler_mesh(s, {192, 48, 16, 32}, 0));
  EXPECT_LT(coarse, exact);
  EXPECT_NEAR(coarse / exact, 1.0, 1e-2);
  EXPECT_LT(fine, exact);
  EXPECT_NEAR(fine / exact, 1.0, 6e-4);
}

TEST(TumblerMesh, UvLayout) {
  const TumblerShape s;
  const Mesh mesh = make_tumbler_mesh(s, TumblerMeshParams{}, 0);
  for (const rp::scene::Vertex& v : mesh.vertices) {
    EXPECT_NEAR(v.uv.y, (v.position.y + 0.2f) / s.height(), 1e-6f);
    EXPECT_GE(v.uv.x, 0.0f);
    EXPECT_LE(v.uv.x, 1.0f);
    const float r = std::sqrt(v.position.x * v.position.x + v.position.z * v.position.z);
    if (r < 1e-4f) continue;  // poles: u is the segment's middle
    // Front (+z) at u = 0.5, +x at u = 0.75, back (-z) at the seam u = 0 or 1.
    const float azimuth = std::atan2(-v.position.x, -v.position.z);  // 0 at -z, pi/2 at -x
    float expected_u = azimuth / (2.0f * static_cast<float>(kPi));
    if (expected_u < 0.0f) expected_u += 1.0f;
    const float du = std::fabs(v.uv.x - expected_u);
    EXPECT_TRUE(du < 1e-5f || std::fabs(du - 1.0f) < 1e-5f) << v.uv.x << " vs " << expected_u;
  }
  // Spot checks by hand: the front-most vertex of the widest ring has u = 0.5.
  float best_z = -1.0f, u_front = -1.0f, best_x = -1.0f, u_right = -1.0f;
  for (const rp::scene::Vertex& v : mesh.vertices) {
    if (v.position.z > best_z) best_z = v.position.z, u_front = v.uv.x;
    if (v.position.x > best_x) best_x = v.position.x, u_right = v.uv.x;
  }
  EXPECT_NEAR(u_front, 0.5f, 1e-6f);
  EXPECT_NEAR(u_right, 0.75f, 1e-6f);
}

}  // namespace
