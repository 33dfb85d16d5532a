// Work model of the hot passes: bytes moved and arithmetic done per frame, counted from each
// kernel's own structure (kernels/*.cl), so the bench can divide by the device's measured peak
// (bench/src/peak_probe.h) and show how close a pass runs to the device's limit.
//
// Conventions (the formulas and their assumptions are next to each pass in pass_work.cpp and
// summarised in README, "Efficiency: bytes and arithmetic per pass"):
//   bytes: bytes named by the kernels' __global loads and stores (what the kernel asks for, not
//          DRAM traffic after caching: repeated gathers may hit cache). Atomic read-modify-writes
//          count 8 bytes per 4-byte word. The small per-frame constant structs are not counted.
//   flops: float add, sub, mul, div, sqrt = 1; mad/fma = 2; mix = 3; min/max/clamp/compare and
//          integer index arithmetic = 0. Order of magnitude, not an instruction count.
//   footprint: unique bytes touched (see PassWork), <= bytes.
//   Data-dependent passes are modelled as stated upper bounds (light: every pixel covered, every
//   cone takes all its steps) or stated typical cases (visibility: tiles per draw item).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rp::bench {

struct WorkParams {
  uint32_t width, height;      // render size in pixels
  uint32_t voxel_resolution;   // level-0 voxels per side (power of two)
  uint32_t shadow_size;        // shadow map texels per side
  uint32_t triangles;          // triangles in the mesh buffers (GpuScene::triangle_count); not
                               // used by any formula: every pass works on drawn triangles
  uint32_t instance_triangles; // triangles drawn per frame (GpuScene::instance_triangle_count)
  uint32_t voxel_triangles;    // triangles voxelized per frame (mesh proxies: scene::voxel_mesh)
  uint32_t shadow_triangles;   // triangles the shadow map draws (casters; scene::shadow_mesh)
  uint32_t spheres;            // analytic spheres (GpuScene::sphere_count)
  bool taa, bloom, motion_blur;  // post-processing passes enabled (else their work is 0)
  bool reference_quality = false;  // --quality reference: "light" is the per-pixel cone tracer
};

struct PassWork {
  double bytes = 0, flops = 0;  // per frame
  // Unique bytes the pass touches per frame (each buffer byte once, however often it is
  // requested): the per-pixel / per-voxel planes it reads and writes and its per-item records.
  // Small shared tables (vertices, instances, materials, textures) are left out, so this is a
  // lower bound; it picks the cache level of the pass's bandwidth ceiling (peak_probe.h).
  double footprint = 0;
};

// Copy bandwidth measured with a working set (source + destination bytes) of
// `working_set_bytes` (bench/src/peak_probe.h).
struct BandwidthLevel {
  double working_set_bytes = 0;
  double gbps = 0;
};

// Work done and the share of the ceiling it reached. Fractions:
// 0 = not counted (pass not modelled, no time, or the device's peak not measured); NaN = the
// model would put the pass above its ceiling (a work bound too loose or bytes served from a
// closer level than the footprint implies): the model cannot be right there, so no figure is
// shown (JSON null). Never above 1.
struct PassEfficiency {
  double bytes = 0.0;             // bytes requested per frame (pass_work's formulas)
  double flops = 0.0;             // arithmetic operations per frame
  double footprint = 0.0;         // unique bytes per frame (PassWork::footprint)
  double gbytes_per_s = 0.0;      // bytes / median time, 1e9 bytes per second
  double gflops_per_s = 0.0;      // flops / median time
  double ceiling_gbps = 0.0;      // bandwidth_ceiling_gbps for this pass (0 = not measured)
  double bandwidth_fraction = 0.0;  // gbytes_per_s / ceiling_gbps
  double compute_fraction = 0.0;    // gflops_per_s / device peak compute
};

// Cache-aware roofline ceiling (GB/s) for a pass that requests `bytes` per frame over a unique
// footprint of `footprint` bytes: the shortest time the measured levels allow is
//   max(bytes / fastest level, footprint / fastest level whose working set holds the footprint
//       (the last, DRAM-sized level when none does)),
// and the ceiling is bytes / that time. 0 when `levels` is empty or bytes <= 0.
double bandwidth_ceiling_gbps(const std::vector<BandwidthLevel>& levels, double bytes,
                              double footprint);

// The efficiency of a pass doing `work` in `median_ms` on a device with the measured `levels`
// (empty = bandwidth not measured) and `peak_gflops` (0 = not measured).
PassEfficiency pass_efficiency(const PassWork& work, double median_ms,
                               const std::vector<BandwidthLevel>& levels, double peak_gflops);

// The work of one pass per frame; zeros for a pass name not modelled here.
PassWork pass_work(const std::string& pass, const WorkParams& p);

// The pass names pass_work models, in pipeline order.
const std::vector<std::string>& modelled_passes();

}  // namespace rp::bench
