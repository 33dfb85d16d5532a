// Work model of the hot passes: bytes moved and arithmetic done per frame, counted from each
// kernel's own structure (kernels/*.cl), so the bench can divide by the device's measured peak
// (src/app/peak_probe.h) and show how close a pass runs to the device's limit.
//
// Conventions (the formulas and their assumptions are next to each pass in pass_work.cpp and
// summarised in README, "Efficiency: bytes and arithmetic per pass"):
//   bytes: bytes named by the kernels' __global loads and stores (what the kernel asks for, not
//          DRAM traffic after caching: repeated gathers may hit cache). Atomic read-modify-writes
//          count 8 bytes per 4-byte word. The small per-frame constant structs are not counted.
//   flops: float add, sub, mul, div, sqrt = 1; mad/fma = 2; mix = 3; min/max/clamp/compare and
//          integer index arithmetic = 0. Order of magnitude, not an instruction count.
//   Data-dependent passes are modelled as stated upper bounds (light: every pixel covered, every
//   cone takes all its steps) or stated typical cases (visibility: tiles per draw item).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rp::app {

struct WorkParams {
  uint32_t width, height;      // render size in pixels
  uint32_t voxel_resolution;   // level-0 voxels per side (power of two)
  uint32_t shadow_size;        // shadow map texels per side
  uint32_t triangles;          // triangles in the mesh buffers (GpuScene::triangle_count); not
                               // used by any formula: every pass works on drawn triangles
  uint32_t instance_triangles; // triangles drawn per frame (GpuScene::instance_triangle_count)
  uint32_t spheres;            // analytic spheres (GpuScene::sphere_count)
  bool taa, bloom, motion_blur;  // post-processing passes enabled (else their work is 0)
  bool reference_quality = false;  // --quality reference: "light" is the per-pixel cone tracer
};

struct PassWork {
  double bytes = 0, flops = 0;  // per frame
};

// The work of one pass per frame; zeros for a pass name not modelled here.
PassWork pass_work(const std::string& pass, const WorkParams& p);

// The pass names pass_work models, in pipeline order.
const std::vector<std::string>& modelled_passes();

}  // namespace rp::app
