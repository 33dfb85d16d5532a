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
  // Decodes scene.texels into linear_texels_ when the scene's texel buffer is not the one
  // decoded last (held in decoded_from_, so its handle cannot be reused by another buffer).
  void update_linear_texels(rp::cl::Profiler& profiler, const render::GpuScene& scene);

  const rp::cl::Context* context_;
  int span_ = 1;  // triangles (voxelize_triangles) or voxel columns (voxelize_large) a work-item
  ::cl::Kernel decode_, clear_, triangles_, large_, spheres_, resolve_;
  ::cl::Buffer linear_texels_;  // float4 per texel: linear rgba of scene.texels
  ::cl::Buffer decoded_from_;   // the texel buffer linear_texels_ was decoded from
  // Large triangles of the frame (flat instance-triangle indices, in no particular order) and
  // their count, written by voxelize_triangles, read by voxelize_large. Grows with the
  // scene's instance triangle count, never per frame otherwise.
  ::cl::Buffer large_count_, large_list_;
  size_t large_capacity_ = 0;
};

}  // namespace rp::passes
