// Runs the kernels of kernels/probe.cl (probe_fill, probe_copy, probe_copy_wrap, probe_compute)
// once at a
// tiny size, for the oclgrind label: the bench's peak probe is otherwise only reached through
// `rolypoly bench`, which is far too big for the simulator, and its gtests check plausible
// GB/s and GFLOP/s that a simulator cannot reach. The probes verify their outputs on the host
// and throw rp::cl::Error on a wrong result; this program then exits non-zero.
#include <cstdio>
#include <exception>

#include "bench/src/peak_probe.h"
#include "cl/context.h"
#include "cl/program_cache.h"

int main() {
  try {
    rp::cl::ensure_pocl_cache_dir();
    // Intentionally leaked: destroying OpenCL objects from exit-time code crashes under
    // oclgrind (see tests/support/cl_fixture.cpp); here they die with the process.
    auto* context = new rp::cl::Context(rp::cl::Context::create(""));
    auto* programs = new rp::cl::ProgramCache(*context);
    // 4 KiB = 256 float4 work-items, one timed copy; 64 work-items, one launch of the
    // shortest calibration step (any launch time is above the 1 us target).
    // A launch time the simulator reports as implausible is not an error here (Unmeasurable is
    // thrown after the output was verified).
    try {
      rp::bench::measure_bandwidth_gbps(*context, *programs, 4096, 1);
    } catch (const rp::bench::Unmeasurable&) {
    }
    // 4 KiB buffers wrapped twice: 512 work-items.
    try {
      rp::bench::measure_cached_bandwidth_gbps(*context, *programs, 4096, 16384, 1);
    } catch (const rp::bench::Unmeasurable&) {
    }
    try {
      rp::bench::measure_gflops(*context, *programs, 64, 1, 0.001);
    } catch (const rp::bench::Unmeasurable&) {
    }
    std::printf("probe kernels: outputs verified\n");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "probe kernels: %s\n", e.what());
    return 1;
  }
}
