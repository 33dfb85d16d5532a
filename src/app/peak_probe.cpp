#include "app/peak_probe.h"

#include <algorithm>
#include <string>
#include <vector>

#include "cl/error.h"
#include "cl/profiler.h"

namespace rp::app {
namespace {

constexpr size_t kGroup = 64;
constexpr double kMadsPerIteration = 8;     // per chain: the 8 RP_PROBE_STEPs of the loop body
constexpr double kLanes = 64;               // 8 float8 chains
constexpr uint32_t kMaxIterations = 32000;  // keeps every lane sum below 2^24 (exact)

// Device time (ms) of one launch recorded under `pass`.
double timed_launch(rp::cl::Profiler& profiler, const std::string& pass, const ::cl::Kernel& k,
                    size_t global) {
  profiler.enqueue(pass, k, ::cl::NDRange(global), ::cl::NDRange(kGroup));
  return profiler.collect()[pass];
}

}  // namespace

size_t probe_buffer_bytes(const rp::cl::DeviceInfo& info) {
  uint64_t bytes = 256ull << 20;
  if (info.max_alloc_bytes > 0) bytes = std::min(bytes, info.max_alloc_bytes);
  if (info.global_mem_bytes > 0) bytes = std::min(bytes, info.global_mem_bytes / 8);
  return size_t(bytes / 4096 * 4096);
}

double measure_bandwidth_gbps(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                              size_t buffer_bytes, int launches) {
  const size_t bytes = buffer_bytes / 4096 * 4096;
  if (bytes == 0 || launches < 1)
    throw rp::cl::Error("bandwidth probe: needs at least 4 KiB and one launch");
  const size_t items = bytes / 16;  // float4 per work-item; a multiple of kGroup
  ::cl::Buffer src(context.context, CL_MEM_READ_WRITE, bytes);
  ::cl::Buffer dst(context.context, CL_MEM_READ_WRITE, bytes);
  rp::cl::Profiler profiler(context.queue);
  ::cl::Kernel fill = programs.kernel("probe.cl", "probe_fill");
  fill.setArg(0, src);
  fill.setArg(1, cl_uint(items));
  timed_launch(profiler, "probe_fill", fill, items);
  ::cl::Kernel copy = programs.kernel("probe.cl", "probe_copy");
  copy.setArg(0, src);
  copy.setArg(1, dst);
  timed_launch(profiler, "probe_copy", copy, items);  // warm-up: first touch of dst's pages
  double best_ms = 0;
  for (int i = 0; i < launches; ++i) {
    const double ms = timed_launch(profiler, "probe_copy", copy, items);
    if (ms > 0 && (best_ms == 0 || ms < best_ms)) best_ms = ms;
  }
  // Verify: dst must hold the fill pattern (i & 0xFFFFFF, 1, 2, 3) everywhere.
  std::vector<float> out(items * 4);
  context.queue.enqueueReadBuffer(dst, CL_TRUE, 0, bytes, out.data());
  for (size_t i = 0; i < items; ++i) {
    const float* v = &out[4 * i];
    if (v[0] != float(i & 0xFFFFFFu) || v[1] != 1.0f || v[2] != 2.0f || v[3] != 3.0f)
      throw rp::cl::Error("bandwidth probe on '" + context.info.name + "': element " +
                          std::to_string(i) + " of the copy is wrong");
  }
  if (best_ms <= 0) throw rp::cl::Error("bandwidth probe: no launch took measurable time");
  return 2.0 * double(bytes) / (best_ms * 1e-3) / 1e9;
}

double measure_gflops(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                      size_t work_items, int launches, double target_ms) {
  const size_t items = rp::cl::round_up(std::max<size_t>(work_items, 1), kGroup);
  if (launches < 1) throw rp::cl::Error("compute probe: needs at least one launch");
  ::cl::Buffer out(context.context, CL_MEM_READ_WRITE, items * sizeof(float));
  rp::cl::Profiler profiler(context.queue);
  ::cl::Kernel k = programs.kernel("probe.cl", "probe_compute");
  k.setArg(0, out);
  k.setArg(1, 1.0f);  // a = b = 1: every mad adds exactly 1 (kernels/probe.cl)
  k.setArg(2, 1.0f);
  // Calibrate: grow the iteration count until one launch takes at least target_ms / 4, then
  // scale it to target_ms.
  uint32_t iterations = 16;
  double ms = 0;
  for (;;) {
    k.setArg(3, cl_uint(iterations));
    ms = timed_launch(profiler, "probe_compute", k, items);
    if (ms >= target_ms / 4 || iterations >= kMaxIterations) break;
    iterations = std::min(kMaxIterations, iterations * 4);
  }
  if (ms > 0 && ms < target_ms)
    iterations = uint32_t(std::min<double>(kMaxIterations, iterations * target_ms / ms));
  k.setArg(3, cl_uint(iterations));
  double best_ms = 0;
  for (int i = 0; i < launches; ++i) {
    ms = timed_launch(profiler, "probe_compute", k, items);
    if (ms > 0 && (best_ms == 0 || ms < best_ms)) best_ms = ms;
  }
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
  if (best_ms <= 0) throw rp::cl::Error("compute probe: no launch took measurable time");
  const double flops = double(items) * iterations * kMadsPerIteration * kLanes * 2.0;
  return flops / (best_ms * 1e-3) / 1e9;
}

DevicePeak measure_peak(const rp::cl::Context& context, rp::cl::ProgramCache& programs) {
  DevicePeak peak;
  peak.bandwidth_gbps =
      measure_bandwidth_gbps(context, programs, probe_buffer_bytes(context.info), 4);
  // Enough items to fill every compute unit many times over (GPUs need tens of thousands).
  const size_t items = std::max<size_t>(4096, size_t(context.info.compute_units) * 2048);
  peak.gflops = measure_gflops(context, programs, items, 3, 60.0);
  return peak;
}

}  // namespace rp::app
