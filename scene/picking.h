// Mouse picking (SPEC.md section 4): the cursor ray from the inverse view-projection, sphere
// tracing of the tumblers' signed distance fields along it, and which drag a hit starts.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/tumbler_shape.h"

namespace rp::scene {

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit length
};

// The world-space ray under a cursor. `cursor_pixels` is a continuous window position: (0,0) is
// the top-left corner of the top-left pixel, pixel (i, j) has its centre at (i + 0.5, j + 0.5),
// y grows downwards (kernels/shared/types.h). NDC is OpenGL style: x_ndc = 2 x / w - 1,
// y_ndc = 1 - 2 y / h. The ray starts on the near plane (z_ndc = -1) and points to the far plane.
Ray camera_ray(const glm::mat4& inv_view_proj, glm::vec2 cursor_pixels, glm::vec2 viewport_size);

struct PickHit {
  size_t index;     // which tumbler (index into tumbler_models)
  glm::vec3 point;  // world-space hit point on the surface
  float distance;   // along the normalised ray direction from ray_origin
};

// Sphere traces every tumbler along the ray (in its local space: the model matrices are rigid,
// rotation + translation) after a bounding-sphere test; the nearest hit wins, nullopt on a miss.
// The hit point lies within kPickSurfaceTolerance of the surface (|SDF| below it). A ray that
// starts inside a tumbler hits it at distance 0.
inline constexpr float kPickSurfaceTolerance = 1e-5f;  // world units
std::optional<PickHit> pick_tumbler(const std::vector<glm::mat4>& tumbler_models,
                                    const TumblerShape& shape, glm::vec3 ray_origin,
                                    glm::vec3 ray_dir);

// A hit below the centre of mass (world y < center_of_mass_y, i.e. -1 + b for a tumbler on the
// floor) drags the tumbler across the floor; at or above it, dragging rolls (rotates) it.
enum class DragMode { Translate, Rotate };
DragMode drag_mode_for(glm::vec3 hit_point, float center_of_mass_y);

// Where the ray crosses the horizontal plane y = plane_y (the translate drag follows the cursor
// on the plane through the first hit point). nullopt when the ray is parallel to the plane or
// the crossing lies behind the origin.
std::optional<glm::vec3> intersect_horizontal_plane(const Ray& ray, float plane_y);

}  // namespace rp::scene
