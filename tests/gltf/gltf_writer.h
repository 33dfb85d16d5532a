// Small glTF files for the loader's tests: a builder for the JSON (nlohmann) and buffer 0's
// bytes, written as .gltf + .bin, as one .gltf with a data URI, or as .glb; and a temporary
// folder that removes itself.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace rp::test {

using Json = nlohmann::json;

// glTF component types.
constexpr int kU8 = 5121, kU16 = 5123, kU32 = 5125, kF32 = 5126, kI8 = 5120, kI16 = 5122;

// A folder under ::testing::TempDir(), removed with everything in it.
class TempFolder {
 public:
  TempFolder();
  ~TempFolder();
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  std::string write(const std::string& name, const std::string& bytes) const;
  std::string write(const std::string& name, const std::vector<uint8_t>& bytes) const;

 private:
  std::string path_;
};

class GltfBuilder {
 public:
  Json doc;                  // the file's JSON; "buffers" is filled in when written
  std::vector<uint8_t> bin;  // buffer 0

  GltfBuilder();

  // Appends `bytes` to buffer 0 (4-byte aligned) as a new bufferView.
  int view(const void* data, size_t bytes, int stride = 0);
  template <typename T>
  int view(const std::vector<T>& v, int stride = 0) {
    return view(v.data(), v.size() * sizeof(T), stride);
  }
  int accessor(int view, int component_type, size_t count, const std::string& type,
               size_t byte_offset = 0, bool normalized = false);
  // A view and a tightly packed accessor in one.
  int vec3s(const std::vector<glm::vec3>& v);
  int vec2s(const std::vector<glm::vec2>& v);
  int vec4s(const std::vector<glm::vec4>& v);
  int indices(const std::vector<uint32_t>& v, int component_type = kU16);

  int mesh(const Json& primitives, const std::string& name = {});
  int node(const Json& node);
  int material(const Json& material);
  int texture(int image, int sampler = -1);
  int sampler(int wrap_s, int wrap_t);
  int image_in_buffer(const std::vector<uint8_t>& png, const std::string& mime = "image/png");
  int image_uri(const std::string& uri);
  int light(const Json& light);  // KHR_lights_punctual
  void scene(const std::vector<int>& roots);
  void use_extension(const std::string& name, bool required = false);

  // Written files; `patch` edits the final JSON (buffers included) just before it is written.
  using Patch = std::function<void(Json&)>;
  std::string write_gltf(const TempFolder& dir, const std::string& stem,
                         const Patch& patch = {}) const;
  std::string write_embedded(const TempFolder& dir, const std::string& stem,
                             const Patch& patch = {}) const;
  std::string write_glb(const TempFolder& dir, const std::string& stem,
                        const Patch& patch = {}) const;
  // The GLB's bytes (JSON chunk, BIN chunk) for tests that damage the container.
  std::vector<uint8_t> glb_bytes(const Patch& patch = {}) const;

  // A unit quad in the z = 0 plane (-1..1), CCW seen from +z, uv (0,0) at the top left
  // (-1, 1): indexed u16. Returns its POSITION, TEXCOORD_0 and indices accessors.
  struct Quad {
    int position, uv, indices;
  };
  Quad quad(float z = 0.0f);

 private:
  static int push(Json& doc, const char* array, const Json& value);
};

// PNG and JPEG bytes of a w x h RGBA image (stb_image_write).
std::vector<uint8_t> png(int w, int h, const std::vector<uint8_t>& rgba);
std::vector<uint8_t> jpeg(int w, int h, const std::vector<uint8_t>& rgba);
std::string base64(const std::vector<uint8_t>& bytes);

}  // namespace rp::test
