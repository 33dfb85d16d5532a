#include "passes/motion_blur.h"

#include <cmath>
#include <string>

#include "cl/error.h"

namespace rp::passes {
namespace {

constexpr const char* kPass = "motion_blur";
constexpr const char* kFile = "motion_blur.cl";
constexpr uint32_t kGroupSide = 10;  // tile kernel: 10x10 items, 2x2 pixels each

}  // namespace

MotionBlurPass::MotionBlurPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs)
    : context_(&context),
      tile_kernel_(programs.kernel(kFile, "motion_blur_tile_max")),
      neighbour_kernel_(programs.kernel(kFile, "motion_blur_neighbour_max")),
      depth_speed_kernel_(programs.kernel(kFile, "motion_blur_depth_speed")),
      reconstruct_kernel_(programs.kernel(kFile, "motion_blur_reconstruct")) {}

void MotionBlurPass::run(rp::cl::Profiler& profiler, const ::cl::Buffer& hdr_in,
                         const render::GBuffer& gbuffer, uint32_t width, uint32_t height,
                         float shutter, ::cl::Buffer& hdr_out) {
  if (gbuffer.width != width || gbuffer.height != height)
    throw rp::cl::Error("motion blur: GBuffer is " + std::to_string(gbuffer.width) + "x" +
                        std::to_string(gbuffer.height) + " but the image is " +
                        std::to_string(width) + "x" + std::to_string(height));
  if (!(shutter >= 0.0f && shutter <= 1.0f))
    throw rp::cl::Error("motion blur: shutter " + std::to_string(shutter) +
                        " is outside [0, 1] (fraction of the frame interval)");
  if (width == 0 || height == 0) return;
  if (width != width_ || height != height_) {
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
  }

  tile_kernel_.setArg(0, gbuffer.velocity);
  tile_kernel_.setArg(1, tile_max_);
  tile_kernel_.setArg(2, cl_uint(width));
  tile_kernel_.setArg(3, cl_uint(height));
  tile_kernel_.setArg(4, shutter);
  profiler.enqueue(kPass, tile_kernel_, ::cl::NDRange(tiles_x_ * kGroupSide, tiles_y_ * kGroupSide),
                   ::cl::NDRange(kGroupSide, kGroupSide));

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
  profiler.enqueue(kPass, depth_speed_kernel_, ::cl::NDRange(width, height));

  reconstruct_kernel_.setArg(0, hdr_in);
  reconstruct_kernel_.setArg(1, depth_speed_);
  reconstruct_kernel_.setArg(2, neighbour_max_);
  reconstruct_kernel_.setArg(3, hdr_out);
  reconstruct_kernel_.setArg(4, cl_uint(width));
  reconstruct_kernel_.setArg(5, cl_uint(height));
  reconstruct_kernel_.setArg(6, cl_uint(tiles_x_));
  profiler.enqueue(kPass, reconstruct_kernel_, ::cl::NDRange(width, height));
}

}  // namespace rp::passes
