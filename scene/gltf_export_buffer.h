// The binary side of the glTF exporter (scene/gltf_export.h): the one buffer every mesh and
// image lives in, its buffer views and accessors, the GLB container, the base64 data URI of a
// .gltf, PNG encoding, and numbers as JSON. Internal to the exporter.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/frame_scene.h"

namespace rp::scene::gltf_export {

// Insertion-ordered, so the file lists asset, scenes, nodes, ... in the order they are built.
using Json = nlohmann::ordered_json;

// glTF 2.0 enums (componentType, bufferView.target).
inline constexpr int kUnsignedShort = 5123;
inline constexpr int kUnsignedInt = 5125;
inline constexpr int kFloat = 5126;
inline constexpr int kArrayBuffer = 34962;
inline constexpr int kElementArrayBuffer = 34963;

// `v` as the JSON number with the fewest digits that still reads back as exactly `v` when a
// reader parses it as a double and rounds that to float ("0.8", not "0.800000011920929");
// -0 as 0. Throws std::invalid_argument for NaN and infinities, which JSON cannot hold.
double json_number(float v);
Json json_numbers(const float* v, size_t n);

// Buffer 0: views appended back to back, each starting on a 4-byte boundary, so accessors at
// offset 0 are aligned for every component type (glTF 2.0, 3.6.2.4), and the total length is
// a multiple of 4 as the GLB's BIN chunk needs.
class BufferBuilder {
 public:
  // One view holding `bytes`; target 0 leaves the view's target out (images).
  int add_view(std::string_view bytes, int target);
  // A FLOAT accessor of `count` elements of `components` (2, 3 or 4) floats, in a view of its
  // own. `bounds`: with min and max per component (POSITION requires them), written as the
  // exact doubles of the floats so any reader's comparison with the data holds.
  int add_floats(const std::vector<float>& values, int components, bool bounds);
  // A SCALAR index accessor: unsigned short when every vertex index fits below 65535 (the
  // primitive-restart value glTF forbids), else unsigned int.
  int add_indices(const std::vector<uint32_t>& indices, size_t vertex_count);

  const std::string& bytes() const { return bytes_; }
  const Json& views() const { return views_; }
  const Json& accessors() const { return accessors_; }

 private:
  std::string bytes_;
  Json views_ = Json::array();
  Json accessors_ = Json::array();
};

// The GLB container (glTF 2.0, 4.4): 12-byte header, JSON chunk padded with spaces, BIN chunk
// (left out when `bin` is empty) padded with zeros.
std::string glb(const std::string& json_text, const std::string& bin);

// "data:application/octet-stream;base64,..." for a .gltf's embedded buffer.
std::string data_uri(std::string_view bytes);

// `texture` as a PNG file's bytes (RGBA8, rows top to bottom as stored). Throws
// std::invalid_argument when its size and pixel count disagree.
std::string encode_png(const Texture& texture);

}  // namespace rp::scene::gltf_export
