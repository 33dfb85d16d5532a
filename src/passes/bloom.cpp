#include "passes/bloom.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "cl/error.h"
#include "cl/kernel_args.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"

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

gpu::BloomStep bloom_step(uint32_t src_width, uint32_t src_height, uint32_t dst_width,
                          uint32_t dst_height) {
  gpu::BloomStep step{};
  step.src_width = int32_t(src_width);
  step.src_height = int32_t(src_height);
  step.dst_width = int32_t(dst_width);
  step.dst_height = int32_t(dst_height);
  return step;
}

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
  gpu::BloomStep step = bloom_step(width, height, first.width, first.height);
  step.karis = karis_ ? 1 : 0;
  rp::cl::bind_args(downsample_first_, hdr_in, first.down, step);
  profiler.enqueue(kPass, downsample_first_,
                   grid(div_up(first.width, 8), div_up(first.height, 2)), kGroup2);

  // Dk from D(k-1): 8 texels of one channel row per work-item.
  for (size_t k = 1; k < levels_.size(); ++k) {
    const Level& src = levels_[k - 1];
    const Level& dst = levels_[k];
    rp::cl::bind_args(downsample_, src.down, dst.down,
                      bloom_step(src.width, src.height, dst.width, dst.height));
    profiler.enqueue(kPass, downsample_, grid(div_up(dst.width, 8), dst.height, kPlanes),
                     kGroup3);
  }

  // Uk = Dk + up(U(k+1)) for k = N-1 .. 1: 16 texels of one channel row per work-item.
  for (int k = levels() - 1; k >= 1; --k) {
    Level& level = levels_[size_t(k - 1)];
    rp::cl::bind_args(upsample_add_, up(k + 1), level.down, level.up,
                      bloom_step(level_width(k + 1), level_height(k + 1), level.width,
                                 level.height));
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
  gpu::BloomStep step = bloom_step(c.level1_width, c.level1_height, width, height);
  step.keep = c.keep;
  step.scale = c.scale;
  rp::cl::bind_args(mix_, hdr_in, *c.level1, hdr_out, step);
  profiler.enqueue(kPass, mix_, grid(div_up(width, 16), div_up(height, 2)), kGroup2);
}

}  // namespace rp::passes
