#include "support/cl_fixture.h"

#include <cstdlib>
#include <memory>

namespace rp::test {

rp::cl::Context& context() {
  static std::unique_ptr<rp::cl::Context> ctx = [] {
    rp::cl::ensure_pocl_cache_dir();
    const char* spec = std::getenv("ROLYPOLY_TEST_DEVICE");
    return std::make_unique<rp::cl::Context>(rp::cl::Context::create(spec ? spec : ""));
  }();
  return *ctx;
}

rp::cl::ProgramCache& programs() {
  static rp::cl::ProgramCache cache(context());
  return cache;
}

}  // namespace rp::test
