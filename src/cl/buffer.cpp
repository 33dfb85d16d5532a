#include "cl/buffer.h"

#include <algorithm>
#include <cstdint>
#include <new>

#include "cl/error.h"

namespace rp::cl {
namespace {

// Rounded up, so that a few bytes never read "0 MiB".
std::string mib(uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

}  // namespace

bool is_out_of_memory(cl_int err) {
  // CL_INVALID_BUFFER_SIZE: above CL_DEVICE_MAX_MEM_ALLOC_SIZE.
  return err == CL_MEM_OBJECT_ALLOCATION_FAILURE || err == CL_OUT_OF_RESOURCES ||
         err == CL_OUT_OF_HOST_MEMORY || err == CL_INVALID_BUFFER_SIZE;
}

std::string allocation_failure(const ::cl::Context& context, size_t bytes, const std::string& what,
                               const std::string& reason, const std::string& advice) {
  std::string message = "allocating " + what + " (" + mib(bytes) + ") failed: " + reason;
  try {  // the limits, when the driver still answers
    const ::cl::Device device = context.getInfo<CL_CONTEXT_DEVICES>().front();
    message += " (the device has " + mib(device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>()) +
               " of global memory, at most " +
               mib(device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>()) + " in one buffer)";
  } catch (const std::exception&) {
  }
  if (!advice.empty()) message += "; " + advice;
  return message;
}

::cl::Buffer make_buffer(const ::cl::Context& context, cl_mem_flags flags, size_t bytes,
                         const std::string& what, const std::string& advice) {
  bytes = std::max<size_t>(bytes, 1);  // OpenCL has no empty buffers
  try {
    return ::cl::Buffer(context, flags, bytes);
  } catch (const ::cl::Error& e) {
    if (!is_out_of_memory(e.err())) throw;
    throw Error(allocation_failure(context, bytes, what, error_name(e.err()), advice));
  } catch (const std::bad_alloc&) {
    throw Error(allocation_failure(context, bytes, what, "out of host memory", advice));
  }
}

}  // namespace rp::cl
