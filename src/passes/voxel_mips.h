// Voxel mips pass (SPEC 6.4): the six directional volumes (+x, -x, +y, -y, +z, -z) of every
// level 1 .. levels-1 of the voxel volume, each built from the level below by front-to-back
// compositing along its direction and averaging across it (kernels/voxel_mips.cl; direction
// convention in kernels/common/voxel.h). One launch per level. Pass name "voxel_mips".
#pragma once

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "render/voxel_volume.h"

namespace rp::passes {

class VoxelMipsPass {
 public:
  VoxelMipsPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs);

  // Reads level 0 of volume.chain and writes levels 1 .. volume.levels - 1. Enqueues only.
  // Throws rp::cl::Error when the volume has not been allocated.
  void run(rp::cl::Profiler& profiler, render::VoxelVolume& volume);

 private:
  ::cl::Kernel kernel_;   // one parent voxel per work-item
  ::cl::Kernel span16_;   // 16 parents along x per work-item (CPUs, levels >= 16 per side)
  bool use_span16_ = false;
};

}  // namespace rp::passes
