// Counts and content hash of a scene file (see scene_file_facts.h).
#include "bench/src/scene_file_facts.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

#include "io/fnv1a.h"

namespace rp::bench {

using app::FileScene;

namespace {

using io::Fnv1a;

bool read_bytes(const std::filesystem::path& path, std::vector<char>& out) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;  // no FIFO may block here
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  out.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return !in.bad();
}

uint32_t read_u32(const std::vector<char>& b, size_t at) {
  uint32_t v = 0;
  std::memcpy(&v, b.data() + at, sizeof v);  // GLB is little-endian, as every host we build on
  return v;
}

// The JSON text of a .gltf, or the JSON chunk of a .glb (magic "glTF", then the first chunk:
// length, type "JSON", data); "" when neither.
std::string json_text(const std::vector<char>& b) {
  if (b.size() >= 20 && std::memcmp(b.data(), "glTF", 4) == 0) {
    const uint32_t length = read_u32(b, 12);
    if (std::memcmp(b.data() + 16, "JSON", 4) != 0 || length > b.size() - 20) return "";
    return std::string(b.data() + 20, length);
  }
  return std::string(b.begin(), b.end());
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// URIs are percent-encoded ("my%20file.bin"): decode as the loader does.
std::string percent_decode(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex_digit(uri[i + 1]) >= 0 &&
        hex_digit(uri[i + 2]) >= 0) {
      out += char(hex_digit(uri[i + 1]) * 16 + hex_digit(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

}  // namespace

std::string scene_file_hash(const std::string& path) {
  std::vector<char> bytes;
  if (!read_bytes(path, bytes)) throw std::runtime_error("cannot read the scene file " + path);
  Fnv1a h;
  h.bytes(bytes.data(), bytes.size());
  const nlohmann::json root = nlohmann::json::parse(json_text(bytes), nullptr, false);
  if (root.is_object()) {
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    for (const char* list : {"buffers", "images"}) {
      const auto it = root.find(list);
      if (it == root.end() || !it->is_array()) continue;
      for (const nlohmann::json& entry : *it) {
        if (!entry.is_object() || !entry.contains("uri") || !entry["uri"].is_string()) continue;
        const std::string uri = entry["uri"].get<std::string>();
        if (uri.rfind("data:", 0) == 0) continue;  // already in the file's own bytes
        h.text(uri);
        std::vector<char> external;
        if (read_bytes(dir / percent_decode(uri), external))
          h.bytes(external.data(), external.size());
        else
          h.text("missing");
      }
    }
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h.get()));
  return hex;
}

SceneFileFacts scene_file_facts(const FileScene& scene) {
  SceneFileFacts f;
  const scene::LoadedScene& s = scene.loaded;
  f.path = scene.path;
  f.content_hash = scene_file_hash(scene.path);
  for (const scene::MeshInstance& inst : s.instances)
    if (inst.mesh < s.assets.meshes.size())
      f.triangles += static_cast<uint32_t>(s.assets.meshes[inst.mesh].triangles.size());
  f.meshes = static_cast<uint32_t>(s.assets.meshes.size());
  f.instances = static_cast<uint32_t>(s.instances.size());
  f.materials = static_cast<uint32_t>(s.assets.materials.size());
  f.textures = static_cast<uint32_t>(s.assets.textures.size());
  f.lights = static_cast<uint32_t>(s.lights.size());
  f.lamp = s.lamp.has_value();
  return f;
}

std::string describe_scene_file(const SceneFileFacts& f) {
  char text[256];
  std::snprintf(text, sizeof text,
                " (%u triangles, %u materials, %u texture%s, %u light%s%s; content %s)",
                f.triangles, f.materials, f.textures, f.textures == 1 ? "" : "s", f.lights,
                f.lights == 1 ? "" : "s",
                f.lamp ? " and the demo's lamp" : "", f.content_hash.c_str());
  return f.path + text;
}

SceneFileFacts parse_scene_file_json(const nlohmann::ordered_json& j) {
  SceneFileFacts f;
  f.path = j.at("path").get<std::string>();
  f.content_hash = j.at("content_hash").get<std::string>();
  f.triangles = j.value("triangles", 0u);
  f.meshes = j.value("meshes", 0u);
  f.instances = j.value("instances", 0u);
  f.materials = j.value("materials", 0u);
  f.textures = j.value("textures", 0u);
  f.lights = j.value("lights", 0u);
  f.lamp = j.value("lamp", false);
  return f;
}

}  // namespace rp::bench
