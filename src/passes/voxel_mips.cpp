#include "passes/voxel_mips.h"

#include "cl/error.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 64;

}  // namespace

VoxelMipsPass::VoxelMipsPass(const rp::cl::Context& /*context*/, rp::cl::ProgramCache& programs)
    : kernel_(programs.kernel("voxel_mips.cl", "voxel_mips_build")) {}

void VoxelMipsPass::run(rp::cl::Profiler& profiler, render::VoxelVolume& volume) {
  if (!render::VoxelVolume::valid_resolution(volume.resolution) || volume.chain() == nullptr ||
      volume.levels != render::VoxelVolume::levels_for(volume.resolution))
    throw rp::cl::Error("voxel_mips pass: the voxel volume has not been allocated (resize it)");
  kernel_.setArg(0, volume.chain);
  kernel_.setArg(1, cl_uint(volume.resolution));
  for (cl_uint level = 1; level < volume.levels; ++level) {
    const size_t n = volume.resolution >> level;
    kernel_.setArg(2, level);
    profiler.enqueue("voxel_mips", kernel_, ::cl::NDRange(rp::cl::round_up(n * n * n, kGroup)),
                     ::cl::NDRange(kGroup));
  }
}

}  // namespace rp::passes
