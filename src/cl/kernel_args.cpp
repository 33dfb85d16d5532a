#include "cl/kernel_args.h"

#include <string>

#include "cl/error.h"

namespace rp::cl {

void check_arg_count(const ::cl::Kernel& kernel, size_t given) {
  const cl_uint expected = kernel.getInfo<CL_KERNEL_NUM_ARGS>();
  if (given == expected) return;
  std::string name = kernel.getInfo<CL_KERNEL_FUNCTION_NAME>();
  while (!name.empty() && name.back() == '\0') name.pop_back();
  throw Error("kernel " + name + " takes " +
              std::to_string(expected) + " arguments but the host bound " +
              std::to_string(given));
}

}  // namespace rp::cl
