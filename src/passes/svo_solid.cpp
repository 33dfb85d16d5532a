#include "passes/svo_solid.h"

#include <algorithm>
#include <cmath>

#include "kernels/shared/svo_layout.h"

namespace rp::passes {

size_t svo_solid_level_offset(uint32_t resolution, uint32_t level) {
  size_t offset = 0;
  for (uint32_t l = kSvoSolidFirstLevel; l < level; ++l) {
    const size_t n = resolution >> l;
    offset += n * n * n;
  }
  return offset;
}

size_t svo_solid_bytes(uint32_t resolution) {
  const uint32_t depths = gpu::rp_svo_log2(resolution);
  return depths > kSvoSolidFirstLevel ? svo_solid_level_offset(resolution, depths) : 0;
}

namespace {

// Signed distance (world units, negative inside) from p to the nearest object, and whether any
// object lies within `reach` of p (cells far from every object are skipped by the caller).
struct Shape {
  bool tumbler = false;
  glm::mat4 to_local{1.0f};
  glm::vec4 sphere{0.0f};
  float sdf(const scene::TumblerShape& t, const glm::vec3& p) const {
    if (tumbler) return t.sdf(glm::vec3(to_local * glm::vec4(p, 1.0f)));
    return glm::length(p - glm::vec3(sphere)) - sphere.w;
  }
};

}  // namespace

std::vector<uint8_t> svo_solid_grid(uint32_t resolution, const SolidObjects& objects) {
  const size_t bytes = svo_solid_bytes(resolution);
  std::vector<uint8_t> grid(bytes, 0);
  if (bytes == 0) return grid;
  const uint32_t depths = gpu::rp_svo_log2(resolution);
  const uint32_t n = resolution >> kSvoSolidFirstLevel;
  const float cell = 2.0f / float(n);  // world units
  const float half_diagonal = 0.5f * std::sqrt(3.0f) * cell;
  std::vector<float> frac(size_t(n) * n * n, 0.0f);

  std::vector<Shape> shapes;
  std::vector<glm::vec3> lo, hi;  // world bounding boxes
  const scene::TumblerShape& t = objects.tumbler;
  // the tumbler in its local frame: within b of the axis, y in [-b, y_t + t]
  for (const glm::mat4& to_local : objects.tumbler_world_to_local) {
    Shape s;
    s.tumbler = true;
    s.to_local = to_local;
    const glm::mat4 to_world = glm::inverse(to_local);
    glm::vec3 l(1e30f), h(-1e30f);
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 corner((c & 1) ? t.b : -t.b, (c & 2) ? t.y_top() : t.y_bottom(),
                             (c & 4) ? t.b : -t.b);
      const glm::vec3 w(to_world * glm::vec4(corner, 1.0f));
      l = glm::min(l, w);
      h = glm::max(h, w);
    }
    shapes.push_back(s);
    lo.push_back(l);
    hi.push_back(h);
  }
  for (const glm::vec4& sp : objects.spheres) {
    Shape s;
    s.sphere = sp;
    shapes.push_back(s);
    lo.push_back(glm::vec3(sp) - sp.w);
    hi.push_back(glm::vec3(sp) + sp.w);
  }

  // Level kSvoSolidFirstLevel. Objects do not overlap in the scenes (and an overlap would only
  // count twice, clamped to 1).
  for (size_t i = 0; i < shapes.size(); ++i) {
    int a0[3], a1[3];
    for (int k = 0; k < 3; ++k) {
      a0[k] = std::clamp(int(std::floor((lo[i][k] + 1.0f) / cell)), 0, int(n) - 1);
      a1[k] = std::clamp(int(std::floor((hi[i][k] + 1.0f) / cell)), 0, int(n) - 1);
    }
    for (int z = a0[2]; z <= a1[2]; ++z)
      for (int y = a0[1]; y <= a1[1]; ++y)
        for (int x = a0[0]; x <= a1[0]; ++x) {
          const glm::vec3 c0(-1.0f + cell * float(x), -1.0f + cell * float(y),
                             -1.0f + cell * float(z));
          const float d = shapes[i].sdf(t, c0 + 0.5f * cell);
          float f = 0.0f;
          if (d <= -half_diagonal) {
            f = 1.0f;
          } else if (d < half_diagonal) {
            // the share of the cell behind a plane at distance d from its centre, along an
            // axis (within 0.05 of it for other normals; the surfaces curve little over a cell)
            f = std::clamp(0.5f - d / cell, 0.0f, 1.0f);
          }
          float& cellf = frac[(size_t(z) * n + y) * n + x];
          cellf = std::min(cellf + f, 1.0f);
        }
  }

  // Store, and the coarser levels as means of 8.
  uint32_t m = n;
  for (uint32_t level = kSvoSolidFirstLevel; level < depths; ++level) {
    uint8_t* out = grid.data() + svo_solid_level_offset(resolution, level);
    for (size_t v = 0; v < frac.size(); ++v) out[v] = uint8_t(std::lround(frac[v] * 255.0f));
    if (level + 1 == depths) break;
    const uint32_t h = m / 2;
    std::vector<float> next(size_t(h) * h * h, 0.0f);
    for (uint32_t z = 0; z < h; ++z)
      for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < h; ++x) {
          float s = 0.0f;
          for (uint32_t o = 0; o < 8; ++o)
            s += frac[(size_t(2 * z + (o >> 2)) * m + 2 * y + ((o >> 1) & 1)) * m + 2 * x +
                      (o & 1)];
          next[(size_t(z) * h + y) * h + x] = s * 0.125f;
        }
    frac.swap(next);
    m = h;
  }
  return grid;
}

}  // namespace rp::passes
