#include "passes/frame_memory.h"

namespace rp::passes {

uint64_t buffer_bytes(std::initializer_list<const ::cl::Buffer*> buffers) {
  uint64_t bytes = 0;
  for (const ::cl::Buffer* b : buffers)
    if (b != nullptr && (*b)() != nullptr) bytes += b->getInfo<CL_MEM_SIZE>();
  return bytes;
}

}  // namespace rp::passes
