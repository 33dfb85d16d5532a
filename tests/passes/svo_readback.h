// The octree's buffer read back to the host, for the octree tests (svo_test.cpp,
// svo_memory_test.cpp): the whole buffer as words (kernels/shared/svo_layout.h) and the frame's
// fragment list, with plain accessors that do not use the kernels' helpers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "kernels/shared/svo_layout.h"
#include "passes/svo.h"
#include "render/svo_volume.h"
#include "support/cl_fixture.h"

namespace rp::test {

struct SvoReadback {
  render::SvoVolume vol;
  std::vector<uint32_t> words;      // the whole buffer
  std::vector<uint32_t> fragments;  // RP_SVO_FRAGMENT_WORDS each

  // Reads vol's buffer and `pass`'s fragment list (blocking).
  void read(const passes::SvoPass& pass) {
    words.resize(vol.buffer_bytes() / 4);
    context().queue.enqueueReadBuffer(vol.buffer, CL_TRUE, 0, words.size() * 4, words.data());
    fragments.resize(size_t(vol.fragments) * RP_SVO_FRAGMENT_WORDS);
    if (!fragments.empty())
      context().queue.enqueueReadBuffer(pass.fragments(), CL_TRUE, 0, fragments.size() * 4,
                                        fragments.data());
  }

  uint32_t header(uint32_t w) const { return words[w]; }
  uint32_t node_word(uint32_t node, uint32_t w) const {
    return words[4 * RP_SVO_HEADER_FLOAT4S + 2 * size_t(node) + w];
  }
  // Brick-table word w of brick index b.
  uint32_t table(uint32_t b, uint32_t w) const {
    return words[header(RP_SVO_HDR_TABLE_OFFSET) + RP_SVO_TABLE_WORDS * size_t(b) + w];
  }
  // Descent from the root to the node at `depth` holding cell (ax, ay, az); -1 when not in the
  // tree.
  int64_t find(uint32_t depth, uint32_t ax, uint32_t ay, uint32_t az) const {
    uint32_t idx = 0;
    for (uint32_t j = 1; j <= depth; ++j) {
      const uint32_t child = node_word(idx, 0) & RP_SVO_NODE_CHILD_MASK;
      if (child == 0) return -1;
      const uint32_t s = depth - j;
      idx = child + (((ax >> s) & 1) | (((ay >> s) & 1) << 1) | (((az >> s) & 1) << 2));
    }
    return idx;
  }
};

}  // namespace rp::test
