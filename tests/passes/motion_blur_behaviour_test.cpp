// Motion blur behaviour on a synthetic GBuffer: a disc (depth 3, bright red) moving at (8, 0)
// px per frame in front of a still, textured background (depth 5): the disc smears along x on
// both sides, not along y; the still background away from it is untouched. Plus: zero motion
// returns the input bit for bit, the output is deterministic, and the 720x720 timing (disabled
// by default: run with --gtest_also_run_disabled_tests).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include "cl/error.h"
#include "passes/motion_blur.h"
#include "passes/pass_names.h"
#include "render/frame_buffers.h"
#include "support/cl_fixture.h"

namespace {

using rp::passes::MotionBlurPass;

struct Px {
  float r = 0, g = 0, b = 0, a = 0;
};

struct Scene {
  uint32_t w = 0, h = 0;
  std::vector<float> velocity;      // float2 per pixel
  std::vector<float> normal_depth;  // float4 per pixel (w = linear depth)
  std::vector<Px> hdr;
};

constexpr float kDiscRed = 4.0f;

// Background: a green/blue texture (red channel 0.05) so any red that appears came from the
// disc. Discs: centre, radius in px, velocity in px per frame, depth 3.
struct Disc {
  float cx, cy, radius, vx, vy;
};

bool inside(const Disc& d, uint32_t x, uint32_t y) {
  const float dx = float(x) + 0.5f - d.cx, dy = float(y) + 0.5f - d.cy;
  return dx * dx + dy * dy < d.radius * d.radius;
}

Scene make_scene(uint32_t w, uint32_t h, const std::vector<Disc>& discs) {
  Scene s;
  s.w = w;
  s.h = h;
  const size_t n = size_t(w) * h;
  s.velocity.assign(2 * n, 0.0f);
  s.normal_depth.assign(4 * n, 0.0f);
  s.hdr.resize(n);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const bool check = ((x / 3) + (y / 3)) % 2 == 0;
      s.hdr[i] = {0.05f, check ? 0.8f : 0.2f, 0.1f + 0.01f * float((x * 7 + y * 13) % 50), 1.0f};
      s.normal_depth[4 * i + 2] = 1.0f;
      s.normal_depth[4 * i + 3] = 5.0f;
      for (const Disc& d : discs)
        if (inside(d, x, y)) {
          s.hdr[i] = {kDiscRed, 0.1f, 0.1f, 1.0f};
          s.velocity[2 * i] = d.vx;
          s.velocity[2 * i + 1] = d.vy;
          s.normal_depth[4 * i + 3] = 3.0f;
        }
    }
  return s;
}

// Holds the device buffers of a scene so a pass can run on it repeatedly.
struct DeviceScene {
  rp::render::GBuffer g;
  ::cl::Buffer in, out;
  uint32_t w, h;

  explicit DeviceScene(const Scene& s) : w(s.w), h(s.h) {
    auto& ctx = rp::test::context();
    const size_t n = size_t(w) * h;
    g.resize(ctx.context, w, h);
    ctx.queue.enqueueWriteBuffer(g.velocity, CL_TRUE, 0, n * 8, s.velocity.data());
    ctx.queue.enqueueWriteBuffer(g.normal_depth, CL_TRUE, 0, n * 16, s.normal_depth.data());
    in = ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16);
    out = ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16);
    ctx.queue.enqueueWriteBuffer(in, CL_TRUE, 0, n * 16, s.hdr.data());
  }
  // Runs the pass and returns hdr_out and the pass time in ms.
  std::vector<Px> run(MotionBlurPass& pass, float shutter, double* ms = nullptr) {
    auto& ctx = rp::test::context();
    rp::cl::Profiler profiler(ctx.queue);
    pass.run(profiler, in, g, w, h, shutter, out);
    const auto times = profiler.collect();
    if (ms) *ms = times.at(rp::passes::pass_name::kMotionBlur);
    std::vector<Px> result(size_t(w) * h);
    ctx.queue.enqueueReadBuffer(out, CL_TRUE, 0, result.size() * 16, result.data());
    return result;
  }
};

bool same_bits(const Px& a, const Px& b) { return std::memcmp(&a, &b, sizeof(Px)) == 0; }

bool nearly_same(const Px& a, const Px& b) {
  auto near = [](float x, float y) { return std::fabs(x - y) <= 1e-6f * std::max(1.0f, std::fabs(y)); };
  return near(a.r, b.r) && near(a.g, b.g) && near(a.b, b.b) && near(a.a, b.a);
}

// 160x120 (8x6 tiles), disc radius 9 at (70.5, 50.5): inside tile (3, 2) only.
const Disc kMovingDisc{70.5f, 50.5f, 9.0f, 8.0f, 0.0f};

TEST(MotionBlurBehaviour, DiscBlursAlongItsMotionOnly) {
  const Scene s = make_scene(160, 120, {kMovingDisc});
  DeviceScene dev(s);
  MotionBlurPass pass(rp::test::context(), rp::test::programs());
  // Shutter 1: the streak is 8 px long, 4 px to each side of the disc.
  const std::vector<Px> out = dev.run(pass, 1.0f);
  auto at = [&](const std::vector<Px>& img, int x, int y) { return img[size_t(y) * s.w + size_t(x)]; };
  const int cx = 70, cy = 50, r = 9;
  // Pixels cx +- r and cy +- r are the first outside the disc (1 px from its last pixels).
  for (int d = 0; d <= 2; ++d) {
    // d + 1 px from the disc's edge along +x and -x: picks up disc red (both directions).
    EXPECT_GT(at(out, cx + r + d, cy).r, 0.05f + 0.02f * kDiscRed) << "right, " << d + 1 << " px out";
    EXPECT_GT(at(out, cx - r - d, cy).r, 0.05f + 0.02f * kDiscRed) << "left, " << d + 1 << " px out";
    // Same distance above and below: no red, background as it was.
    EXPECT_TRUE(nearly_same(at(out, cx, cy - r - d), at(s.hdr, cx, cy - r - d))) << "above " << d;
    EXPECT_TRUE(nearly_same(at(out, cx, cy + r + d), at(s.hdr, cx, cy + r + d))) << "below " << d;
  }
  // Inside the disc near its leading and trailing edges the background shows through a little.
  EXPECT_LT(at(out, cx + r - 1, cy).r, kDiscRed * 0.99f);
  EXPECT_LT(at(out, cx - r + 1, cy).r, kDiscRed * 0.99f);

  // Background: bit-identical outside the disc's 3x3 tile neighbourhood (tiles x 2..4, y 1..3:
  // skipped tiles), within 1e-6 where the blur cannot reach (more than 4 + 1 px from the disc
  // along x, or on rows the disc does not cover).
  int exact = 0;
  for (int y = 0; y < int(s.h); ++y)
    for (int x = 0; x < int(s.w); ++x) {
      const int tx = x / 20, ty = y / 20;
      const bool near_tiles = tx >= 2 && tx <= 4 && ty >= 1 && ty <= 3;
      if (!near_tiles) {
        ASSERT_TRUE(same_bits(at(out, x, y), at(s.hdr, x, y))) << "far pixel " << x << "," << y;
        ++exact;
        continue;
      }
      bool reachable = false;
      for (int dx = -5; dx <= 5; ++dx)
        reachable |= x + dx >= 0 && inside(kMovingDisc, uint32_t(x + dx), uint32_t(y));
      if (!reachable) {
        EXPECT_TRUE(nearly_same(at(out, x, y), at(s.hdr, x, y))) << "still pixel " << x << "," << y;
      }
    }
  EXPECT_GT(exact, 15000);
}

TEST(MotionBlurBehaviour, ZeroVelocityOrShutterReturnsInputExactly) {
  const Scene still = make_scene(90, 70, {{45.0f, 35.0f, 10.0f, 0.0f, 0.0f}});
  DeviceScene dev(still);
  MotionBlurPass pass(rp::test::context(), rp::test::programs());
  const std::vector<Px> out = dev.run(pass, 1.0f);
  ASSERT_EQ(std::memcmp(out.data(), still.hdr.data(), out.size() * sizeof(Px)), 0);

  const Scene moving = make_scene(90, 70, {{45.0f, 35.0f, 10.0f, 12.0f, -5.0f}});
  DeviceScene dev_moving(moving);
  const std::vector<Px> closed = dev_moving.run(pass, 0.0f);  // shutter closed: no blur
  ASSERT_EQ(std::memcmp(closed.data(), moving.hdr.data(), closed.size() * sizeof(Px)), 0);
  const std::vector<Px> open = dev_moving.run(pass, 1.0f);
  EXPECT_NE(std::memcmp(open.data(), moving.hdr.data(), open.size() * sizeof(Px)), 0);
}

TEST(MotionBlurBehaviour, Deterministic) {
  const Scene s = make_scene(130, 90, {{40.0f, 40.0f, 12.0f, 15.0f, 9.0f},
                                       {80.0f, 50.0f, 8.0f, -30.0f, 4.0f}});
  DeviceScene dev(s);
  MotionBlurPass pass(rp::test::context(), rp::test::programs());
  const std::vector<Px> a = dev.run(pass, 0.75f);
  MotionBlurPass other(rp::test::context(), rp::test::programs());
  const std::vector<Px> b = dev.run(other, 0.75f);
  const std::vector<Px> c = dev.run(pass, 0.75f);
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Px)), 0);
  EXPECT_EQ(std::memcmp(a.data(), c.data(), a.size() * sizeof(Px)), 0);
}

TEST(MotionBlurBehaviour, RejectsBadArguments) {
  const Scene s = make_scene(40, 40, {});
  DeviceScene dev(s);
  MotionBlurPass pass(rp::test::context(), rp::test::programs());
  rp::cl::Profiler profiler(rp::test::context().queue);
  EXPECT_THROW(pass.run(profiler, dev.in, dev.g, 41, 40, 0.5f, dev.out), rp::cl::Error);
  EXPECT_THROW(pass.run(profiler, dev.in, dev.g, 40, 40, 1.5f, dev.out), rp::cl::Error);
  EXPECT_THROW(pass.run(profiler, dev.in, dev.g, 40, 40, NAN, dev.out), rp::cl::Error);
}

// 720x720: a still frame (every tile skipped) and one with ~20 % of the tiles in motion
// (6 discs of radius 38 px moving at ~15 px per frame, shutter 0.5). Median of 5 runs.
TEST(MotionBlurBehaviour, DISABLED_Timing720) {
  std::vector<Disc> discs;
  for (int k = 0; k < 6; ++k)
    discs.push_back({120.0f + 240.0f * float(k % 3), 180.0f + 360.0f * float(k / 3), 38.0f,
                     15.0f, float(k) - 2.5f});
  MotionBlurPass pass(rp::test::context(), rp::test::programs());
  for (int moving = 0; moving < 2; ++moving) {
    std::vector<Disc> d = discs;
    if (!moving) {
      for (Disc& x : d) x.vx = x.vy = 0.0f;
    }
    const Scene s = make_scene(720, 720, d);
    DeviceScene dev(s);
    dev.run(pass, 0.5f);  // warm-up (kernel build, allocation)
    std::vector<double> ms(5);
    for (double& m : ms) dev.run(pass, 0.5f, &m);
    std::sort(ms.begin(), ms.end());
    std::printf("motion_blur 720x720 %s: %.2f ms (median of 5; min %.2f)\n",
                moving ? "20 % tiles moving" : "still", ms[2], ms[0]);
    // Tiles whose neighbourhood moves, out of 36x36.
    if (moving) {
      std::vector<float> nmax(36 * 36 * 2);
      rp::test::context().queue.enqueueReadBuffer(pass.neighbour_max(), CL_TRUE, 0,
                                                  nmax.size() * 4, nmax.data());
      int active = 0;
      for (size_t t = 0; t < 36 * 36; ++t)
        active += nmax[2 * t] * nmax[2 * t] + nmax[2 * t + 1] * nmax[2 * t + 1] > 0.25f;
      std::printf("  active tiles: %d of 1296 (%.0f %%)\n", active, 100.0 * active / 1296.0);
    }
  }
}

}  // namespace
