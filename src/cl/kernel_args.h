// Binds a kernel's arguments in one call, in the order of its signature: buffers, local-memory
// sizes and (by value) one parameter struct of kernels/shared/pass_params.h holding the
// kernel's scalars by name. It throws rp::cl::Error, naming the kernel, when the number of
// values is not the kernel's argument count: a kernel object keeps the values of its last
// launch, so an argument the host forgot to set after a signature change would otherwise run
// silently with a stale value.
#pragma once

#include <cstddef>
#include <string>

#include <CL/opencl.hpp>

namespace rp::cl {

// The kernel's function name (CL_KERNEL_FUNCTION_NAME without the terminating NULs some
// bindings keep), for messages and logs.
std::string kernel_name(const ::cl::Kernel& kernel);

// Throws rp::cl::Error unless `kernel` takes exactly `given` arguments (CL_KERNEL_NUM_ARGS).
void check_arg_count(const ::cl::Kernel& kernel, size_t given);

template <typename... Args>
void bind_args(::cl::Kernel& kernel, const Args&... args) {
  check_arg_count(kernel, sizeof...(Args));
  cl_uint index = 0;
  (kernel.setArg(index++, args), ...);
}

}  // namespace rp::cl
