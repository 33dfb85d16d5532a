// Plain C++ reference of the voxelize pass (kernels/voxelize.cl): every triangle against every
// voxel of its voxel range (no dominant-axis candidate search),
// every sphere against every voxel of its bounding box, the same float operations in the same
// order (FP contraction is off in the kernel and the host compiler does not contract), the
// same fixed-point rounding and wrap-around sums, so the integer sums must agree exactly where
// the radiance is exact (emission; lighting uses rsqrt/normalize whose rounding differs, so lit
// values agree to a tolerance). The facing coverage words (vx_add_facing, vx_add_facing_all)
// are mirrored operation for operation too: exact for spheres; for triangles exact except
// where the kernel's rsqrt-normalised normal may round a contribution to the other side of a
// tie (counted in VoxelSums::facing_slack, compare_sums allows 1 unit per such contribution).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cl/profiler.h"
#include "passes/voxelize.h"
#include "render/gpu_scene.h"
#include "render/gpu_types.h"
#include "render/voxel_volume.h"
#include "scene/frame_scene.h"

namespace rp::test {

struct RefF3 {
  float x = 0.0f, y = 0.0f, z = 0.0f;
};

// The voxelizer's sums for an R^3 volume: accum holds RP_VOXEL_ACCUM_WORDS (8) words per
// voxel (kernels/shared/voxel_layout.h): (r*a, g*a, b*a, a) in fixed point
// (render/voxel_volume.h), the facing coverage along x, y, z (low 16 bits: surfaces facing +,
// high 16 bits: facing -) and an unused word that stays 0; overflow the wrapped-channel bits.
inline constexpr size_t kAccumWords = RP_VOXEL_ACCUM_WORDS;
struct VoxelSums {
  uint32_t resolution = 0;
  std::vector<uint32_t> accum;     // kAccumWords per voxel, x fastest
  std::vector<uint32_t> overflow;  // 1 per voxel
  // Reference only (empty in device output): per voxel and facing half (6 per voxel, index
  // 2 * axis + (0: low half, 1: high half)), the number of triangle contributions whose
  // rounding the kernel may decide the other way: round(c) with c within 1e-3 of k + 0.5.
  // The kernel normalises the triangle normal with rsqrt, the reference with 1 / sqrt; the
  // ratio |n_i| / max|n| is the same to a few ulps, so only such contributions can differ,
  // each by at most 1 unit.
  std::vector<uint32_t> facing_slack;
};

// One facing half of voxel v: axis 0..2 (x, y, z), half 0 (low 16 bits: surfaces whose normal
// points along +axis) or 1 (high 16 bits: along -axis).
inline uint32_t facing_half(const VoxelSums& s, size_t v, int axis, int half) {
  const uint32_t w = s.accum[kAccumWords * v + 4 + size_t(axis)];
  return half == 0 ? (w & 0xFFFFu) : (w >> 16);
}

// Compares device sums with the reference: words 0-3 and 7 and the overflow bits exactly, each
// facing half exactly or within want.facing_slack units. Returns the number of differing
// voxels; the first `report` are described in `first` (one line each).
size_t compare_sums(const VoxelSums& got, const VoxelSums& want, std::vector<std::string>* first,
                    size_t report = 6);

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

// vx_texture_level's level of detail of a textured triangle (world vertices, uv in .x / .y, a
// width x height texture of `levels` mip levels) in an R^3 volume, clamped to the levels.
float reference_texture_lod(const std::array<RefF3, 3>& world, const std::array<RefF3, 3>& uv,
                            uint32_t width, uint32_t height, uint32_t levels,
                            uint32_t resolution);

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
// bounce: a bounce grid (common/bounce.h, bounce_cells per side) the voxels reflect, or none.
VoxelGpuOutput run_voxelize(render::GpuScene& gpu, const std::vector<float>& shadow, uint32_t r,
                            const ::cl::Buffer* bounce = nullptr, uint32_t bounce_cells = 0);

// The same with a given pass (its state, the static surface cache, carries over between
// calls) and volume (resized to r; garbage is written into it first all the same). shadow_map:
// the depth buffer to write `shadow` into and voxelize with (kept across calls, as the
// renderer's is), or nullptr for a new one per call.
VoxelGpuOutput run_voxelize(passes::VoxelizePass& pass, render::VoxelVolume& vol,
                            render::GpuScene& gpu, const std::vector<float>& shadow, uint32_t r,
                            const ::cl::Buffer* bounce = nullptr, uint32_t bounce_cells = 0,
                            render::ShadowMap* shadow_map = nullptr);

// The reference input for the same scene.
VoxelRefInput reference_input(const scene::SceneAssets& assets, const scene::FrameScene& frame,
                              const render::GpuScene& gpu, const std::vector<float>& shadow);

}  // namespace rp::test
