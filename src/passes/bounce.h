// Bounce pass (several bounces): gathers, by cone tracing the frame's voxel chain,
// the irradiance that a coarse grid of cells receives (kernels/bounce.cl; layout and lookup in
// kernels/common/bounce.h). The voxelizer adds albedo x that light to the voxels' radiance the
// next time it runs, so every gather adds a bounce and the grid converges to all bounces.
// The grid is world-space and view-independent: camera cuts keep it, a world reset (R) or a
// new voxel resolution starts it again. Pass name "bounce".
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "render/gpu_scene.h"
#include "render/voxel_volume.h"

namespace rp::passes {

class BouncePass {
 public:
  // Cones per face and gather: the whole 16-cone set (a face's estimate replaced) or one cone
  // (blended into the face's running estimate).
  enum class Cones { kAll, kOne };

  // gi_options: "-DRP_GI_SVO" when the voxels given to run are the sparse voxel octree
  // (kernels/shared/svo_layout.h) instead of the dense chain; "" otherwise.
  BouncePass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
             const std::string& gi_options = "");

  // Gathers into the grid from volume.chain (levels built); cones that leave the volume take
  // the sky of `scene`'s frame (its FrameConstants and environment texels). frame: the frame
  // index (jitters and the cone rotation). Enqueues only.
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
           const render::VoxelVolume& volume, uint32_t frame, Cones cones);
  // The same from any GI volume buffer (the dense chain or, with RP_GI_SVO, the octree) of
  // `resolution` voxels per side and `levels` levels.
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene, const ::cl::Buffer& voxels,
           uint32_t resolution, uint32_t levels, uint32_t frame, Cones cones);

  // The grid the voxelizer reads (float4 per cell face), sized for the last volume run with;
  // valid() is false until a gather has run since the last reset.
  const ::cl::Buffer& grid() const { return grid_; }
  bool valid() const { return valid_; }
  // Forgets the gathered light (the next run starts from nothing).
  void reset() { valid_ = false; }

  // Cells per side for a volume of `resolution` voxels per side (kernels/common/bounce.h).
  static uint32_t cells(uint32_t resolution) {
    return resolution <= 32 ? std::min(resolution, 16u) : std::min(resolution / 2, 32u);
  }

 private:
  // The gather kernel with the diffuse cones' sky code or without (render/sky_texture.h:
  // kNoDiffuseSkyOption), built on first use (the constructor builds the one without).
  ::cl::Kernel& gather_kernel(bool sky);

  const rp::cl::Context* context_;
  rp::cl::ProgramCache* programs_;
  std::string gi_options_;
  std::optional<::cl::Kernel> gathers_[2];  // [sky]
  ::cl::Buffer grid_;
  uint32_t resolution_ = 0;  // the volume the grid was made for
  bool valid_ = false;
};

}  // namespace rp::passes
