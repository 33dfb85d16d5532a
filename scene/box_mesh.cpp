#include "scene/box_mesh.h"

namespace rp::scene {

void append_box(Mesh& m, glm::vec3 center, glm::vec3 half, uint32_t material, float uv_repeat) {
  for (int axis = 0; axis < 3; ++axis)
    for (float s : {-1.0f, 1.0f}) {
      glm::vec3 n(0.0f), u(0.0f), v(0.0f);
      n[axis] = s;
      u[(axis + 1) % 3] = 1.0f;
      v[(axis + 2) % 3] = 1.0f;
      const uint32_t b = uint32_t(m.vertices.size());
      const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const auto& k : corners)
        m.vertices.push_back({center + half * (n + k[0] * u + k[1] * v), n,
                              glm::vec2(0.5f + 0.5f * k[0], 0.5f + 0.5f * k[1]) * uv_repeat});
      const float w = glm::dot(glm::cross(n, u), v) > 0.0f ? 1.0f : -1.0f;
      for (int k = 0; k < 4; ++k) m.tangents.push_back(glm::vec4(u, w));
      if (s > 0) {
        m.triangles.push_back({b, b + 1, b + 2});
        m.triangles.push_back({b, b + 2, b + 3});
      } else {
        m.triangles.push_back({b, b + 2, b + 1});
        m.triangles.push_back({b, b + 3, b + 2});
      }
      m.materials.insert(m.materials.end(), {material, material});
    }
}

}  // namespace rp::scene
