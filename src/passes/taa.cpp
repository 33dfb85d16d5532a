#include "passes/taa.h"

#include <string>

#include "cl/error.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 8;  // 8x8 work-groups over the image, rounded up (kernel bounds-checks)

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
    : context_(context.context), kernel_(programs.kernel("taa.cl", "taa_resolve")),
      settings_(settings) {
  check(settings_);
}

void TaaPass::set_settings(const TaaSettings& settings) {
  check(settings);
  settings_ = settings;
}

void TaaPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                  const ::cl::Buffer& hdr_in, const render::GBuffer& gbuffer,
                  ::cl::Buffer& hdr_out) {
  const uint32_t w = scene.constants.width, h = scene.constants.height;
  if (w == 0 || h == 0) return;
  if (gbuffer.width != w || gbuffer.height != h)
    throw rp::cl::Error("TAA: GBuffer is " + std::to_string(gbuffer.width) + "x" +
                        std::to_string(gbuffer.height) + " but the frame is " +
                        std::to_string(w) + "x" + std::to_string(h));
  if (w != width_ || h != height_) {
    const size_t bytes = size_t(w) * h * 16;
    history_[0] = ::cl::Buffer(context_, CL_MEM_READ_WRITE, bytes);
    history_[1] = ::cl::Buffer(context_, CL_MEM_READ_WRITE, bytes);
    width_ = w;
    height_ = h;
    history_valid_ = false;
  }
  const int next = 1 - current_;
  cl_uint arg = 0;
  kernel_.setArg(arg++, hdr_in);
  kernel_.setArg(arg++, gbuffer.velocity);
  kernel_.setArg(arg++, gbuffer.normal_depth);
  kernel_.setArg(arg++, history_[current_]);
  kernel_.setArg(arg++, history_[next]);
  kernel_.setArg(arg++, hdr_out);
  kernel_.setArg(arg++, cl_uint(w));
  kernel_.setArg(arg++, cl_uint(h));
  kernel_.setArg(arg++, scene.constants.jitter.x);
  kernel_.setArg(arg++, scene.constants.jitter.y);
  kernel_.setArg(arg++, settings_.history_weight);
  kernel_.setArg(arg++, settings_.gamma);
  kernel_.setArg(arg++, cl_uint(history_valid_ ? 1u : 0u));
  kernel_.setArg(arg++, cl_uint(settings_.unjitter_current ? 1u : 0u));
  profiler.enqueue("taa", kernel_,
                   ::cl::NDRange(rp::cl::round_up(w, kGroup), rp::cl::round_up(h, kGroup)),
                   ::cl::NDRange(kGroup, kGroup));
  current_ = next;
  history_valid_ = true;
}

}  // namespace rp::passes
