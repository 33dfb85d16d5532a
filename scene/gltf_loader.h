// Opening glTF 2.0 scenes (.gltf with external or data-URI buffers and images, or .glb) as a
// static scene: assets, placed instances, lights and the file's camera, in the file's world
// units (metres). The renderer's view of it (volume fit, camera) is built by
// scene/file_scene.h; this file only reads and checks.
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "scene/asset_error.h"
#include "scene/frame_scene.h"

namespace rp::scene {

// A scene file that cannot be used: missing, unreadable, not glTF 2.0, or malformed. The
// message names the file and what is wrong where (node, mesh, accessor or image index); the
// app reports it as a usage error (exit status 2).
class SceneFileError : public AssetError {
 public:
  using AssetError::AssetError;
};

struct LoadedScene {
  SceneAssets assets;                  // one Mesh per glTF mesh (its primitives merged, one
                                       // material per triangle); materials; textures
  std::vector<MeshInstance> instances; // one per node that has a mesh, model = world matrix of
                                       // the node (prev_model equal), casting shadows
  std::vector<PunctualLight> lights;   // world positions and directions
  std::optional<Camera> camera;        // the first camera met walking the default scene
  Bounds bounds;                       // world bounds of every instance's vertices
  // The GI volume the file asks for (its scene's extras {"rolypoly": {"volume": [x0, y0, z0,
  // x1, y1, z1]}}, written by `rolypoly export`), else none: fitted to `bounds`.
  std::optional<Bounds> volume;
  // The demo's ceiling lamp, when the file carries it (written by `rolypoly export`: a
  // KHR_lights_punctual point light whose extras are {"rolypoly": {"lamp": {"radius": r,
  // "shadow_fov_y_deg": f, "shadow_near": n, "shadow_far": f}}}); that light is then not in
  // `lights`. Its intensity is in the renderer's units (PointLight), position in world units.
  std::optional<PointLight> lamp;
  // One line per kind of unsupported feature met (skins, morph targets, extensions, BLEND
  // materials treated as MASK, ...), for the app to print once.
  std::vector<std::string> warnings;
  // Wall-clock milliseconds of the load: everything, and its parts: reading the file, parsing
  // (the JSON checks and tinygltf's parse, external buffers read) and decoding images; the rest
  // is the accessors' conversion into meshes, the node walk and the materials.
  struct Times {
    double total_ms = 0.0;
    double read_ms = 0.0;
    double parse_ms = 0.0;
    double decode_ms = 0.0;
    double accessors_ms() const { return std::max(0.0, total_ms - read_ms - parse_ms - decode_ms); }
  } times;
};

// Reads `path` (.gltf or .glb; decided by content, not by name). Throws SceneFileError.
LoadedScene load_gltf(const std::string& path);

}  // namespace rp::scene
