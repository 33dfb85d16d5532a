#include "scene/picking.h"

#include <algorithm>
#include <cmath>

namespace rp::scene {

namespace {

// The SDF is exact outside the tumbler (distance to a convex hull of two spheres), so each step
// of length SDF is safe. 256 steps are plenty: only rays grazing the silhouette get close to the
// limit, and those are reported as misses.
constexpr int kMaxTraceSteps = 256;

// Smallest sphere around both of the tumbler's spheres, hence around their convex hull (local
// space): centre on the axis halfway between the bottom and top poles.
struct BoundingSphere {
  float center_y;
  float radius;
};

BoundingSphere bounding_sphere(const TumblerShape& shape) {
  const float c = 0.5f * (shape.y_bottom() + shape.y_top());
  const float r = std::max(std::abs(c) + shape.b, std::abs(shape.y_t - c) + shape.t);
  return {c, r * 1.0001f + 1e-6f};  // a hair larger so rounding never cuts the surface
}

// Ray parameters [t_in, t_out] inside a sphere, or false. `dir` is unit length.
bool ray_sphere(const glm::vec3& origin, const glm::vec3& dir, const glm::vec3& center,
                float radius, float& t_in, float& t_out) {
  const glm::vec3 oc = origin - center;
  const float half_b = glm::dot(oc, dir);
  const float c = glm::dot(oc, oc) - radius * radius;
  const float disc = half_b * half_b - c;
  if (disc < 0.0f) return false;
  const float root = std::sqrt(disc);
  t_in = -half_b - root;
  t_out = -half_b + root;
  return t_out >= 0.0f;
}

}  // namespace

Ray camera_ray(const glm::mat4& inv_view_proj, glm::vec2 cursor_pixels, glm::vec2 viewport_size) {
  const float x_ndc = 2.0f * cursor_pixels.x / viewport_size.x - 1.0f;
  const float y_ndc = 1.0f - 2.0f * cursor_pixels.y / viewport_size.y;
  const glm::vec4 near_h = inv_view_proj * glm::vec4(x_ndc, y_ndc, -1.0f, 1.0f);
  const glm::vec4 far_h = inv_view_proj * glm::vec4(x_ndc, y_ndc, 1.0f, 1.0f);
  const glm::vec3 near_p = glm::vec3(near_h) / near_h.w;
  const glm::vec3 far_p = glm::vec3(far_h) / far_h.w;
  return {near_p, glm::normalize(far_p - near_p)};
}

std::optional<PickHit> pick_tumbler(const std::vector<glm::mat4>& tumbler_models,
                                    const TumblerShape& shape, glm::vec3 ray_origin,
                                    glm::vec3 ray_dir) {
  const float dir_len = glm::length(ray_dir);
  if (!(dir_len > 0.0f) || !std::isfinite(dir_len)) return std::nullopt;
  const glm::vec3 dir = ray_dir / dir_len;
  const BoundingSphere bound = bounding_sphere(shape);
  const glm::vec3 bound_center(0.0f, bound.center_y, 0.0f);

  std::optional<PickHit> best;
  for (size_t i = 0; i < tumbler_models.size(); ++i) {
    const glm::mat4& model = tumbler_models[i];
    // Rigid inverse: local = R^T (world - p). Distances and t are the same in both spaces.
    const glm::mat3 rot_t = glm::transpose(glm::mat3(model));
    const glm::vec3 o = rot_t * (ray_origin - glm::vec3(model[3]));
    const glm::vec3 d = rot_t * dir;

    float t_in = 0.0f, t_out = 0.0f;
    if (!ray_sphere(o, d, bound_center, bound.radius, t_in, t_out)) continue;
    float t = std::max(t_in, 0.0f);
    const float t_limit = best ? std::min(t_out, best->distance) : t_out;
    if (t > t_limit) continue;

    for (int k = 0; k < kMaxTraceSteps; ++k) {
      const float dist = shape.sdf(o + t * d);
      if (dist < kPickSurfaceTolerance) {
        best = PickHit{i, ray_origin + t * dir, t};
        break;
      }
      t += dist;
      if (t > t_limit) break;
    }
  }
  return best;
}

DragMode drag_mode_for(glm::vec3 hit_point, float center_of_mass_y) {
  return hit_point.y < center_of_mass_y ? DragMode::Translate : DragMode::Rotate;
}

std::optional<glm::vec3> intersect_horizontal_plane(const Ray& ray, float plane_y) {
  if (std::abs(ray.direction.y) < 1e-8f) return std::nullopt;
  const float t = (plane_y - ray.origin.y) / ray.direction.y;
  if (!(t >= 0.0f)) return std::nullopt;
  glm::vec3 p = ray.origin + t * ray.direction;
  p.y = plane_y;  // exact, so repeated drags do not creep
  return p;
}

}  // namespace rp::scene
