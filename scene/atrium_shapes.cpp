// Mesh builders of the atrium (scene/atrium_build.h).
#include <cmath>

#include "scene/atrium_build.h"

namespace rp::scene::atrium {

namespace {

constexpr double kTwoPi = 6.283185307179586;

uint32_t push(Mesh& m, const GridVertex& v) {
  m.vertices.push_back({v.p, v.n, v.uv});
  m.tangents.push_back(glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));  // compute_tangents sets them
  return uint32_t(m.vertices.size() - 1);
}

// Adds a b c, turned to face the sum of its vertex normals; drops a degenerate triangle.
void triangle(Mesh& m, uint32_t a, uint32_t b, uint32_t c, uint32_t material) {
  const glm::vec3 pa = m.vertices[a].position;
  const glm::vec3 cr = glm::cross(m.vertices[b].position - pa, m.vertices[c].position - pa);
  if (glm::dot(cr, cr) < 1e-14f) return;
  const glm::vec3 n = m.vertices[a].normal + m.vertices[b].normal + m.vertices[c].normal;
  if (glm::dot(cr, n) >= 0.0f)
    m.triangles.push_back({a, b, c});
  else
    m.triangles.push_back({a, c, b});
  m.materials.push_back(material);
}

}  // namespace

void append_grid(Mesh& m, int nu, int nv, uint32_t material, const GridFn& f) {
  const uint32_t base = uint32_t(m.vertices.size());
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) push(m, f(i, j));
  const auto at = [&](int i, int j) { return base + uint32_t(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      triangle(m, at(i, j), at(i + 1, j), at(i + 1, j + 1), material);
      triangle(m, at(i, j), at(i + 1, j + 1), at(i, j + 1), material);
    }
}

void append_tri_grid(Mesh& m, int n, uint32_t material, const GridFn& f) {
  const uint32_t base = uint32_t(m.vertices.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= j; ++i) push(m, f(i, j));
  const auto at = [&](int i, int j) { return base + uint32_t(j * (j + 1) / 2 + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i <= j; ++i) triangle(m, at(i, j), at(i, j + 1), at(i + 1, j + 1), material);
    for (int i = 0; i < j; ++i) triangle(m, at(i, j), at(i + 1, j + 1), at(i + 1, j), material);
  }
}

void append_block(Mesh& m, glm::vec3 lo, glm::vec3 hi, uint32_t material, float tile) {
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      glm::vec3 n(0.0f);
      n[axis] = side ? 1.0f : -1.0f;
      // u, v: the face's two other axes; v is y on the walls so textures stand upright.
      const int ua = axis == 1 ? 0 : (axis == 0 ? 2 : 0);
      const int va = axis == 1 ? 2 : 1;
      append_grid(m, 1, 1, material, [&](int i, int j) {
        glm::vec3 p = side ? hi : lo;
        p[ua] = i ? hi[ua] : lo[ua];
        p[va] = j ? hi[va] : lo[va];
        return GridVertex{p, n, glm::vec2(p[ua], p[va]) / tile};
      });
    }
}

void append_lathe(Mesh& m, glm::vec3 base, const std::vector<glm::vec2>& profile, int segments,
                  uint32_t material, float u_repeat, float tile) {
  const int last = int(profile.size()) - 1;
  std::vector<float> v(profile.size(), 0.0f);
  for (int k = 1; k <= last; ++k)
    v[size_t(k)] =
        v[size_t(k - 1)] + glm::length(profile[size_t(k)] - profile[size_t(k - 1)]) / tile;
  append_grid(m, segments, last, material, [&](int i, int j) {
    const double a = kTwoPi * double(i) / double(segments);
    const float c = float(std::cos(a)), s = float(std::sin(a));
    const glm::vec2 q = profile[size_t(j)];
    const glm::vec2 d =
        profile[size_t(std::min(j + 1, last))] - profile[size_t(std::max(j - 1, 0))];
    glm::vec2 rn = glm::vec2(d.y, -d.x);  // outward in the (radius, height) plane
    rn = glm::dot(rn, rn) > 0.0f ? glm::normalize(rn) : glm::vec2(1.0f, 0.0f);
    return GridVertex{base + glm::vec3(q.x * c, q.y, q.x * s), glm::vec3(rn.x * c, rn.y, rn.x * s),
                      glm::vec2(u_repeat * float(i) / float(segments), v[size_t(j)])};
  });
}

void append_tube(Mesh& m, glm::vec3 a, glm::vec3 b, float radius, int segments, uint32_t material) {
  const glm::vec3 axis = glm::normalize(b - a);
  const glm::vec3 side = std::abs(axis.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 e1 = glm::normalize(glm::cross(axis, side)), e2 = glm::cross(axis, e1);
  const float length = glm::length(b - a);
  append_grid(m, segments, 1, material, [&](int i, int j) {
    const double t = kTwoPi * double(i) / double(segments);
    const glm::vec3 n = e1 * float(std::cos(t)) + e2 * float(std::sin(t));
    return GridVertex{(j ? b : a) + radius * n, n,
                      glm::vec2(float(i) / float(segments), j ? length : 0.0f)};
  });
}

void compute_tangents(Mesh& m) {
  std::vector<glm::vec3> t(m.vertices.size(), glm::vec3(0.0f)),
      b(m.vertices.size(), glm::vec3(0.0f));
  for (const glm::uvec3& tri : m.triangles) {
    const Vertex& v0 = m.vertices[tri.x];
    const glm::vec3 e1 = m.vertices[tri.y].position - v0.position;
    const glm::vec3 e2 = m.vertices[tri.z].position - v0.position;
    const glm::vec2 d1 = m.vertices[tri.y].uv - v0.uv, d2 = m.vertices[tri.z].uv - v0.uv;
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-12f) continue;
    const glm::vec3 tu = (e1 * d2.y - e2 * d1.y) / det, tv = (e2 * d1.x - e1 * d2.x) / det;
    for (uint32_t k : {tri.x, tri.y, tri.z}) {
      t[k] += tu;
      b[k] += tv;
    }
  }
  m.tangents.resize(m.vertices.size());
  for (size_t k = 0; k < m.vertices.size(); ++k) {
    const glm::vec3 n = m.vertices[k].normal;
    glm::vec3 tk = t[k] - n * glm::dot(n, t[k]);
    if (glm::dot(tk, tk) < 1e-20f) {  // no uv gradient: any unit vector across the normal
      tk = glm::cross(n, std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0));
    }
    tk = glm::normalize(tk);
    const float w = glm::dot(glm::cross(n, tk), b[k]) < 0.0f ? -1.0f : 1.0f;
    m.tangents[k] = glm::vec4(tk, w);
  }
}

void append_mesh(Mesh& m, const Mesh& part, const glm::mat4& model) {
  const uint32_t base = uint32_t(m.vertices.size());
  const glm::mat3 r(model);
  for (size_t k = 0; k < part.vertices.size(); ++k) {
    const Vertex& v = part.vertices[k];
    m.vertices.push_back({glm::vec3(model * glm::vec4(v.position, 1.0f)), r * v.normal, v.uv});
    const glm::vec4 t = k < part.tangents.size() ? part.tangents[k] : glm::vec4(1, 0, 0, 1);
    m.tangents.push_back(glm::vec4(r * glm::vec3(t), t.w));
  }
  for (const glm::uvec3& tri : part.triangles) m.triangles.push_back(tri + glm::uvec3(base));
  m.materials.insert(m.materials.end(), part.materials.begin(), part.materials.end());
}

}  // namespace rp::scene::atrium
