#include "passes/voxel_mips.h"

#include <cstdlib>
#include <string>

#include "cl/error.h"
#include "cl/kernel_args.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 64;

// 16 parents per work-item on CPUs (float16 code maps onto PoCL's SIMD registers); one per
// work-item on GPUs. ROLYPOLY_VOXEL_MIPS_SPAN (1 or 16) overrides the choice (tests).
bool choose_span16(const rp::cl::Context& context) {
  if (const char* env = std::getenv("ROLYPOLY_VOXEL_MIPS_SPAN"); env && *env) {
    const std::string s = env;
    if (s == "1" || s == "16") return s == "16";
    throw rp::cl::Error("ROLYPOLY_VOXEL_MIPS_SPAN must be 1 or 16, not '" + s + "'");
  }
  return context.info.is_cpu;
}

}  // namespace

VoxelMipsPass::VoxelMipsPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs)
    : kernel_(programs.kernel("voxel_mips.cl", "voxel_mips_build")),
      use_span16_(choose_span16(context)) {
  if (use_span16_) span16_ = programs.kernel("voxel_mips.cl", "voxel_mips_build", "-DRP_SPAN=16");
}

void VoxelMipsPass::run(rp::cl::Profiler& profiler, render::VoxelVolume& volume) {
  if (!render::VoxelVolume::valid_resolution(volume.resolution) || volume.chain() == nullptr ||
      volume.levels != render::VoxelVolume::levels_for(volume.resolution))
    throw rp::cl::Error("voxel_mips pass: the voxel volume has not been allocated (resize it)");
  for (cl_uint level = 1; level < volume.levels; ++level) {
    const size_t n = volume.resolution >> level;
    const bool span16 = use_span16_ && n % 16 == 0;
    ::cl::Kernel& k = span16 ? span16_ : kernel_;
    rp::cl::bind_args(k, volume.chain, volume.accum,
                      gpu::VoxelMipsParams{volume.resolution, level, 0u, 0u});
    const size_t items = span16 ? n / 16 * n * n : n * n * n;
    profiler.enqueue(pass_name::kVoxelMips, k, ::cl::NDRange(rp::cl::round_up(items, kGroup)),
                     ::cl::NDRange(kGroup));
  }
}

}  // namespace rp::passes
