// load_gltf: a glTF 2.0 file as a static scene. The steps live in their own files:
// gltf_files.cpp (reading files), gltf_source.cpp and gltf_json_checks.cpp (checking the file,
// then tinygltf), gltf_accessors.cpp, gltf_meshes.cpp, gltf_materials.cpp and gltf_nodes.cpp.
// This file picks the scene, places instances, lights and the camera, and computes the bounds.
#include "scene/gltf_loader.h"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <tiny_gltf.h>

#include "scene/gltf_internal.h"

namespace rp::scene {
namespace gltf {
namespace {

// Extensions the loader implements; the contents of any other are ignored (one warning).
const std::set<std::string> kImplemented = {"KHR_lights_punctual",
                                            "KHR_materials_emissive_strength", "KHR_materials_ior"};

void warn_unsupported(Context& ctx) {
  const tinygltf::Model& m = *ctx.model;
  std::string names;
  size_t count = 0;
  for (const std::string& e : m.extensionsUsed) {
    if (kImplemented.count(e)) continue;
    if (++count <= 12) names += (names.empty() ? "" : ", ") + e.substr(0, 64);
  }
  if (count > 12) names += " and " + std::to_string(count - 12) + " more";
  if (count) ctx.warnings.add("unsupported extensions are ignored: " + names);
  if (!m.animations.empty()) ctx.warnings.add("animations are ignored (the static pose is drawn)");
  if (!m.skins.empty()) ctx.warnings.add("skins are ignored (skinned meshes are drawn unposed)");
}

// The default scene's root nodes; scene 0's without a default; without scenes, every node that
// is no node's child. `scene` is the index used, or -1.
std::vector<int> scene_roots(Context& ctx, int* scene) {
  const tinygltf::Model& m = *ctx.model;
  *scene = m.defaultScene >= 0 ? m.defaultScene : (m.scenes.empty() ? -1 : 0);
  if (*scene >= 0) {
    if (static_cast<size_t>(*scene) >= m.scenes.size())
      ctx.fail("scene " + std::to_string(*scene) + " (the default) does not exist (" +
               std::to_string(m.scenes.size()) + " scenes)");
    if (m.scenes.size() > 1)
      ctx.warnings.add("only scene " + std::to_string(*scene) + " of the file's " +
                       std::to_string(m.scenes.size()) + " is loaded");
    return m.scenes[static_cast<size_t>(*scene)].nodes;
  }
  std::vector<char> is_child(m.nodes.size(), 0);
  for (const tinygltf::Node& n : m.nodes)
    for (const int c : n.children)
      if (c >= 0 && static_cast<size_t>(c) < m.nodes.size()) is_child[static_cast<size_t>(c)] = 1;
  std::vector<int> roots;
  for (size_t i = 0; i < m.nodes.size(); ++i)
    if (!is_child[i]) roots.push_back(static_cast<int>(i));
  return roots;
}

// The scene's (else the asset's) extras {"rolypoly": {"volume": [x0, y0, z0, x1, y1, z1]}}.
std::optional<Bounds> volume_extra(Context& ctx, int scene) {
  const tinygltf::Model& m = *ctx.model;
  const tinygltf::Value* extras = &m.asset.extras;
  std::string where = "asset";
  if (scene >= 0 && m.scenes[static_cast<size_t>(scene)].extras.Has("rolypoly")) {
    extras = &m.scenes[static_cast<size_t>(scene)].extras;
    where = "scene " + std::to_string(scene);
  }
  if (!extras->Has("rolypoly") || !extras->Get("rolypoly").Has("volume")) return std::nullopt;
  const tinygltf::Value& v = extras->Get("rolypoly").Get("volume");
  const std::string bad = where +
                          ": extras.rolypoly.volume must be 6 finite numbers "
                          "[x0, y0, z0, x1, y1, z1] with x0 < x1, y0 < y1, z0 < z1";
  if (!v.IsArray() || v.ArrayLen() != 6) ctx.fail(bad);
  float c[6];
  for (int i = 0; i < 6; ++i) {
    const tinygltf::Value& e = v.Get(i);
    if (!e.IsNumber() || !fits_float(e.GetNumberAsDouble())) ctx.fail(bad);
    c[i] = static_cast<float>(e.GetNumberAsDouble());
  }
  if (!(c[0] < c[3] && c[1] < c[4] && c[2] < c[5])) ctx.fail(bad);
  return Bounds{{c[0], c[1], c[2]}, {c[3], c[4], c[5]}};
}

void grow(Bounds& b, glm::vec3 p) {
  b.lo = glm::min(b.lo, p);
  b.hi = glm::max(b.hi, p);
}

// World bounds of every instance's vertices. Exact while the instance-vertex transforms stay
// within the limit; past it (thousands of instances of big meshes) each instance adds its
// mesh's transformed box, which holds the exact bounds and costs 8 points.
Bounds world_bounds(const Context& ctx, const LoadedScene& s) {
  Bounds b{glm::vec3(std::numeric_limits<float>::max()),
           glm::vec3(-std::numeric_limits<float>::max())};
  uint64_t work = 0;
  for (const MeshInstance& inst : s.instances) work += s.assets.meshes[inst.mesh].vertices.size();
  const bool exact = work <= ctx.limits.max_bounds_work;
  std::vector<Bounds> local(s.assets.meshes.size(), b);
  if (!exact)
    for (size_t i = 0; i < local.size(); ++i)
      for (const Vertex& v : s.assets.meshes[i].vertices) grow(local[i], v.position);
  for (const MeshInstance& inst : s.instances) {
    if (exact) {
      for (const Vertex& v : s.assets.meshes[inst.mesh].vertices)
        grow(b, glm::vec3(inst.model * glm::vec4(v.position, 1.0f)));
    } else {
      const Bounds& l = local[inst.mesh];
      for (int k = 0; k < 8; ++k) {
        const glm::vec3 corner(k & 1 ? l.hi.x : l.lo.x, k & 2 ? l.hi.y : l.lo.y,
                               k & 4 ? l.hi.z : l.lo.z);
        grow(b, glm::vec3(inst.model * glm::vec4(corner, 1.0f)));
      }
    }
  }
  return b;
}

}  // namespace

void Warnings::add(const std::string& kind, const std::string& place) {
  auto it =
      std::find_if(kinds_.begin(), kinds_.end(), [&](const auto& k) { return k.first == kind; });
  if (it == kinds_.end()) it = kinds_.insert(kinds_.end(), {kind, Kind{}});
  ++it->second.count;
  if (!place.empty() && it->second.places.size() < 4) it->second.places.push_back(place);
}

std::vector<std::string> Warnings::lines() const {
  std::vector<std::string> out;
  for (const auto& [kind, k] : kinds_) {
    std::string line = kind;
    for (size_t i = 0; i < k.places.size(); ++i) line += (i == 0 ? ": " : ", ") + k.places[i];
    if (!k.places.empty() && k.count > k.places.size())
      line += " and " + std::to_string(k.count - k.places.size()) + " more";
    out.push_back(line);
  }
  return out;
}

void Context::fail(const std::string& what) const { throw SceneFileError(file + ": " + what); }

LoadedScene load_gltf_from_memory(const std::vector<uint8_t>& bytes, const std::string& path,
                                  const Limits& limits) {
  Context ctx;
  ctx.file = path;
  ctx.limits = limits;
  tinygltf::Model model;
  const auto parse_start = std::chrono::steady_clock::now();
  load_model(ctx, bytes, &model);
  const double parse_ms = std::chrono::duration<double, std::milli>(
                              std::chrono::steady_clock::now() - parse_start)
                              .count();
  ctx.model = &model;
  warn_unsupported(ctx);

  LoadedScene out;
  int scene = -1;
  const std::vector<int> roots = scene_roots(ctx, &scene);
  MaterialTable materials(ctx, out.assets);
  // (glTF mesh, mirrored) -> index into out.assets.meshes, or -1: no triangles.
  std::map<std::pair<int, bool>, int> slots;
  auto mesh_slot = [&](int mesh, bool mirror) {
    if (const auto it = slots.find({mesh, mirror}); it != slots.end()) return it->second;
    std::optional<Mesh> converted;
    if (const auto other = slots.find({mesh, !mirror}); other != slots.end()) {
      if (other->second >= 0) {
        // Mirroring twice gives the mesh back; the copy counts against the limits again.
        converted = mirrored(out.assets.meshes[static_cast<size_t>(other->second)]);
        ctx.vertices += converted->vertices.size();
        ctx.triangles += converted->triangles.size();
        if (ctx.vertices > ctx.limits.max_vertices || ctx.triangles > ctx.limits.max_triangles)
          ctx.fail("mesh " + std::to_string(mesh) +
                   ": the scene has too many vertices or triangles");
      }
    } else {
      converted = convert_mesh(ctx, mesh, materials);
      if (converted && mirror) converted = mirrored(*converted);
    }
    if (converted) {
      const std::string& name = model.meshes[static_cast<size_t>(mesh)].name;
      converted->name =
          (name.empty() ? "mesh " + std::to_string(mesh) : name) + (mirror ? " (mirrored)" : "");
    }
    int slot = -1;
    if (converted) {
      slot = static_cast<int>(out.assets.meshes.size());
      out.assets.meshes.push_back(std::move(*converted));
    }
    slots[{mesh, mirror}] = slot;
    return slot;
  };

  std::optional<PlacedCamera> camera;
  walk_nodes(ctx, roots, [&](int node, const glm::dmat4& world) {
    const tinygltf::Node& n = model.nodes[static_cast<size_t>(node)];
    const std::string where = "node " + std::to_string(node);
    if (n.mesh >= 0) {
      if (static_cast<size_t>(n.mesh) >= model.meshes.size())
        ctx.fail(where + ": mesh " + std::to_string(n.mesh) + " does not exist (" +
                 std::to_string(model.meshes.size()) + " meshes)");
      // A mirroring transform turns counter-clockwise triangles clockwise; such instances
      // draw a copy with the winding reversed.
      const bool mirror = glm::determinant(glm::dmat3(world)) < 0.0;
      if (const int slot = mesh_slot(n.mesh, mirror); slot >= 0) {
        MeshInstance inst;
        inst.mesh = static_cast<uint32_t>(slot);
        inst.model = inst.prev_model = glm::mat4(world);
        instance_flags(ctx, node, &inst);
        out.instances.push_back(inst);
      }
    }
    if (const int light = node_light(ctx, node); light >= 0) {
      if (auto l = convert_light(ctx, light, world, where)) {
        // The demo's lamp (exported by rolypoly) is restored as the lamp, once.
        if (auto lamp = lamp_of(ctx, light, *l); lamp && !out.lamp) {
          out.lamp = *lamp;
        } else {
          if (lamp)
            ctx.warnings.add("only the first light marked as rolypoly's lamp is the lamp", where);
          out.lights.push_back(std::move(*l));
        }
      }
    }
    if (n.camera >= 0 && !camera) camera = convert_camera(ctx, n.camera, world, where);
  });
  if (out.instances.empty())
    ctx.fail("has no triangles to render (" + std::to_string(roots.size()) + " root nodes, " +
             std::to_string(model.meshes.size()) + " meshes)");

  out.bounds = world_bounds(ctx, out);
  for (int c = 0; c < 3; ++c)
    if (!fits_float(out.bounds.lo[c]) || !fits_float(out.bounds.hi[c]))
      ctx.fail("the scene's world coordinates overflow the float range");
  if (camera) {
    if (camera->far_from_bounds) {
      // No zfar in the file: far enough to hold the whole scene from where the camera is.
      const float reach = glm::distance(camera->camera.position, out.bounds.center()) +
                          0.5f * glm::length(out.bounds.size());
      const float far = std::max(1.5f * reach, 2.0f * camera->camera.near_plane);
      camera->camera.far_plane = std::isfinite(far) ? far : std::numeric_limits<float>::max();
    }
    out.camera = camera->camera;
  }
  out.volume = volume_extra(ctx, scene);
  out.warnings = ctx.warnings.lines();
  out.times.decode_ms = ctx.decode_ms;
  out.times.parse_ms = parse_ms;
  return out;
}

}  // namespace gltf

LoadedScene load_gltf(const std::string& path) {
  const auto start = std::chrono::steady_clock::now();
  const gltf::Limits limits;
  std::vector<uint8_t> bytes;
  std::string why;
  if (!gltf::read_regular_file(path, limits.max_file_bytes, &bytes, &why))
    throw SceneFileError(path + ": cannot open the scene file: " + why);
  const double read_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  LoadedScene scene = gltf::load_gltf_from_memory(bytes, path, limits);
  scene.times.read_ms = read_ms;
  scene.times.total_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return scene;
}

}  // namespace rp::scene
