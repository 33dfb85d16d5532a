// Voxelize pass (SPEC 6.3): every instance triangle and analytic sphere of the frame -> level 0
// of the voxel radiance volume (rgb premultiplied radiance: direct light with one shadow-map
// lookup times albedo, plus emission; a opacity). Order independent fixed-point accumulation,
// so a frame voxelizes bit-identically every run. Pass name "voxelize". Details and formulas:
// kernels/voxelize.cl; coordinates and direction convention: kernels/common/voxel.h.
#pragma once

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"
#include "render/voxel_volume.h"

namespace rp::passes {

class VoxelizePass {
 public:
  VoxelizePass(const rp::cl::Context& context, rp::cl::ProgramCache& programs);

  // Clears volume.accum/overflow, voxelizes scene's instances and spheres (world [-1,1]^3 into
  // volume.resolution^3 voxels) and resolves the sums into level 0 of volume.chain. The
  // resolution comes from `volume`; scene.constants.voxel_resolution and voxel_levels must
  // match it (they are what the cone tracer reads), and shadow.size must equal
  // scene.constants.shadow_size: otherwise throws rp::cl::Error. Enqueues only (no wait).
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
           const render::ShadowMap& shadow, render::VoxelVolume& volume);

 private:
  ::cl::Kernel clear_, triangles_, spheres_, resolve_;
};

}  // namespace rp::passes
