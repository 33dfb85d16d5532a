// What the bench records of a scene file (SceneFileFacts, bench/src/bench_matrix.h): its counts
// and a hash of its content. The hash keys the accuracy report's truth cache for the file
// (bench/src/accuracy_file.h): the same path with other content must not find an old truth, and
// the truth cache's own key leaves out what only a file has (punctual lights, normal and
// metallic-roughness maps, alpha masks).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "app/scene_input.h"
#include "bench/src/bench_matrix.h"

namespace rp::bench {

// 64-bit FNV-1a, as 16 hex digits, of the file's bytes and, for a .gltf or .glb whose JSON
// names external buffers or images (relative URIs, not data: URIs), of each such URI and the
// bytes of the file it names ("missing" for one that cannot be read: the loader would have
// refused the scene). Throws std::runtime_error when `path` itself cannot be read.
std::string scene_file_hash(const std::string& path);

// The counts of a loaded scene and scene_file_hash of its path.
SceneFileFacts scene_file_facts(const app::FileScene& scene);

// "FILE (12 triangles, 3 materials, 0 textures, 2 lights; content 0123456789abcdef)"
std::string describe_scene_file(const SceneFileFacts& facts);

// As JSON {"path", "content_hash", "triangles", "meshes", "instances", "materials",
// "textures", "lights", "lamp"}: the bench's "scene_file" and the accuracy report's "scene".
template <class Json>
Json scene_file_json(const SceneFileFacts& f) {
  Json j;
  j["path"] = f.path;
  j["content_hash"] = f.content_hash;
  j["triangles"] = f.triangles;
  j["meshes"] = f.meshes;
  j["instances"] = f.instances;
  j["materials"] = f.materials;
  j["textures"] = f.textures;
  j["lights"] = f.lights;
  j["lamp"] = f.lamp;
  return j;
}

// scene_file_json read back (missing counts read as 0). Throws nlohmann::json's exceptions
// for a missing path or hash.
SceneFileFacts parse_scene_file_json(const nlohmann::ordered_json& j);

}  // namespace rp::bench
