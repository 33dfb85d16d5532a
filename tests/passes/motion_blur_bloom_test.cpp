// The bloom's full-resolution mix fused into the motion blur pass (MotionBlurPass::run with a
// BloomPass::Composite): with the shutter closed it is BloomPass::run's output bit for bit; with
// motion, pixels in still tiles still are, and every pixel is the plain motion blur's output
// with the bloom composited onto it: rgb * keep + tent(U1) * scale (the tent as a
// double-precision C++ reference of kernels/common/bloom_composite.h's weights, 1e-5 relative),
// alpha exactly the blurred alpha.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "cl/error.h"
#include "passes/bloom.h"
#include "passes/motion_blur.h"
#include "render/frame_buffers.h"
#include "support/cl_fixture.h"

namespace {

using rp::passes::BloomPass;
using rp::passes::MotionBlurPass;

struct Frame {
  uint32_t w = 0, h = 0;
  std::vector<float> hdr;           // float4 per pixel
  std::vector<float> velocity;      // float2 per pixel
  std::vector<float> normal_depth;  // float4 per pixel, w = depth
};

// Deterministic HDR colours (a few bright texels, alpha 1), still background at depth 5, and
// rectangles moving at different speeds in front of it.
Frame make_frame(uint32_t w, uint32_t h) {
  Frame f;
  f.w = w;
  f.h = h;
  const size_t n = size_t(w) * h;
  f.hdr.resize(4 * n);
  f.velocity.assign(2 * n, 0.0f);
  f.normal_depth.assign(4 * n, 0.0f);
  uint32_t state = 12345u;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
  };
  for (size_t i = 0; i < n; ++i) {
    for (size_t c = 0; c < 3; ++c)
      f.hdr[4 * i + c] = next() % 50u == 0u ? 30.0f : float(next() % 1000u) / 500.0f;
    f.hdr[4 * i + 3] = 1.0f;
    f.normal_depth[4 * i + 2] = 1.0f;
    f.normal_depth[4 * i + 3] = 5.0f;
  }
  struct Rect {
    uint32_t x0, y0, x1, y1;
    float vx, vy, depth;
  };
  for (const Rect& r : {Rect{20, 15, 45, 35, 12.0f, 2.0f, 2.0f}, Rect{90, 50, 110, 70, -3.0f, 2.5f, 3.0f},
                        Rect{130, 5, 150, 20, 30.0f, -30.0f, 1.5f}})
    for (uint32_t y = r.y0; y < std::min(r.y1, h); ++y)
      for (uint32_t x = r.x0; x < std::min(r.x1, w); ++x) {
        const size_t i = size_t(y) * w + x;
        f.velocity[2 * i] = r.vx;
        f.velocity[2 * i + 1] = r.vy;
        f.normal_depth[4 * i + 3] = r.depth;
      }
  return f;
}

struct Device {
  rp::render::GBuffer g;
  ::cl::Buffer in, out;
  explicit Device(const Frame& f) {
    auto& ctx = rp::test::context();
    const size_t n = size_t(f.w) * f.h;
    g.resize(ctx.context, f.w, f.h);
    ctx.queue.enqueueWriteBuffer(g.velocity, CL_TRUE, 0, n * 8, f.velocity.data());
    ctx.queue.enqueueWriteBuffer(g.normal_depth, CL_TRUE, 0, n * 16, f.normal_depth.data());
    in = ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16);
    out = ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16);
    ctx.queue.enqueueWriteBuffer(in, CL_TRUE, 0, n * 16, f.hdr.data());
  }
};

std::vector<float> read(const ::cl::Buffer& b, size_t floats) {
  std::vector<float> v(floats);
  rp::test::context().queue.enqueueReadBuffer(b, CL_TRUE, 0, floats * 4, v.data());
  return v;
}

constexpr float kStrength = 0.1f;
constexpr float kShutter = 0.5f;

// BloomPass::run's output.
std::vector<float> bloom_alone(const Frame& f, Device& d) {
  BloomPass bloom(rp::test::context(), rp::test::programs());
  rp::cl::Profiler profiler(rp::test::context().queue);
  bloom.run(profiler, d.in, f.w, f.h, kStrength, d.out);
  profiler.collect();
  return read(d.out, f.hdr.size());
}

TEST(MotionBlurBloom, ShutterClosedIsTheBloomMixBitForBit) {
  const Frame f = make_frame(157, 93);  // odd sizes, partial tiles
  Device d(f);
  const std::vector<float> want = bloom_alone(f, d);
  BloomPass bloom(rp::test::context(), rp::test::programs());
  MotionBlurPass blur(rp::test::context(), rp::test::programs());
  rp::cl::Profiler profiler(rp::test::context().queue);
  bloom.run_chain(profiler, d.in, f.w, f.h);
  blur.run(profiler, d.in, d.g, f.w, f.h, 0.0f, bloom.composite(kStrength), d.out);
  profiler.collect();
  const std::vector<float> got = read(d.out, f.hdr.size());
  EXPECT_EQ(std::memcmp(got.data(), want.data(), got.size() * 4), 0);
}

// up(U1) at pixel (x, y), channel c, from the planar level 1 (double precision).
double tent(const std::vector<float>& level1, int cw, int ch, int x, int y, int c) {
  auto weights = [](int i, int n, int idx[3], double w[3]) {
    const int m = i >> 1;
    idx[0] = std::clamp(m - 1, 0, n - 1);
    idx[1] = std::min(m, n - 1);
    idx[2] = std::min(m + 1, n - 1);
    w[0] = (i & 1) ? 1.0 / 16 : 5.0 / 16;
    w[1] = 10.0 / 16;
    w[2] = (i & 1) ? 5.0 / 16 : 1.0 / 16;
  };
  int ix[3], iy[3];
  double wx[3], wy[3];
  weights(x, cw, ix, wx);
  weights(y, ch, iy, wy);
  double sum = 0.0;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      sum += wy[j] * wx[i] *
             level1[size_t(c) * size_t(cw) * size_t(ch) + size_t(iy[j]) * size_t(cw) + size_t(ix[i])];
  return sum;
}

// Runs the plain and the fused pass on a w x h frame and checks every pixel (see the top).
void check_fused(uint32_t w, uint32_t h, int min_moving, int min_still) {
  const Frame f = make_frame(w, h);
  Device d(f);
  const std::vector<float> mixed = bloom_alone(f, d);
  auto& ctx = rp::test::context();
  MotionBlurPass blur(ctx, rp::test::programs());
  rp::cl::Profiler profiler(ctx.queue);
  blur.run(profiler, d.in, d.g, f.w, f.h, kShutter, d.out);  // plain motion blur
  profiler.collect();
  const std::vector<float> blurred = read(d.out, f.hdr.size());

  BloomPass bloom(ctx, rp::test::programs());
  bloom.run_chain(profiler, d.in, f.w, f.h);
  const BloomPass::Composite c = bloom.composite(kStrength);
  blur.run(profiler, d.in, d.g, f.w, f.h, kShutter, c, d.out);
  profiler.collect();
  const std::vector<float> got = read(d.out, f.hdr.size());
  const std::vector<float> level1 =
      read(*c.level1, size_t(c.level1_width) * c.level1_height * 3);
  std::vector<float> nmax(size_t(blur.tiles_x()) * blur.tiles_y() * 2);
  ctx.queue.enqueueReadBuffer(blur.neighbour_max(), CL_TRUE, 0, nmax.size() * 4, nmax.data());

  int moving = 0, still = 0;
  for (uint32_t y = 0; y < f.h; ++y)
    for (uint32_t x = 0; x < f.w; ++x) {
      const size_t i = size_t(y) * f.w + x;
      const size_t t = size_t(y / MotionBlurPass::kTileSize) * blur.tiles_x() +
                       x / MotionBlurPass::kTileSize;
      const bool active = nmax[2 * t] * nmax[2 * t] + nmax[2 * t + 1] * nmax[2 * t + 1] > 0.25f;
      if (!active) {  // a still tile: exactly the bloom's own mix
        ASSERT_EQ(std::memcmp(&got[4 * i], &mixed[4 * i], 16), 0) << x << "," << y;
        ++still;
        continue;
      }
      ++moving;
      for (int ch = 0; ch < 3; ++ch) {
        const double want = double(blurred[4 * i + size_t(ch)]) * c.keep +
                            tent(level1, int(c.level1_width), int(c.level1_height), int(x),
                                 int(y), ch) * c.scale;
        ASSERT_NEAR(got[4 * i + size_t(ch)], want, 1e-5 * std::max(1.0, std::fabs(want)))
            << x << "," << y << " channel " << ch;
      }
      ASSERT_EQ(got[4 * i + 3], blurred[4 * i + 3]) << x << "," << y;
    }
  EXPECT_GE(moving, min_moving);
  EXPECT_GE(still, min_still);
}

TEST(MotionBlurBloom, FusedIsTheBlurWithTheBloomComposited) { check_fused(157, 93, 2000, 2000); }

// The same at a size small enough for oclgrind (tests/oclgrind: the fused kernels' paths): a
// moving rectangle in tiles 1 and 2 of 5 x 2, the last (partial) tile column still.
TEST(MotionBlurBloom, SmallFrame) { check_fused(84, 24, 1000, 96); }

TEST(MotionBlurBloom, RejectsACompositeOfAnotherSize) {
  const Frame f = make_frame(64, 48);
  Device d(f);
  auto& ctx = rp::test::context();
  BloomPass bloom(ctx, rp::test::programs());
  MotionBlurPass blur(ctx, rp::test::programs());
  rp::cl::Profiler profiler(ctx.queue);
  bloom.run_chain(profiler, d.in, 32, 48);  // the chain of a narrower image
  EXPECT_THROW(blur.run(profiler, d.in, d.g, 64, 48, kShutter, bloom.composite(kStrength), d.out),
               rp::cl::Error);
  EXPECT_THROW(blur.run(profiler, d.in, d.g, 64, 48, kShutter, BloomPass::Composite{}, d.out),
               rp::cl::Error);
  profiler.collect();
}

}  // namespace
