// Counts C++ heap allocations (every global operator new / new[] of the test_app binary, on every
// thread) for tests that check a code path allocates nothing, and says where the ones it saw
// came from. alloc_counter.cpp replaces the global allocation functions of this binary; malloc
// calls from C code (the OpenCL runtime, ocl-icd) are not operator new and are not counted.
//
// Not available under AddressSanitizer (the sanitizer's own operator new stays in place so that
// new/delete mismatches are still caught): enabled() is then false.
#pragma once

#include <cstdint>
#include <string>

namespace rp::test {

class AllocationCounter {
 public:
  // False when the replacement is compiled out (AddressSanitizer builds).
  static bool enabled();
  // operator new calls since the process started.
  static uint64_t count();

  // While recording, the call stack of each allocation (up to kMaxTraces of them) is kept in a
  // fixed array (the recording itself allocates nothing).
  static void start_recording();
  static void stop_recording();
  // The recorded allocations grouped by call stack, most frequent first, with function names
  // (addr2line for this binary, dladdr for shared libraries): "N x\n  frame\n  frame...".
  // `per` divides the counts (e.g. the number of frames measured) for "N.N per frame".
  static std::string report(double per = 1.0);
};

}  // namespace rp::test
