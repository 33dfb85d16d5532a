// libFuzzer target: the glTF loader (scene/gltf_*.cpp) on arbitrary bytes, read twice: as the
// file's content as given (JSON text, or a GLB when it starts with "glTF"), and wrapped in a
// GLB container (the bytes before the first NUL as the JSON chunk, the rest as the BIN chunk).
// The scene's folder holds buffer.bin and image.png (below) for URIs to point at.
//
// tinygltf's implementation is compiled into this target (not Debian's libtinygltf.so as in the
// app) so that it runs under ASan/UBSan too: whatever it trusts without checking is found here.
//
// Findings are crashes, sanitizer reports, leaks, hangs, and these broken properties:
// - a refused file throws scene::SceneFileError (any other exception escapes and aborts) whose
//   message starts with the file's path;
// - a loaded scene is usable: every triangle's vertices, material and texture indices are in
//   range, tangents are absent or one per vertex, textures hold width x height RGBA texels,
//   positions, normals, bounds, lights and the camera are finite, normals and light directions
//   unit length, and at least one instance is drawn.
#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

// The stb implementation is libstb's; tinygltf's needs only its declarations.
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#include <tiny_gltf.h>

#include "scene/gltf_internal.h"

namespace {

using rp::scene::LoadedScene;
namespace gltf = rp::scene::gltf;

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_gltf_loader: %s\n", what.c_str());
  std::abort();
}

// The scene's folder, made once: buffer.bin (64 bytes: a triangle's three float positions,
// then 0..27) and image.png (2 x 2 RGBA) for the seeds' external URIs.
struct Folder {
  std::string path;
  Folder() {
    path = (std::filesystem::temp_directory_path() / "fuzz_gltf_XXXXXX").string();
    if (!::mkdtemp(path.data())) finding("mkdtemp failed");
    std::vector<uint8_t> bin(64);
    const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::memcpy(bin.data(), triangle, sizeof triangle);
    for (size_t i = sizeof triangle; i < bin.size(); ++i)
      bin[i] = static_cast<uint8_t>(i - sizeof triangle);
    std::ofstream(path + "/buffer.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
    const uint8_t rgba[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128};
    stbi_write_png((path + "/image.png").c_str(), 2, 2, 4, rgba, 8);
  }
  ~Folder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

const std::string& folder() {
  static const Folder f;
  return f.path;
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool unit(glm::vec3 v) { return finite(v) && std::abs(glm::length(v) - 1.0f) < 1e-3f; }

void check_scene(const LoadedScene& s) {
  const auto& a = s.assets;
  if (s.instances.empty()) finding("a loaded scene draws nothing");
  for (const auto& inst : s.instances)
    if (inst.mesh >= a.meshes.size()) finding("instance of a mesh that does not exist");
  for (const auto& m : a.meshes) {
    if (m.triangles.empty()) finding("a mesh without triangles");
    if (m.materials.size() != m.triangles.size()) finding("materials are not one per triangle");
    if (!m.tangents.empty() && m.tangents.size() != m.vertices.size())
      finding("tangents are not one per vertex");
    for (const auto& t : m.triangles)
      if (t.x >= m.vertices.size() || t.y >= m.vertices.size() || t.z >= m.vertices.size())
        finding("a triangle's vertex is out of range");
    for (uint32_t mat : m.materials)
      if (mat >= a.materials.size()) finding("a triangle's material is out of range");
    for (const auto& v : m.vertices)
      if (!finite(v.position) || !unit(v.normal) || !std::isfinite(v.uv.x) ||
          !std::isfinite(v.uv.y))
        finding("a vertex is not finite or its normal not unit length");
    for (const auto& t : m.tangents)
      if (!unit(glm::vec3(t)) || (t.w != 1.0f && t.w != -1.0f))
        finding("a tangent is not unit with w = +-1");
  }
  const int textures = static_cast<int>(a.textures.size());
  for (const auto& m : a.materials)
    for (int t : {m.texture, m.metallic_roughness_texture, m.normal_texture, m.emission_texture})
      if (t < -1 || t >= textures) finding("a material's texture is out of range");
  for (const auto& t : a.textures)
    if (t.width <= 0 || t.height <= 0 ||
        t.rgba.size() != static_cast<size_t>(t.width) * static_cast<size_t>(t.height) * 4)
      finding("a texture's size does not match its texels");
  if (!finite(s.bounds.lo) || !finite(s.bounds.hi) || s.bounds.empty())
    finding("bounds are not finite");
  for (const auto& l : s.lights)
    if (!finite(l.position) || !unit(l.direction) || !finite(l.intensity))
      finding("a light is not finite");
  if (s.camera &&
      (!finite(s.camera->position) || !finite(s.camera->target) || !unit(s.camera->up) ||
       !(s.camera->near_plane > 0.0f) || !(s.camera->far_plane > s.camera->near_plane)))
    finding("the camera is not usable");
  if (s.volume && (!finite(s.volume->lo) || !finite(s.volume->hi) || s.volume->empty()))
    finding("the volume is not a finite box");
}

void load(const std::vector<uint8_t>& bytes, const std::string& name) {
  // Small limits: a fuzzer's input that passes every check must not exhaust its memory.
  gltf::Limits limits;
  limits.max_vertices = limits.max_triangles = uint64_t{1} << 20;
  limits.max_image_side = 2048;
  limits.max_texels = uint64_t{1} << 22;
  limits.max_bounds_work = uint64_t{1} << 20;
  limits.max_accessor_reads = uint64_t{1} << 22;
  const std::string path = folder() + "/" + name;
  try {
    check_scene(gltf::load_gltf_from_memory(bytes, path, limits));
  } catch (const rp::scene::SceneFileError& e) {
    if (std::string(e.what()).rfind(path + ": ", 0) != 0)
      finding(std::string("an error that does not start with the file: ") + e.what());
  }
}

void put32(std::vector<uint8_t>& out, size_t value) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<uint8_t>(value >> (8 * k)));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<uint8_t> bytes(data, data + size);
  load(bytes, "scene.gltf");
  if (size >= 4 && std::memcmp(data, "glTF", 4) == 0) return 0;
  // The same bytes as a GLB: JSON up to the first NUL, BIN after it (both padded to 4 bytes).
  const uint8_t* nul = static_cast<const uint8_t*>(std::memchr(data, 0, size));
  std::vector<uint8_t> json(data, nul ? nul : data + size), bin;
  if (nul) bin.assign(nul + 1, data + size);
  while (json.size() % 4) json.push_back(' ');
  while (bin.size() % 4) bin.push_back(0);
  std::vector<uint8_t> glb = {'g', 'l', 'T', 'F'};
  put32(glb, 2);
  put32(glb, 20 + json.size() + (bin.empty() ? 0 : 8 + bin.size()));
  put32(glb, json.size());
  put32(glb, 0x4E4F534A);
  glb.insert(glb.end(), json.begin(), json.end());
  if (!bin.empty()) {
    put32(glb, bin.size());
    put32(glb, 0x004E4942);
    glb.insert(glb.end(), bin.begin(), bin.end());
  }
  load(glb, "scene.glb");
  return 0;
}
