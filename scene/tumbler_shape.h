// The tumbler (roly-poly toy) as a solid of revolution (SPEC.md section 2): profile R(y), analytic
// signed distance and its gradient, and a triangle mesh.
//
// Local space: y is the axis of revolution, the bottom sphere centre is the origin. The surface
// is the convex hull of two spheres: the bottom one (radius b, centre origin) and the top one
// (radius t, centre (0, y_t, 0)), joined by a cone whose side makes the angle alpha with the axis.
#pragma once

#include <cmath>
#include <numbers>

#include <glm/glm.hpp>

#include "scene/frame_scene.h"

namespace rp::scene {

struct TumblerShape {
  float b = 0.2f;                                   // bottom sphere radius
  float t = 0.1f;                                   // top sphere radius
  float alpha = std::numbers::pi_v<float> / 9.0f;   // angle between the cone side and the axis
  float y_t = (0.2f - 0.1f) / std::sin(std::numbers::pi_v<float> / 9.0f);  // top centre height

  // Another shape; y_t = (b - t) / sin(alpha) is derived (set b, t, alpha only through here).
  static TumblerShape with(float b, float t, float alpha) {
    return TumblerShape{b, t, alpha, (b - t) / std::sin(alpha)};
  }

  float y_bottom() const { return -b; }
  float y_top() const { return y_t + t; }
  float height() const { return y_top() - y_bottom(); }
  // Where the cone meets the bottom and the top sphere (the profile's two joins).
  float y_join_bottom() const { return b * std::sin(alpha); }
  float y_join_top() const { return y_t + t * std::sin(alpha); }

  // Profile radius at height y, for y in [-b, y_t + t] (0 outside).
  float radius(float y) const;
  // dR/dy (infinite at the two poles; finite everywhere else).
  float radius_slope(float y) const;

  // Signed distance from local point p to the surface (negative inside). SPEC.md section 2, with
  // one correction: the top sphere takes over where y' > (b - t) / tan(alpha) = y_t cos(alpha),
  // the cone's length between its two tangent points. SPEC/000 print y_t / tan(alpha), which
  // lies beyond the cone's apex, so the top sphere would never be used.
  float sdf(const glm::vec3& p) const;
  // Outward unit normal of the piece that sdf() uses at p (the SDF gradient). On the axis inside
  // the cone the radial direction is undefined; +x is used there.
  glm::vec3 sdf_gradient(const glm::vec3& p) const;
};

// Resolution of the tumbler mesh. `segments` vertices around each ring; rings per piece along y.
struct TumblerMeshParams {
  int segments = 48;
  int bottom_rings = 12;   // latitude bands on the bottom cap (pole to the bottom join)
  int cone_rings = 4;      // bands along the cone
  int top_rings = 8;       // latitude bands on the top cap (top join to the pole)
};

// Closed triangle mesh of the tumbler surface, counter-clockwise seen from outside, smooth
// normals from the analytic surface, every triangle using `material`.
// UVs: u = azimuth / 2pi with the front (+z) at u = 0.5 and u growing towards +x there, the seam
// at the back (-z); v = (y + b) / (y_t + t + b), v = 1 at the top. The seam and the poles have
// duplicated vertices (different u) with bit-identical positions, so the mesh is watertight by
// position: a rasterizer sees no cracks.
// Triangles: 2 * segments * (bottom_rings + cone_rings + top_rings - 1).
Mesh make_tumbler_mesh(const TumblerShape& shape, const TumblerMeshParams& params,
                       uint32_t material);

}  // namespace rp::scene
