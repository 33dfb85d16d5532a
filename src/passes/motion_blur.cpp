#include "passes/motion_blur.h"

#include <cmath>
#include <string>

#include "cl/error.h"
#include "passes/pass_names.h"

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
                         const render::GBuffer& gbuffer, uint32_t width, uint32_t height,
                         float shutter, ::cl::Buffer& hdr_out) {
  enqueue(profiler, hdr_in, gbuffer, width, height, shutter, nullptr, hdr_out);
}

void MotionBlurPass::run(rp::cl::Profiler& profiler, const ::cl::Buffer& hdr_in,
                         const render::GBuffer& gbuffer, uint32_t width, uint32_t height,
                         float shutter, const BloomPass::Composite& bloom,
                         ::cl::Buffer& hdr_out) {
  if (bloom.level1 == nullptr || bloom.level1_width != (width + 1) / 2 ||
      bloom.level1_height != (height + 1) / 2)
    throw rp::cl::Error("motion blur: the bloom composite is not that of a " +
                        std::to_string(width) + "x" + std::to_string(height) + " image");
  enqueue(profiler, hdr_in, gbuffer, width, height, shutter, &bloom, hdr_out);
}

uint64_t MotionBlurPass::frame_bytes(uint32_t width, uint32_t height) {
  const uint64_t tiles = uint64_t((width + kTileSize - 1) / kTileSize) *
                         ((height + kTileSize - 1) / kTileSize);
  // tile_max, neighbour_max float2; plane_needed uint; block_speed a float per 4x4 block
  const uint64_t per_tile = 2 * 8 + 4 + kBlocksPerTile * kBlocksPerTile * sizeof(float);
  return tiles * per_tile + pixel_count(width, height) * 2 * sizeof(uint16_t);
}

void MotionBlurPass::enqueue(rp::cl::Profiler& profiler, const ::cl::Buffer& hdr_in,
                             const render::GBuffer& gbuffer, uint32_t width, uint32_t height,
                             float shutter, const BloomPass::Composite* bloom,
                             ::cl::Buffer& hdr_out) {
  if (gbuffer.width != width || gbuffer.height != height)
    throw rp::cl::Error("motion blur: GBuffer is " + std::to_string(gbuffer.width) + "x" +
                        std::to_string(gbuffer.height) + " but the image is " +
                        std::to_string(width) + "x" + std::to_string(height));
  if (!(shutter >= 0.0f && shutter <= 1.0f))
    throw rp::cl::Error("motion blur: shutter " + std::to_string(shutter) +
                        " is outside [0, 1] (fraction of the frame interval)");
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
    depth_speed_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE,
                                size_t(width) * height * 2 * sizeof(uint16_t));
    block_speed_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE,
                                tiles * kBlocksPerTile * kBlocksPerTile * sizeof(float));
  }

  tile_kernel_.setArg(0, gbuffer.velocity);
  tile_kernel_.setArg(1, tile_max_);
  tile_kernel_.setArg(2, cl_uint(width));
  tile_kernel_.setArg(3, cl_uint(height));
  tile_kernel_.setArg(4, shutter);
  profiler.enqueue(kPass, tile_kernel_, ::cl::NDRange(tiles_x_, tiles_y_ * kTileSize),
                   ::cl::NDRange(1, kTileSize));

  neighbour_kernel_.setArg(0, tile_max_);
  neighbour_kernel_.setArg(1, neighbour_max_);
  neighbour_kernel_.setArg(2, plane_needed_);
  neighbour_kernel_.setArg(3, cl_uint(tiles_x_));
  neighbour_kernel_.setArg(4, cl_uint(tiles_y_));
  profiler.enqueue(kPass, neighbour_kernel_, ::cl::NDRange(tiles_x_, tiles_y_));

  depth_speed_kernel_.setArg(0, gbuffer.velocity);
  depth_speed_kernel_.setArg(1, gbuffer.normal_depth);
  depth_speed_kernel_.setArg(2, plane_needed_);
  depth_speed_kernel_.setArg(3, depth_speed_);
  depth_speed_kernel_.setArg(4, cl_uint(width));
  depth_speed_kernel_.setArg(5, cl_uint(height));
  depth_speed_kernel_.setArg(6, cl_uint(tiles_x_));
  depth_speed_kernel_.setArg(7, shutter);
  profiler.enqueue(kPass, depth_speed_kernel_, ::cl::NDRange(tiles_x_, height),
                   ::cl::NDRange(tiles_x_, 1));

  // The largest blur radius of every 4x4 block of the flagged tiles.
  block_max_kernel_.setArg(0, depth_speed_);
  block_max_kernel_.setArg(1, plane_needed_);
  block_max_kernel_.setArg(2, block_speed_);
  block_max_kernel_.setArg(3, cl_int(width));
  block_max_kernel_.setArg(4, cl_int(height));
  block_max_kernel_.setArg(5, cl_int(tiles_x_));
  profiler.enqueue(kPass, block_max_kernel_,
                   ::cl::NDRange(tiles_x_ * kBlocksPerTile, tiles_y_ * kBlocksPerTile),
                   ::cl::NDRange(kBlocksPerTile, kBlocksPerTile));

  // The image outside the moving tiles: the whole buffer copied, or the bloom composited.
  if (bloom) {
    composite_kernel_.setArg(0, hdr_in);
    composite_kernel_.setArg(1, *bloom->level1);
    composite_kernel_.setArg(2, cl_int(bloom->level1_width));
    composite_kernel_.setArg(3, cl_int(bloom->level1_height));
    composite_kernel_.setArg(4, bloom->keep);
    composite_kernel_.setArg(5, bloom->scale);
    composite_kernel_.setArg(6, neighbour_max_);
    composite_kernel_.setArg(7, cl_int(tiles_x_));
    composite_kernel_.setArg(8, hdr_out);
    composite_kernel_.setArg(9, cl_int(width));
    composite_kernel_.setArg(10, cl_int(height));
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
  reconstruct_kernel_.setArg(0, hdr_in);
  reconstruct_kernel_.setArg(1, depth_speed_);
  reconstruct_kernel_.setArg(2, neighbour_max_);
  reconstruct_kernel_.setArg(3, block_speed_);
  reconstruct_kernel_.setArg(4, bloom ? *bloom->level1 : neighbour_max_);
  reconstruct_kernel_.setArg(5, cl_int(bloom ? bloom->level1_width : 0));
  reconstruct_kernel_.setArg(6, cl_int(bloom ? bloom->level1_height : 0));
  reconstruct_kernel_.setArg(7, bloom ? bloom->keep : 1.0f);
  reconstruct_kernel_.setArg(8, bloom ? bloom->scale : 0.0f);
  reconstruct_kernel_.setArg(9, cl_int(bloom ? 1 : 0));
  reconstruct_kernel_.setArg(10, hdr_out);
  reconstruct_kernel_.setArg(11, cl_int(width));
  reconstruct_kernel_.setArg(12, cl_int(height));
  reconstruct_kernel_.setArg(13, cl_int(tiles_x_));
  profiler.enqueue(kPass, reconstruct_kernel_,
                   ::cl::NDRange(tiles_x_ * kBlocksPerTile, tiles_y_ * kBlocksPerTile),
                   ::cl::NDRange(kBlocksPerTile, kBlocksPerTile));
}

}  // namespace rp::passes
