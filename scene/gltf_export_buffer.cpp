#include "scene/gltf_export_buffer.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

// The implementation lives in libstb (Debian's libstb-dev), so no STB_IMAGE_WRITE_IMPLEMENTATION.
#include <stb/stb_image_write.h>

namespace rp::scene::gltf_export {
namespace {

// Accessor data is copied from memory as is: glTF buffers are little-endian.
static_assert(std::endian::native == std::endian::little);

void pad_to_4(std::string& bytes, char fill) { bytes.append((4 - bytes.size() % 4) % 4, fill); }

void append_u32(std::string& out, uint32_t v) {
  // GLB is little-endian whatever the host.
  for (int shift = 0; shift < 32; shift += 8)
    out.push_back(static_cast<char>((v >> shift) & 0xFFu));
}

uint32_t checked_u32(size_t n) {
  if (n > std::numeric_limits<uint32_t>::max())
    throw std::invalid_argument("export_gltf: the scene needs more than 4 GiB, GLB's limit");
  return static_cast<uint32_t>(n);
}

}  // namespace

double json_number(float v) {
  if (!std::isfinite(v))
    throw std::invalid_argument("export_gltf: the frame holds a number that is not finite");
  if (v == 0.0f) return 0.0;  // "-0.0" in a camera matrix reads as noise
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, v).ptr;
  double shortest = 0.0;
  std::from_chars(text, end, shortest);
  // Decimal -> double -> float can round twice; then the exact double of v is written.
  return static_cast<float>(shortest) == v ? shortest : static_cast<double>(v);
}

Json json_numbers(const float* v, size_t n) {
  Json a = Json::array();
  for (size_t i = 0; i < n; ++i) a.push_back(json_number(v[i]));
  return a;
}

int BufferBuilder::add_view(std::string_view bytes, int target) {
  pad_to_4(bytes_, '\0');
  Json view = {{"buffer", 0}, {"byteOffset", bytes_.size()}, {"byteLength", bytes.size()}};
  if (target != 0) view["target"] = target;
  bytes_.append(bytes);
  pad_to_4(bytes_, '\0');
  views_.push_back(std::move(view));
  return static_cast<int>(views_.size() - 1);
}

int BufferBuilder::add_floats(const std::vector<float>& values, int components, bool bounds) {
  const size_t n = static_cast<size_t>(components);
  const size_t count = values.size() / n;
  Json accessor = {{"bufferView", add_view({reinterpret_cast<const char*>(values.data()),
                                            values.size() * sizeof(float)},
                                           kArrayBuffer)},
                   {"componentType", kFloat},
                   {"count", count},
                   {"type", "VEC" + std::to_string(components)}};
  if (bounds) {
    std::vector<float> lo(n, std::numeric_limits<float>::infinity());
    std::vector<float> hi(n, -std::numeric_limits<float>::infinity());
    for (size_t i = 0; i < values.size(); ++i) {
      lo[i % n] = std::min(lo[i % n], values[i]);
      hi[i % n] = std::max(hi[i % n], values[i]);
    }
    accessor["min"] = Json::array();
    accessor["max"] = Json::array();
    for (size_t c = 0; c < n; ++c) {
      accessor["min"].push_back(static_cast<double>(lo[c]));
      accessor["max"].push_back(static_cast<double>(hi[c]));
    }
  }
  accessors_.push_back(std::move(accessor));
  return static_cast<int>(accessors_.size() - 1);
}

int BufferBuilder::add_indices(const std::vector<uint32_t>& indices, size_t vertex_count) {
  int view = 0, type = kUnsignedInt;
  if (vertex_count <= 0xFFFFu) {
    std::vector<uint16_t> narrow(indices.begin(), indices.end());
    view = add_view({reinterpret_cast<const char*>(narrow.data()), narrow.size() * 2},
                    kElementArrayBuffer);
    type = kUnsignedShort;
  } else {
    view = add_view({reinterpret_cast<const char*>(indices.data()), indices.size() * 4},
                    kElementArrayBuffer);
  }
  accessors_.push_back({{"bufferView", view},
                        {"componentType", type},
                        {"count", indices.size()},
                        {"type", "SCALAR"}});
  return static_cast<int>(accessors_.size() - 1);
}

std::string glb(const std::string& json_text, const std::string& bin) {
  std::string json_chunk = json_text;
  pad_to_4(json_chunk, ' ');
  std::string bin_chunk = bin;
  pad_to_4(bin_chunk, '\0');
  const size_t total = 12 + 8 + json_chunk.size() + (bin_chunk.empty() ? 0 : 8 + bin_chunk.size());
  std::string out;
  out.reserve(total);
  append_u32(out, 0x46546C67u);  // "glTF"
  append_u32(out, 2u);
  append_u32(out, checked_u32(total));
  append_u32(out, checked_u32(json_chunk.size()));
  append_u32(out, 0x4E4F534Au);  // "JSON"
  out += json_chunk;
  if (!bin_chunk.empty()) {
    append_u32(out, checked_u32(bin_chunk.size()));
    append_u32(out, 0x004E4942u);  // "BIN\0"
    out += bin_chunk;
  }
  return out;
}

std::string data_uri(std::string_view bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out = "data:application/octet-stream;base64,";
  out.reserve(out.size() + (bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t group = 0;
    for (size_t k = 0; k < 3; ++k)
      group = (group << 8) | (k < n ? static_cast<uint8_t>(bytes[i + k]) : 0u);
    for (size_t k = 0; k < 4; ++k)
      out.push_back(k <= n ? kAlphabet[(group >> (18 - 6 * k)) & 0x3Fu] : '=');
  }
  return out;
}

std::string encode_png(const Texture& texture) {
  const size_t texels = static_cast<size_t>(std::max(texture.width, 0)) *
                        static_cast<size_t>(std::max(texture.height, 0));
  if (texels == 0 || texture.rgba.size() != texels * 4 ||
      texture.width > std::numeric_limits<int>::max() / 4)
    throw std::invalid_argument("export_gltf: texture '" + texture.name + "' is " +
                                std::to_string(texture.width) + "x" +
                                std::to_string(texture.height) + " but holds " +
                                std::to_string(texture.rgba.size()) + " bytes");
  std::string png;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &png, texture.width, texture.height, 4, texture.rgba.data(),
                              texture.width * 4))
    throw std::invalid_argument("export_gltf: texture '" + texture.name +
                                "' cannot be encoded as PNG");
  return png;
}

}  // namespace rp::scene::gltf_export
