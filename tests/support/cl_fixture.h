// Test access to one OpenCL device: ROLYPOLY_TEST_DEVICE if set, else the default choice
// (first GPU, else first CPU: PoCL on the CI machine). One context and program cache per test
// binary, so kernels build once.
#pragma once

#include "cl/context.h"
#include "cl/profiler.h"
#include "cl/program_cache.h"

namespace rp::test {

rp::cl::Context& context();
rp::cl::ProgramCache& programs();

}  // namespace rp::test
