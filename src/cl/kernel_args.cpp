#include "cl/kernel_args.h"

#include "cl/error.h"

namespace rp::cl {

std::string kernel_name(const ::cl::Kernel& kernel) {
  std::string name = kernel.getInfo<CL_KERNEL_FUNCTION_NAME>();
  while (!name.empty() && name.back() == '\0') name.pop_back();
  return name;
}

void check_arg_count(const ::cl::Kernel& kernel, size_t given) {
  const cl_uint expected = kernel.getInfo<CL_KERNEL_NUM_ARGS>();
  if (given == expected) return;
  throw Error("kernel " + kernel_name(kernel) + " takes " + std::to_string(expected) +
              " arguments but the host bound " + std::to_string(given));
}

}  // namespace rp::cl
