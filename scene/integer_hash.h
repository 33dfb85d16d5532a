// A 32-bit integer mixer (xorshift-multiply, two rounds): the only source of variation in the
// generated scenes (tools/gen_load_scene, scene/atrium*), so the same arguments write the same
// bytes on every run.
#pragma once

#include <cstdint>

namespace rp::scene {

inline uint32_t integer_hash(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

}  // namespace rp::scene
