#include "passes/taa.h"

#include <string>

#include "cl/error.h"
#include "cl/kernel_args.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"

namespace rp::passes {
namespace {

// One work-item per block of 8 pixels of a row (kernels/taa.cl): the whole blocks in work-groups
// of 16 blocks along the row (rounded up; the kernel skips blocks past the last whole one), the
// block crossing the right border (width % 8 != 0) by the RP_TAA_BORDER build, 16 rows a group.
constexpr uint32_t kPixelsPerItem = 8;
constexpr size_t kGroup = 16;

void check(const TaaSettings& s) {
  if (!(s.history_weight >= 0.0f && s.history_weight < 1.0f))
    throw rp::cl::Error("TAA: history weight " + std::to_string(s.history_weight) +
                        " is outside [0, 1)");
  if (!(s.gamma > 0.0f))
    throw rp::cl::Error("TAA: clip box gamma " + std::to_string(s.gamma) + " must be positive");
}

}  // namespace

TaaPass::TaaPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                 TaaSettings settings)
    : context_(context.context), programs_(&programs),
      kernel_(programs.kernel("taa.cl", "taa_resolve")), settings_(settings) {
  check(settings_);
}

void TaaPass::set_settings(const TaaSettings& settings) {
  check(settings);
  settings_ = settings;
}

void TaaPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                  const ::cl::Buffer& hdr_in, const render::GBuffer& gbuffer,
                  const ::cl::Buffer& depth, ::cl::Buffer& hdr_out) {
  const uint32_t w = scene.constants.width, h = scene.constants.height;
  if (w == 0 || h == 0) return;
  if (gbuffer.width != w || gbuffer.height != h)
    throw rp::cl::Error("TAA: GBuffer is " + std::to_string(gbuffer.width) + "x" +
                        std::to_string(gbuffer.height) + " but the frame is " +
                        std::to_string(w) + "x" + std::to_string(h));
  if (w != width_ || h != height_) {
    const size_t bytes = size_t(w) * h * 3 * sizeof(float);  // three planes, see taa.h
    history_[0] = ::cl::Buffer(context_, CL_MEM_READ_WRITE, bytes);
    history_[1] = ::cl::Buffer(context_, CL_MEM_READ_WRITE, bytes);
    width_ = w;
    height_ = h;
    history_valid_ = false;
  }
  const int next = 1 - current_;
  gpu::TaaParams params{};
  params.render_width = params.out_width = w;
  params.render_height = params.out_height = h;
  params.jitter_x = scene.constants.jitter.x;
  params.jitter_y = scene.constants.jitter.y;
  params.history_weight = settings_.history_weight;
  params.gamma = settings_.gamma;
  params.history_valid = history_valid_ ? 1u : 0u;
  params.unjitter = settings_.unjitter_current ? 1u : 0u;
  auto set_args = [&](::cl::Kernel& kernel, uint32_t x_first) {
    params.x_first = x_first;
    rp::cl::bind_args(kernel, hdr_in, gbuffer.velocity, depth, history_[current_],
                      history_[next], hdr_out, params);
  };
  const uint32_t whole_blocks = w / kPixelsPerItem;
  if (whole_blocks > 0) {
    set_args(kernel_, 0);
    profiler.enqueue(pass_name::kTaa, kernel_,
                     ::cl::NDRange(rp::cl::round_up(whole_blocks, kGroup), h),
                     ::cl::NDRange(kGroup, 1));
  }
  if (w % kPixelsPerItem != 0) {
    if (!border_kernel_())
      border_kernel_ = programs_->kernel("taa.cl", "taa_resolve", "-DRP_TAA_BORDER=1");
    set_args(border_kernel_, whole_blocks * kPixelsPerItem);
    profiler.enqueue(pass_name::kTaa, border_kernel_, ::cl::NDRange(1, rp::cl::round_up(h, kGroup)),
                     ::cl::NDRange(1, kGroup));
  }
  current_ = next;
  history_valid_ = true;
}

}  // namespace rp::passes
