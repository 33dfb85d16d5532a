#include "gltf/gltf_writer.h"

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>
#include <stdlib.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace rp::test {

TempFolder::TempFolder() {
  std::string pattern = ::testing::TempDir() + "gltf_test_XXXXXX";
  if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed: " + pattern);
  path_ = pattern;
}

TempFolder::~TempFolder() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

std::string TempFolder::write(const std::string& name, const std::string& bytes) const {
  const std::string p = file(name);
  std::ofstream out(p, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + p);
  return p;
}

std::string TempFolder::write(const std::string& name, const std::vector<uint8_t>& bytes) const {
  return write(name, std::string(bytes.begin(), bytes.end()));
}

GltfBuilder::GltfBuilder() { doc["asset"] = {{"version", "2.0"}, {"generator", "rolypoly tests"}}; }

int GltfBuilder::push(Json& d, const char* array, const Json& value) {
  if (!d.contains(array)) d[array] = Json::array();
  d[array].push_back(value);
  return static_cast<int>(d[array].size()) - 1;
}

int GltfBuilder::view(const void* data, size_t bytes, int stride) {
  while (bin.size() % 4) bin.push_back(0);
  const size_t offset = bin.size();
  bin.resize(offset + bytes);
  std::memcpy(bin.data() + offset, data, bytes);
  Json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
  if (stride) v["byteStride"] = stride;
  return push(doc, "bufferViews", v);
}

int GltfBuilder::accessor(int v, int component_type, size_t count, const std::string& type,
                          size_t byte_offset, bool normalized) {
  Json a = {{"bufferView", v}, {"componentType", component_type}, {"count", count}, {"type", type}};
  if (byte_offset) a["byteOffset"] = byte_offset;
  if (normalized) a["normalized"] = true;
  return push(doc, "accessors", a);
}

int GltfBuilder::vec3s(const std::vector<glm::vec3>& v) {
  const int a = accessor(view(v), kF32, v.size(), "VEC3");
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : v) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  doc["accessors"][a]["min"] = {lo.x, lo.y, lo.z};
  doc["accessors"][a]["max"] = {hi.x, hi.y, hi.z};
  return a;
}

int GltfBuilder::vec2s(const std::vector<glm::vec2>& v) {
  return accessor(view(v), kF32, v.size(), "VEC2");
}
int GltfBuilder::vec4s(const std::vector<glm::vec4>& v) {
  return accessor(view(v), kF32, v.size(), "VEC4");
}

int GltfBuilder::indices(const std::vector<uint32_t>& v, int component_type) {
  std::vector<uint8_t> bytes;
  for (uint32_t i : v) {
    const size_t size = component_type == kU8 ? 1 : component_type == kU16 ? 2 : 4;
    for (size_t k = 0; k < size; ++k) bytes.push_back(static_cast<uint8_t>(i >> (8 * k)));
  }
  return accessor(view(bytes), component_type, v.size(), "SCALAR");
}

int GltfBuilder::mesh(const Json& primitives, const std::string& name) {
  Json m = {{"primitives", primitives}};
  if (!name.empty()) m["name"] = name;
  return push(doc, "meshes", m);
}

int GltfBuilder::node(const Json& n) { return push(doc, "nodes", n); }
int GltfBuilder::material(const Json& m) { return push(doc, "materials", m); }

int GltfBuilder::texture(int image, int sampler_index) {
  Json t = {{"source", image}};
  if (sampler_index >= 0) t["sampler"] = sampler_index;
  return push(doc, "textures", t);
}

int GltfBuilder::sampler(int wrap_s, int wrap_t) {
  return push(doc, "samplers", {{"wrapS", wrap_s}, {"wrapT", wrap_t}});
}

int GltfBuilder::image_in_buffer(const std::vector<uint8_t>& bytes, const std::string& mime) {
  return push(doc, "images", {{"bufferView", view(bytes)}, {"mimeType", mime}});
}

int GltfBuilder::image_uri(const std::string& uri) { return push(doc, "images", {{"uri", uri}}); }

int GltfBuilder::light(const Json& l) {
  use_extension("KHR_lights_punctual");
  Json& lights = doc["extensions"]["KHR_lights_punctual"]["lights"];
  if (!lights.is_array()) lights = Json::array();
  lights.push_back(l);
  return static_cast<int>(lights.size()) - 1;
}

void GltfBuilder::scene(const std::vector<int>& roots) {
  doc["scenes"] = {{{"nodes", roots}}};
  doc["scene"] = 0;
}

void GltfBuilder::use_extension(const std::string& name, bool required) {
  auto add = [&](const char* key) {
    if (!doc.contains(key)) doc[key] = Json::array();
    for (const Json& e : doc[key])
      if (e == name) return;
    doc[key].push_back(name);
  };
  add("extensionsUsed");
  if (required) add("extensionsRequired");
}

GltfBuilder::Quad GltfBuilder::quad(float z) {
  Quad q;
  q.position = vec3s({{-1, 1, z}, {1, 1, z}, {-1, -1, z}, {1, -1, z}});
  q.uv = vec2s({{0, 0}, {1, 0}, {0, 1}, {1, 1}});
  q.indices = indices({0, 2, 1, 1, 2, 3});
  return q;
}

std::string GltfBuilder::write_gltf(const TempFolder& dir, const std::string& stem,
                                    const Patch& patch) const {
  Json d = doc;
  if (!bin.empty()) {
    dir.write(stem + ".bin", bin);
    d["buffers"] = {{{"uri", stem + ".bin"}, {"byteLength", bin.size()}}};
  }
  if (patch) patch(d);
  return dir.write(stem + ".gltf", d.dump(1));
}

std::string GltfBuilder::write_embedded(const TempFolder& dir, const std::string& stem,
                                        const Patch& patch) const {
  Json d = doc;
  if (!bin.empty())
    d["buffers"] = {{{"uri", "data:application/octet-stream;base64," + base64(bin)},
                     {"byteLength", bin.size()}}};
  if (patch) patch(d);
  return dir.write(stem + ".gltf", d.dump());
}

std::vector<uint8_t> GltfBuilder::glb_bytes(const Patch& patch) const {
  Json d = doc;
  if (!bin.empty()) d["buffers"] = {{{"byteLength", bin.size()}}};
  if (patch) patch(d);
  std::string json = d.dump();
  while (json.size() % 4) json += ' ';
  std::vector<uint8_t> b(bin);
  while (b.size() % 4) b.push_back(0);
  std::vector<uint8_t> out;
  out.reserve(28 + json.size() + b.size());
  auto u32 = [&](uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(static_cast<uint8_t>(v >> (8 * k)));
  };
  const uint32_t total =
      static_cast<uint32_t>(12 + 8 + json.size() + (b.empty() ? 0 : 8 + b.size()));
  for (const char c : {'g', 'l', 'T', 'F'}) out.push_back(static_cast<uint8_t>(c));
  u32(2);
  u32(total);
  u32(static_cast<uint32_t>(json.size()));
  u32(0x4E4F534A);  // JSON
  out.insert(out.end(), json.begin(), json.end());
  if (!b.empty()) {
    u32(static_cast<uint32_t>(b.size()));
    u32(0x004E4942);  // BIN
    out.insert(out.end(), b.begin(), b.end());
  }
  return out;
}

std::string GltfBuilder::write_glb(const TempFolder& dir, const std::string& stem,
                                   const Patch& patch) const {
  return dir.write(stem + ".glb", glb_bytes(patch));
}

namespace {
void append(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<uint8_t>*>(context);
  out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
}
}  // namespace

std::vector<uint8_t> png(int w, int h, const std::vector<uint8_t>& rgba) {
  std::vector<uint8_t> out;
  if (!stbi_write_png_to_func(&append, &out, w, h, 4, rgba.data(), w * 4))
    throw std::runtime_error("stbi_write_png_to_func failed");
  return out;
}

std::vector<uint8_t> jpeg(int w, int h, const std::vector<uint8_t>& rgba) {
  std::vector<uint8_t> out;
  if (!stbi_write_jpg_to_func(&append, &out, w, h, 4, rgba.data(), 95))
    throw std::runtime_error("stbi_write_jpg_to_func failed");
  return out;
}

std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = uint32_t{bytes[i]} << 16 |
                       (i + 1 < bytes.size() ? uint32_t{bytes[i + 1]} << 8 : 0u) |
                       (i + 2 < bytes.size() ? uint32_t{bytes[i + 2]} : 0u);
    out += kAlphabet[n >> 18 & 63];
    out += kAlphabet[n >> 12 & 63];
    out += i + 1 < bytes.size() ? kAlphabet[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[n & 63] : '=';
  }
  return out;
}

}  // namespace rp::test
