// Plain C++ reference of the voxelize pass (kernels/voxelize.cl): every triangle against every
// voxel of its voxel range (no dominant-axis candidate search),
// every sphere against every voxel of its bounding box, the same float operations in the same
// order (FP contraction is off in the kernel and the host compiler does not contract), the
// same fixed-point rounding and wrap-around sums, so the integer sums must agree exactly where
// the radiance is exact (emission; lighting uses rsqrt/normalize whose rounding differs, so lit
// values agree to a tolerance).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cl/profiler.h"
#include "passes/voxelize.h"
#include "render/gpu_scene.h"
#include "render/gpu_types.h"
#include "scene/frame_scene.h"

namespace rp::test {

struct RefF3 {
  float x = 0.0f, y = 0.0f, z = 0.0f;
};

// The voxelizer's sums for an R^3 volume: accum holds (r*a, g*a, b*a, a) per voxel in
// fixed point (render/voxel_volume.h), overflow the wrapped-channel bits.
struct VoxelSums {
  uint32_t resolution = 0;
  std::vector<uint32_t> accum;     // 4 per voxel, x fastest
  std::vector<uint32_t> overflow;  // 1 per voxel
};

// Inputs as the kernels see them: the frame constants and the instance / sphere arrays of
// render::GpuScene, the assets' meshes (instance i draws frame.instances[i].mesh), and the
// shadow map (constants.shadow_size^2 depths).
struct VoxelRefInput {
  const scene::SceneAssets* assets = nullptr;
  const scene::FrameScene* frame = nullptr;
  gpu::FrameConstants constants{};
  std::vector<gpu::Instance> instances;
  std::vector<gpu::Sphere> spheres;
  std::vector<float> shadow;
};

VoxelSums reference_voxelize(const VoxelRefInput& in, uint32_t resolution);

// Level 0 from the sums (voxelize_resolve): x y z w per voxel.
std::vector<float> reference_resolve(const VoxelSums& sums);

// A triangle's vertices in grid units (object position -> world by `model` -> grid), exactly as
// the kernel computes them.
std::array<RefF3, 3> reference_grid_triangle(const gpu::rp_mat4& model,
                                             const std::array<RefF3, 3>& object,
                                             uint32_t resolution);

// The kernel's exact triangle / closed voxel box test on a grid-unit triangle in an R^3 volume
// (the triangle's voxel range clipped to the volume, then the ten other separating axes).
bool reference_triangle_box(const std::array<RefF3, 3>& tri, uint32_t resolution, int x, int y,
                            int z);

// ---- Device harness shared by the voxelize tests ----

struct VoxelGpuOutput {
  VoxelSums sums;
  std::vector<float> level0;  // x y z w per voxel
  rp::cl::PassTimes times;
};

// Runs the voxelize pass at resolution r on `gpu` (already update()d; this sets its constants'
// voxel_resolution / voxel_levels and rewrites its frame buffer) with the shadow map `shadow`
// (gpu.constants.shadow_size^2 depths). The volume's buffers start filled with garbage so a
// missing clear or resolve shows.
VoxelGpuOutput run_voxelize(render::GpuScene& gpu, const std::vector<float>& shadow, uint32_t r);

// The same with a given pass (its state, the static surface cache, carries over between
// calls) and volume (resized to r; garbage is written into it first all the same).
VoxelGpuOutput run_voxelize(passes::VoxelizePass& pass, render::VoxelVolume& vol,
                            render::GpuScene& gpu, const std::vector<float>& shadow, uint32_t r);

// The reference input for the same scene.
VoxelRefInput reference_input(const scene::SceneAssets& assets, const scene::FrameScene& frame,
                              const render::GpuScene& gpu, const std::vector<float>& shadow);

}  // namespace rp::test
