// FNV-1a, 64 bits: the content hash of cache keys (the path tracer's truth cache, a scene
// file's content). Not cryptographic: it tells files and settings apart, no more.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

namespace rp::io {

class Fnv1a {
 public:
  void bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h_ = (h_ ^ p[i]) * 0x100000001B3ull;
  }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
  void vec(glm::vec3 v) { bytes(&v.x, 3 * sizeof(float)); }
  void mat(const glm::mat4& m) { bytes(&m[0][0], 16 * sizeof(float)); }
  // The length first: "ab" + "c" and "a" + "bc" differ.
  void text(const std::string& s) {
    value(uint64_t(s.size()));
    bytes(s.data(), s.size());
  }
  uint64_t get() const { return h_; }

 private:
  uint64_t h_ = 0xCBF29CE484222325ull;
};

}  // namespace rp::io
