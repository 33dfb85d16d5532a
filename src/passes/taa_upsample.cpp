#include "passes/taa_upsample.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "cl/error.h"
#include "cl/kernel_args.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"

namespace rp::passes {
namespace {

// One work-item per 8 pixels of a row (kernels/taa_upsample.cl: render pixels for the box
// kernel, output pixels for the resolve), 16 of them along the row, one row a group (as
// kernels/taa.cl); blocks past the image return.
constexpr uint32_t kPixelsPerItem = 8;
constexpr size_t kGroupX = 16, kGroupY = 1;

}  // namespace

uint32_t upsample_jitter_frames(float scale) {
  const float s = std::clamp(scale, 0.25f, 1.0f);
  return std::max(16u, static_cast<uint32_t>(std::ceil(8.0f / (s * s))));
}

TaaUpsamplePass::TaaUpsamplePass(const rp::cl::Context& context, rp::cl::ProgramCache& programs)
    : context_(context.context), programs_(&programs) {}

void TaaUpsamplePass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                          const ::cl::Buffer& hdr_in, const render::GBuffer& gbuffer,
                          uint32_t out_width, uint32_t out_height, ::cl::Buffer& hdr_out) {
  const uint32_t w = scene.constants.width, h = scene.constants.height;
  if (w == 0 || h == 0 || out_width == 0 || out_height == 0) return;
  if (gbuffer.width != w || gbuffer.height != h)
    throw rp::cl::Error("temporal upsampling: GBuffer is " + std::to_string(gbuffer.width) + "x" +
                        std::to_string(gbuffer.height) + " but the frame is " +
                        std::to_string(w) + "x" + std::to_string(h));
  if (out_width < w || out_height < h)
    throw rp::cl::Error("temporal upsampling: the output " + std::to_string(out_width) + "x" +
                        std::to_string(out_height) + " is smaller than the render size " +
                        std::to_string(w) + "x" + std::to_string(h));
  if (out_width != width_ || out_height != height_) {
    const size_t n = size_t(out_width) * out_height;
    history_[0] = ::cl::Buffer(context_, CL_MEM_READ_WRITE, n * 3 * sizeof(float));
    history_[1] = ::cl::Buffer(context_, CL_MEM_READ_WRITE, n * 3 * sizeof(float));
    velocity_ = ::cl::Buffer(context_, CL_MEM_READ_WRITE, n * 2 * sizeof(float));
    depth_speed_ = ::cl::Buffer(context_, CL_MEM_READ_WRITE, n * sizeof(cl_uint));
    width_ = out_width;
    height_ = out_height;
    history_valid_ = false;
  }
  if (w != render_width_ || h != render_height_) {
    const size_t n = size_t(w) * h * 4 * sizeof(float);
    colour_ = ::cl::Buffer(context_, CL_MEM_READ_WRITE, n);
    box_centre_ = ::cl::Buffer(context_, CL_MEM_READ_WRITE, n);
    box_extent_ = ::cl::Buffer(context_, CL_MEM_READ_WRITE, n);
    render_width_ = w;
    render_height_ = h;
  }
  // built on first use: renders at scale 1 never pay for their compilation
  if (!kernel_()) {
    box_kernel_ = programs_->kernel("taa_upsample.cl", "taa_upsample_box");
    kernel_ = programs_->kernel("taa_upsample.cl", "taa_upsample");
  }
  const int next = 1 - current_;
  gpu::TaaParams params{};
  params.render_width = w;
  params.render_height = h;
  params.out_width = out_width;
  params.out_height = out_height;
  params.jitter_x = scene.constants.jitter.x;
  params.jitter_y = scene.constants.jitter.y;
  params.history_weight = settings_.history_weight;
  params.gamma = settings_.gamma;
  params.history_valid = history_valid_ ? 1u : 0u;
  params.blur_half = blur_shutter_ > 0.0f ? blur_shutter_ * 0.5f : 0.0f;  // as motion_blur.cl's
  rp::cl::bind_args(box_kernel_, hdr_in, gbuffer.velocity, gbuffer.normal_depth, colour_,
                    box_centre_, box_extent_, params);
  profiler.enqueue(pass_name::kTaa, box_kernel_,
                   ::cl::NDRange(rp::cl::round_up((w + kPixelsPerItem - 1) / kPixelsPerItem,
                                                  kGroupX),
                                 rp::cl::round_up(h, kGroupY)),
                   ::cl::NDRange(kGroupX, kGroupY));
  rp::cl::bind_args(kernel_, colour_, box_centre_, box_extent_, gbuffer.normal_depth,
                    history_[current_], history_[next], hdr_out, velocity_, depth_speed_,
                    params);
  profiler.enqueue(pass_name::kTaa, kernel_,
                   ::cl::NDRange(rp::cl::round_up((out_width + kPixelsPerItem - 1) / kPixelsPerItem,
                                                  kGroupX),
                                 rp::cl::round_up(out_height, kGroupY)),
                   ::cl::NDRange(kGroupX, kGroupY));
  current_ = next;
  history_valid_ = true;
}

}  // namespace rp::passes
