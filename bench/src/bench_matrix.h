// The cross-device bench matrix: every chosen device x every image size x every voxel
// resolution, the same simulated frames on each, plus the power-law fits of how the frame time
// grows with the work. Results only (no OpenCL here): the measuring itself is a callback, so the
// loop, the per-device skip on errors and the fits are testable without a device.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/pass_stats.h"
#include "bench/src/pass_work.h"  // PassEfficiency, BandwidthLevel
#include "cl/context.h"

namespace rp::bench {

// Concatenation by appends: `"literal" + std::string(...)` trips GCC 12's -Wrestrict false
// positive under -O2 -Werror.
template <class... Parts>
std::string str_cat(const Parts&... parts) {
  std::string out;
  (out.append(std::string_view(parts)), ...);
  return out;
}

struct PassResult {
  std::string name;
  app::TimeSummary ms;
  PassEfficiency efficiency;
};

// One (size, voxel resolution) cell on one device.
struct RunResult {
  uint32_t width = 0, height = 0;
  uint32_t voxels = 0;           // voxel volume resolution per side
  uint32_t frames = 0;           // measured frames
  std::string timing = "device";  // "device" or "host": how its pass times were taken
  std::string gi_volume = "dense";  // --gi-volume: "dense" or "svo"
  // The render scale and render size of the last frame (--render-scale, or where --target-ms
  // left it); 1 and the output size without either.
  float render_scale = 1.0f;
  uint32_t render_width = 0, render_height = 0;
  // The scales the measured frames were rendered at: the smallest, the largest, and how often
  // it changed from one measured frame to the next (under --target-ms; 1, 1, 0 without).
  float scale_min = 1.0f, scale_max = 1.0f;
  uint32_t scale_changes = 0;
  // svo only (0 otherwise): the octree path's device memory after the last frame and its peak
  // (pools + build scratch, CL_MEM_SIZE), the pools alone, in bytes
  uint64_t octree_device_bytes = 0, octree_peak_bytes = 0, octree_pool_bytes = 0;
  // Of the octree: the node pool, the brick pool (table + own samples) in use, the
  // fragments and the fragment list's bytes.
  uint64_t octree_node_bytes = 0, octree_brick_bytes = 0, octree_fragments = 0,
           octree_fragment_bytes = 0;
  // The device memory of the buffers that follow the image, per part (pass name, bytes) as the
  // renderer held them after the last frame (render::Renderer::frame_device_memory).
  std::vector<std::pair<std::string, uint64_t>> frame_memory;
  std::vector<PassResult> passes;  // pipeline order (pipeline_rank)
  app::TimeSummary frame;             // wall clock of Renderer::render per frame
  // What the measured frames drew (the last one; every device draws the same frames).
  uint32_t spheres = 0, instances = 0, instance_triangles = 0;
  // Of those, the triangles the voxelizer and the shadow map took (mesh proxies, casters).
  uint32_t voxel_triangles = 0, shadow_triangles = 0;

  double fps() const { return frame.median_ms > 0.0 ? 1000.0 / frame.median_ms : 0.0; }
  double pixels() const { return double(width) * double(height); }
  // The pass's entry, nullptr when this run has no timings for it.
  const PassResult* pass(const std::string& name) const;
};

// From the frames' statistics (needs at least one frame).
RunResult make_run_result(uint32_t width, uint32_t height, uint32_t voxels,
                          const app::PassStats& stats);

// time ~ a * x^k, fitted by least squares on (log x, log time).
struct PowerFit {
  double a = 0.0;     // ms at x = 1
  double k = 0.0;     // exponent: doubling x multiplies the time by 2^k
  double r2 = 0.0;    // coefficient of determination on the log-log data (1 = exact)
  uint32_t points = 0;
};

// Needs >= 2 points with distinct x, every x and y > 0; otherwise std::invalid_argument.
PowerFit fit_power_law(const std::vector<double>& x, const std::vector<double>& y);

// Frame time against pixel count (w*h) at one voxel resolution.
struct PixelScaling {
  uint32_t voxels = 0;
  PowerFit fit;
};
// Frame time against voxel count (resolution^3) at one image size.
struct VoxelScaling {
  uint32_t width = 0, height = 0;
  PowerFit fit;
};

struct DeviceResult {
  int index = 0;             // in rp::cl::list_devices()
  std::string name, type, platform;
  uint32_t compute_units = 0;
  std::string skipped;       // "" = ran; else the error that stopped this device
  // How pass times were taken: "device" (profiling events) or "host" (finish after each pass,
  // wall clock: the device's timestamps were unusable; rp::cl::Timing).
  std::string timing = "device";
  double peak_bandwidth_gbps = 0.0;  // measured peak, DRAM-sized stream (0 = not measured)
  double peak_gflops = 0.0;          // (0 = not measured)
  std::vector<BandwidthLevel> bandwidth_levels;  // by working set, ascending; last = DRAM
  std::string bandwidth_note, compute_note;      // why a peak was not measured ("" = it was)
  std::vector<RunResult> runs;       // voxels outer, sizes inner, as planned
  std::vector<PixelScaling> pixel_scaling;  // one per voxel resolution with >= 2 sizes
  std::vector<VoxelScaling> voxel_scaling;  // one per size with >= 2 voxel resolutions

  bool ok() const { return skipped.empty(); }
  std::string label() const;  // "[0] pthread-... (CPU)"
};

// What the bench records of a scene file (bench --scene FILE; bench/src/bench_scene.h).
struct SceneFileFacts {
  std::string path;          // as given on the command line
  std::string content_hash;  // 16 hex digits: the file's bytes and those of the files it names
  uint32_t triangles = 0;    // drawn by the file's instances (a mesh drawn twice counts twice)
  uint32_t meshes = 0, instances = 0, materials = 0, textures = 0;
  uint32_t lights = 0;       // punctual lights (KHR_lights_punctual), the demo's lamp not counted
  bool lamp = false;         // the file carries the demo's lamp (written by `rolypoly export`)
};

struct BenchMatrix {
  std::string command;     // the command line that produced it (informational)
  std::string scene;       // "default", "busy" or "file" (then `file` says which)
  std::optional<SceneFileFacts> file;
  uint64_t seed = 1;
  // --bounces of the real-time modes (1 = single bounce); older files have no
  // field and read as 1, the only count the renderer had then.
  uint32_t bounces = 1;
  uint32_t frames = 0, warmup = 0;
  std::vector<std::pair<uint32_t, uint32_t>> sizes;  // (width, height)
  std::vector<uint32_t> voxels;
  std::vector<DeviceResult> devices;

  size_t devices_ok() const;
};

// Fills pixel_scaling and voxel_scaling of `device` from its runs (frame median ms).
void fit_scaling(DeviceResult& device);

// Devices named by `spec`: "all" = every device; otherwise a comma-separated list of indices
// (as `rolypoly devices` prints them) and/or case-insensitive substrings of the device or
// platform name (a substring picks every device it matches). Order of the list, duplicates
// dropped. Throws rp::cl::Error naming the token and listing the devices when one matches none.
std::vector<rp::cl::DeviceInfo> select_devices(const std::string& spec,
                                               const std::vector<rp::cl::DeviceInfo>& all);

struct MatrixPlan {
  std::vector<rp::cl::DeviceInfo> devices;
  std::vector<std::pair<uint32_t, uint32_t>> sizes;
  std::vector<uint32_t> voxels;
};

// Measures one cell; throws rp::cl::Error (or ::cl::Error) when the device cannot build or run
// a kernel.
using MeasureRun = std::function<RunResult(const rp::cl::DeviceInfo& device, uint32_t width,
                                           uint32_t height, uint32_t voxels)>;
// Optional per-device step after its runs (efficiency: peak probe); may throw like MeasureRun.
using FinishDevice = std::function<void(const rp::cl::DeviceInfo& device, DeviceResult& result)>;

// Runs every device in turn (voxels outer, sizes inner). A device whose MeasureRun or
// FinishDevice throws rp::cl::Error or ::cl::Error is recorded as skipped with the message (its
// finished runs dropped) and the next device runs; "device <label> skipped: <message>" goes to
// `log` (nullptr = silent). Other exceptions propagate. Fits the scaling of every device that ran.
// `matrix` must hold the metadata (command, scene, ...); its devices are replaced.
void run_matrix(const MatrixPlan& plan, const MeasureRun& measure, const FinishDevice& finish,
                BenchMatrix& matrix, std::FILE* log);

}  // namespace rp::bench
