#include "passes/bloom.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "cl/error.h"
#include "passes/pass_names.h"

namespace rp::passes {
namespace {

constexpr const char* kPass = pass_name::kBloom;
constexpr size_t kPlanes = 3;  // the chain's levels are planar r, g, b

// Grids of `x` by `y` work-items (by `z` channels) in work-groups of 16 x 1 (x 1), x rounded up
// (the kernels bounds-check). Wide, flat groups measured fastest on PoCL: its work-item loop over
// a short x range gets fully unrolled, which bloats these large kernel bodies.
constexpr size_t kGroupWidth = 16;
::cl::NDRange grid(size_t x, size_t y) {
  return ::cl::NDRange(rp::cl::round_up(x, kGroupWidth), y);
}
::cl::NDRange grid(size_t x, size_t y, size_t z) {
  return ::cl::NDRange(rp::cl::round_up(x, kGroupWidth), y, z);
}
const ::cl::NDRange kGroup2(kGroupWidth, 1), kGroup3(kGroupWidth, 1, 1);

size_t div_up(size_t a, size_t b) { return (a + b - 1) / b; }

void check_buffer(const ::cl::Buffer& buffer, uint32_t width, uint32_t height) {
  if (buffer.getInfo<CL_MEM_SIZE>() < size_t(width) * height * 4 * sizeof(float))
    throw rp::cl::Error("bloom pass: the HDR buffers are smaller than " + std::to_string(width) +
                        "x" + std::to_string(height) + " float4 pixels");
}

void check_strength(float strength) {
  if (!(strength >= 0.0f && strength <= 1.0f))
    throw rp::cl::Error("bloom pass: strength " + std::to_string(strength) +
                        " is outside [0, 1]");
}

}  // namespace

BloomPass::BloomPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs)
    : context_(&context),
      downsample_(programs.kernel("bloom.cl", "bloom_downsample")),
      downsample_first_(programs.kernel("bloom.cl", "bloom_downsample_first")),
      upsample_add_(programs.kernel("bloom.cl", "bloom_upsample_add")),
      mix_(programs.kernel("bloom.cl", "bloom_mix")) {}

const ::cl::Buffer& BloomPass::up(int k) const {
  const Level& level = levels_.at(size_t(k - 1));
  return k == levels() ? level.down : level.up;
}

std::vector<std::pair<uint32_t, uint32_t>> BloomPass::level_sizes(uint32_t width,
                                                                  uint32_t height) {
  std::vector<std::pair<uint32_t, uint32_t>> sizes;
  uint32_t w = width, h = height;
  for (int k = 1; k <= kMaxLevels; ++k) {
    w = (w + 1) / 2;
    h = (h + 1) / 2;
    if (k > 1 && std::min(w, h) < kMinLevelSide) break;
    sizes.emplace_back(w, h);
  }
  return sizes;
}

uint64_t BloomPass::frame_bytes(uint32_t width, uint32_t height) {
  const std::vector<std::pair<uint32_t, uint32_t>> sizes = level_sizes(width, height);
  uint64_t bytes = 0;
  for (size_t k = 0; k < sizes.size(); ++k)  // Dk, and Uk but for the last level
    bytes += (k + 1 < sizes.size() ? 2 : 1) * pixel_count(sizes[k].first, sizes[k].second) *
             kPlanes * sizeof(float);
  return bytes;
}

uint64_t BloomPass::frame_device_bytes() const {
  uint64_t bytes = 0;
  for (const Level& level : levels_) bytes += buffer_bytes({&level.down, &level.up});
  return bytes;
}

void BloomPass::allocate(uint32_t width, uint32_t height) {
  if (width == width_ && height == height_) return;
  levels_.clear();
  for (const auto& [w, h] : level_sizes(width, height)) {
    Level level;
    level.width = w;
    level.height = h;
    level.down = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE,
                              size_t(w) * h * kPlanes * sizeof(float));
    levels_.push_back(level);
  }
  // Uk for k < N (UN is DN itself).
  for (size_t k = 0; k + 1 < levels_.size(); ++k)
    levels_[k].up = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE,
                                 size_t(levels_[k].width) * levels_[k].height * kPlanes *
                                     sizeof(float));
  width_ = width;
  height_ = height;
}

void BloomPass::run_chain(rp::cl::Profiler& profiler, const ::cl::Buffer& hdr_in, uint32_t width,
                          uint32_t height) {
  if (width == 0 || height == 0) return;
  check_buffer(hdr_in, width, height);
  allocate(width, height);

  // D1 from the input (Karis average unless switched off): 8 texels of two rows per work-item.
  const Level& first = levels_.front();
  downsample_first_.setArg(0, hdr_in);
  downsample_first_.setArg(1, cl_int(width));
  downsample_first_.setArg(2, cl_int(height));
  downsample_first_.setArg(3, first.down);
  downsample_first_.setArg(4, cl_int(first.width));
  downsample_first_.setArg(5, cl_int(first.height));
  downsample_first_.setArg(6, cl_int(karis_ ? 1 : 0));
  profiler.enqueue(kPass, downsample_first_,
                   grid(div_up(first.width, 8), div_up(first.height, 2)), kGroup2);

  // Dk from D(k-1): 8 texels of one channel row per work-item.
  for (size_t k = 1; k < levels_.size(); ++k) {
    const Level& src = levels_[k - 1];
    const Level& dst = levels_[k];
    downsample_.setArg(0, src.down);
    downsample_.setArg(1, cl_int(src.width));
    downsample_.setArg(2, cl_int(src.height));
    downsample_.setArg(3, dst.down);
    downsample_.setArg(4, cl_int(dst.width));
    downsample_.setArg(5, cl_int(dst.height));
    profiler.enqueue(kPass, downsample_, grid(div_up(dst.width, 8), dst.height, kPlanes),
                     kGroup3);
  }

  // Uk = Dk + up(U(k+1)) for k = N-1 .. 1: 16 texels of one channel row per work-item.
  for (int k = levels() - 1; k >= 1; --k) {
    Level& level = levels_[size_t(k - 1)];
    upsample_add_.setArg(0, up(k + 1));
    upsample_add_.setArg(1, cl_int(level_width(k + 1)));
    upsample_add_.setArg(2, cl_int(level_height(k + 1)));
    upsample_add_.setArg(3, level.down);
    upsample_add_.setArg(4, level.up);
    upsample_add_.setArg(5, cl_int(level.width));
    upsample_add_.setArg(6, cl_int(level.height));
    profiler.enqueue(kPass, upsample_add_, grid(div_up(level.width, 16), level.height, kPlanes),
                     kGroup3);
  }
}

BloomPass::Composite BloomPass::composite(float strength) const {
  check_strength(strength);
  if (levels_.empty()) throw rp::cl::Error("bloom pass: composite() before run_chain()");
  Composite c;
  c.level1 = &up(1);
  c.level1_width = level_width(1);
  c.level1_height = level_height(1);
  c.keep = 1.0f - strength;
  c.scale = strength / float(levels());
  return c;
}

void BloomPass::run(rp::cl::Profiler& profiler, const ::cl::Buffer& hdr_in, uint32_t width,
                    uint32_t height, float strength, ::cl::Buffer& hdr_out) {
  check_strength(strength);
  if (width == 0 || height == 0) return;
  check_buffer(hdr_in, width, height);
  check_buffer(hdr_out, width, height);
  if (strength == 0.0f) {  // exactly the input, no chain
    if (hdr_in() != hdr_out()) {
      ::cl::Event copied;
      profiler.queue().enqueueCopyBuffer(hdr_in, hdr_out, 0, 0,
                                         size_t(width) * height * 4 * sizeof(float), nullptr,
                                         &copied);
      profiler.record(kPass, copied);
    }
    return;
  }
  run_chain(profiler, hdr_in, width, height);

  // Mix at full resolution (16 pixels of two rows per work-item): bloom = up(U1) / N.
  const Composite c = composite(strength);
  mix_.setArg(0, hdr_in);
  mix_.setArg(1, *c.level1);
  mix_.setArg(2, cl_int(c.level1_width));
  mix_.setArg(3, cl_int(c.level1_height));
  mix_.setArg(4, hdr_out);
  mix_.setArg(5, cl_int(width));
  mix_.setArg(6, cl_int(height));
  mix_.setArg(7, c.keep);
  mix_.setArg(8, c.scale);
  profiler.enqueue(kPass, mix_, grid(div_up(width, 16), div_up(height, 2)), kGroup2);
}

}  // namespace rp::passes
