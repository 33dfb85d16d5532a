#include "scene/tumbler_shape.h"

#include <algorithm>
#include <stdexcept>

namespace rp::scene {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// One ring of the mesh: height, profile radius, and the outward normal in the (y, r) half-plane.
struct Ring {
  float y, r;
  float normal_y, normal_r;
};

}  // namespace

float TumblerShape::radius(float y) const {
  if (y < -b || y > y_top()) return 0.0f;
  if (y < y_join_bottom()) return std::sqrt(std::max(0.0f, b * b - y * y));
  if (y <= y_join_top()) return -y * std::tan(alpha) + b / std::cos(alpha);
  const float dy = y - y_t;
  return std::sqrt(std::max(0.0f, t * t - dy * dy));
}

float TumblerShape::radius_slope(float y) const {
  if (y < y_join_bottom()) return -y / std::sqrt(b * b - y * y);
  if (y <= y_join_top()) return -std::tan(alpha);
  const float dy = y - y_t;
  return -dy / std::sqrt(t * t - dy * dy);
}

float TumblerShape::sdf(const glm::vec3& p) const {
  const float c = std::cos(alpha), s = std::sin(alpha);
  const float r = std::sqrt(p.x * p.x + p.z * p.z);
  const float y_rot = c * p.y - s * r;  // coordinate along the cone's side line
  const float r_rot = s * p.y + c * r;  // coordinate across it (b on the line)
  if (y_rot < 0.0f) return glm::length(p) - b;
  if (y_rot > y_t * c) return glm::length(p - glm::vec3(0.0f, y_t, 0.0f)) - t;
  return r_rot - b;
}

glm::vec3 TumblerShape::sdf_gradient(const glm::vec3& p) const {
  const float c = std::cos(alpha), s = std::sin(alpha);
  const float r = std::sqrt(p.x * p.x + p.z * p.z);
  const float y_rot = c * p.y - s * r;
  constexpr float kTiny = 1e-12f;
  if (y_rot < 0.0f) {
    const float len = glm::length(p);
    return len > kTiny ? p / len : glm::vec3(0.0f, -1.0f, 0.0f);
  }
  if (y_rot > y_t * c) {
    const glm::vec3 d = p - glm::vec3(0.0f, y_t, 0.0f);
    const float len = glm::length(d);
    return len > kTiny ? d / len : glm::vec3(0.0f, 1.0f, 0.0f);
  }
  if (r <= kTiny) return {c, s, 0.0f};
  return {c * p.x / r, s, c * p.z / r};
}

Mesh make_tumbler_mesh(const TumblerShape& shape, const TumblerMeshParams& params,
                       uint32_t material) {
  if (params.segments < 3 || params.bottom_rings < 1 || params.cone_rings < 1 ||
      params.top_rings < 1) {
    throw std::invalid_argument("make_tumbler_mesh: need segments >= 3 and rings >= 1");
  }
  const float sa = std::sin(shape.alpha), ca = std::cos(shape.alpha);

  // Rings strictly between the poles, bottom to top. Each join ring is generated once and shared
  // by the two pieces that meet there, so the pieces connect without cracks.
  std::vector<Ring> rings;
  const float phi_bottom = kPi / 2.0f + shape.alpha;  // bottom cap: angle from -y, pole to join
  for (int k = 1; k <= params.bottom_rings; ++k) {
    const float phi = phi_bottom * static_cast<float>(k) / static_cast<float>(params.bottom_rings);
    rings.push_back({-shape.b * std::cos(phi), shape.b * std::sin(phi), -std::cos(phi),
                     std::sin(phi)});
  }
  rings.back() = {shape.y_join_bottom(), shape.b * ca, sa, ca};  // exact join values
  for (int k = 1; k <= params.cone_rings; ++k) {
    const float f = static_cast<float>(k) / static_cast<float>(params.cone_rings);
    const float y = shape.y_join_bottom() + f * (shape.y_join_top() - shape.y_join_bottom());
    rings.push_back({y, -y * std::tan(shape.alpha) + shape.b / ca, sa, ca});
  }
  rings.back() = {shape.y_join_top(), shape.t * ca, sa, ca};
  const float phi_top = kPi / 2.0f - shape.alpha;  // top cap: angle from +y, join to pole
  for (int k = 1; k < params.top_rings; ++k) {
    const float phi =
        phi_top * (1.0f - static_cast<float>(k) / static_cast<float>(params.top_rings));
    rings.push_back({shape.y_t + shape.t * std::cos(phi), shape.t * std::sin(phi), std::cos(phi),
                     std::sin(phi)});
  }

  // Azimuth table: column j has u = j / S; the front (+z) is at u = 0.5, +x at u = 0.75.
  // Column S repeats column 0's direction exactly (seam with u = 1).
  const int S = params.segments;
  std::vector<glm::vec2> dir(static_cast<size_t>(S) + 1);
  for (int j = 0; j <= S; ++j) {
    const float theta = 2.0f * kPi * static_cast<float>(j % S) / static_cast<float>(S);
    dir[j] = {-std::sin(theta), -std::cos(theta)};
  }

  Mesh mesh;
  mesh.name = "tumbler";
  const float v_scale = 1.0f / shape.height();
  auto v_of = [&](float y) { return (y - shape.y_bottom()) * v_scale; };

  // Bottom pole: one vertex per segment (same position, u at the segment's middle).
  const uint32_t bottom_pole = 0;
  for (int j = 0; j < S; ++j) {
    mesh.vertices.push_back({glm::vec3(0.0f, shape.y_bottom(), 0.0f), glm::vec3(0.0f, -1.0f, 0.0f),
                             glm::vec2((static_cast<float>(j) + 0.5f) / static_cast<float>(S), 0.0f)});
  }
  const uint32_t first_ring = static_cast<uint32_t>(mesh.vertices.size());
  for (const Ring& ring : rings) {
    for (int j = 0; j <= S; ++j) {
      mesh.vertices.push_back(
          {glm::vec3(ring.r * dir[j].x, ring.y, ring.r * dir[j].y),
           glm::normalize(glm::vec3(ring.normal_r * dir[j].x, ring.normal_y, ring.normal_r * dir[j].y)),
           glm::vec2(static_cast<float>(j) / static_cast<float>(S), v_of(ring.y))});
    }
  }
  const uint32_t top_pole = static_cast<uint32_t>(mesh.vertices.size());
  for (int j = 0; j < S; ++j) {
    mesh.vertices.push_back({glm::vec3(0.0f, shape.y_top(), 0.0f), glm::vec3(0.0f, 1.0f, 0.0f),
                             glm::vec2((static_cast<float>(j) + 0.5f) / static_cast<float>(S), 1.0f)});
  }

  const uint32_t stride = static_cast<uint32_t>(S) + 1;
  auto at = [&](size_t ring, int j) {
    return first_ring + static_cast<uint32_t>(ring) * stride + static_cast<uint32_t>(j);
  };
  // Seen from outside, u grows to the right and y grows upwards, so (lower-left, lower-right,
  // upper-right) is counter-clockwise.
  for (int j = 0; j < S; ++j) {
    mesh.triangles.push_back({bottom_pole + static_cast<uint32_t>(j), at(0, j + 1), at(0, j)});
  }
  for (size_t i = 0; i + 1 < rings.size(); ++i) {
    for (int j = 0; j < S; ++j) {
      mesh.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  }
  const size_t last = rings.size() - 1;
  for (int j = 0; j < S; ++j) {
    mesh.triangles.push_back({at(last, j), at(last, j + 1), top_pole + static_cast<uint32_t>(j)});
  }
  mesh.materials.assign(mesh.triangles.size(), material);
  return mesh;
}

}  // namespace rp::scene
