#include "passes/motion_blur.h"

#include <cmath>
#include <string>

#include "cl/error.h"
#include "cl/kernel_args.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"

namespace rp::passes {
namespace {

constexpr const char* kPass = pass_name::kMotionBlur;
constexpr const char* kFile = "motion_blur.cl";
constexpr uint32_t kBlocksPerTile = 5;  // reconstruction: 4x4 pixel blocks, five per tile side

size_t div_up(size_t a, size_t b) { return (a + b - 1) / b; }

}  // namespace

MotionBlurPass::MotionBlurPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs)
    : context_(&context),
      tile_kernel_(programs.kernel(kFile, "motion_blur_tile_max")),
      neighbour_kernel_(programs.kernel(kFile, "motion_blur_neighbour_max")),
      depth_speed_kernel_(programs.kernel(kFile, "motion_blur_depth_speed")),
      block_max_kernel_(programs.kernel(kFile, "motion_blur_block_max")),
      composite_kernel_(programs.kernel(kFile, "motion_blur_composite")),
      reconstruct_kernel_(programs.kernel(kFile, "motion_blur_reconstruct")) {}

void MotionBlurPass::run(rp::cl::Profiler& profiler, const ::cl::Buffer& hdr_in,
                         const MotionInputs& motion, uint32_t width, uint32_t height,
                         float shutter, ::cl::Buffer& hdr_out) {
  enqueue(profiler, hdr_in, motion, width, height, shutter, nullptr, hdr_out);
}

void MotionBlurPass::run(rp::cl::Profiler& profiler, const ::cl::Buffer& hdr_in,
                         const MotionInputs& motion, uint32_t width, uint32_t height,
                         float shutter, const BloomPass::Composite& bloom,
                         ::cl::Buffer& hdr_out) {
  if (bloom.level1 == nullptr || bloom.level1_width != (width + 1) / 2 ||
      bloom.level1_height != (height + 1) / 2)
    throw rp::cl::Error("motion blur: the bloom composite is not that of a " +
                        std::to_string(width) + "x" + std::to_string(height) + " image");
  enqueue(profiler, hdr_in, motion, width, height, shutter, &bloom, hdr_out);
}

uint64_t MotionBlurPass::frame_bytes(uint32_t width, uint32_t height, bool makes_plane) {
  const uint64_t tiles = uint64_t((width + kTileSize - 1) / kTileSize) *
                         ((height + kTileSize - 1) / kTileSize);
  // tile_max, neighbour_max float2; plane_needed uint; block_speed a float per 4x4 block
  const uint64_t per_tile = 2 * 8 + 4 + kBlocksPerTile * kBlocksPerTile * sizeof(float);
  return tiles * per_tile + (makes_plane ? pixel_count(width, height) * 2 * sizeof(uint16_t) : 0);
}

void MotionBlurPass::enqueue(rp::cl::Profiler& profiler, const ::cl::Buffer& hdr_in,
                             const MotionInputs& motion, uint32_t width, uint32_t height,
                             float shutter, const BloomPass::Composite* bloom,
                             ::cl::Buffer& hdr_out) {
  if (motion.width != width || motion.height != height)
    throw rp::cl::Error("motion blur: the velocity and depth are " + std::to_string(motion.width) +
                        "x" + std::to_string(motion.height) + " but the image is " +
                        std::to_string(width) + "x" + std::to_string(height));
  if (!(shutter >= 0.0f && shutter <= 1.0f))
    throw rp::cl::Error("motion blur: shutter " + std::to_string(shutter) +
                        " is outside [0, 1] (fraction of the frame interval)");
  if (motion.velocity == nullptr ||
      (motion.normal_depth == nullptr && motion.depth_speed == nullptr))
    throw rp::cl::Error("motion blur: no velocity, or neither a depth nor a depth/speed plane");
  if (motion.depth_speed != nullptr && motion.plane_shutter != shutter)
    throw rp::cl::Error("motion blur: the depth/speed plane was made for shutter " +
                        std::to_string(motion.plane_shutter) + ", not " +
                        std::to_string(shutter));
  if (width == 0 || height == 0) return;
  if (width != width_ || height != height_) {  // the buffers of frame_bytes
    width_ = width;
    height_ = height;
    tiles_x_ = (width + kTileSize - 1) / kTileSize;
    tiles_y_ = (height + kTileSize - 1) / kTileSize;
    const size_t tiles = size_t(tiles_x_) * tiles_y_;
    tile_max_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, tiles * 2 * sizeof(float));
    neighbour_max_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, tiles * 2 * sizeof(float));
    plane_needed_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, tiles * sizeof(cl_uint));
    depth_speed_ = ::cl::Buffer();
    block_speed_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE,
                                tiles * kBlocksPerTile * kBlocksPerTile * sizeof(float));
  }

  gpu::MotionBlurParams params{};
  params.width = width;
  params.height = height;
  params.tiles_x = tiles_x_;
  params.tiles_y = tiles_y_;
  params.shutter = shutter;
  params.fuse_bloom = bloom ? 1u : 0u;
  params.bloom_width = bloom ? bloom->level1_width : 0u;
  params.bloom_height = bloom ? bloom->level1_height : 0u;
  params.bloom_keep = bloom ? bloom->keep : 1.0f;
  params.bloom_scale = bloom ? bloom->scale : 0.0f;

  rp::cl::bind_args(tile_kernel_, *motion.velocity, tile_max_, params);
  profiler.enqueue(kPass, tile_kernel_, ::cl::NDRange(tiles_x_, tiles_y_ * kTileSize),
                   ::cl::NDRange(1, kTileSize));

  rp::cl::bind_args(neighbour_kernel_, tile_max_, neighbour_max_, plane_needed_, params);
  profiler.enqueue(kPass, neighbour_kernel_, ::cl::NDRange(tiles_x_, tiles_y_));

  if (motion.depth_speed == nullptr) {  // the plane from the velocity and the depth
    if (!depth_speed_())
      depth_speed_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE,
                                  size_t(width) * height * 2 * sizeof(uint16_t));
    rp::cl::bind_args(depth_speed_kernel_, *motion.velocity, *motion.normal_depth, plane_needed_,
                      depth_speed_, params);
    profiler.enqueue(kPass, depth_speed_kernel_, ::cl::NDRange(tiles_x_, height),
                     ::cl::NDRange(tiles_x_, 1));
  }
  last_depth_speed_ = motion.depth_speed != nullptr ? *motion.depth_speed : depth_speed_;

  // The largest blur radius of every 4x4 block of the flagged tiles.
  rp::cl::bind_args(block_max_kernel_, last_depth_speed_, plane_needed_, block_speed_, params);
  profiler.enqueue(kPass, block_max_kernel_,
                   ::cl::NDRange(tiles_x_ * kBlocksPerTile, tiles_y_ * kBlocksPerTile),
                   ::cl::NDRange(kBlocksPerTile, kBlocksPerTile));

  // The image outside the moving tiles: the whole buffer copied, or the bloom composited.
  if (bloom) {
    rp::cl::bind_args(composite_kernel_, hdr_in, *bloom->level1, neighbour_max_, hdr_out,
                      params);
    profiler.enqueue(kPass, composite_kernel_,
                     ::cl::NDRange(rp::cl::round_up(div_up(width, 16), 16), div_up(height, 2)),
                     ::cl::NDRange(16, 1));
  } else {
    ::cl::Event copied;
    profiler.queue().enqueueCopyBuffer(hdr_in, hdr_out, 0, 0, size_t(width) * height * 16,
                                       nullptr, &copied);
    profiler.record(kPass, copied);
  }

  // The moving tiles, over the copy: 4x4 pixel blocks, one tile's 5x5 blocks per work-group.
  // Without the bloom its level is not read: any buffer will do.
  rp::cl::bind_args(reconstruct_kernel_, hdr_in, last_depth_speed_, neighbour_max_, block_speed_,
                    bloom ? *bloom->level1 : neighbour_max_, hdr_out, params);
  profiler.enqueue(kPass, reconstruct_kernel_,
                   ::cl::NDRange(tiles_x_ * kBlocksPerTile, tiles_y_ * kBlocksPerTile),
                   ::cl::NDRange(kBlocksPerTile, kBlocksPerTile));
}

}  // namespace rp::passes
