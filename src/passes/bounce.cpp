#include "passes/bounce.h"

#include "cl/error.h"
#include "cl/kernel_args.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"
#include "render/sky_texture.h"

namespace rp::passes {
namespace {
constexpr size_t kGroup = 64;
}  // namespace

BouncePass::BouncePass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                       const std::string& gi_options)
    : context_(&context), programs_(&programs), gi_options_(gi_options) {
  gather_kernel(false);
}

::cl::Kernel& BouncePass::gather_kernel(bool sky) {
  std::optional<::cl::Kernel>& k = gathers_[sky];
  if (!k) {
    const char* sky_option = sky ? "" : render::kNoDiffuseSkyOption;
    k = programs_->kernel("bounce.cl", "bounce_gather",
                          rp::cl::join_options({sky_option, gi_options_}));
  }
  return *k;
}

void BouncePass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                     const render::VoxelVolume& volume, uint32_t frame, Cones cones) {
  if (!render::VoxelVolume::valid_resolution(volume.resolution) || volume.chain() == nullptr)
    throw rp::cl::Error("bounce pass: the voxel volume has not been allocated (resize it)");
  run(profiler, scene, volume.chain, volume.resolution, volume.levels, frame, cones);
}

void BouncePass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                     const ::cl::Buffer& voxels, uint32_t resolution, uint32_t levels,
                     uint32_t frame, Cones cones) {
  const size_t g = cells(resolution);
  const size_t faces = 6 * g * g * g;
  if (resolution_ != resolution || grid_() == nullptr) {
    grid_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, faces * 4 * sizeof(float));
    resolution_ = resolution;
    valid_ = false;
  }
  if (!valid_)  // start from nothing: every face age 0 (in queue order, no host copy)
    context_->queue.enqueueFillBuffer(grid_, cl_float4{{0.0f, 0.0f, 0.0f, 0.0f}}, 0,
                                      faces * 4 * sizeof(float));
  gpu::BounceParams params{};
  params.resolution = resolution;
  params.levels = levels;
  params.frame = frame;
  params.cones = cones == Cones::kAll ? 16u : 1u;
  ::cl::Kernel& gather = gather_kernel(scene.constants.sky.diffuse_cones != 0);
  rp::cl::bind_args(gather, voxels, grid_, scene.frame, scene.sky, params);
  // one cone: one face in RP_BOUNCE_FACE_STRIDE a frame (kernels/bounce.cl)
  const size_t items =
      cones == Cones::kAll ? faces : (faces + RP_BOUNCE_FACE_STRIDE - 1) / RP_BOUNCE_FACE_STRIDE;
  profiler.enqueue(pass_name::kBounce, gather, ::cl::NDRange(rp::cl::round_up(items, kGroup)),
                   ::cl::NDRange(kGroup));
  valid_ = true;
}

}  // namespace rp::passes
