// The pieces of the glTF loader (scene/gltf_*.cpp) and what they share: the limits every size
// claim is held to, the warnings collected while loading, and the error that names the file.
// Not part of the scene's public interface (that is scene/gltf_loader.h); the tests and the
// fuzzer use load_gltf_from_memory with smaller limits.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "scene/frame_scene.h"
#include "scene/gltf_loader.h"
#include "scene/regular_file.h"

namespace tinygltf {
class Model;
}

namespace rp::scene::gltf {

// Every count or size a file claims is checked against these before anything is allocated for
// it. The defaults are far beyond real scenes and far below what would exhaust a machine.
struct Limits {
  uint64_t max_file_bytes = (uint64_t{1} << 31) - 1;  // one file (.gltf, .glb, .bin, image);
                                                      // tinygltf indexes them with 32 bits
  int max_json_depth = 64;                            // nesting of JSON arrays/objects
  uint64_t max_vertices = uint64_t{1} << 28;          // the whole scene, flat normals expanded
  uint64_t max_triangles = uint64_t{1} << 28;         // the whole scene
  int max_image_side = 16384;                         // texels, either side of one image
  uint64_t max_texels = uint64_t{1} << 30;            // all decoded textures: 4 GiB of RGBA8
  uint64_t max_accessor_reads = uint64_t{1} << 30;    // accessor elements read, all primitives
                                                      // together (one accessor may be read by
                                                      // many primitives)
  int max_node_depth = 1024;                          // levels of the node hierarchy
  uint64_t max_bounds_work = uint64_t{1} << 28;       // instance-vertex transforms for exact
                                                      // bounds; beyond: transformed mesh boxes
};

// One line per kind of unsupported feature, however often it occurs; the line names the first
// few places (mesh 2 primitive 0, ...) and how many there were.
class Warnings {
 public:
  void add(const std::string& kind, const std::string& place = {});
  std::vector<std::string> lines() const;

 private:
  struct Kind {
    std::vector<std::string> places;
    size_t count = 0;
  };
  std::vector<std::pair<std::string, Kind>> kinds_;  // in order of first occurrence
};

// What every piece of the loader works with.
struct Context {
  std::string file;  // the path as given, first in every message
  Limits limits;
  Warnings warnings;
  const tinygltf::Model* model = nullptr;
  uint64_t vertices = 0;  // running totals against the limits
  uint64_t triangles = 0;
  uint64_t texels = 0;
  uint64_t accessor_reads = 0;
  double decode_ms = 0.0;  // wall clock spent decoding images (LoadedScene::times)

  [[noreturn]] void fail(const std::string& what) const;
};

// Checked narrowing: a double the file gave (or a product of them) as a float, refusing values a
// float cannot hold (converting those is undefined behaviour, and they are no use to render).
bool fits_float(double v);
float to_float(const Context& ctx, double v, const std::string& where);

// ---- gltf_files.cpp: reading files (scene/regular_file.h), resolving URIs ----

using scene::read_file_start;
using scene::read_regular_file;
using scene::regular_file_size;

// The directory a relative URI is resolved against, and tinygltf's percent-decoding of URIs.
std::string base_dir_of(const std::string& path);
std::string uri_decode(const std::string& uri);
std::string join_path(const std::string& dir, const std::string& name);

// ---- gltf_json_checks.cpp ----

// What the GLB container holds besides the JSON.
struct GlbChunks {
  bool binary = false;  // a GLB at all
  bool has_bin = false;
  uint64_t bin_size = 0;
};
// The parsed JSON checked where tinygltf would truncate, trust or allocate for a claim: the
// asset version, index types, required extensions, buffers against their real data (external
// buffers' paths and checked byteLength go to `exact_size`), bufferViews, images' views.
void check_json(const Context& ctx, const nlohmann::json& root, const GlbChunks& glb,
                const std::string& base_dir, std::map<std::string, uint64_t>* exact_size);

// ---- gltf_source.cpp ----

// Parses `bytes` (GLB or JSON text), checks what tinygltf trusts without checking (JSON depth,
// index types, buffer and bufferView sizes against the real data, the GLB's chunks), then runs
// tinygltf with file callbacks that read only regular files with a size bound, and an image
// callback that keeps the encoded bytes (images are decoded on use, gltf_materials.cpp).
void load_model(Context& ctx, const std::vector<uint8_t>& bytes, tinygltf::Model* model);

// ---- gltf_accessors.cpp: typed, bounds-checked reads of accessors (byteStride, sparse) ----

// `components` floats per element. FLOAT always; normalized unsigned byte/short where
// `allow_unorm` (texture coordinates). Every value is finite.
std::vector<float> read_floats(Context& ctx, int accessor, int components, bool allow_unorm,
                               const std::string& where);
// SCALAR unsigned byte, short or int.
std::vector<uint32_t> read_indices(Context& ctx, int accessor, const std::string& where);

// ---- gltf_materials.cpp: materials and their textures, converted on first use ----

class MaterialTable {
 public:
  MaterialTable(Context& ctx, SceneAssets& assets) : ctx_(ctx), assets_(assets) {}
  // Index into assets.materials of glTF material `index` (-1: glTF's default material).
  uint32_t material(int index, const std::string& where);
  // Whether glTF material `index` has a normal map (no conversion, nothing decoded).
  bool has_normal_map(int index) const;

 private:
  int texture(int texture_index, int tex_coord, bool srgb, const std::string& where);
  std::vector<uint8_t> decoded_image(int image, int* width, int* height, const std::string& where);

  Context& ctx_;
  SceneAssets& assets_;
  std::map<int, uint32_t> materials_;
  std::map<std::pair<int, bool>, int> textures_;  // (glTF texture, sRGB) -> assets.textures
};

// ---- gltf_meshes.cpp: a glTF mesh (all its triangle primitives) as one scene::Mesh ----

// std::nullopt when the mesh has no triangles (every primitive skipped).
std::optional<Mesh> convert_mesh(Context& ctx, int mesh, MaterialTable& materials);
// The same mesh for an instance whose transform mirrors (negative determinant): the winding
// is reversed so front faces stay counter-clockwise, and tangent handedness flips with it.
Mesh mirrored(const Mesh& mesh);

// ---- gltf_nodes.cpp: the node hierarchy, lights and the camera ----

// Calls `visit(node, world)` for every node under `roots`, parents first, depth first in file
// order. World matrices are composed in double precision and checked finite. Refuses
// out-of-range node indices, nodes with two parents, cycles and hierarchies deeper than the
// limit.
void walk_nodes(Context& ctx, const std::vector<int>& roots,
                const std::function<void(int node, const glm::dmat4& world)>& visit);

// The KHR_lights_punctual light a node carries, or -1.
int node_light(const Context& ctx, int node);
// std::nullopt (and a warning) where the node's transform gives a spot or directional light
// no direction.
std::optional<PunctualLight> convert_light(Context& ctx, int light, const glm::dmat4& world,
                                           const std::string& where);

// The demo's ceiling lamp when light `light` carries it (its extras {"rolypoly": {"lamp":
// {"radius", "shadow_fov_y_deg", "shadow_near", "shadow_far"}}}, written by `rolypoly
// export`), placed and converted as `placed` (convert_light's result); else nothing.
std::optional<PointLight> lamp_of(Context& ctx, int light, const PunctualLight& placed);
// A node's extras {"rolypoly": {"casts_shadow": false, "voxelize": false}} on its instance.
void instance_flags(const Context& ctx, int node, MeshInstance* instance);

// A perspective camera placed by a node; its far plane may wait for the scene bounds.
struct PlacedCamera {
  Camera camera;
  bool far_from_bounds = false;  // the file gave no zfar
};
// std::nullopt (and a warning) for orthographic cameras and collapsed transforms.
std::optional<PlacedCamera> convert_camera(Context& ctx, int camera, const glm::dmat4& world,
                                           const std::string& where);

// ---- gltf_loader.cpp ----

// load_gltf on bytes already in memory; `path` names the file in messages and places relative
// URIs. For tests and the fuzzer, which pass smaller limits.
LoadedScene load_gltf_from_memory(const std::vector<uint8_t>& bytes, const std::string& path,
                                  const Limits& limits);

}  // namespace rp::scene::gltf
