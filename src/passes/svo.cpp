#include "passes/svo.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "cl/buffer.h"
#include "cl/error.h"
#include "cl/kernel_args.h"
#include "passes/pass_names.h"
#include "passes/svo_solid.h"
#include "render/gpu_types.h"
#include "render/voxel_volume.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 64;
constexpr uint32_t kChunk = 256;  // nodes per work-item of svo_count / svo_allocate
constexpr uint32_t kFlagChunk = 32;  // fragments per work-item of svo_flag (SVO_FLAG_CHUNK)
// Brick levels >= this one take their flags from occupancy bits (svo_flag_bits: one pass over
// the fragments for all of them) instead of a pass over the fragments each: at 512^3 the top
// 6 of 9 depths. Level 3's bits: (R/8)^3 (32 KiB at 512^3), the coarser levels 1/7 more.
constexpr uint32_t kBitsLevel = 3;

// First word of level l's occupancy bits (levels kBitsLevel .. D-1, each rounded to words).
uint32_t occ_offset(uint32_t resolution, uint32_t level) {
  uint32_t words = 0;
  for (uint32_t l = kBitsLevel; l < level; ++l) {
    const uint32_t n = resolution >> l;
    words += (n * n * n + 31) / 32;
  }
  return words;
}

std::string svo_options(bool float_samples) {
  return "-DRP_VOXEL_FIXED_BITS=" + std::to_string(render::kVoxelFixedBits) +
         " -DRP_VOXEL_SATURATED=" + std::to_string(render::kVoxelSaturatedSum) + "f" +
         " -DRP_SVO_FLOAT_SAMPLES=" + (float_samples ? "1" : "0");
}

size_t items(size_t n) { return rp::cl::round_up(std::max<size_t>(n, 1), kGroup); }

// What the octree's buffers are called in an allocation failure ("the octree's fragment list at
// 512^3"), and what would need less: the pools grow with the scene's surface at R^2.
std::string at_resolution(const char* what, uint32_t resolution) {
  return std::string("the octree's ") + what + " at " + std::to_string(resolution) + "^3";
}
std::string svo_advice(uint32_t resolution) {
  return "the octree grows with the scene's surface and the square of --voxels (" +
         std::to_string(resolution) + " here): a smaller --voxels or --gi-volume dense needs less";
}

}  // namespace

SvoPass::SvoPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                 bool float_samples)
    : context_(&context), float_samples_(float_samples) {
  voxelize_ = std::make_unique<VoxelizePass>(context, programs, /*fragments=*/true);
  const std::string o = svo_options(float_samples);
  clear_nodes_ = programs.kernel("svo.cl", "svo_clear_nodes", o);
  flag_ = programs.kernel("svo.cl", "svo_flag", o);
  occ_clear_ = programs.kernel("svo.cl", "svo_occ_clear", o);
  occ_mark_ = programs.kernel("svo.cl", "svo_occ_mark", o);
  occ_reduce_ = programs.kernel("svo.cl", "svo_occ_reduce", o);
  flag_bits_ = programs.kernel("svo.cl", "svo_flag_bits", o);
  dilate_ = programs.kernel("svo.cl", "svo_dilate", o);
  count_ = programs.kernel("svo.cl", "svo_count", o);
  scan_ = programs.kernel("svo.cl", "svo_scan", o);
  allocate_ = programs.kernel("svo.cl", "svo_allocate", o);
  link_ = programs.kernel("svo.cl", "svo_link", o);
  leaves_ = programs.kernel("svo.cl", "svo_leaves", o);
  border_ = programs.kernel("svo.cl", "svo_border", o);
  mips_ = programs.kernel("svo.cl", "svo_mips", o);
  counter_ = ::cl::Buffer(context.context, CL_MEM_READ_WRITE, 2 * sizeof(cl_uint));
  totals_ = ::cl::Buffer(context.context, CL_MEM_READ_WRITE,
                         2 * RP_SVO_MAX_DEPTHS * sizeof(cl_uint));
}

void SvoPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                  const render::ShadowMap& shadow, uint32_t resolution, render::SvoVolume& svo,
                  const ::cl::Buffer* bounce, uint32_t bounce_cells) {
  ::cl::CommandQueue& queue = profiler.queue();
  if (fragment_capacity_ == 0) {
    fragment_capacity_ = 1u << 16;
    fragments_ = rp::cl::make_buffer(
        context_->context, CL_MEM_READ_WRITE,
        fragment_capacity_ * RP_SVO_FRAGMENT_WORDS * sizeof(cl_uint),
        at_resolution("fragment list", resolution), svo_advice(resolution));
  }
  // The voxelizer's static surface cache costs 80 bytes a cached sample: 45 MiB at 256^3
  // on the demo, 181 MiB at 512^3, where the octree and its build scratch took 251 MiB of the
  // 256 MB budget (now 97 MiB, 142 MiB on the atrium). So from 512^3 on
  // the room is voxelized every frame like the moving objects (the same fragments; the cost:
  // bench/results/epyc-2core-pocl-svo2.md).
  voxelize_->set_cache_limit(resolution >= 512 ? 0 : UINT64_MAX);
  cl_uint count = 0;
  for (;;) {
    const cl_uint init[2] = {0, cl_uint(fragment_capacity_)};
    queue.enqueueWriteBuffer(counter_, CL_TRUE, 0, sizeof(init), init);
    voxelize_->run_fragments(profiler, scene, shadow, resolution, fragments_, counter_, bounce,
                             bounce_cells);
    queue.enqueueReadBuffer(counter_, CL_TRUE, 0, sizeof(cl_uint), &count);
    if (count <= fragment_capacity_) break;
    // 1/16 slack: a moving scene does not regrow every frame (the demo's count varies by a
    // few per cent); released first, so the old and the new list never coexist
    fragment_capacity_ = size_t(count) + count / 16;
    fragments_ = ::cl::Buffer();
    fragments_ = rp::cl::make_buffer(
        context_->context, CL_MEM_READ_WRITE,
        fragment_capacity_ * RP_SVO_FRAGMENT_WORDS * sizeof(cl_uint),
        at_resolution("fragment list", resolution) + " (" + std::to_string(count) + " fragments)",
        svo_advice(resolution));
  }
  build(profiler, fragments_, count, resolution, svo);
  svo.voxelizer_bytes = voxelize_->device_bytes();
  if (solid_ && svo.solid_capacity > 0) {
    SolidObjects objects;
    objects.tumbler = solid_tumbler_;
    for (const gpu::Instance& inst : scene.host_instances) {
      if (inst.first_triangle != solid_first_triangle_ || inst.voxelize == 0) continue;
      glm::mat4 model;
      for (int c = 0; c < 4; ++c)
        model[c] = glm::vec4(inst.model.c[c].x, inst.model.c[c].y, inst.model.c[c].z,
                             inst.model.c[c].w);
      objects.tumbler_world_to_local.push_back(glm::inverse(model));
    }
    for (const gpu::Sphere& sp : scene.host_spheres)
      objects.spheres.emplace_back(sp.center_radius.x, sp.center_radius.y, sp.center_radius.z,
                                   sp.center_radius.w);
    // The host computes while the device builds; the upload does not block (the last
    // frame's upload must be done before its data is overwritten).
    if (solid_upload_() != nullptr) solid_upload_.wait();
    const auto t0 = std::chrono::steady_clock::now();
    solid_grid_ = svo_solid_grid(resolution, objects);
    svo.solid_host_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    queue.enqueueWriteBuffer(svo.buffer, CL_FALSE, svo.solid_offset(), solid_grid_.size(),
                             solid_grid_.data(), nullptr, &solid_upload_);
    solid_header_[0] = cl_uint(svo.solid_offset());
    solid_header_[1] = kSvoSolidFirstLevel;
    queue.enqueueWriteBuffer(svo.buffer, CL_FALSE, RP_SVO_HDR_SOLID_OFFSET * sizeof(cl_uint),
                             sizeof(solid_header_), solid_header_);
  }
}

void SvoPass::enable_solid(uint32_t tumbler_first_triangle, const scene::TumblerShape& tumbler) {
  solid_ = true;
  solid_first_triangle_ = tumbler_first_triangle;
  solid_tumbler_ = tumbler;
}

void SvoPass::allocate(render::SvoVolume& svo, size_t nodes, size_t bricks, size_t samples) {
  if (bricks > RP_SVO_MAX_BRICKS)
    throw rp::cl::Error(at_resolution("brick table", svo.resolution) + " would need " +
                        std::to_string(bricks) + " bricks, more than the layout addresses (" +
                        std::to_string(RP_SVO_MAX_BRICKS) + "): " + svo_advice(svo.resolution));
  svo.node_capacity = nodes;
  svo.brick_capacity = bricks;
  svo.sample_capacity = samples;
  svo.sample_bytes = float_samples_ ? 16 : 5;
  svo.solid_capacity = solid_ ? svo_solid_bytes(svo.resolution) : 0;
  svo.buffer = ::cl::Buffer();  // the old pools go first (the build restarts anyway)
  svo.buffer = rp::cl::make_buffer(
      context_->context, CL_MEM_READ_WRITE, svo.buffer_bytes(),
      at_resolution("node and brick pools", svo.resolution) + " (" + std::to_string(nodes) +
          " nodes, " + std::to_string(bricks) + " bricks, " + std::to_string(samples) +
          " samples)",
      svo_advice(svo.resolution));
}

uint64_t SvoPass::device_bytes(const render::SvoVolume& svo) const {
  uint64_t total = 0;
  for (const ::cl::Buffer* b : {&svo.buffer, &fragments_, &counter_, &own_, &coords_, &cur_,
                                &sums_, &totals_, &occ_})
    if ((*b)() != nullptr) total += b->getInfo<CL_MEM_SIZE>();
  return total;
}

void SvoPass::ensure_scratch(uint32_t resolution, size_t nodes, size_t fragments) {
  const auto& ctx = context_->context;
  const auto scratch = [&](size_t bytes) {
    return rp::cl::make_buffer(ctx, CL_MEM_READ_WRITE, bytes,
                               at_resolution("build scratch", resolution),
                               svo_advice(resolution));
  };
  if (nodes > scratch_nodes_) {
    scratch_nodes_ = nodes;
    own_ = ::cl::Buffer();  // released before their successors exist
    coords_ = ::cl::Buffer();
    sums_ = ::cl::Buffer();
    own_ = scratch(nodes * sizeof(cl_uint));
    coords_ = scratch(nodes * sizeof(cl_uint));
    sums_ = scratch((nodes / kChunk + 1) * 2 * sizeof(cl_uint));
  }
  if (fragments > scratch_fragments_) {
    scratch_fragments_ = fragments;
    cur_ = ::cl::Buffer();
    cur_ = scratch(fragments * sizeof(cl_uint));
  }
}

void SvoPass::build(rp::cl::Profiler& profiler, const ::cl::Buffer& fragments, uint32_t count,
                    uint32_t resolution, render::SvoVolume& svo) {
  if (resolution < 2 || resolution > 1024 || (resolution & (resolution - 1)) != 0)
    throw rp::cl::Error("octree resolution " + std::to_string(resolution) +
                        " is not supported: use a power of two from 2 to 1024 (256 or 512)");
  svo.resolution = resolution;
  svo.depths = gpu::rp_svo_log2(resolution);
  svo.fragments = count;
  // A first guess below what the scenes measured (the 512^3 demo: 0.59 nodes, 0.30 bricks and
  // 2.5 samples a fragment; the atrium 0.47, 0.25, 1.6); a build that needs more grows the
  // pools to what it counted plus 1/64 and restarts (try_build: the first frame's few restarts
  // repeat only the top-down steps), so the pools end at the counts, not at a fraction of the
  // worst case.
  const bool fresh = svo.buffer() == nullptr ||
                     svo.sample_bytes != (float_samples_ ? 16u : 5u) ||
                     svo.solid_capacity != (solid_ ? svo_solid_bytes(resolution) : 0);
  if (fresh) {
    allocate(svo, std::max<size_t>(4096, size_t(count) / 8),
             std::max<size_t>(512, size_t(count) / 16),
             std::max<size_t>(4096, size_t(count) / 2));
    fitted_ = false;
  }
  for (int attempt = 0; attempt < 16; ++attempt)
    if (try_build(profiler, fragments, count, svo)) return;
  throw rp::cl::Error("octree build: the pools kept growing (16 attempts)");
}

bool SvoPass::try_build(rp::cl::Profiler& profiler, const ::cl::Buffer& fragments,
                        uint32_t count, render::SvoVolume& svo) {
  ::cl::CommandQueue& queue = profiler.queue();
  const uint32_t D = svo.depths;
  // cur: one word per fragment of the list's capacity (not the count), so that a list that
  // grew once is matched at once and a moving scene reallocates neither
  ensure_scratch(svo.resolution, svo.node_capacity,
                 std::max<size_t>(fragment_capacity_, std::max(count, 1u)));
  const cl_uint zero = 0;
  queue.enqueueFillBuffer(coords_, zero, 0, sizeof(cl_uint));  // the root's coordinate
  const cl_uint brick_offset = cl_uint(svo.brick_offset());
  const cl_uint alpha_offset = cl_uint(svo.alpha_offset());
  const cl_uint table_offset = cl_uint(svo.table_offset());
  // The builder's kernels' parameters: the fields every launch shares, each adds its own.
  gpu::SvoBuildParams shared{};
  shared.resolution_log2 = D;
  shared.fragment_count = cl_uint(count);
  shared.chunk = kChunk;
  shared.table_offset = table_offset;
  shared.brick_offset = brick_offset;
  shared.alpha_offset = alpha_offset;

  // Occupancy bits for the depths whose brick level is >= kBitsLevel (last_bits_depth and
  // above; none when D - 1 < kBitsLevel).
  const int last_bits_depth = int(D) - 1 - int(kBitsLevel);
  if (last_bits_depth >= 0) {
    const uint32_t words = occ_offset(svo.resolution, D);
    if (words > occ_words_) {
      occ_words_ = words;
      occ_ = ::cl::Buffer();
      occ_ = rp::cl::make_buffer(context_->context, CL_MEM_READ_WRITE, words * sizeof(cl_uint),
                                 at_resolution("occupancy bits", svo.resolution),
                                 svo_advice(svo.resolution));
    }
    gpu::SvoBuildParams clear = shared;
    clear.words = words;
    rp::cl::bind_args(occ_clear_, occ_, clear);
    profiler.enqueue(pass_name::kSvoNodes, occ_clear_, ::cl::NDRange(items(words)),
                     ::cl::NDRange(kGroup));
    if (count > 0) {
      gpu::SvoBuildParams mark = shared;
      mark.level = kBitsLevel;
      rp::cl::bind_args(occ_mark_, fragments, occ_, mark);
      profiler.enqueue(pass_name::kSvoNodes, occ_mark_,
                       ::cl::NDRange(items((count + kFlagChunk - 1) / kFlagChunk)),
                       ::cl::NDRange(kGroup));
    }
    for (uint32_t l = kBitsLevel; l + 1 < D; ++l) {
      const uint32_t n = svo.resolution >> (l + 1);
      gpu::SvoBuildParams reduce = shared;
      reduce.src = occ_offset(svo.resolution, l);
      reduce.dst = occ_offset(svo.resolution, l + 1);
      reduce.n = n;
      rp::cl::bind_args(occ_reduce_, occ_, reduce);
      profiler.enqueue(pass_name::kSvoNodes, occ_reduce_,
                       ::cl::NDRange(items((n * n * n + 31) / 32)),
                       ::cl::NDRange(kGroup));
    }
  }

  std::vector<uint32_t> first(D + 1, 0), nodes(D, 0), bricks(D, 0), owns(D, 0),
      brick_first(D, 0);
  nodes[0] = 1;
  uint64_t samples = 0, brick_count = 0;
  for (uint32_t k = 0; k < D; ++k) {
    const cl_uint n = nodes[k], f0 = first[k];
    if (size_t(f0) + n > svo.node_capacity) {  // cannot happen: checked before allocating
      allocate(svo, (size_t(f0) + n) * 2, svo.brick_capacity, svo.sample_capacity);
      return false;
    }
    gpu::SvoBuildParams depth = shared;  // this depth's nodes
    depth.first = f0;
    depth.count = n;
    depth.depth = k;
    rp::cl::bind_args(clear_nodes_, svo.buffer, own_, depth);
    profiler.enqueue(pass_name::kSvoNodes, clear_nodes_, ::cl::NDRange(items(n)),
                     ::cl::NDRange(kGroup));
    if (int(k) <= last_bits_depth) {
      gpu::SvoBuildParams bits = depth;
      bits.offset = occ_offset(svo.resolution, D - 1 - k);
      rp::cl::bind_args(flag_bits_, own_, coords_, occ_, bits);
      profiler.enqueue(pass_name::kSvoNodes, flag_bits_, ::cl::NDRange(items(n)),
                       ::cl::NDRange(kGroup));
    } else if (count > 0) {
      gpu::SvoBuildParams flag = depth;
      flag.descend = int(k) == last_bits_depth + 1 && k > 0 ? 1u : 0u;
      rp::cl::bind_args(flag_, fragments, svo.buffer, cur_, own_, flag);
      const size_t flag_items = items((count + kFlagChunk - 1) / kFlagChunk);
      profiler.enqueue(pass_name::kSvoNodes, flag_, ::cl::NDRange(flag_items),
                       ::cl::NDRange(kGroup));
    }
    if (k > 0) {
      rp::cl::bind_args(dilate_, svo.buffer, own_, coords_, depth);
      profiler.enqueue(pass_name::kSvoNodes, dilate_, ::cl::NDRange(items(n)),
                       ::cl::NDRange(kGroup));
    }
    const cl_uint chunks = (n + kChunk - 1) / kChunk;
    rp::cl::bind_args(count_, svo.buffer, own_, sums_, depth);
    profiler.enqueue(pass_name::kSvoNodes, count_, ::cl::NDRange(items(chunks)),
                     ::cl::NDRange(kGroup));
    gpu::SvoBuildParams scan = depth;
    scan.chunks = chunks;
    scan.slot = k;
    rp::cl::bind_args(scan_, sums_, totals_, scan);
    profiler.enqueue(pass_name::kSvoNodes, scan_, ::cl::NDRange(1), ::cl::NullRange);
    cl_uint totals[2] = {0, 0};  // existing nodes, occupied own voxels
    queue.enqueueReadBuffer(totals_, CL_TRUE, 2 * k * sizeof(cl_uint), sizeof(totals), totals);
    const cl_uint exist = totals[0], own = totals[1];
    const bool leaf = k + 1 == D;
    const uint32_t size = gpu::rp_svo_directions(D - 1 - k);  // samples per occupied voxel
    const size_t need_nodes = size_t(f0) + n + (leaf ? 0 : 8 * size_t(exist));
    const size_t need_bricks = brick_count + exist;
    const size_t need_samples = samples + size_t(own) * size;
    if (need_nodes > svo.node_capacity || need_bricks > svo.brick_capacity ||
        need_samples > svo.sample_capacity) {
      // Slack: 1/64 while the pools are still growing from the first guess (a static scene
      // keeps them), 1/16 when a later frame outgrows pools that held an earlier one (a moving
      // scene then does not reallocate every frame)
      const size_t slack = fitted_ ? 16 : 64;
      const auto grow = [slack](size_t need, size_t have) {
        return need > have ? need + need / slack : have;
      };
      allocate(svo, grow(need_nodes, svo.node_capacity), grow(need_bricks, svo.brick_capacity),
               grow(need_samples, svo.sample_capacity));
      return false;
    }
    bricks[k] = exist;
    owns[k] = own;
    brick_first[k] = cl_uint(brick_count);
    gpu::SvoBuildParams alloc = depth;
    alloc.child_first = f0 + n;
    alloc.brick_first = cl_uint(brick_count);
    alloc.own_first = cl_uint(samples);
    alloc.directions = size;
    alloc.leaf = leaf ? 1u : 0u;
    rp::cl::bind_args(allocate_, svo.buffer, own_, coords_, sums_, alloc);
    profiler.enqueue(pass_name::kSvoNodes, allocate_, ::cl::NDRange(items(chunks)),
                     ::cl::NDRange(kGroup));
    samples += size_t(own) * size;
    brick_count += exist;
    first[k + 1] = f0 + n;
    if (!leaf) nodes[k + 1] = 8 * exist;
  }

  // Leaves: fragment lists, sums and samples (and level 1's own samples), borders.
  const uint32_t L = D - 1;
  if (count > 0) {
    rp::cl::bind_args(link_, cur_, own_, shared);
    profiler.enqueue(pass_name::kSvoInject, link_, ::cl::NDRange(items(count)),
                     ::cl::NDRange(kGroup));
  }
  gpu::SvoBuildParams leaves = shared;
  leaves.first = first[L];
  leaves.count = nodes[L];
  leaves.depth = L;
  leaves.parent_brick_first = L > 0 ? cl_uint(brick_first[L - 1]) : cl_uint(RP_SVO_NO_BRICK);
  rp::cl::bind_args(leaves_, fragments, cur_, own_, svo.buffer, leaves);
  profiler.enqueue(pass_name::kSvoInject, leaves_, ::cl::NDRange(items(nodes[L])),
                   ::cl::NDRange(kGroup));
  // The borders: the brick table's face links to the neighbours' bricks (no values are copied,
  // so every depth's links could be made right after its allocation; kept here, per depth).
  const auto border = [&](uint32_t k) {
    gpu::SvoBuildParams at_depth = shared;
    at_depth.first = first[k];
    at_depth.count = nodes[k];
    at_depth.depth = k;
    rp::cl::bind_args(border_, svo.buffer, coords_, at_depth);
    profiler.enqueue(pass_name::kSvoBorder, border_, ::cl::NDRange(items(nodes[k])),
                     ::cl::NDRange(kGroup));
  };
  border(L);
  for (uint32_t level = 1; level < D; ++level) {
    const uint32_t k = D - 1 - level;
    if (level >= 2) {
      gpu::SvoBuildParams mips = shared;
      mips.first = first[k];
      mips.count = nodes[k];
      mips.depth = k;
      rp::cl::bind_args(mips_, svo.buffer, mips);
      profiler.enqueue(pass_name::kSvoMips, mips_, ::cl::NDRange(items(nodes[k])),
                       ::cl::NDRange(kGroup));
    }
    border(k);
  }

  // The header (svo_layout.h).
  header_.assign(4 * RP_SVO_HEADER_FLOAT4S, 0);
  header_[RP_SVO_HDR_RESOLUTION] = svo.resolution;
  header_[RP_SVO_HDR_DEPTHS] = D;
  header_[RP_SVO_HDR_NODES] = first[D];
  header_[RP_SVO_HDR_BRICK_OFFSET] = brick_offset;
  header_[RP_SVO_HDR_SAMPLES] = cl_uint(samples);
  header_[RP_SVO_HDR_SAMPLE_BYTES] = svo.sample_bytes;
  header_[RP_SVO_HDR_FRAGMENTS] = count;
  header_[RP_SVO_HDR_ALPHA_OFFSET] = alpha_offset;
  header_[RP_SVO_HDR_TABLE_OFFSET] = table_offset;
  for (uint32_t k = 0; k <= D; ++k) header_[RP_SVO_HDR_LEVEL_START + k] = first[k];
  queue.enqueueWriteBuffer(svo.buffer, CL_FALSE, 0, header_.size() * sizeof(cl_uint),
                           header_.data());
  // What the runtime says the buffers hold (CL_MEM_SIZE), not what the counts would need.
  // Buffers only grow, and a buffer that grows is released before its successor is created,
  // so the end of a build holds the most the octree path has had at once.
  svo.device_bytes = device_bytes(svo);
  peak_bytes_ = std::max(peak_bytes_, svo.device_bytes);
  svo.scratch_bytes = svo.device_bytes - svo.buffer.getInfo<CL_MEM_SIZE>();
  svo.fragment_bytes = fragments_() != nullptr ? fragments_.getInfo<CL_MEM_SIZE>() : 0;
  svo.peak_device_bytes = peak_bytes_;
  fitted_ = true;
  svo.nodes_per_depth = nodes;
  svo.bricks_per_depth = bricks;
  svo.own_per_depth = owns;
  svo.samples = samples;
  return true;
}

}  // namespace rp::passes
