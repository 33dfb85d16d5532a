// Device discovery and choice, and the context + in-order profiling queue every pass uses.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <CL/opencl.hpp>

#include "cl/pocl_cache.h"  // ensure_pocl_cache_dir: before the first OpenCL call
#include "cl/profiler.h"

namespace rp::cl {

struct DeviceInfo {
  int index = 0;              // position in list_devices(): what `--device N` means
  int platform_index = 0;
  std::string platform_name;
  std::string name;
  std::string vendor;
  std::string type;           // "GPU", "CPU", "accelerator", ...
  bool is_gpu = false;
  bool is_cpu = false;
  uint32_t compute_units = 0;
  uint64_t global_mem_bytes = 0;
  uint64_t max_alloc_bytes = 0;
  uint64_t local_mem_bytes = 0;
  size_t max_work_group_size = 0;
  uint32_t native_float_width = 1;  // CL_DEVICE_NATIVE_VECTOR_WIDTH_FLOAT: 8 on AVX2, 16 on AVX-512
  std::string version;        // CL_DEVICE_VERSION, e.g. "OpenCL 3.0 PoCL ..."
  std::string c_version;      // CL_DEVICE_OPENCL_C_VERSION
  ::cl::Device device;
};

// Every device of every platform, in platform order. Throws rp::cl::Error when there is no
// OpenCL platform at all (with a hint on what to install).
std::vector<DeviceInfo> list_devices();

// Picks a device: empty spec = first GPU, else first CPU; a number = that index in
// list_devices(); anything else = first device whose name (or platform name) contains spec,
// case-insensitively. Throws rp::cl::Error listing the devices when nothing matches.
DeviceInfo choose_device(const std::string& spec);

// Pixels (triangles, voxels) per work-item of the span kernels (kernels/common/span.h) on a
// CPU: the device's native float vector width, 8 or 16, so that a span fills the SIMD
// registers without spilling them. PoCL reports 8 on AVX2 and 16 on AVX-512. Measured on the
// 2-core AVX2 EPYC (busy 720, perf cpu-clock, both threads): gbuffer_resolve 42.3 CPU ms a
// frame with 16 lanes against 32.1 with 8 (16 lanes are two registers each, and the texture
// footprint's live values spill); the raster and the voxelizer within noise. On the AVX-512
// EPYC 16 was the faster choice for all three (comments in passes/gbuffer.cpp, visibility.cpp).
int cpu_span_lanes(const DeviceInfo& info);

// Context and one in-order queue with profiling enabled, on one device.
struct Context {
  DeviceInfo info;
  ::cl::Context context;
  ::cl::CommandQueue queue;
  // How passes are timed on this device: kDevice when two 4 MiB buffer fills report usable
  // profiling timestamps (timestamps_usable), else kHost. ROLYPOLY_TIMING=host or =device in
  // the environment overrides the check (tests and diagnosis).
  Timing timing = Timing::kDevice;

  static Context create(const std::string& device_spec);
  static Context create(const DeviceInfo& info);
};

// Runs the timestamp check of Context::create on `queue` (no override): two back-to-back fills
// of a 4 MiB buffer, their events' timestamps judged by timestamps_usable (each must take
// >= 100 ns). Any OpenCL error reading the timestamps counts as unusable.
Timing detect_timing(const ::cl::Context& context, const ::cl::CommandQueue& queue);

}  // namespace rp::cl
