#include "bench/src/peak_probe.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "cl/kernel_args.h"
#include "cl/profiler.h"

namespace rp::bench {
namespace {

constexpr size_t kGroup = 64;
constexpr double kMadsPerIteration = 8;     // per chain: the 8 RP_PROBE_STEPs of the loop body
constexpr double kLanes = 64;               // 8 float8 chains
constexpr uint32_t kMaxIterations = 32000;  // keeps every lane sum below 2^24 (exact)
// Rates no device reaches: a figure above them means the launch was not really timed.
constexpr double kMaxBytesPerSecond = 1e15;  // 1 PB/s
constexpr double kMaxFlopsPerSecond = 1e17;  // 100 PFLOP/s

// Time (ms) of one launch recorded under `pass` (device or host timing, as the profiler does).
double timed_launch(rp::cl::Profiler& profiler, const std::string& pass, const ::cl::Kernel& k,
                    size_t global) {
  profiler.enqueue(pass, k, ::cl::NDRange(global), ::cl::NDRange(kGroup));
  return profiler.collect()[pass];
}

std::string mib(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g MiB", bytes / (1 << 20));
  return buf;
}

// Best plausible time of `ms`, or throws Unmeasurable naming what was timed.
double best_plausible(const std::vector<double>& ms, double amount, double max_rate,
                      const std::string& what, const rp::cl::Context& context) {
  double best = 0;
  for (double t : ms)
    if (plausible_launch(t, amount, max_rate) && (best == 0 || t < best)) best = t;
  if (best > 0) return best;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g ms", ms.empty() ? 0.0 : *std::min_element(ms.begin(), ms.end()));
  throw Unmeasurable(what + " on '" + context.info.name + "': no launch took a measurable time (" +
                     std::string(rp::cl::timing_name(context.timing)) +
                     " timing, shortest launch " + buf + ")");
}

// Fills `src` with the pattern (i & 0xFFFFFF, 1, 2, 3) and checks `dst` holds it after a copy.
void fill(rp::cl::Profiler& profiler, rp::cl::ProgramCache& programs, const ::cl::Buffer& src,
          size_t items) {
  ::cl::Kernel k = programs.kernel("probe.cl", "probe_fill");
  rp::cl::bind_args(k, src, cl_uint(items));
  timed_launch(profiler, "probe_fill", k, items);
}

void verify_copy(const rp::cl::Context& context, const ::cl::Buffer& dst, size_t items) {
  std::vector<float> out(items * 4);
  context.queue.enqueueReadBuffer(dst, CL_TRUE, 0, items * 16, out.data());
  for (size_t i = 0; i < items; ++i) {
    const float* v = &out[4 * i];
    if (v[0] != float(i & 0xFFFFFFu) || v[1] != 1.0f || v[2] != 2.0f || v[3] != 3.0f)
      throw rp::cl::Error("bandwidth probe on '" + context.info.name + "': element " +
                          std::to_string(i) + " of the copy is wrong");
  }
}

}  // namespace

bool plausible_launch(double ms, double amount, double max_rate) {
  return ms >= 1e-3 && amount / (ms * 1e-3) <= max_rate;
}

size_t probe_buffer_bytes(const rp::cl::DeviceInfo& info) {
  uint64_t bytes = 256ull << 20;
  if (info.max_alloc_bytes > 0) bytes = std::min(bytes, info.max_alloc_bytes);
  if (info.global_mem_bytes > 0) bytes = std::min(bytes, info.global_mem_bytes / 8);
  return size_t(bytes / 4096 * 4096);
}

std::vector<size_t> cache_working_sets(size_t stream_buffer_bytes) {
  std::vector<size_t> sets;
  for (size_t ws : {size_t(32) << 10, size_t(256) << 10, size_t(2) << 20, size_t(16) << 20})
    if (ws < 2 * stream_buffer_bytes) sets.push_back(ws);
  return sets;
}

double measure_bandwidth_gbps(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                              size_t buffer_bytes, int launches) {
  const size_t bytes = buffer_bytes / 4096 * 4096;
  if (bytes == 0 || launches < 1)
    throw rp::cl::Error("bandwidth probe: needs at least 4 KiB and one launch");
  const size_t items = bytes / 16;  // float4 per work-item; a multiple of kGroup
  ::cl::Buffer src(context.context, CL_MEM_READ_WRITE, bytes);
  ::cl::Buffer dst(context.context, CL_MEM_READ_WRITE, bytes);
  rp::cl::Profiler profiler(context.queue, context.timing);
  fill(profiler, programs, src, items);
  ::cl::Kernel copy = programs.kernel("probe.cl", "probe_copy");
  rp::cl::bind_args(copy, src, dst);
  timed_launch(profiler, "probe_copy", copy, items);  // warm-up: first touch of dst's pages
  std::vector<double> ms;
  for (int i = 0; i < launches; ++i) ms.push_back(timed_launch(profiler, "probe_copy", copy, items));
  verify_copy(context, dst, items);
  const double traffic = 2.0 * double(bytes);
  const double best = best_plausible(ms, traffic, kMaxBytesPerSecond,
                                     "bandwidth probe (" + mib(traffic) + " per launch)", context);
  return traffic / (best * 1e-3) / 1e9;
}

double measure_cached_bandwidth_gbps(const rp::cl::Context& context,
                                     rp::cl::ProgramCache& programs, size_t buffer_bytes,
                                     size_t traffic_bytes, int launches) {
  const size_t items = buffer_bytes / 16;
  if (buffer_bytes < 4096 || (items & (items - 1)) != 0 || launches < 1)
    throw rp::cl::Error("cached bandwidth probe: needs a power-of-two buffer of at least 4 KiB "
                        "and one launch");
  const size_t global = rp::cl::round_up(std::max(items, traffic_bytes / 32), items);
  ::cl::Buffer src(context.context, CL_MEM_READ_WRITE, buffer_bytes);
  ::cl::Buffer dst(context.context, CL_MEM_READ_WRITE, buffer_bytes);
  rp::cl::Profiler profiler(context.queue, context.timing);
  fill(profiler, programs, src, items);
  ::cl::Kernel copy = programs.kernel("probe.cl", "probe_copy_wrap");
  rp::cl::bind_args(copy, src, dst, cl_uint(items - 1));
  timed_launch(profiler, "probe_copy_wrap", copy, global);  // warm-up: caches filled
  std::vector<double> ms;
  for (int i = 0; i < launches; ++i)
    ms.push_back(timed_launch(profiler, "probe_copy_wrap", copy, global));
  verify_copy(context, dst, items);
  const double traffic = 32.0 * double(global);
  const double best =
      best_plausible(ms, traffic, kMaxBytesPerSecond,
                     "cached bandwidth probe (" + mib(2.0 * double(buffer_bytes)) + " working set)", context);
  return traffic / (best * 1e-3) / 1e9;
}

double measure_gflops(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                      size_t work_items, int launches, double target_ms) {
  const size_t items = rp::cl::round_up(std::max<size_t>(work_items, 1), kGroup);
  if (launches < 1) throw rp::cl::Error("compute probe: needs at least one launch");
  ::cl::Buffer out(context.context, CL_MEM_READ_WRITE, items * sizeof(float));
  rp::cl::Profiler profiler(context.queue, context.timing);
  ::cl::Kernel k = programs.kernel("probe.cl", "probe_compute");
  // a = b = 1: every mad adds exactly 1 (kernels/probe.cl)
  const auto bind = [&](uint32_t iterations) {
    rp::cl::bind_args(k, out, 1.0f, 1.0f, cl_uint(iterations));
  };
  // Calibrate: grow the iteration count until one launch takes at least target_ms / 4, then
  // scale it to target_ms. (A device with unusable time stops at kMaxIterations.)
  uint32_t iterations = 16;
  double ms = 0;
  for (;;) {
    bind(iterations);
    ms = timed_launch(profiler, "probe_compute", k, items);
    if (ms >= target_ms / 4 || iterations >= kMaxIterations) break;
    iterations = std::min(kMaxIterations, iterations * 4);
  }
  if (ms > 0 && ms < target_ms)
    iterations = uint32_t(std::min<double>(kMaxIterations, iterations * target_ms / ms));
  bind(iterations);
  std::vector<double> times;
  for (int i = 0; i < launches; ++i) times.push_back(timed_launch(profiler, "probe_compute", k, items));
  // Verify: item g holds sum over lanes j = 0..63 of ((g & 255) + j + 8 * iterations).
  std::vector<float> result(items);
  context.queue.enqueueReadBuffer(out, CL_TRUE, 0, items * sizeof(float), result.data());
  for (size_t g = 0; g < items; ++g) {
    const double expected = 64.0 * double(g & 255u) + 2016.0 + 512.0 * iterations;
    if (double(result[g]) != expected)
      throw rp::cl::Error("compute probe on '" + context.info.name + "': item " +
                          std::to_string(g) + " summed " + std::to_string(result[g]) +
                          ", expected " + std::to_string(expected));
  }
  const double flops = double(items) * iterations * kMadsPerIteration * kLanes * 2.0;
  const double best =
      best_plausible(times, flops, kMaxFlopsPerSecond, "compute probe", context);
  return flops / (best * 1e-3) / 1e9;
}

DevicePeak measure_peak(const rp::cl::Context& context, rp::cl::ProgramCache& programs) {
  DevicePeak peak;
  peak.timing = context.timing;
  const size_t stream = probe_buffer_bytes(context.info);
  try {
    for (size_t ws : cache_working_sets(stream)) {
      // 64 MiB of traffic per launch, or 16 passes over the working set if that is more.
      const size_t traffic = std::max<size_t>(64u << 20, 16 * ws);
      peak.levels.push_back(
          {double(ws), measure_cached_bandwidth_gbps(context, programs, ws / 2, traffic, 4)});
    }
    peak.bandwidth_gbps = measure_bandwidth_gbps(context, programs, stream, 4);
    peak.levels.push_back({2.0 * double(stream), peak.bandwidth_gbps});
  } catch (const Unmeasurable& e) {
    peak.bandwidth_gbps = 0;
    peak.levels.clear();
    peak.bandwidth_note = e.what();
  }
  // Enough items to fill every compute unit many times over (GPUs need tens of thousands).
  const size_t items = std::max<size_t>(4096, size_t(context.info.compute_units) * 2048);
  try {
    peak.gflops = measure_gflops(context, programs, items, 3, 60.0);
  } catch (const Unmeasurable& e) {
    peak.gflops = 0;
    peak.compute_note = e.what();
  }
  return peak;
}

}  // namespace rp::bench
