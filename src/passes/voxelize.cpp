#include "passes/voxelize.h"

#include <algorithm>
#include <array>
#include <compare>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "cl/buffer.h"
#include "cl/error.h"
#include "cl/kernel_args.h"
#include "io/fnv1a.h"
#include "passes/pass_names.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 64;       // 1D work-groups for the per-voxel and per-sphere kernels
constexpr size_t kSpanGroup = 16;   // work-groups of the span kernels (16 x 16 triangles on CPUs)

// The fixed-point format of render/voxel_volume.h, handed to the kernels (one definition).
std::string fixed_point_options() {
  return "-DRP_VOXEL_FIXED_BITS=" + std::to_string(render::kVoxelFixedBits) +
         " -DRP_VOXEL_MAX_CONTRIB=" + std::to_string(render::kVoxelMaxContribution) + "f" +
         " -DRP_VOXEL_SATURATED=" + std::to_string(render::kVoxelSaturatedSum) + "f";
}

// Lanes per work-item of voxelize_triangles / voxelize_large: the CPU's native float vector
// width (rp::cl::cpu_span_lanes: 16 on AVX-512, 8 on AVX2, where 8 and 16 measured within
// noise), 1 on GPUs. ROLYPOLY_VOXELIZE_SPAN (1, 4, 8 or 16) overrides it
// (tests compare the variants).
int choose_span(const rp::cl::Context& context) {
  if (const char* env = std::getenv("ROLYPOLY_VOXELIZE_SPAN"); env && *env) {
    const std::string s = env;
    if (s == "1" || s == "4" || s == "8" || s == "16") return std::stoi(s);
    throw rp::cl::Error("ROLYPOLY_VOXELIZE_SPAN must be 1, 4, 8 or 16, not '" + s + "'");
  }
  return context.info.is_cpu ? rp::cl::cpu_span_lanes(context.info) : 1;
}

// Work-items that share one large triangle's voxel columns (voxelize_large) and one sphere's
// voxel rows (voxelize_spheres): 1 on CPUs (few cores, each busy with other triangles). On
// GPUs a triangle gets R^2 / 1024 up to 256, so a wall's triangle (R^2 / 2 columns) gives a
// thread at most about 512 columns, and a sphere R / 8 up to 64 (a marble of radius 0.05 is
// about R^2 / 200 rows). Powers of two. ROLYPOLY_VOXELIZE_SLICES (a power of two, 1 to 1024)
// sets both (tests compare).
struct Slices {
  cl_uint triangle = 1, sphere = 1;
};
Slices choose_slices(const rp::cl::Context& context, uint32_t resolution) {
  if (const char* env = std::getenv("ROLYPOLY_VOXELIZE_SLICES"); env && *env) {
    const std::string s = env;
    const unsigned long v = std::strtoul(s.c_str(), nullptr, 10);
    if (s.find_first_not_of("0123456789") != std::string::npos || v < 1 || v > 1024 ||
        (v & (v - 1)) != 0)
      throw rp::cl::Error("ROLYPOLY_VOXELIZE_SLICES must be a power of two from 1 to 1024, not '" +
                          s + "'");
    return {cl_uint(v), cl_uint(v)};
  }
  Slices n;
  if (context.info.is_cpu) return n;
  while (n.triangle < 256 && uint64_t(n.triangle) * 2 * 1024 <= uint64_t(resolution) * resolution)
    n.triangle *= 2;
  while (n.sphere < 64 && n.sphere * 2 * 8 <= resolution) n.sphere *= 2;
  return n;
}

// voxelize_triangles' and voxelize_large's modes (VX_ACCUMULATE, VX_COUNT, VX_RECORD in
// voxelize.cl).
constexpr cl_uint kAccumulate = 0, kCount = 1, kRecord = 2;
constexpr size_t kSampleBytes = 5 * 4 * sizeof(float);  // one cache sample: 5 float4

// The part of an instance voxelization depends on apart from the light.
bool same_geometry(const gpu::Instance& a, const gpu::Instance& b) {
  return std::memcmp(&a.model, &b.model, sizeof(a.model)) == 0 &&
         a.voxel_first_triangle == b.voxel_first_triangle &&
         a.voxel_triangle_count == b.voxel_triangle_count &&
         a.voxelize == b.voxelize;
}

// Orders the first `samples` cache samples by voxel (then by position, so the cache's bytes do
// not depend on the recording's racy slots). voxelize_cached then finds a voxel's samples in
// neighbouring lanes and adds them with one set of atomics (vx_accumulate_span): at 64^3 the
// atrium's still surfaces are about ten samples a voxel. The sums are integers, so the volume
// is the same in any order; this runs only when the cache is recorded.
void sort_cache_by_voxel(::cl::CommandQueue& queue, const ::cl::Buffer& cache, size_t samples) {
  constexpr size_t kFloats = kSampleBytes / sizeof(float);
  std::vector<float> data(samples * kFloats);
  queue.enqueueReadBuffer(cache, CL_TRUE, 0, data.size() * sizeof(float), data.data());
  struct Key {
    uint32_t voxel;
    std::array<uint32_t, 3> position;  // the point's bits: any fixed order will do
    uint32_t index;
    auto operator<=>(const Key&) const = default;
  };
  std::vector<Key> keys(samples);
  for (size_t i = 0; i < samples; ++i) {
    const float* q = data.data() + i * kFloats;
    Key& k = keys[i];
    std::memcpy(&k.voxel, q + 3, sizeof(uint32_t));
    std::memcpy(k.position.data(), q, 3 * sizeof(uint32_t));
    k.index = uint32_t(i);
  }
  std::sort(keys.begin(), keys.end());
  // written back in chunks of 64k samples (5 MiB), not as a second copy of the whole cache
  constexpr size_t kChunk = size_t(1) << 16;
  std::vector<float> chunk(std::min(samples, kChunk) * kFloats);
  for (size_t first = 0; first < samples; first += kChunk) {
    const size_t count = std::min(kChunk, samples - first);
    for (size_t i = 0; i < count; ++i)
      std::memcpy(chunk.data() + i * kFloats,
                  data.data() + size_t(keys[first + i].index) * kFloats, kSampleBytes);
    queue.enqueueWriteBuffer(cache, CL_TRUE, first * kSampleBytes, count * kSampleBytes,
                             chunk.data());
  }
}

}  // namespace

VoxelizePass::VoxelizePass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                           bool fragments)
    : context_(&context), fragments_(fragments), span_(choose_span(context)) {
  const std::string options = fixed_point_options() + " -DRP_SPAN=" + std::to_string(span_) +
                              (fragments ? " -DRP_VOXEL_FRAGMENTS" : "");
  clear_ = programs.kernel("voxelize.cl", "voxelize_clear", options);
  triangles_ = programs.kernel("voxelize.cl", "voxelize_triangles", options);
  large_ = programs.kernel("voxelize.cl", "voxelize_large", options);
  cached_ = programs.kernel("voxelize.cl", "voxelize_cached", options);
  spheres_ = programs.kernel("voxelize.cl", "voxelize_spheres", options);
  resolve_ = programs.kernel("voxelize.cl", "voxelize_resolve", options);
  large_count_ = ::cl::Buffer(context.context, CL_MEM_READ_WRITE, sizeof(cl_uint));
  cache_count_ = ::cl::Buffer(context.context, CL_MEM_READ_WRITE, sizeof(cl_uint));
  if (const char* env = std::getenv("ROLYPOLY_VOXELIZE_CACHE"); env && std::string(env) == "0")
    cache_enabled_ = false;
}

bool VoxelizePass::update_texels(const render::GpuScene& scene) {
  if (!scene.texels() && !no_texels_())
    no_texels_ = ::cl::Buffer(context_->context, CL_MEM_READ_ONLY, sizeof(cl_uint));
  texels_ = scene.texels() ? scene.texels : no_texels_;
  if (seen_texels_() != nullptr && seen_texels_() == scene.texels()) return false;
  seen_texels_ = scene.texels;
  return true;
}

bool VoxelizePass::update_cache_plan(const render::GpuScene& scene, uint32_t resolution,
                                     bool scene_changed) {
  const std::vector<gpu::Instance>& now = scene.host_instances;
  const size_t n = now.size();
  const bool reset = scene_changed || tracked_.size() != n || resolution != cache_resolution_ ||
                     cache_vertices_() != scene.vertices() ||
                     cache_triangles_() != scene.triangles() ||
                     cache_materials_() != scene.materials();
  if (reset) {
    tracked_ = now;
    still_.assign(n, cache_enabled_ ? 1u : 0u);
    cache_valid_ = false;
    cache_resolution_ = resolution;
    cache_vertices_ = scene.vertices;
    cache_triangles_ = scene.triangles;
    cache_materials_ = scene.materials;
  } else {
    for (size_t i = 0; i < n; ++i) {
      if (!same_geometry(now[i], tracked_[i])) {
        still_[i] = 0;
        if (cached_host_[i]) cache_valid_ = false;
      }
      tracked_[i] = now[i];
    }
  }
  if (flags_capacity_ < std::max<size_t>(n, 1)) {
    flags_capacity_ = std::max<size_t>(n, 1);
    cached_flags_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE,
                                 flags_capacity_ * sizeof(cl_uint));
    cache_valid_ = false;
  }
  if (cache_valid_) return false;
  // A new plan: the instances that are still and voxelized.
  cached_host_.assign(flags_capacity_, 0u);
  bool any = false;
  for (size_t i = 0; i < n; ++i) {
    cached_host_[i] = still_[i] && now[i].voxelize ? 1u : 0u;
    any |= cached_host_[i] != 0u;
  }
  context_->queue.enqueueWriteBuffer(cached_flags_, CL_TRUE, 0,
                                     cached_host_.size() * sizeof(cl_uint), cached_host_.data());
  cache_samples_ = 0;
  cache_valid_ = true;
  return any;
}

gpu::VoxelizeParams VoxelizePass::params_for(const render::GpuScene& scene) const {
  gpu::VoxelizeParams params{};
  params.resolution = target_resolution_;
  params.instance_count = scene.instance_count;
  params.triangle_total = scene.voxel_triangle_count;
  params.sphere_count = scene.sphere_count;
  params.bounce_cells = bounce_cells_;
  return params;
}

void VoxelizePass::enqueue_triangles(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                                     const render::ShadowMap& shadow, cl_uint record) {
  gpu::VoxelizeParams params = params_for(scene);
  params.record = record;
  params.cache_capacity = cl_uint(cache_capacity_);
  rp::cl::bind_args(triangles_, scene.frame, scene.instances, scene.vertices, scene.triangles,
                    scene.materials, scene.textures, texels_, shadow.depth, target_accum_,
                    target_overflow_, large_count_, large_list_, cached_flags_, cache_count_,
                    cache_() ? cache_ : cache_count_,  // a valid buffer before the first
                    *bounce_, params);
  const size_t span = static_cast<size_t>(span_);
  const size_t items = (size_t(scene.voxel_triangle_count) + span - 1) / span;
  profiler.enqueue(pass_name::kVoxelize, triangles_,
                   ::cl::NDRange(rp::cl::round_up(items, kSpanGroup)), ::cl::NDRange(kSpanGroup));
}

void VoxelizePass::enqueue_large(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                                 const render::ShadowMap& shadow, cl_uint record) {
  gpu::VoxelizeParams params = params_for(scene);
  params.record = record;
  params.cache_capacity = cl_uint(cache_capacity_);
  params.slices = large_slices_;
  rp::cl::bind_args(large_, scene.frame, scene.instances, scene.vertices, scene.triangles,
                    scene.materials, scene.textures, texels_, shadow.depth, target_accum_,
                    target_overflow_, large_count_, large_list_, cached_flags_, cache_count_,
                    cache_() ? cache_ : cache_count_,  // a valid buffer before the first
                    *bounce_, params);
  // The list's length is only known on the device (reading it back would stall the queue): a
  // fixed number of work-items strides over it.
  profiler.enqueue(pass_name::kVoxelize, large_, ::cl::NDRange(large_items_),
                   ::cl::NDRange(kSpanGroup));
}

void VoxelizePass::build_cache(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                               const render::ShadowMap& shadow) {
  // Rare (the first frame, a cached instance that moved): blocking reads and writes are fine.
  ::cl::CommandQueue& queue = profiler.queue();
  // Counting lists the cached instances' large triangles (from an empty list); recording
  // reads the same list. The caller empties the list again before its own launches.
  const cl_uint zero = 0;
  queue.enqueueWriteBuffer(cache_count_, CL_TRUE, 0, sizeof(cl_uint), &zero);
  queue.enqueueWriteBuffer(large_count_, CL_TRUE, 0, sizeof(cl_uint), &zero);
  enqueue_triangles(profiler, scene, shadow, kCount);
  enqueue_large(profiler, scene, shadow, kCount);
  cl_uint samples = 0;
  queue.enqueueReadBuffer(cache_count_, CL_TRUE, 0, sizeof(cl_uint), &samples);
  if (uint64_t(samples) * kSampleBytes > cache_limit_) {
    // Over the owner's memory limit (the octree at 512^3): no cache for this session, the
    // instances are voxelized every frame like moving ones (the same volume, more time).
    cache_enabled_ = false;
    std::fill(still_.begin(), still_.end(), 0u);
    std::fill(cached_host_.begin(), cached_host_.end(), 0u);
    queue.enqueueWriteBuffer(cached_flags_, CL_TRUE, 0, cached_host_.size() * sizeof(cl_uint),
                             cached_host_.data());
    cache_ = ::cl::Buffer();
    cache_capacity_ = 0;
    cache_samples_ = 0;
    return;
  }
  if (samples > cache_capacity_) {
    cache_capacity_ = samples + samples / 4;
    cache_ = rp::cl::make_buffer(context_->context, CL_MEM_READ_WRITE,
                                 cache_capacity_ * kSampleBytes,
                                 "the voxelizer's surface cache (" + std::to_string(samples) +
                                     " samples of the scene's still surfaces)",
                                 "it grows with the scene's surface and the square of --voxels");
  }
  queue.enqueueWriteBuffer(cache_count_, CL_TRUE, 0, sizeof(cl_uint), &zero);
  if (samples > 0) {
    enqueue_triangles(profiler, scene, shadow, kRecord);
    enqueue_large(profiler, scene, shadow, kRecord);
    // Lanes of one work-item merge a voxel's samples (CPUs); GPUs run one sample a work-item,
    // where a sorted cache would only put neighbouring threads on one voxel's atomics. The
    // octree's fragments are not merged.
    if (span_ > 1 && !fragments_) sort_cache_by_voxel(queue, cache_, samples);
  }
  cache_samples_ = samples;
  cache_bounce_fresh_ = false;  // recorded with no bounce light
  direct_key_valid_ = false;    // nor direct light
}

bool VoxelizePass::update_direct_key(const render::GpuScene& scene,
                                     const render::ShadowMap& shadow) {
  // What the samples' direct light reads: the lamp (position, intensity, shadow projection and
  // planes), the punctual lights and their shadow views, and the shadow maps, which are drawn
  // from the instances and spheres through those views (the renderer redraws them only when
  // one of these changed). A 64-bit hash of those bytes, not the bytes: no allocation per
  // frame (the busy scene's sphere count varies), and two states mistaken for one are about
  // 2^-64 likely. The depth buffer is held, so its handle cannot come back as another
  // buffer's.
  io::Fnv1a h;
  scene.hash_lights_and_objects(h);
  const bool fresh =
      direct_key_valid_ && h.get() == direct_key_ && direct_shadow_() == shadow.depth();
  direct_key_ = h.get();
  direct_key_valid_ = true;
  direct_shadow_ = shadow.depth;
  return fresh;
}

void VoxelizePass::set_bounce(const ::cl::Buffer* bounce, uint32_t bounce_cells) {
  if (bounce != nullptr && bounce_cells == 0)
    throw rp::cl::Error("voxelize pass: a bounce grid needs its cells per side");
  if (no_bounce_() == nullptr)  // a valid argument when there is no grid (never read)
    no_bounce_ = ::cl::Buffer(context_->context, CL_MEM_READ_ONLY, 4 * sizeof(float));
  bounce_ = bounce != nullptr ? bounce : &no_bounce_;
  bounce_cells_ = bounce != nullptr ? bounce_cells : 0;
}

uint64_t VoxelizePass::device_bytes() const {
  uint64_t total = 0;
  for (const ::cl::Buffer* b : {&no_bounce_, &no_texels_, &large_count_, &large_list_,
                                &cached_flags_, &cache_, &cache_count_})
    if ((*b)() != nullptr) total += b->getInfo<CL_MEM_SIZE>();
  return total;
}

void VoxelizePass::run_fragments(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                                 const render::ShadowMap& shadow, uint32_t resolution,
                                 const ::cl::Buffer& fragments, const ::cl::Buffer& counter,
                                 const ::cl::Buffer* bounce, uint32_t bounce_cells) {
  if (!fragments_)
    throw rp::cl::Error("voxelize pass: run_fragments needs a pass built for fragments");
  if (resolution < 2 || resolution > 1024 || (resolution & (resolution - 1)) != 0)
    throw rp::cl::Error("voxelize pass: fragment resolution " + std::to_string(resolution) +
                        " is not a power of two from 2 to 1024");
  if (shadow.size != scene.constants.shadow_size)
    throw rp::cl::Error("voxelize pass: shadow map is " + std::to_string(shadow.size) +
                        " texels wide but the frame constants say " +
                        std::to_string(scene.constants.shadow_size));
  set_bounce(bounce, bounce_cells);
  target_resolution_ = resolution;
  target_accum_ = fragments;
  target_overflow_ = counter;
  const cl_uint zero = 0;  // voxelize_clear resets it in the dense mode
  profiler.queue().enqueueFillBuffer(large_count_, zero, 0, sizeof(cl_uint));
  voxelize(profiler, scene, shadow);
}

void VoxelizePass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                       const render::ShadowMap& shadow, render::VoxelVolume& volume,
                       const ::cl::Buffer* bounce, uint32_t bounce_cells) {
  if (fragments_) throw rp::cl::Error("voxelize pass: built for fragments (run_fragments)");
  const cl_uint r = volume.resolution;
  set_bounce(bounce, bounce_cells);
  if (!render::VoxelVolume::valid_resolution(r) || volume.chain() == nullptr)
    throw rp::cl::Error("voxelize pass: the voxel volume has not been allocated (resize it)");
  if (scene.constants.voxel_resolution != r || scene.constants.voxel_levels != volume.levels)
    throw rp::cl::Error("voxelize pass: the volume is " + std::to_string(r) + "^3 with " +
                        std::to_string(volume.levels) + " levels but the frame constants say " +
                        std::to_string(scene.constants.voxel_resolution) + "^3 with " +
                        std::to_string(scene.constants.voxel_levels) + " levels");
  if (shadow.size != scene.constants.shadow_size)
    throw rp::cl::Error("voxelize pass: shadow map is " + std::to_string(shadow.size) +
                        " texels wide but the frame constants say " +
                        std::to_string(scene.constants.shadow_size));
  const cl_uint voxels = r * r * r;
  target_resolution_ = r;
  target_accum_ = volume.accum;
  target_overflow_ = volume.overflow;
  rp::cl::bind_args(clear_, volume.accum, volume.overflow, voxels, large_count_);
  profiler.enqueue(pass_name::kVoxelize, clear_, ::cl::NDRange(rp::cl::round_up(voxels, kGroup)),
                   ::cl::NDRange(kGroup));
  voxelize(profiler, scene, shadow);
  rp::cl::bind_args(resolve_, volume.accum, volume.overflow, volume.chain, voxels);
  profiler.enqueue(pass_name::kVoxelize, resolve_, ::cl::NDRange(rp::cl::round_up(voxels, kGroup)),
                   ::cl::NDRange(kGroup));
}

void VoxelizePass::voxelize(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                            const render::ShadowMap& shadow) {
  const cl_uint r = target_resolution_;
  const cl_uint triangles = scene.voxel_triangle_count;
  if (large_capacity_ < std::max<size_t>(triangles, 1)) {
    large_capacity_ = std::max<size_t>(triangles, 1);
    large_list_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE,
                               large_capacity_ * sizeof(cl_uint));
  }
  const bool scene_changed = update_texels(scene);
  const bool rebuild = update_cache_plan(scene, r, scene_changed);
  const Slices slices = choose_slices(*context_, r);
  large_slices_ = slices.triangle;
  sphere_slices_ = slices.sphere;
  // Few work-items on CPUs, where every work-group costs a few microseconds even when it has
  // nothing to do; on GPUs enough for a few hundred triangles in flight at any slicing.
  const size_t max_items = context_->info.is_cpu ? 128 : 65536;
  const size_t in_flight =
      std::clamp<size_t>(triangles, 1, std::max<size_t>(max_items / large_slices_, 1));
  // A multiple of both the group and the slices (both powers of two).
  large_items_ = rp::cl::round_up(in_flight * large_slices_, kSpanGroup);

  if (triangles > 0 && rebuild) {
    build_cache(profiler, scene, shadow);
    const cl_uint zero = 0;
    profiler.queue().enqueueFillBuffer(large_count_, zero, 0, sizeof(cl_uint));
  }
  // The instances outside the cache, shaded and accumulated triangle by triangle (none in a
  // still scene once its cache is built).
  bool any_uncached = false;
  for (size_t i = 0; i < scene.host_instances.size() && !any_uncached; ++i) {
    const gpu::Instance& inst = scene.host_instances[i];
    any_uncached = inst.voxelize != 0 && inst.voxel_triangle_count != 0 && !cached_host_[i];
  }
  if (triangles > 0 && any_uncached) {
    enqueue_triangles(profiler, scene, shadow, kAccumulate);
    enqueue_large(profiler, scene, shadow, kAccumulate);
  }

  if (cache_samples_ > 0) {
    // The bounce light's refresh (set_bounce_refresh_stride): all of it unless every sample
    // already holds a light of this very grid.
    const bool reuse = bounce_cells_ != 0 && cache_bounce_fresh_ &&
                       cache_bounce_grid_ == (*bounce_)() && bounce_refresh_stride_ > 1;
    gpu::VoxelizeParams params = params_for(scene);
    params.samples = cache_samples_;
    params.refresh_stride = reuse ? bounce_refresh_stride_ : 1u;
    params.refresh_phase = reuse ? bounce_refresh_runs_++ % params.refresh_stride : 0u;
    params.direct_fresh = update_direct_key(scene, shadow) ? 1u : 0u;
    rp::cl::bind_args(cached_, scene.frame, shadow.depth, cache_, target_accum_,
                      target_overflow_, *bounce_, params);
    cache_bounce_fresh_ = bounce_cells_ != 0;
    cache_bounce_grid_ = (*bounce_)();
    const size_t span = static_cast<size_t>(span_);
    profiler.enqueue(pass_name::kVoxelize, cached_,
                     ::cl::NDRange(rp::cl::round_up((cache_samples_ + span - 1) / span,
                                                    kSpanGroup)),
                     ::cl::NDRange(kSpanGroup));
  }

  if (scene.sphere_count > 0) {
    gpu::VoxelizeParams params = params_for(scene);
    params.slices = sphere_slices_;
    rp::cl::bind_args(spheres_, scene.frame, scene.spheres, shadow.depth, target_accum_,
                      target_overflow_, *bounce_, params);
    profiler.enqueue(pass_name::kVoxelize, spheres_,
                     ::cl::NDRange(rp::cl::round_up(size_t(scene.sphere_count) * sphere_slices_, kGroup)),
                     ::cl::NDRange(kGroup));
  }
}

}  // namespace rp::passes
