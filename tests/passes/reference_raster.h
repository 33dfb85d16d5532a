// Plain C++ reference of the compute rasterizer (kernels/visibility.cl): brute force over every
// pixel and primitive, no binning, same conventions (kernels/shared/types.h) and the same float
// operations in the same order (kernels/common/raster.h), so coverage and ids must agree
// exactly and depth / barycentrics to rounding of divisions. Alpha-masked materials cut holes
// by the host's rule (scene/alpha_mask.h).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/frame_scene.h"

namespace rp::test {

struct RefView {
  glm::mat4 view_proj{1.0f};
  glm::mat4 inv_view_proj{1.0f};  // used for sphere rays
  uint32_t width = 0, height = 0;
  bool depth_only = false;        // shadow map: only instances / spheres that cast shadows
};

struct RefImage {
  uint32_t width = 0, height = 0;
  std::vector<float> depth;           // z_ndc * 0.5 + 0.5 of the nearest surface, 1 where none
  std::vector<float> back;            // depth_only views: of the farthest surface, 0 where none
  std::vector<glm::uvec2> ids;        // (instance, primitive), RP_ID_* conventions
  std::vector<glm::vec2> bary;        // perspective-correct (b1, b2); 0 for spheres / none
  // Triangles whose inside test passes at the pixel centre with z_ndc in [-1, 1], split by the
  // sign of the triangle's homogeneous determinant (its winding as seen from the view).
  std::vector<uint32_t> hits_positive, hits_negative;
  // 1 where an alpha-masked triangle's point is within rounding of its cutoff (either answer
  // is right there): the comparisons skip those pixels.
  std::vector<uint8_t> alpha_edge;

  size_t index(uint32_t x, uint32_t y) const { return size_t(y) * width + x; }
};

// Renders `frame` (instances of `assets` meshes and analytic spheres) for `view`.
RefImage reference_raster(const scene::SceneAssets& assets, const scene::FrameScene& frame,
                          const RefView& view);

// ---- Small scene builders shared by the visibility tests ----

// A mesh from positions and triangles (normals +z, uv 0, material 0).
scene::Mesh make_test_mesh(const std::vector<glm::vec3>& positions,
                           const std::vector<glm::uvec3>& triangles);

// Icosahedron subdivided `levels` times, vertices on the sphere of `radius` about the origin,
// counter-clockwise seen from outside; shared vertices (a closed mesh).
scene::Mesh make_icosphere(int levels, float radius);

// Assets holding `meshes` and one grey double-sided material (both windings drawn).
scene::SceneAssets make_test_assets(std::vector<scene::Mesh> meshes);

// An empty frame with the camera the visibility tests assume (independent of the defaults):
// at (0, 0, 2.75) looking at the origin, 60 degrees vertical field of view, near 0.1, far 4.
scene::FrameScene make_test_frame();

// The frame's camera view at width x height (as GpuScene::update computes it).
RefView camera_view(const scene::FrameScene& frame, uint32_t width, uint32_t height);

}  // namespace rp::test
