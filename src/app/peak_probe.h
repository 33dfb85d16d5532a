// Measured peak memory bandwidth and arithmetic rate of one OpenCL device (kernels/probe.cl),
// the denominators of the bench's efficiency columns (src/app/pass_work.h). Each kernel runs a
// few times and the best launch counts (device time from profiling events); the outputs are
// checked on the host so a launch that did not do its work throws instead of reporting a peak.
#pragma once

#include <cstddef>
#include <cstdint>

#include "cl/context.h"
#include "cl/program_cache.h"

namespace rp::app {

struct DevicePeak {
  double bandwidth_gbps = 0;  // GB/s (1e9 bytes), float4 copy: bytes read + bytes written
  double gflops = 0;          // GFLOP/s (1e9), float mads counted as 2 flops
};

// Both probes with sizes chosen from the device (about 1 s on a 2-core PoCL CPU, including
// the first build of probe.cl). Throws rp::cl::Error when a probe's output is wrong.
DevicePeak measure_peak(const rp::cl::Context& context, rp::cl::ProgramCache& programs);

// Best-of-`launches` float4 copy over two buffers of `buffer_bytes` each (rounded down to a
// multiple of 4 KiB); the whole destination is compared with the source afterwards.
double measure_bandwidth_gbps(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                              size_t buffer_bytes, int launches);

// Best-of-`launches` mad chains over `work_items` work-items; `target_ms` sets the work per
// launch (iterations grow from a short calibration launch until a launch takes about that
// long). Every item's checksum is verified.
double measure_gflops(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                      size_t work_items, int launches, double target_ms);

// The copy buffer size measure_peak uses: min(256 MiB, max alloc, global memory / 8), a
// multiple of 4 KiB.
size_t probe_buffer_bytes(const rp::cl::DeviceInfo& info);

}  // namespace rp::app
