// Physically based bloom (SPEC 6.6; kernels/bloom.cl has the filters and their derivation).
// A chain of 13-tap downsamples by halves (ceil for odd sizes; a Karis average on the first step
// so single bright pixels do not flicker), then 3x3 tent upsamples that accumulate each level's
// own content on the way up (UN = DN, Uk = Dk + up(U(k+1))); the full-resolution bloom is
// up(U1) / N, whose total energy equals the input's away from the borders, and the output is
// hdr_out.rgb = hdr_in.rgb * (1 - f) + bloom * f, hdr_out.a = hdr_in.a. Pass name "bloom".
//
// The chain's levels are planar rgb (kernels/bloom.cl). The full-resolution mix can run on its
// own (run) or be left to the next full-resolution kernel: run_chain builds the chain only and
// composite() describes what that kernel must add (MotionBlurPass::run takes it), which saves a
// float4 write and read of the whole image.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "passes/frame_memory.h"

namespace rp::passes {

class BloomPass {
 public:
  // At most this many downsampled levels; a level after the first is made only while its
  // smaller side stays >= kMinLevelSide texels (720x720: 360 .. 12, six levels).
  static constexpr int kMaxLevels = 6;
  static constexpr uint32_t kMinLevelSide = 8;
  static constexpr float kDefaultStrength = 0.1f;

  BloomPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs);

  // hdr_in, hdr_out: float4 per pixel (rgb linear HDR; alpha is copied), width * height,
  // row-major; hdr_out may be hdr_in. strength f in [0, 1]: f = 0 copies the input exactly (and
  // builds no chain). Enqueues only. The mip chain is reallocated only when the size changes.
  // Throws rp::cl::Error for a strength outside [0, 1] or a buffer smaller than the image.
  void run(rp::cl::Profiler& profiler, const ::cl::Buffer& hdr_in, uint32_t width,
           uint32_t height, float strength, ::cl::Buffer& hdr_out);

  // The Karis average on the first downsample (on by default). Off makes the chain linear (for
  // energy tests and comparisons).
  void set_karis_average(bool enabled) { karis_ = enabled; }

  // The chain alone (D1 .. DN, U(N-1) .. U1) from hdr_in (float4 per pixel, width x height),
  // without the mix; composite(f) then says how to add the bloom. Enqueues only. Throws
  // rp::cl::Error for a buffer smaller than the image.
  void run_chain(rp::cl::Profiler& profiler, const ::cl::Buffer& hdr_in, uint32_t width,
                 uint32_t height);

  // What the full-resolution mix needs after run_chain: out.rgb = in.rgb * keep + up(U1) * scale,
  // out.a = in.a, up = the tent upsample of kernels/common/bloom_tent.h. The buffer is owned by
  // the pass (valid until the next run at another size).
  struct Composite {
    const ::cl::Buffer* level1 = nullptr;  // U1: planar rgb, level1_width x level1_height
    uint32_t level1_width = 0, level1_height = 0;
    float keep = 1.0f;   // 1 - f
    float scale = 0.0f;  // f / N
  };
  // Throws rp::cl::Error before any run_chain or for a strength outside [0, 1].
  Composite composite(float strength) const;

  // Inspection of the last run's chain (tests, debug views). Levels are numbered 1 .. levels();
  // down(k) = Dk, up(k) = Uk (up(levels()) is down(levels())). Planar rgb: 3 planes of
  // level_width(k) x level_height(k) floats (r, g, b).
  int levels() const { return static_cast<int>(levels_.size()); }
  uint32_t level_width(int k) const { return levels_.at(size_t(k - 1)).width; }
  uint32_t level_height(int k) const { return levels_.at(size_t(k - 1)).height; }
  const ::cl::Buffer& down(int k) const { return levels_.at(size_t(k - 1)).down; }
  const ::cl::Buffer& up(int k) const;

  // The chain's level sizes for a width x height image (D1 .. DN), and its device memory
  // (passes/frame_memory.h): Dk and Uk (k < N) as planar rgb floats; what the pass holds now.
  static std::vector<std::pair<uint32_t, uint32_t>> level_sizes(uint32_t width, uint32_t height);
  static uint64_t frame_bytes(uint32_t width, uint32_t height);
  uint64_t frame_device_bytes() const;

 private:
  struct Level {
    uint32_t width = 0, height = 0;
    ::cl::Buffer down, up;  // up is empty for the last (coarsest) level
  };
  void allocate(uint32_t width, uint32_t height);

  const rp::cl::Context* context_;
  ::cl::Kernel downsample_, downsample_first_, upsample_add_, mix_;
  bool karis_ = true;
  uint32_t width_ = 0, height_ = 0;  // size the chain was allocated for
  std::vector<Level> levels_;
};

}  // namespace rp::passes
