#include "support/cl_fixture.h"

#include <cstdlib>

namespace rp::test {

// The shared context and program cache are intentionally never destroyed (leaked on purpose).
// Static destructors run after the OpenCL implementation's own exit-time teardown: under
// oclgrind, releasing the context or its programs then aborts the process ("corrupted
// double-linked list"), which would make every gtest binary fail under the oclgrind label
// even though all tests passed. The OS reclaims the memory at exit; LeakSanitizer does not
// report it because the pointers stay reachable from these statics.
rp::cl::Context& context() {
  static rp::cl::Context* const ctx = [] {
    rp::cl::ensure_pocl_cache_dir();
    const char* spec = std::getenv("ROLYPOLY_TEST_DEVICE");
    return new rp::cl::Context(rp::cl::Context::create(spec ? spec : ""));
  }();
  return *ctx;
}

rp::cl::ProgramCache& programs() {
  static rp::cl::ProgramCache* const cache = new rp::cl::ProgramCache(context());
  return *cache;
}

}  // namespace rp::test
