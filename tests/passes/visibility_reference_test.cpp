// The reference rasterizer's fill rule on its own: no cracks and no double hits on shared edges
// and vertices (the GPU tests then require the kernels to agree with the reference exactly).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "passes/reference_raster.h"

namespace rp::test {
namespace {

// World (x, y) in pixels -> NDC, so pixel (x, y) sees world point (x, y); z_ndc = z. With
// power-of-two sizes every step is exact in float, so vertices land exactly on pixel centres
// and edges exactly through them: ties are settled by the top-left rule alone.
// (With inexact inputs, float rounding decides ties: still consistent along shared edges by
// construction, see kernels/common/raster.h.)
RefView pixel_ortho_view(uint32_t width, uint32_t height) {
  RefView view;
  glm::mat4 m(1.0f);
  m[0][0] = 2.0f / float(width);
  m[1][1] = -2.0f / float(height);
  m[3][0] = -1.0f;
  m[3][1] = 1.0f;
  view.view_proj = m;
  view.inv_view_proj = glm::inverse(m);
  view.width = width;
  view.height = height;
  return view;
}

// A jittered grid of quads whose nodes sit exactly on pixel centres, split along alternating
// diagonals: edges pass through pixel centres and interior nodes are pixel centres shared by
// 4-8 triangles, the cases the top-left rule must settle.
struct Grid {
  static constexpr int kN = 6;  // quads per side
  std::vector<glm::vec3> nodes;
  std::vector<glm::uvec3> triangles;
  glm::vec2 node(int i, int j) const { return glm::vec2(nodes[size_t(j) * (kN + 1) + i]); }
};

Grid make_grid() {
  Grid g;
  for (int j = 0; j <= Grid::kN; ++j)
    for (int i = 0; i <= Grid::kN; ++i) {
      float jx = float((i * 7 + j * 3) % 3) - 1.0f, jy = float((i * 5 + j * 2) % 3) - 1.0f;
      if (i == 0 || i == Grid::kN) jx = 0.0f;  // straight outer boundary
      if (j == 0 || j == Grid::kN) jy = 0.0f;
      g.nodes.emplace_back(6.0f + 8.0f * float(i) + jx + 0.5f, 4.0f + 6.0f * float(j) + jy + 0.5f,
                           0.0f);
    }
  auto id = [](int i, int j) { return uint32_t(j * (Grid::kN + 1) + i); };
  for (int j = 0; j < Grid::kN; ++j)
    for (int i = 0; i < Grid::kN; ++i) {
      uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        g.triangles.push_back({a, b, c});
        g.triangles.push_back({a, c, d});
      } else {
        g.triangles.push_back({a, b, d});
        g.triangles.push_back({b, c, d});
      }
    }
  return g;
}

TEST(VisibilityReference, GridOnPixelCentresCoversEachInteriorPixelOnce) {
  Grid grid = make_grid();
  scene::SceneAssets assets = make_test_assets({make_test_mesh(grid.nodes, grid.triangles)});
  scene::FrameScene frame = make_test_frame();
  frame.instances.push_back({});
  RefView view = pixel_ortho_view(64, 64);
  RefImage img = reference_raster(assets, frame, view);

  // The grid's outline is the rectangle through the outer nodes (unjittered there).
  const glm::vec2 lo = grid.node(0, 0), hi = grid.node(Grid::kN, Grid::kN);
  int interior = 0, on_vertex = 0;
  for (uint32_t y = 0; y < view.height; ++y)
    for (uint32_t x = 0; x < view.width; ++x) {
      const float px = float(x) + 0.5f, py = float(y) + 0.5f;
      const uint32_t hits = img.hits_positive[img.index(x, y)] + img.hits_negative[img.index(x, y)];
      const bool inside = px > lo.x && px < hi.x && py > lo.y && py < hi.y;
      const bool outside = px < lo.x || px > hi.x || py < lo.y || py > hi.y;
      if (inside) {
        EXPECT_EQ(hits, 1u) << "pixel " << x << "," << y;
        ++interior;
        for (const glm::vec3& n : grid.nodes) on_vertex += (n.x == px && n.y == py) ? 1 : 0;
      } else if (outside) {
        EXPECT_EQ(hits, 0u) << "pixel " << x << "," << y;
      } else {
        EXPECT_LE(hits, 1u) << "boundary pixel " << x << "," << y;
      }
    }
  EXPECT_GT(interior, 1000);
  EXPECT_EQ(on_vertex, (Grid::kN - 1) * (Grid::kN - 1));  // every interior node is a centre
}

TEST(VisibilityReference, GridTopLeftRuleOnOutline) {
  // Left and top outline edges take the pixel centres on them, right and bottom ones do not.
  Grid grid = make_grid();
  scene::SceneAssets assets = make_test_assets({make_test_mesh(grid.nodes, grid.triangles)});
  scene::FrameScene frame = make_test_frame();
  frame.instances.push_back({});
  RefImage img = reference_raster(assets, frame, pixel_ortho_view(64, 64));
  const glm::vec2 lo = grid.node(0, 0), hi = grid.node(Grid::kN, Grid::kN);
  auto hits = [&](float px, float py) {
    size_t i = img.index(uint32_t(px), uint32_t(py));
    return img.hits_positive[i] + img.hits_negative[i];
  };
  const float mid_x = std::floor((lo.x + hi.x) / 2) + 0.5f, mid_y = std::floor((lo.y + hi.y) / 2) + 0.5f;
  EXPECT_EQ(hits(lo.x, mid_y), 1u);  // left edge
  EXPECT_EQ(hits(mid_x, lo.y), 1u);  // top edge
  EXPECT_EQ(hits(hi.x, mid_y), 0u);  // right edge
  EXPECT_EQ(hits(mid_x, hi.y), 0u);  // bottom edge
  EXPECT_EQ(hits(lo.x, lo.y), 1u);   // top-left corner
  EXPECT_EQ(hits(hi.x, hi.y), 0u);   // bottom-right corner
}

TEST(VisibilityReference, ClosedIcosphereHasNoCracksOrDoubleHits) {
  // In perspective, seen from outside: every pixel centre inside the silhouette is covered by
  // exactly one front-facing and one back-facing triangle, outside by none.
  const scene::Mesh sphere = make_icosphere(2, 0.8f);
  double r_in = 1e9;  // inscribed radius: the nearest face plane
  for (const glm::uvec3& t : sphere.triangles) {
    glm::dvec3 a(sphere.vertices[t.x].position), b(sphere.vertices[t.y].position),
        c(sphere.vertices[t.z].position);
    r_in = std::min(r_in, std::abs(glm::dot(a, glm::normalize(glm::cross(b - a, c - a)))));
  }
  scene::SceneAssets assets = make_test_assets({sphere});
  scene::FrameScene frame = make_test_frame();
  scene::MeshInstance inst;
  inst.model = glm::mat4(glm::vec4(0.96f, 0.28f, 0.0f, 0.0f), glm::vec4(-0.28f, 0.96f, 0.0f, 0.0f),
                         glm::vec4(0.0f, 0.0f, 1.0f, 0.0f), glm::vec4(0.05f, -0.1f, 0.3f, 1.0f));
  frame.instances.push_back(inst);
  RefView view = camera_view(frame, 64, 64);
  RefImage img = reference_raster(assets, frame, view);

  // Distance of each pixel ray from the sphere centre, in double.
  const glm::dmat4 inv = glm::inverse(glm::dmat4(view.view_proj));
  const glm::dvec3 centre(0.05, -0.1, 0.3), eye(frame.camera.position);
  const double r_out = 0.8;
  int inside = 0;
  for (uint32_t y = 0; y < 64; ++y)
    for (uint32_t x = 0; x < 64; ++x) {
      const size_t i = img.index(x, y);
      EXPECT_EQ(img.hits_positive[i], img.hits_negative[i]) << "pixel " << x << "," << y;
      EXPECT_LE(img.hits_positive[i], 1u) << "pixel " << x << "," << y;
      glm::dvec4 far = inv * glm::dvec4((x + 0.5) / 32.0 - 1.0, 1.0 - (y + 0.5) / 32.0, 1.0, 1.0);
      glm::dvec3 dir = glm::normalize(glm::dvec3(far) / far.w - eye);
      glm::dvec3 oc = centre - eye;
      double dist = glm::length(oc - dir * glm::dot(oc, dir));
      if (dist < r_in) {
        EXPECT_EQ(img.hits_positive[i], 1u) << "pixel " << x << "," << y;
        ++inside;
      }
      if (dist > r_out) {
        EXPECT_EQ(img.hits_positive[i], 0u) << "pixel " << x << "," << y;
      }
    }
  EXPECT_GT(inside, 500);
}

}  // namespace
}  // namespace rp::test
