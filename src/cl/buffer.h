// Device buffers created with a name: a creation that fails for lack of memory (the driver's
// CL_MEM_OBJECT_ALLOCATION_FAILURE, CL_OUT_OF_RESOURCES, CL_OUT_OF_HOST_MEMORY, a size above
// CL_DEVICE_MAX_MEM_ALLOC_SIZE, or std::bad_alloc on the host) becomes one rp::cl::Error that
// says what was being allocated and how large it was, instead of a bare "clCreateBuffer failed"
// or a message that blames the image size.
#pragma once

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include <CL/opencl.hpp>

namespace rp::cl {

// True for the error codes a driver gives when memory runs out or a buffer is too large.
bool is_out_of_memory(cl_int err);

// The message for a failed allocation of `bytes` for `what`, with the device's limits (MiB):
// "allocating the octree's node and brick pools (812 MiB) failed: CL_MEM_OBJECT_ALLOCATION_
// FAILURE (the device has 1024 MiB of global memory, at most 256 MiB in one buffer); <advice>".
// `reason` is the driver's error name or "out of host memory".
std::string allocation_failure(const ::cl::Context& context, size_t bytes, const std::string& what,
                               const std::string& reason, const std::string& advice);

// clCreateBuffer of `bytes` (at least 1) that throws allocation_failure's message as an Error
// when memory runs out; other OpenCL errors pass through as ::cl::Error. Costs nothing more than
// clCreateBuffer when it succeeds (the limits are only asked after a failure).
::cl::Buffer make_buffer(const ::cl::Context& context, cl_mem_flags flags, size_t bytes,
                         const std::string& what, const std::string& advice = "");

// A read-only buffer holding `data` (at least one element: OpenCL has no empty buffers),
// written with a blocking copy on `queue`; make_buffer's message when memory runs out.
template <typename T>
::cl::Buffer upload_buffer(const ::cl::Context& context, const ::cl::CommandQueue& queue,
                           const std::vector<T>& data, const std::string& what,
                           const std::string& advice = "") {
  const size_t bytes = std::max<size_t>(1, data.size()) * sizeof(T);
  ::cl::Buffer buffer = make_buffer(context, CL_MEM_READ_ONLY, bytes, what, advice);
  if (!data.empty())
    queue.enqueueWriteBuffer(buffer, CL_TRUE, 0, data.size() * sizeof(T), data.data());
  return buffer;
}

}  // namespace rp::cl
