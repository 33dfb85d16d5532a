#include "scene/box_mesh.h"

#include <algorithm>
#include <cmath>

namespace rp::scene {

void append_box(Mesh& m, glm::vec3 center, glm::vec3 half, uint32_t material, float uv_repeat,
                float max_cell) {
  for (int axis = 0; axis < 3; ++axis)
    for (float s : {-1.0f, 1.0f}) {
      glm::vec3 n(0.0f), u(0.0f), v(0.0f);
      n[axis] = s;
      u[(axis + 1) % 3] = 1.0f;
      v[(axis + 2) % 3] = 1.0f;
      // Quads along u and v: one, or as many as keep each side within max_cell.
      const auto cells = [&](float side) {
        return max_cell > 0.0f ? std::max(1, int(std::ceil(side / max_cell - 1e-4f))) : 1;
      };
      const int cu = cells(2.0f * glm::dot(half, u)), cv = cells(2.0f * glm::dot(half, v));
      const uint32_t b = uint32_t(m.vertices.size());
      const float w = glm::dot(glm::cross(n, u), v) > 0.0f ? 1.0f : -1.0f;
      if (cu == 1 && cv == 1) {  // one quad, its corners in the order the files have always had
        const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (const auto& k : corners)
          m.vertices.push_back({center + half * (n + k[0] * u + k[1] * v), n,
                                glm::vec2(0.5f + 0.5f * k[0], 0.5f + 0.5f * k[1]) * uv_repeat});
        for (int k = 0; k < 4; ++k) m.tangents.push_back(glm::vec4(u, w));
        if (s > 0) {
          m.triangles.push_back({b, b + 1, b + 2});
          m.triangles.push_back({b, b + 2, b + 3});
        } else {
          m.triangles.push_back({b, b + 2, b + 1});
          m.triangles.push_back({b, b + 3, b + 2});
        }
        m.materials.insert(m.materials.end(), {material, material});
        continue;
      }
      for (int j = 0; j <= cv; ++j)
        for (int i = 0; i <= cu; ++i) {
          const float ku = -1.0f + 2.0f * float(i) / float(cu);
          const float kv = -1.0f + 2.0f * float(j) / float(cv);
          m.vertices.push_back({center + half * (n + ku * u + kv * v), n,
                                glm::vec2(0.5f + 0.5f * ku, 0.5f + 0.5f * kv) * uv_repeat});
        }
      for (int k = 0; k < (cu + 1) * (cv + 1); ++k) m.tangents.push_back(glm::vec4(u, w));
      for (int j = 0; j < cv; ++j)
        for (int i = 0; i < cu; ++i) {
          // corners counter-clockwise in (u, v): as the single quad's -1,-1 / 1,-1 / 1,1 / -1,1
          const uint32_t c0 = b + uint32_t(j * (cu + 1) + i), c1 = c0 + 1,
                         c2 = c1 + uint32_t(cu + 1), c3 = c0 + uint32_t(cu + 1);
          if (s > 0) {
            m.triangles.push_back({c0, c1, c2});
            m.triangles.push_back({c0, c2, c3});
          } else {
            m.triangles.push_back({c0, c2, c1});
            m.triangles.push_back({c0, c3, c2});
          }
          m.materials.insert(m.materials.end(), {material, material});
        }
    }
}

}  // namespace rp::scene
