// TAA resolve (kernels/taa.cl, kernels/common/taa.h) against the C++ reference in
// taa_reference.cpp: YCoCg round trip, the history clip, reprojection by velocity, full
// multi-frame resolves, resets and determinism. Tolerances are on tone-mapped values in [0, 1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "cl/error.h"
#include "cl/program_cache.h"
#include "support/cl_fixture.h"
#include "taa_reference.h"

namespace {

using rp::test::taa::Frame;
using rp::test::taa::Harness;

// HDR image with values in [0, max_value) per channel, w = 1.
std::vector<glm::vec4> random_hdr(uint32_t w, uint32_t h, float max_value, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, max_value);
  std::vector<glm::vec4> img(size_t(w) * h);
  for (glm::vec4& p : img) p = {u(rng), u(rng), u(rng), 1.0f};
  return img;
}

// Whole-resolve tolerance on tone-mapped values against the double-precision reference:
// measured worst 3.8e-7 on PoCL (float maths; the kernel sums the 5-tap statistics as offsets
// from the centre pixel, so the variance does not cancel).
constexpr float kResolveTolerance = 2e-6f;

float max_tone_mapped_difference(const std::vector<glm::vec4>& hdr_out,
                                 const std::vector<glm::vec3>& mapped_ref) {
  float worst = 0.0f;
  for (size_t i = 0; i < hdr_out.size(); ++i)
    worst = std::max(worst, glm::length(rp::test::taa::tone(glm::vec3(hdr_out[i])) - mapped_ref[i]));
  return worst;
}

// Probe kernel over common/taa.h: YCoCg both ways and the clip, one work-item per colour.
class TaaHelpers : public ::testing::Test {
 protected:
  void SetUp() override {
    auto& ctx = rp::test::context();
    std::string source = rp::cl::kernel_source("common/taa.h") + R"CLC(
__kernel void taa_probe(__global const float4* colour, __global const float4* centre,
                        __global const float4* extent, __global float4* ycocg,
                        __global float4* round_trip, __global float4* clipped, uint n) {
  uint i = get_global_id(0);
  if (i >= n) return;
  float3 y = rp_rgb_to_ycocg(colour[i].xyz);
  ycocg[i] = (float4)(y, 0.0f);
  round_trip[i] = (float4)(rp_ycocg_to_rgb(y), 0.0f);
  clipped[i] = (float4)(rp_taa_clip(colour[i].xyz, centre[i].xyz, extent[i].xyz), 0.0f);
}
)CLC";
    program_ = ::cl::Program(ctx.context, source);
    try {
      program_.build(std::vector<::cl::Device>{ctx.info.device});
    } catch (const ::cl::Error&) {
      FAIL() << program_.getBuildInfo<CL_PROGRAM_BUILD_LOG>(ctx.info.device);
    }
  }

  struct Result {
    std::vector<glm::vec4> ycocg, round_trip, clipped;
  };
  Result probe(const std::vector<glm::vec4>& colour, const std::vector<glm::vec4>& centre,
               const std::vector<glm::vec4>& extent) {
    auto& ctx = rp::test::context();
    const size_t n = colour.size(), bytes = n * 16;
    auto input = [&](const std::vector<glm::vec4>& v) {
      return ::cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes,
                          const_cast<glm::vec4*>(v.data()));
    };
    ::cl::Buffer c = input(colour), m = input(centre), e = input(extent);
    ::cl::Buffer y(ctx.context, CL_MEM_WRITE_ONLY, bytes), r(ctx.context, CL_MEM_WRITE_ONLY, bytes),
        k(ctx.context, CL_MEM_WRITE_ONLY, bytes);
    ::cl::Kernel kernel(program_, "taa_probe");
    kernel.setArg(0, c);
    kernel.setArg(1, m);
    kernel.setArg(2, e);
    kernel.setArg(3, y);
    kernel.setArg(4, r);
    kernel.setArg(5, k);
    kernel.setArg(6, cl_uint(n));
    ctx.queue.enqueueNDRangeKernel(kernel, ::cl::NullRange, ::cl::NDRange(n));
    Result out{std::vector<glm::vec4>(n), std::vector<glm::vec4>(n), std::vector<glm::vec4>(n)};
    ctx.queue.enqueueReadBuffer(y, CL_TRUE, 0, bytes, out.ycocg.data());
    ctx.queue.enqueueReadBuffer(r, CL_TRUE, 0, bytes, out.round_trip.data());
    ctx.queue.enqueueReadBuffer(k, CL_TRUE, 0, bytes, out.clipped.data());
    return out;
  }

  ::cl::Program program_;
};

TEST_F(TaaHelpers, YCoCgMatchesReferenceAndRoundTrips) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec4> colour(1024), zero(1024, glm::vec4(0.0f));
  for (glm::vec4& c : colour) c = {u(rng), u(rng), u(rng), 0.0f};
  colour[0] = {1, 0, 0, 0};
  colour[1] = {0, 1, 0, 0};
  colour[2] = {0, 0, 1, 0};
  Result r = probe(colour, zero, zero);
  // Hand values: pure red is (1/4, 1/2, -1/4), green (1/2, 0, 1/2), blue (1/4, -1/2, -1/4).
  EXPECT_EQ(glm::vec3(r.ycocg[0]), glm::vec3(0.25f, 0.5f, -0.25f));
  EXPECT_EQ(glm::vec3(r.ycocg[1]), glm::vec3(0.5f, 0.0f, 0.5f));
  EXPECT_EQ(glm::vec3(r.ycocg[2]), glm::vec3(0.25f, -0.5f, -0.25f));
  for (size_t i = 0; i < colour.size(); ++i) {
    glm::vec3 want = rp::test::taa::to_ycocg(glm::vec3(colour[i]));
    for (int c = 0; c < 3; ++c) {
      ASSERT_NEAR(r.ycocg[i][c], want[c], 1e-6f) << "colour " << i;
      ASSERT_NEAR(r.round_trip[i][c], colour[i][c], 1e-6f) << "colour " << i;
    }
  }
}

TEST_F(TaaHelpers, ClipKeepsInsideAndMovesOutsideToTheSurfaceTowardTheCentre) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(0.01f, 0.5f);
  const size_t n = 2048;
  std::vector<glm::vec4> q(n), centre(n), extent(n);
  for (size_t i = 0; i < n; ++i) {
    centre[i] = {u(rng), u(rng), u(rng), 0.0f};
    extent[i] = {pos(rng), pos(rng), pos(rng), 0.0f};
    if (i % 2 == 0) {  // inside: centre + extent * [-1, 1]
      q[i] = centre[i] + extent[i] * glm::vec4(u(rng), u(rng), u(rng), 0.0f);
    } else {           // anywhere in a larger cube: mostly outside
      q[i] = centre[i] + glm::vec4(2.0f * u(rng), 2.0f * u(rng), 2.0f * u(rng), 0.0f);
    }
  }
  q[1] = centre[1] + glm::vec4(extent[1].x, 0, 0, 0);  // exactly on a face: unchanged
  extent[3] = {0.0f, 0.2f, 0.2f, 0.0f};                 // flat channel: clips onto the centre in x
  q[3] = centre[3] + glm::vec4(0.1f, 0.05f, 0.0f, 0.0f);
  Result r = probe(q, centre, extent);

  int outside = 0;
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 qi(q[i]), ci(centre[i]), ei(extent[i]), got(r.clipped[i]);
    const glm::vec3 d = qi - ci;
    const bool inside = glm::all(glm::lessThanEqual(glm::abs(d), ei));
    if (inside) {
      ASSERT_EQ(got, qi) << "inside point " << i << " must be unchanged";
      continue;
    }
    ++outside;
    const glm::vec3 want = rp::test::taa::clip_to_box(qi, ci, ei);
    ASSERT_LT(glm::length(got - want), 1e-6f) << "point " << i;
    // On the surface: largest normalised offset is 1 (skip the degenerate flat box).
    if (i != 3) {
      const glm::vec3 a = glm::abs(got - ci) / ei;
      ASSERT_NEAR(std::max(a.x, std::max(a.y, a.z)), 1.0f, 1e-5f) << "point " << i;
    }
    // On the segment from q to the centre: got - c = s (q - c) with 0 <= s < 1.
    const float s = glm::dot(got - ci, d) / glm::dot(d, d);
    ASSERT_GE(s, 0.0f);
    ASSERT_LT(s, 1.0f);
    ASSERT_LT(glm::length((got - ci) - s * d), 1e-5f) << "point " << i << " left the line";
  }
  EXPECT_GT(outside, int(n) / 4);
  EXPECT_NEAR(r.clipped[3].x, centre[3].x, 1e-5f);  // flat channel: onto the centre
}

// Frame 1 fills the history with A; frame 2 (current B, uniform velocity v) must blend the
// history sampled at pixel centre - v. gamma is huge so the clip never acts (B is noisy, so
// its box is wide): what remains is reprojection + blend.
void check_reprojection(glm::vec2 v) {
  const uint32_t w = 16, h = 12;
  rp::passes::TaaSettings settings;
  settings.gamma = 1.0e6f;
  Harness gpu(settings);
  Frame a = rp::test::taa::still_frame(w, h, random_hdr(w, h, 3.0f, 1));
  Frame b = rp::test::taa::still_frame(w, h, random_hdr(w, h, 3.0f, 2));
  b.velocity.assign(size_t(w) * h, v);
  gpu.run(a);
  std::vector<glm::vec4> out = gpu.run(b);

  std::vector<glm::vec3> hist(size_t(w) * h);
  for (size_t i = 0; i < hist.size(); ++i) hist[i] = rp::test::taa::tone(glm::vec3(a.hdr[i]));
  int reprojected = 0, fresh = 0;
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const glm::vec2 prev = glm::vec2(float(x) + 0.5f, float(y) + 0.5f) - v;
      const glm::vec3 cur = rp::test::taa::tone(glm::vec3(b.hdr[i]));
      glm::vec3 want = cur;
      if (prev.x >= 0 && prev.y >= 0 && prev.x <= float(w) && prev.y <= float(h)) {
        want = rp::test::taa::bilinear(hist, w, h, prev) * 0.9f + cur * 0.1f;
        ++reprojected;
      } else {
        ++fresh;
      }
      const glm::vec3 got = rp::test::taa::tone(glm::vec3(out[i]));
      ASSERT_LT(glm::length(got - want), 2e-6f) << "pixel " << x << "," << y << " v " << v.x
                                                 << "," << v.y;
      ASSERT_EQ(out[i].w, 1.0f);
    }
  }
  EXPECT_GT(reprojected, 0);
  EXPECT_GT(fresh, 0) << "the velocity should move some history off screen";
}

TEST(TaaPass, ReprojectsHistoryByIntegerVelocity) { check_reprojection({2.0f, -1.0f}); }
TEST(TaaPass, ReprojectsHistoryBilinearlyAtFractionalVelocity) {
  check_reprojection({1.25f, 0.7f});
  check_reprojection({-3.5f, -0.25f});
}

// Random images, velocities and depths over several frames, gamma 1 (the clip acts often),
// both current-sample modes: the whole resolve against the reference. The kernel resolves blocks
// of 8 pixels of a row (the last block of a row moved left to end at the image border; images
// narrower than 8 use a clamping build), so the sizes cover whole blocks, a partial last block
// and narrow images.
void check_against_reference(bool unjitter, uint32_t w = 24, uint32_t h = 16) {
  rp::passes::TaaSettings settings;
  settings.unjitter_current = unjitter;
  Harness gpu(settings);
  rp::test::taa::Reference ref(settings);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> vel(-2.5f, 2.5f), depth(0.5f, 3.0f);
  for (uint32_t k = 0; k < 5; ++k) {
    Frame f = rp::test::taa::still_frame(w, h, random_hdr(w, h, 4.0f, 100 + k));
    for (glm::vec2& v : f.velocity) v = {vel(rng), vel(rng)};
    for (float& d : f.depth) d = depth(rng);
    f.jitter = rp::render::taa_jitter_px(k, 16);
    std::vector<glm::vec4> out = gpu.run(f);
    std::vector<glm::vec3> want = ref.resolve(f);
    EXPECT_LT(max_tone_mapped_difference(out, want), kResolveTolerance)
        << "frame " << k << ", " << w << "x" << h;
  }
}

TEST(TaaPass, MatchesReferenceOverFrames) { check_against_reference(false); }
TEST(TaaPass, MatchesReferenceOverFramesWithUnjitteredCurrent) { check_against_reference(true); }
TEST(TaaPass, MatchesReferenceAtWidthsThatAreNotWholeBlocks) {
  for (uint32_t w : {1u, 5u, 7u, 8u, 9u, 21u, 30u}) {
    check_against_reference(false, w, 6);
    check_against_reference(true, w, 5);
  }
}

// Uniform velocities make every block's history taps 8 consecutive pixels (the kernel's vector
// load path); a velocity that changes inside blocks sends some blocks down the per-lane path.
// Both must give the reference's answer.
TEST(TaaPass, MatchesReferenceWithCoherentAndMixedVelocities) {
  const uint32_t w = 40, h = 12;
  rp::passes::TaaSettings settings;
  Harness gpu(settings);
  rp::test::taa::Reference ref(settings);
  for (uint32_t k = 0; k < 4; ++k) {
    Frame f = rp::test::taa::still_frame(w, h, random_hdr(w, h, 3.0f, 200 + k));
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) {
        // Left half: one sub-pixel velocity; right half: a slow ramp (crosses pixel steps).
        f.velocity[size_t(y) * w + x] = x < w / 2
                                            ? glm::vec2(1.37f, -0.61f) * float(k)
                                            : glm::vec2(0.07f * float(x) - 1.0f, 0.05f * float(y));
      }
    std::vector<glm::vec4> out = gpu.run(f);
    std::vector<glm::vec3> want = ref.resolve(f);
    EXPECT_LT(max_tone_mapped_difference(out, want), kResolveTolerance) << "frame " << k;
  }
}

TEST(TaaPass, ClipRejectsStaleHistory) {
  // History all white, current all black with a flat neighbourhood: the box collapses onto
  // black, so the output is (nearly) black, not 0.9 white.
  const uint32_t w = 8, h = 8;
  Harness gpu;
  gpu.run(rp::test::taa::still_frame(w, h, std::vector<glm::vec4>(w * h, glm::vec4(10, 10, 10, 1))));
  std::vector<glm::vec4> out =
      gpu.run(rp::test::taa::still_frame(w, h, std::vector<glm::vec4>(w * h, glm::vec4(0, 0, 0, 1))));
  for (const glm::vec4& p : out) ASSERT_LT(std::max(p.x, std::max(p.y, p.z)), 1e-5f);
}

std::vector<glm::vec4> uniform_image(uint32_t w, uint32_t h, float value) {
  return std::vector<glm::vec4>(size_t(w) * h, glm::vec4(value, value * 0.5f, value * 0.25f, 1.0f));
}

TEST(TaaPass, FirstFrameAfterResetOrResizeIsTheCurrentFrame) {
  Harness gpu;
  const auto a = rp::test::taa::still_frame(16, 16, random_hdr(16, 16, 2.0f, 3));
  const auto b = rp::test::taa::still_frame(16, 16, random_hdr(16, 16, 2.0f, 4));
  auto expect_current = [](const std::vector<glm::vec4>& out, const Frame& f, const char* what) {
    for (size_t i = 0; i < out.size(); ++i)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(out[i][c], f.hdr[i][c], 1e-5f * (1.0f + f.hdr[i][c])) << what << " " << i;
  };
  expect_current(gpu.run(a), a, "first frame");
  // Without a reset the history (A) shows through.
  std::vector<glm::vec4> blended = gpu.run(b);
  float diff = 0.0f;
  for (size_t i = 0; i < blended.size(); ++i) diff += std::abs(blended[i].x - b.hdr[i].x);
  EXPECT_GT(diff / float(blended.size()), 0.05f);

  gpu.run(a);
  gpu.pass().reset_history();
  expect_current(gpu.run(b), b, "after reset_history");

  gpu.run(a);
  const auto wide = rp::test::taa::still_frame(24, 16, random_hdr(24, 16, 2.0f, 5));
  expect_current(gpu.run(wide), wide, "after resize");
  const auto back = rp::test::taa::still_frame(16, 16, uniform_image(16, 16, 0.5f));
  expect_current(gpu.run(back), back, "after resizing back");
}

TEST(TaaPass, Deterministic) {
  auto sequence = [] {
    Harness gpu;
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> vel(-1.5f, 1.5f);
    std::vector<glm::vec4> all;
    for (uint32_t k = 0; k < 4; ++k) {
      Frame f = rp::test::taa::still_frame(20, 12, random_hdr(20, 12, 5.0f, 50 + k));
      for (glm::vec2& v : f.velocity) v = {vel(rng), vel(rng)};
      std::vector<glm::vec4> out = gpu.run(f);
      all.insert(all.end(), out.begin(), out.end());
    }
    return all;
  };
  const std::vector<glm::vec4> first = sequence(), second = sequence();
  ASSERT_EQ(first.size(), second.size());
  EXPECT_EQ(0, std::memcmp(first.data(), second.data(), first.size() * sizeof(glm::vec4)));
}

TEST(TaaPass, RejectsBadSettings) {
  rp::passes::TaaSettings bad;
  bad.history_weight = 1.0f;
  EXPECT_THROW(rp::passes::TaaPass pass(rp::test::context(), rp::test::programs(), bad),
               rp::cl::Error);
  bad = {};
  bad.gamma = 0.0f;
  EXPECT_THROW(rp::passes::TaaPass pass(rp::test::context(), rp::test::programs(), bad),
               rp::cl::Error);
}

}  // namespace

namespace {

// Not a check: prints the pass time at 720x720 (run with --gtest_also_run_disabled_tests).
TEST(TaaPass, DISABLED_Time720) {
  const uint32_t n = 720;
  Harness gpu;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> vel(-3.0f, 3.0f);
  Frame f = rp::test::taa::still_frame(n, n, random_hdr(n, n, 4.0f, 8));
  for (glm::vec2& v : f.velocity) v = {vel(rng), vel(rng)};
  double best = 1e30, sum = 0.0;
  const int runs = 10;
  for (int k = 0; k < runs + 2; ++k) {
    f.jitter = rp::render::taa_jitter_px(uint32_t(k), 16);
    gpu.run(f);
    if (k < 2) continue;  // first run builds nothing but fills the history; warm up
    best = std::min(best, gpu.last_ms());
    sum += gpu.last_ms();
  }
  std::printf("taa 720x720: best %.2f ms, mean %.2f ms over %d runs\n", best, sum / runs, runs);
}

}  // namespace
