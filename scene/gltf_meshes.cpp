// A glTF mesh as one scene::Mesh: its TRIANGLES primitives merged (the material per triangle),
// texture v flipped to rolypoly's v-up, normals and tangents made where the file has none.
#include <cmath>

#include <tiny_gltf.h>

#include "scene/gltf_internal.h"

namespace rp::scene::gltf {
namespace {

// A unit vector perpendicular to unit `n`, for tangents that UVs cannot give.
glm::vec3 any_perpendicular(glm::vec3 n) {
  const glm::vec3 axis = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(axis, n));
}

// Unit normal, or `fallback` where the vector has no direction.
glm::vec3 unit_or(glm::dvec3 v, glm::vec3 fallback) {
  const double len = glm::length(v);
  if (!(len > 1e-30) || !std::isfinite(len)) return fallback;
  return glm::vec3(v / len);
}

glm::dvec3 face_normal(const std::vector<Vertex>& v, const glm::uvec3& t) {  // |n| = 2 x area
  const glm::dvec3 a(v[t.x].position), b(v[t.y].position), c(v[t.z].position);
  return glm::cross(b - a, c - a);
}

// Per-vertex tangents from the UV layout: each triangle's dP/du and dP/dv (v up, as stored)
// summed at its corners, then made perpendicular to the normal (Gram-Schmidt); w is the sign
// that makes w * cross(normal, tangent) point along dP/dv, as glTF's TANGENT defines it.
std::vector<glm::vec4> compute_tangents(const std::vector<Vertex>& v,
                                        const std::vector<glm::uvec3>& tris) {
  std::vector<glm::dvec3> du(v.size(), glm::dvec3(0.0)), dv(v.size(), glm::dvec3(0.0));
  for (const glm::uvec3& t : tris) {
    const glm::dvec3 p0(v[t.x].position), e1 = glm::dvec3(v[t.y].position) - p0,
                                          e2 = glm::dvec3(v[t.z].position) - p0;
    const glm::dvec2 t0(v[t.x].uv), d1 = glm::dvec2(v[t.y].uv) - t0,
                                    d2 = glm::dvec2(v[t.z].uv) - t0;
    const double det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-20) continue;  // no UV area: no direction to give
    const glm::dvec3 tu = (e1 * d2.y - e2 * d1.y) / det, tv = (e2 * d1.x - e1 * d2.x) / det;
    if (!std::isfinite(glm::dot(tu, tu)) || !std::isfinite(glm::dot(tv, tv))) continue;
    for (uint32_t i : {t.x, t.y, t.z}) {
      du[i] += tu;
      dv[i] += tv;
    }
  }
  std::vector<glm::vec4> out(v.size());
  for (size_t i = 0; i < v.size(); ++i) {
    const glm::dvec3 n(v[i].normal);
    const glm::vec3 t = unit_or(du[i] - n * glm::dot(n, du[i]), any_perpendicular(v[i].normal));
    const double w = glm::dot(glm::cross(n, glm::dvec3(t)), dv[i]) < 0.0 ? -1.0 : 1.0;
    out[i] = glm::vec4(t, static_cast<float>(w));
  }
  return out;
}

struct Attributes {
  std::vector<float> position, normal, uv, tangent;
};

int attribute(const tinygltf::Primitive& p, const char* name) {
  const auto it = p.attributes.find(name);
  return it == p.attributes.end() ? -1 : it->second;
}

Attributes read_attributes(Context& ctx, const tinygltf::Primitive& p, bool want_tangents,
                           const std::string& where) {
  Attributes a;
  const int position = attribute(p, "POSITION");
  if (position < 0) ctx.fail(where + " has no POSITION");
  a.position = read_floats(ctx, position, 3, false, where + " POSITION");
  const size_t n = a.position.size() / 3;
  auto read = [&](const char* name, int components, bool unorm, std::vector<float>* out) {
    const int index = attribute(p, name);
    if (index < 0) return;
    *out = read_floats(ctx, index, components, unorm, where + " " + name);
    if (out->size() / static_cast<size_t>(components) != n)
      ctx.fail(where + ": " + name + " has " +
               std::to_string(out->size() / static_cast<size_t>(components)) +
               " elements, POSITION " + std::to_string(n));
  };
  read("NORMAL", 3, false, &a.normal);
  read("TEXCOORD_0", 2, true, &a.uv);
  if (want_tangents) read("TANGENT", 4, false, &a.tangent);
  return a;
}

void add_vertices(Context& ctx, uint64_t n, const std::string& where) {
  if (ctx.vertices + n > ctx.limits.max_vertices)
    ctx.fail(where + ": the scene has more than " + std::to_string(ctx.limits.max_vertices) +
             " vertices");
  ctx.vertices += n;
}

// One primitive's vertices, triangles (local indices) and tangents (when wanted).
struct Part {
  std::vector<Vertex> vertices;
  std::vector<glm::uvec3> triangles;
  std::vector<glm::vec4> tangents;
};

Part build_part(Context& ctx, const Attributes& a, const std::vector<uint32_t>& indices,
                bool want_tangents, const std::string& where) {
  const size_t n = a.position.size() / 3;
  auto vertex = [&](size_t i) {
    Vertex v;
    v.position = {a.position[3 * i], a.position[3 * i + 1], a.position[3 * i + 2]};
    v.normal = a.normal.empty()
                   ? glm::vec3(0.0f)
                   : glm::vec3(a.normal[3 * i], a.normal[3 * i + 1], a.normal[3 * i + 2]);
    // glTF's v runs down the image, rolypoly's up (texel row = (1 - v) * height).
    v.uv = a.uv.empty() ? glm::vec2(0.0f) : glm::vec2(a.uv[2 * i], 1.0f - a.uv[2 * i + 1]);
    return v;
  };
  auto tangent = [&](size_t i, glm::vec3 normal) {
    const glm::vec3 t(a.tangent[4 * i], a.tangent[4 * i + 1], a.tangent[4 * i + 2]);
    return glm::vec4(unit_or(t, any_perpendicular(normal)),
                     a.tangent[4 * i + 3] < 0.0f ? -1.0f : 1.0f);
  };
  Part part;
  const size_t tris = indices.size() / 3;
  if (a.normal.empty()) {
    // glTF: without normals, flat shading. Each triangle gets its own three vertices.
    add_vertices(ctx, 3 * uint64_t{tris}, where);
    part.vertices.reserve(3 * tris);
    part.triangles.reserve(tris);
    for (size_t t = 0; t < tris; ++t) {
      const uint32_t base = static_cast<uint32_t>(3 * t);
      for (int k = 0; k < 3; ++k)
        part.vertices.push_back(vertex(indices[3 * t + static_cast<size_t>(k)]));
      const glm::uvec3 tri(base, base + 1, base + 2);
      const glm::vec3 normal = unit_or(face_normal(part.vertices, tri), glm::vec3(0, 0, 1));
      for (int k = 0; k < 3; ++k) part.vertices[base + static_cast<uint32_t>(k)].normal = normal;
      part.triangles.push_back(tri);
    }
    if (want_tangents && !a.tangent.empty())
      for (size_t t = 0; t < tris; ++t)
        for (int k = 0; k < 3; ++k)
          part.tangents.push_back(
              tangent(indices[3 * t + static_cast<size_t>(k)], part.vertices[3 * t].normal));
  } else {
    add_vertices(ctx, n, where);
    part.vertices.reserve(n);
    for (size_t i = 0; i < n; ++i) part.vertices.push_back(vertex(i));
    part.triangles.reserve(tris);
    for (size_t t = 0; t < tris; ++t)
      part.triangles.emplace_back(indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]);
    // Normals the file gives are made unit; one of no length takes the area-weighted normal of
    // the triangles around it.
    std::vector<glm::dvec3> around;
    for (size_t i = 0; i < n; ++i) {
      const glm::vec3 given = part.vertices[i].normal;
      part.vertices[i].normal = unit_or(glm::dvec3(given), glm::vec3(0.0f));
      if (part.vertices[i].normal == glm::vec3(0.0f) && around.empty()) {
        around.assign(n, glm::dvec3(0.0));
        for (const glm::uvec3& t : part.triangles) {
          const glm::dvec3 f = face_normal(part.vertices, t);
          around[t.x] += f;
          around[t.y] += f;
          around[t.z] += f;
        }
      }
      if (part.vertices[i].normal == glm::vec3(0.0f))
        part.vertices[i].normal = unit_or(around[i], glm::vec3(0, 0, 1));
    }
    if (want_tangents && !a.tangent.empty())
      for (size_t i = 0; i < n; ++i) part.tangents.push_back(tangent(i, part.vertices[i].normal));
  }
  if (want_tangents && part.tangents.empty())
    part.tangents = compute_tangents(part.vertices, part.triangles);
  return part;
}

}  // namespace

std::optional<Mesh> convert_mesh(Context& ctx, int index, MaterialTable& materials) {
  const tinygltf::Model& model = *ctx.model;
  const tinygltf::Mesh& g = model.meshes.at(static_cast<size_t>(index));  // checked by the caller
  const std::string at = "mesh " + std::to_string(index);
  auto draws_triangles = [](const tinygltf::Primitive& p) { return p.mode == -1 || p.mode == 4; };
  // One normal-mapped primitive gives the whole mesh tangents (scene::Mesh has one array).
  bool want_tangents = false;
  for (const tinygltf::Primitive& p : g.primitives)
    want_tangents = want_tangents || (draws_triangles(p) && materials.has_normal_map(p.material));

  Mesh mesh;
  mesh.name = g.name.empty() ? at : g.name;  // the loader appends " (mirrored)" to copies
  for (size_t pi = 0; pi < g.primitives.size(); ++pi) {
    const tinygltf::Primitive& p = g.primitives[pi];
    const std::string where = at + " primitive " + std::to_string(pi);
    if (!p.targets.empty())
      ctx.warnings.add("morph targets are ignored (the base shape is drawn)", where);
    if (!draws_triangles(p)) {
      ctx.warnings.add(
          "primitives that are not TRIANGLES (points, lines, strips, fans) are skipped", where);
      continue;
    }
    const Attributes a = read_attributes(ctx, p, want_tangents, where);
    const size_t n = a.position.size() / 3;
    std::vector<uint32_t> indices;
    if (p.indices >= 0) {
      indices = read_indices(ctx, p.indices, where + " indices");
      for (size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= n)
          ctx.fail(where + ": index " + std::to_string(i) + " of accessor " +
                   std::to_string(p.indices) + " is vertex " + std::to_string(indices[i]) +
                   ", and there are " + std::to_string(n));
    } else {
      indices.resize(n);
      for (size_t i = 0; i < n; ++i) indices[i] = static_cast<uint32_t>(i);
    }
    if (indices.size() % 3 != 0)
      ctx.warnings.add("index counts that are not a multiple of 3 lose their last indices", where);
    const uint64_t tris = indices.size() / 3;
    if (tris == 0) continue;
    if (ctx.triangles + tris > ctx.limits.max_triangles)
      ctx.fail(where + ": the scene has more than " + std::to_string(ctx.limits.max_triangles) +
               " triangles");
    ctx.triangles += tris;
    const uint32_t material = materials.material(p.material, where);
    const Part part = build_part(ctx, a, indices, want_tangents, where);
    const uint32_t base = static_cast<uint32_t>(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), part.vertices.begin(), part.vertices.end());
    mesh.tangents.insert(mesh.tangents.end(), part.tangents.begin(), part.tangents.end());
    for (const glm::uvec3& t : part.triangles) mesh.triangles.push_back(t + base);
    mesh.materials.resize(mesh.triangles.size(), material);
  }
  if (mesh.triangles.empty()) return std::nullopt;
  return mesh;
}

Mesh mirrored(const Mesh& mesh) {
  Mesh m = mesh;
  for (glm::uvec3& t : m.triangles) std::swap(t.y, t.z);
  for (glm::vec4& t : m.tangents) t.w = -t.w;
  return m;
}

}  // namespace rp::scene::gltf
