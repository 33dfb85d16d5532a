// ROLYPOLY_KERNEL_LOG=FILE: each kernel's function name is appended to FILE, one line, on its
// first launch in the process. The oclgrind suite sets it for every run and then checks that
// each __kernel in kernels/ was launched by at least one of them
// (tests/oclgrind/check_kernel_coverage.sh). Without the variable a launch costs one branch.
#pragma once

#include <CL/opencl.hpp>

namespace rp::cl {

// Called by Profiler::enqueue for every launch; tests that launch a product kernel themselves
// call it too. Throws nothing: a log that cannot be written is skipped (and the coverage check
// then reports the kernel as never launched).
void note_kernel_launch(const ::cl::Kernel& kernel) noexcept;

}  // namespace rp::cl
