#include "scene/file_scene.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace rp::scene {
namespace {

// A cube around `b` (its largest side plus `margin` of it on each side), centred on b.
Bounds cube_around(const Bounds& b, float margin) {
  if (b.empty()) return {glm::vec3(-1.0f), glm::vec3(1.0f)};
  const glm::vec3 size = b.size();
  float side = std::max({size.x, size.y, size.z});
  if (!(side > 0.0f)) side = std::max(1.0f, glm::length(b.center()) * 1e-3f);
  const float half = 0.5f * side * (1.0f + 2.0f * margin);
  return {b.center() - glm::vec3(half), b.center() + glm::vec3(half)};
}

}  // namespace

glm::mat4 VolumeFit::matrix() const {
  return glm::scale(glm::mat4(1.0f), glm::vec3(scale)) *
         glm::translate(glm::mat4(1.0f), -center);
}

Bounds VolumeFit::world_volume() const {
  const glm::vec3 half(1.0f / scale);
  return {center - half, center + half};
}

VolumeFit fit_volume(const LoadedScene& scene, float margin) {
  Bounds cube;
  if (scene.volume && !scene.volume->empty()) {
    // The file names its volume: take it as the cube around it without a margin (a cube given
    // as one is kept exactly, so an exported scene voxelizes on the grid it was made with).
    cube = cube_around(*scene.volume, 0.0f);
  } else {
    cube = cube_around(scene.bounds, margin);
  }
  VolumeFit fit;
  fit.center = cube.center();
  fit.scale = 2.0f / (cube.hi.x - cube.lo.x);
  return fit;
}

Camera initial_camera(const LoadedScene& scene) {
  const Bounds b = scene.bounds.empty() ? Bounds{glm::vec3(-1.0f), glm::vec3(1.0f)} : scene.bounds;
  const float radius = std::max(0.5f * glm::length(b.size()), 1e-6f);
  Camera camera;
  if (scene.camera) {
    camera = *scene.camera;
  } else {
    camera.fov_y_deg = 60.0f;
    // Distance at which the bounding sphere fills the vertical view, seen from the front and a
    // little above (15 degrees), looking at the centre.
    const float distance = radius / std::sin(glm::radians(0.5f * camera.fov_y_deg));
    const glm::vec3 dir = glm::normalize(glm::vec3(0.0f, std::sin(glm::radians(15.0f)),
                                                   std::cos(glm::radians(15.0f))));
    camera.target = b.center();
    camera.position = b.center() + dir * distance;
    camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    camera.near_plane = std::max(distance - radius, distance * 1e-3f) * 0.5f;
    camera.far_plane = distance + radius * 1.5f;
  }
  // A camera without a far plane (glTF's infinite projection) or with planes that do not hold
  // the scene: reach past the farthest corner of the bounds.
  float farthest = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y,
                           (i & 4) ? b.hi.z : b.lo.z);
    farthest = std::max(farthest, glm::length(corner - camera.position));
  }
  if (!(camera.far_plane > camera.near_plane) || !std::isfinite(camera.far_plane))
    camera.far_plane = farthest * 1.05f;
  if (!(camera.near_plane > 0.0f)) camera.near_plane = camera.far_plane * 1e-4f;
  return camera;
}

Camera to_render_space(const Camera& camera, const VolumeFit& fit) {
  Camera c = camera;
  c.position = fit.to_render(camera.position);
  c.target = fit.to_render(camera.target);
  c.near_plane = camera.near_plane * fit.scale;
  c.far_plane = camera.far_plane * fit.scale;
  return c;
}

FrameScene make_file_frame(const LoadedScene& scene, const VolumeFit& fit, const Camera& camera,
                           const Camera& previous, uint32_t frame_index) {
  FrameScene frame;
  frame.camera = to_render_space(camera, fit);
  frame.prev_camera = to_render_space(previous, fit);
  frame.lamp = false;
  frame.light.intensity = glm::vec3(0.0f);
  frame.frame_index = frame_index;
  const glm::mat4 m = fit.matrix();
  frame.instances.reserve(scene.instances.size());
  for (MeshInstance inst : scene.instances) {
    inst.model = m * inst.model;
    inst.prev_model = m * inst.prev_model;
    frame.instances.push_back(inst);
  }
  const float s2 = fit.scale * fit.scale;
  for (PunctualLight light : scene.lights) {
    light.position = fit.to_render(light.position);
    if (light.type != LightType::kDirectional) {
      light.intensity *= s2;
      light.range *= fit.scale;
    }
    frame.lights.push_back(light);
  }
  return frame;
}

}  // namespace rp::scene
