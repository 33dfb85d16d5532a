// Measured peak memory bandwidth and arithmetic rate of one OpenCL device (kernels/probe.cl),
// the ceilings of the bench's efficiency columns (bench/src/pass_work.h). Each kernel runs a few
// times and the best launch counts (device time from profiling events, or the host's clock
// around a finished launch where the device's timestamps are unusable: Context::timing); the
// outputs are checked on the host so a launch that did not do its work throws instead of
// reporting a peak. A probe whose launches cannot be timed (no measurable time, or a figure no
// device reaches) reports "not measured" and why, never a number.
//
// Cache-aware roofline: bandwidth is measured at working sets that fit the cache levels (copy
// kernels that wrap around a small buffer) as well as at a DRAM-sized stream; a pass's
// requested bytes are set against the ceiling its unique footprint implies
// (bandwidth_ceiling_gbps in pass_work.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "bench/src/pass_work.h"  // BandwidthLevel
#include "cl/context.h"
#include "cl/error.h"
#include "cl/program_cache.h"

namespace rp::bench {

// A probe launch that could not be timed (zero or implausibly short time): the figure would be
// meaningless. measure_peak turns it into a "not measured" note.
class Unmeasurable : public rp::cl::Error {
 public:
  using rp::cl::Error::Error;
};

struct DevicePeak {
  double bandwidth_gbps = 0;  // GB/s (1e9 bytes), DRAM-sized float4 copy: read + written bytes
  double gflops = 0;          // GFLOP/s (1e9), float mads counted as 2 flops
  // Copy bandwidth by working set, ascending; the last entry is the DRAM-sized stream
  // (bandwidth_gbps). Empty when bandwidth was not measured.
  std::vector<BandwidthLevel> levels;
  // "" when measured; else why not (then the figure is 0).
  std::string bandwidth_note, compute_note;
  rp::cl::Timing timing = rp::cl::Timing::kDevice;  // how the launches were timed
};

// Both probes with sizes chosen from the device (about 1-2 s on a 2-core PoCL CPU, including
// the first build of probe.cl). Throws rp::cl::Error when a probe's output is wrong.
DevicePeak measure_peak(const rp::cl::Context& context, rp::cl::ProgramCache& programs);

// Best-of-`launches` float4 copy over two buffers of `buffer_bytes` each (rounded down to a
// multiple of 4 KiB); the whole destination is compared with the source afterwards. Throws
// Unmeasurable when no launch took a plausible time.
double measure_bandwidth_gbps(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                              size_t buffer_bytes, int launches);

// Best-of-`launches` float4 copy within two buffers of `buffer_bytes` each (a power of two,
// >= 4 KiB), wrapping around them until `traffic_bytes` (read + written) have moved per launch:
// the bandwidth of the cache level that holds 2 x buffer_bytes. Verified like the stream copy.
double measure_cached_bandwidth_gbps(const rp::cl::Context& context,
                                     rp::cl::ProgramCache& programs, size_t buffer_bytes,
                                     size_t traffic_bytes, int launches);

// Best-of-`launches` mad chains over `work_items` work-items; `target_ms` sets the work per
// launch (iterations grow from a short calibration launch until a launch takes about that
// long). Every item's checksum is verified. Throws Unmeasurable like the copies.
double measure_gflops(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                      size_t work_items, int launches, double target_ms);

// The copy buffer size measure_peak uses: min(256 MiB, max alloc, global memory / 8), a
// multiple of 4 KiB.
size_t probe_buffer_bytes(const rp::cl::DeviceInfo& info);

// The working sets (source + destination bytes) the cached-bandwidth probes use: 32 KiB,
// 256 KiB, 2 MiB and 16 MiB (typical L1, L2, L3 slice and L3 sizes), each below the DRAM
// stream's working set.
std::vector<size_t> cache_working_sets(size_t stream_buffer_bytes);

// A launch time is plausible when it is at least 1 microsecond and the rate it implies
// (`amount` per launch: bytes or flops) is at most `max_rate` per second.
bool plausible_launch(double ms, double amount, double max_rate);

}  // namespace rp::bench
