// Voxelize pass (SPEC 6.3): every instance triangle and analytic sphere of the frame -> level 0
// of the voxel radiance volume (rgb premultiplied radiance: direct light with one shadow-map
// lookup times albedo, plus emission; a opacity). Order independent fixed-point accumulation,
// so a frame voxelizes bit-identically every run. Pass name "voxelize". Details and formulas:
// kernels/voxelize.cl; coordinates and direction convention: kernels/common/voxel.h.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"
#include "render/voxel_volume.h"

namespace rp::passes {

class VoxelizePass {
 public:
  // fragments: build the kernels for run_fragments (the octree's fragment list) instead of run.
  VoxelizePass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
               bool fragments = false);

  // Clears volume.accum/overflow, voxelizes scene's instances and spheres (world [-1,1]^3 into
  // volume.resolution^3 voxels) and resolves the sums into level 0 of volume.chain. The
  // resolution comes from `volume`; scene.constants.voxel_resolution and voxel_levels must
  // match it (they are what the cone tracer reads), and shadow.size must equal
  // scene.constants.shadow_size: otherwise throws rp::cl::Error. Enqueues only (no wait).
  // bounce: the bounce grid (passes/bounce.h, bounce_cells per side) whose light the voxels
  // reflect besides the lamp's (several bounces), or nullptr (one bounce).
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
           const render::ShadowMap& shadow, render::VoxelVolume& volume,
           const ::cl::Buffer* bounce = nullptr, uint32_t bounce_cells = 0);

  // Fragment mode (a pass built with fragments = true): the same contributions as run() adds,
  // at `resolution` (a power of two up to 1024; the frame constants are not checked), written
  // as a fragment list (kernels/shared/svo_layout.h) to `fragments` (RP_SVO_FRAGMENT_WORDS
  // uints per fragment).
  // counter: uint[2] = {0, capacity in fragments}, written by the caller before; afterwards
  // counter[0] holds the number of fragments (also when it exceeds the capacity: then only the
  // first `capacity` were written, in no particular order, and the caller must grow the list
  // and run again). Enqueues only.
  void run_fragments(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                     const render::ShadowMap& shadow, uint32_t resolution,
                     const ::cl::Buffer& fragments, const ::cl::Buffer& counter,
                     const ::cl::Buffer* bounce = nullptr, uint32_t bounce_cells = 0);

  // The static surface cache's samples keep the bounce grid's light of the run that last
  // refreshed them; a run refreshes one in `stride` of them (by a hash of their voxel, with a
  // phase that advances every run) and reuses the stored light for the others. 1 (the default):
  // every run refreshes all, exactly the per-frame result. Runs after a cache rebuild, after a
  // run without a bounce grid or with a different grid refresh all, whatever the stride. The
  // grid blends each frame's gather in at 1/32, so a few runs' delay changes little: the fast
  // mode's renderer uses kBounceRefreshFast.
  // stride: 1 to 256.
  void set_bounce_refresh_stride(uint32_t stride) {
    bounce_refresh_stride_ = std::clamp(stride, 1u, 256u);
  }

  // Largest static surface cache allowed (bytes of its samples); a larger one is not built and
  // the cache stays off for the pass's life (default: no limit).
  void set_cache_limit(uint64_t bytes) { cache_limit_ = bytes; }

  // Bytes of this pass's own device buffers (CL_MEM_SIZE): the static surface cache, the
  // large-triangle list and their small companions (not the output it is given).
  uint64_t device_bytes() const;

 private:
  // Everything but the dense clear and resolve: triangles, large triangles, cached samples
  // and spheres into target_accum_ / target_overflow_ at target_resolution_.
  void voxelize(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                const render::ShadowMap& shadow);
  void set_bounce(const ::cl::Buffer* bounce, uint32_t bounce_cells);
  // Binds scene.texels (packed RGBA8 sRGB, decoded per tap by the kernels) as texels_ and
  // returns true when it is not the texel buffer of the last run (held in seen_texels_, so its
  // handle cannot be reused by another buffer): the scene changed.
  bool update_texels(const render::GpuScene& scene);
  // Follows which instances have not changed since tracking began (still_) and decides the
  // instances of the static surface cache; returns true when the cache must be rebuilt.
  bool update_cache_plan(const render::GpuScene& scene, uint32_t resolution, bool scene_changed);
  // VX_COUNT then VX_RECORD passes of voxelize_triangles and voxelize_large over the cached
  // instances; leaves their large triangles in the large-triangle list.
  void build_cache(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                   const render::ShadowMap& shadow);
  // One launch of voxelize_triangles / voxelize_large in mode `record` (VX_* of voxelize.cl).
  void enqueue_triangles(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                         const render::ShadowMap& shadow, cl_uint record);
  void enqueue_large(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                     const render::ShadowMap& shadow, cl_uint record);
  // Records what the cached samples' direct light depends on; true when it is what the last
  // call recorded (the samples' stored direct light is then this run's).
  bool update_direct_key(const render::GpuScene& scene, const render::ShadowMap& shadow);
  // The kernels' parameters every launch shares (the target, the frame's counts, the bounce
  // grid); each launch adds its own.
  gpu::VoxelizeParams params_for(const render::GpuScene& scene) const;

  const rp::cl::Context* context_;
  bool fragments_ = false;  // built with RP_VOXEL_FRAGMENTS (run_fragments)
  // This run's output: the dense sums (run) or the fragment list and its counter.
  cl_uint target_resolution_ = 0;
  ::cl::Buffer target_accum_, target_overflow_;
  const ::cl::Buffer* bounce_ = nullptr;  // this run's bounce grid (or no_bounce_)
  cl_uint bounce_cells_ = 0;
  ::cl::Buffer no_bounce_;
  int span_ = 1;  // triangles (voxelize_triangles) or voxel columns (voxelize_large) a work-item
  ::cl::Kernel clear_, triangles_, large_, cached_, spheres_, resolve_;
  ::cl::Buffer texels_;       // scene.texels, or no_texels_ when the scene has none
  ::cl::Buffer no_texels_;    // one texel
  ::cl::Buffer seen_texels_;  // the texel buffer of the last run
  // Large triangles of the frame (flat instance-triangle indices, in no particular order) and
  // their count, written by voxelize_triangles, read by voxelize_large. Grows with the
  // scene's instance triangle count, never per frame otherwise.
  ::cl::Buffer large_count_, large_list_;
  size_t large_capacity_ = 0;
  size_t large_items_ = 0;  // work-items of voxelize_large (a fixed number strides the list)
  cl_uint large_slices_ = 1;   // work-items sharing one large triangle (choose_slices)
  cl_uint sphere_slices_ = 1;  // work-items sharing one sphere (choose_slices)

  // Static surface cache (kernels/voxelize.cl voxelize_cached): per-voxel samples of the
  // triangles of instances that have not changed (model, triangle range, voxelize flag) since
  // tracking began, with their last direct and bounce light; tracking restarts when the instance count, the scene's buffers or the
  // resolution change. An instance that changes leaves the cache for good (a rebuild without
  // it), so a session rebuilds at most once per instance. The volume is bit-identical with or
  // without the cache. ROLYPOLY_VOXELIZE_CACHE=0
  // turns it off (tests compare both).
  bool cache_enabled_ = true;
  std::vector<gpu::Instance> tracked_;   // the instances as of the last frame
  std::vector<uint32_t> still_;          // 1: unchanged since tracking began
  std::vector<uint32_t> cached_host_;    // 1: in the cache (what cached_flags_ holds)
  ::cl::Buffer cached_flags_;            // uint per instance
  size_t flags_capacity_ = 0;
  ::cl::Buffer cache_, cache_count_;     // 4 float4 per sample; sample count scratch
  size_t cache_capacity_ = 0;            // samples
  uint64_t cache_limit_ = UINT64_MAX;    // set_cache_limit
  uint32_t cache_samples_ = 0;
  bool cache_valid_ = false;
  uint32_t bounce_refresh_stride_ = 1;    // set_bounce_refresh_stride
  uint32_t bounce_refresh_runs_ = 0;      // runs with a stride > 1: the phase
  bool cache_bounce_fresh_ = false;       // every sample holds a light of cache_bounce_grid_
  cl_mem cache_bounce_grid_ = nullptr;    // the grid the samples' bounce light came from
  uint32_t cache_resolution_ = 0;
  ::cl::Buffer cache_vertices_, cache_triangles_, cache_materials_;  // scene buffers tracked
  // What the samples' stored direct light was computed under (update_direct_key's hash).
  uint64_t direct_key_ = 0;
  bool direct_key_valid_ = false;
  ::cl::Buffer direct_shadow_;  // the shadow depth buffer it read
};

}  // namespace rp::passes
