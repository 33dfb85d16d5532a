#include "scene/frame_scene.h"

#include <glm/gtc/matrix_transform.hpp>

namespace rp::scene {

uint32_t voxel_mesh(const std::vector<Mesh>& meshes, uint32_t mesh, uint32_t voxel_resolution) {
  if (mesh >= meshes.size()) return mesh;  // the caller reports the bad index
  const Mesh& m = meshes[mesh];
  if (m.proxy < 0 || voxel_resolution > m.proxy_max_voxels) return mesh;
  return static_cast<uint32_t>(m.proxy);
}

uint32_t shadow_mesh(const std::vector<Mesh>& meshes, uint32_t mesh, uint32_t shadow_size) {
  if (mesh >= meshes.size()) return mesh;
  const Mesh& m = meshes[mesh];
  if (m.proxy < 0 || shadow_size > m.proxy_max_shadow_texels) return mesh;
  return static_cast<uint32_t>(m.proxy);
}

glm::mat4 Camera::view() const { return glm::lookAt(position, target, up); }

glm::mat4 Camera::projection(float aspect) const {
  // GLM's default clip convention is OpenGL's (right-handed, z_ndc in [-1, 1]).
  return glm::perspective(glm::radians(fov_y_deg), aspect, near_plane, far_plane);
}

glm::mat4 PointLight::view_proj() const {
  // Looks straight down (-y). The up vector -z (towards the back wall) is never parallel to the
  // view direction, so the basis is stable: image right = +x, image up = -z.
  const glm::mat4 view =
      glm::lookAt(position, position - glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
  const glm::mat4 proj =
      glm::perspective(glm::radians(shadow_fov_y_deg), 1.0f, shadow_near, shadow_far);
  return proj * view;
}

}  // namespace rp::scene
