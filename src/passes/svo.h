// Sparse voxel octree pass (seed 001): the frame's fragment list at the octree's
// resolution (the voxelizer in fragment mode), then the octree built top-down level by level
// (flags, prefix-sum allocation), leaf injection, the bottom-up anisotropic mips and the
// border transfer (kernels/svo.cl). Pass names: "voxelize" (the fragments), "svo_nodes" (the
// top-down flags and allocation), "svo_inject" (leaf sums and values), "svo_mips" and
// "svo_border" (the border transfer of every level).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "passes/voxelize.h"
#include "render/gpu_scene.h"
#include "render/svo_volume.h"
#include "scene/tumbler_shape.h"

namespace rp::passes {

class SvoPass {
 public:
  // float_samples: float4 brick samples instead of the packed 5-byte ones (tests compare bit
  // for bit with the dense chain).
  SvoPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
          bool float_samples = false);

  // Voxelizes the frame into fragments at `resolution` (a power of two, 2 .. 1024) and builds
  // the octree into svo (allocated or grown as needed). Blocks on small reads (a fragment and
  // node count per depth): the sizes of the next step are only known on the device.
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
           const render::ShadowMap& shadow, uint32_t resolution, render::SvoVolume& svo,
           const ::cl::Buffer* bounce = nullptr, uint32_t bounce_cells = 0);

  // Closed objects made solid at the coarse levels (passes/svo_solid.h): the tumbler instances
  // (those whose triangles start at `tumbler_first_triangle`, of shape `tumbler`) and every
  // sphere, from the scene run() is given. Off until called (the tests that compare with the
  // dense chain leave it off).
  void enable_solid(uint32_t tumbler_first_triangle, const scene::TumblerShape& tumbler);

  // Builds svo at `resolution` from `count` fragments (svo_layout.h) in `fragments`.
  void build(rp::cl::Profiler& profiler, const ::cl::Buffer& fragments, uint32_t count,
             uint32_t resolution, render::SvoVolume& svo);

  // Fragments of the last run (RP_SVO_FRAGMENT_WORDS uints each).
  const ::cl::Buffer& fragments() const { return fragments_; }

 private:
  // One attempt; false when a pool was too small (grown, try again).
  bool try_build(rp::cl::Profiler& profiler, const ::cl::Buffer& fragments, uint32_t count,
                 render::SvoVolume& svo);
  void allocate(render::SvoVolume& svo, size_t nodes, size_t bricks, size_t samples);
  void ensure_scratch(uint32_t resolution, size_t nodes, size_t fragments);
  // Bytes of every device buffer of the octree path now: svo's pools and this pass's scratch
  // (CL_MEM_SIZE of each; the voxelizer's own buffers not included).
  uint64_t device_bytes(const render::SvoVolume& svo) const;

  const rp::cl::Context* context_;
  bool float_samples_;
  std::unique_ptr<VoxelizePass> voxelize_;  // built for fragments
  ::cl::Kernel occ_clear_, occ_mark_, occ_reduce_, flag_bits_;
  ::cl::Kernel clear_nodes_, flag_, dilate_, count_, scan_, allocate_, link_, leaves_, border_,
      mips_;
  ::cl::Buffer fragments_, counter_;
  size_t fragment_capacity_ = 0;
  // Build scratch: per node its flag word (then, at the leaves, the head of its fragment list)
  // and coordinates; per fragment its owner node (then the next fragment of its leaf's list);
  // chunk sums; per-depth totals.
  ::cl::Buffer own_, coords_, cur_, sums_, totals_;
  ::cl::Buffer occ_;  // occupancy bits of the top levels (svo.cl svo_occ_*)
  uint32_t occ_words_ = 0;
  size_t scratch_nodes_ = 0, scratch_fragments_ = 0;
  bool fitted_ = false;  // a build has completed since the pools started from the first guess
  uint64_t peak_bytes_ = 0;
  // Solid grid (enable_solid).
  bool solid_ = false;
  uint32_t solid_first_triangle_ = 0;
  scene::TumblerShape solid_tumbler_;
  std::vector<uint8_t> solid_grid_;     // read by its upload (solid_upload_)
  ::cl::Event solid_upload_;
  cl_uint solid_header_[2] = {0, 0};    // header words 28-29, read by a non-blocking write  // the most device_bytes() has been at the end of a build
  std::vector<uint32_t> header_;
};

}  // namespace rp::passes
