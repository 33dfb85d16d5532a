// Device memory that follows the frame's size. Each pass that allocates buffers for an image of
// width x height (or a shadow map) states their size once, in a static frame_bytes(), and
// reports what it holds, frame_device_bytes() (the same buffers' CL_MEM_SIZE, 0 before its
// first run). render::Renderer sums both per pass (render/frame_memory.h): the app's memory
// estimate from the first, and tests/render/frame_memory_test.cpp checks after real frames that
// the two agree, so a new buffer cannot be left out of the estimate unnoticed.
#pragma once

#include <cstdint>
#include <initializer_list>

#include <CL/opencl.hpp>

namespace rp::passes {

// Bytes the buffers hold (CL_MEM_SIZE); a null buffer counts 0.
uint64_t buffer_bytes(std::initializer_list<const ::cl::Buffer*> buffers);

inline uint64_t pixel_count(uint32_t width, uint32_t height) { return uint64_t(width) * height; }

}  // namespace rp::passes
