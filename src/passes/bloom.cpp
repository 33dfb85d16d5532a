#include "passes/bloom.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "cl/error.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 64;
constexpr const char* kPass = "bloom";

::cl::NDRange global_for(size_t items) { return ::cl::NDRange(rp::cl::round_up(items, kGroup)); }

}  // namespace

BloomPass::BloomPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs)
    : context_(&context),
      downsample_(programs.kernel("bloom.cl", "bloom_downsample")),
      downsample_karis_(programs.kernel("bloom.cl", "bloom_downsample_karis")),
      upsample_add_(programs.kernel("bloom.cl", "bloom_upsample_add")),
      mix_(programs.kernel("bloom.cl", "bloom_mix")) {}

const ::cl::Buffer& BloomPass::up(int k) const {
  const Level& level = levels_.at(size_t(k - 1));
  return k == levels() ? level.down : level.up;
}

void BloomPass::allocate(uint32_t width, uint32_t height) {
  if (width == width_ && height == height_) return;
  levels_.clear();
  uint32_t w = width, h = height;
  for (int k = 1; k <= kMaxLevels; ++k) {
    w = (w + 1) / 2;
    h = (h + 1) / 2;
    if (k > 1 && std::min(w, h) < kMinLevelSide) break;
    Level level;
    level.width = w;
    level.height = h;
    const size_t bytes = size_t(w) * h * 4 * sizeof(float);
    level.down = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, bytes);
    levels_.push_back(level);
  }
  // Uk for k < N (UN is DN itself).
  for (size_t k = 0; k + 1 < levels_.size(); ++k)
    levels_[k].up = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE,
                                 size_t(levels_[k].width) * levels_[k].height * 4 * sizeof(float));
  width_ = width;
  height_ = height;
}

void BloomPass::run(rp::cl::Profiler& profiler, const ::cl::Buffer& hdr_in, uint32_t width,
                    uint32_t height, float strength, ::cl::Buffer& hdr_out) {
  if (!(strength >= 0.0f && strength <= 1.0f))
    throw rp::cl::Error("bloom pass: strength " + std::to_string(strength) +
                        " is outside [0, 1]");
  if (width == 0 || height == 0) return;
  const size_t bytes = size_t(width) * height * 4 * sizeof(float);
  if (hdr_in.getInfo<CL_MEM_SIZE>() < bytes || hdr_out.getInfo<CL_MEM_SIZE>() < bytes)
    throw rp::cl::Error("bloom pass: the HDR buffers are smaller than " + std::to_string(width) +
                        "x" + std::to_string(height) + " float4 pixels");
  if (strength == 0.0f) {  // exactly the input, no chain
    if (hdr_in() != hdr_out()) {
      ::cl::Event copied;
      profiler.queue().enqueueCopyBuffer(hdr_in, hdr_out, 0, 0, bytes, nullptr, &copied);
      profiler.record(kPass, copied);
    }
    return;
  }
  allocate(width, height);

  // Down: D1 from the input (Karis), Dk from D(k-1).
  const ::cl::Buffer* src = &hdr_in;
  cl_int src_w = cl_int(width), src_h = cl_int(height);
  for (Level& level : levels_) {
    const bool first = src == &hdr_in;
    ::cl::Kernel& kernel = first && karis_ ? downsample_karis_ : downsample_;
    const size_t items = size_t(level.width) * level.height * (first && karis_ ? 1 : 4);
    kernel.setArg(0, *src);
    kernel.setArg(1, src_w);
    kernel.setArg(2, src_h);
    kernel.setArg(3, level.down);
    kernel.setArg(4, cl_int(level.width));
    kernel.setArg(5, cl_int(level.height));
    profiler.enqueue(kPass, kernel, global_for(items), ::cl::NDRange(kGroup));
    src = &level.down;
    src_w = cl_int(level.width);
    src_h = cl_int(level.height);
  }

  // Up: Uk = Dk + up(U(k+1)) for k = N-1 .. 1.
  for (int k = levels() - 1; k >= 1; --k) {
    Level& level = levels_[size_t(k - 1)];
    upsample_add_.setArg(0, up(k + 1));
    upsample_add_.setArg(1, cl_int(level_width(k + 1)));
    upsample_add_.setArg(2, cl_int(level_height(k + 1)));
    upsample_add_.setArg(3, level.down);
    upsample_add_.setArg(4, level.up);
    upsample_add_.setArg(5, cl_int(level.width));
    upsample_add_.setArg(6, cl_int(level.height));
    profiler.enqueue(kPass, upsample_add_, global_for(size_t(level.width) * level.height * 4),
                     ::cl::NDRange(kGroup));
  }

  // Mix at full resolution: bloom = up(U1) / N.
  mix_.setArg(0, hdr_in);
  mix_.setArg(1, up(1));
  mix_.setArg(2, cl_int(level_width(1)));
  mix_.setArg(3, cl_int(level_height(1)));
  mix_.setArg(4, hdr_out);
  mix_.setArg(5, cl_int(width));
  mix_.setArg(6, cl_int(height));
  mix_.setArg(7, 1.0f - strength);
  mix_.setArg(8, strength / float(levels()));
  profiler.enqueue(kPass, mix_, global_for(size_t(width) * height * 4), ::cl::NDRange(kGroup));
}

}  // namespace rp::passes
