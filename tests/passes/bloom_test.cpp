// Bloom pass (kernels/bloom.cl, src/passes/bloom.*) against a double-precision C++ reference
// that implements the filters LITERALLY: 13 bilinear taps (clamp-to-edge) grouped into the inner
// box (0.5) and four outer boxes (0.125 each), Karis weights 1 / (1 + luma) per group on the
// first step, and the upsample as nine bilinear taps at +-1 destination texel with (1 2 1)^2 / 16
// (the kernel uses the equivalent collapsed 3x3 texel stencil). The chain's levels are planar rgb
// (alpha is not filtered; the mix keeps the input's alpha, which nothing downstream displays).
// Plus behaviour: symmetry, energy conservation, the Karis average bounding a firefly,
// strength 0, determinism, the composite description, timing.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "cl/error.h"
#include "passes/bloom.h"
#include "passes/pass_names.h"
#include "support/cl_fixture.h"

namespace {

namespace pass_name = rp::passes::pass_name;

// float4 per texel, row-major, top row first (the pass's layout), in double.
struct Image {
  int w = 0, h = 0;
  std::vector<double> px;  // 4 per texel
  Image() = default;
  Image(int width, int height) : w(width), h(height), px(size_t(width) * size_t(height) * 4, 0.0) {}
  double& at(int x, int y, int c) { return px[(size_t(y) * size_t(w) + size_t(x)) * 4 + size_t(c)]; }
  double at(int x, int y, int c) const {
    return px[(size_t(y) * size_t(w) + size_t(x)) * 4 + size_t(c)];
  }
};

using Colour = std::array<double, 4>;

// Bilinear sample at pixel position (px, py) (texel centres at +0.5), clamp-to-edge.
Colour bilinear(const Image& im, double px, double py) {
  const double x = std::clamp(px - 0.5, 0.0, double(im.w - 1));
  const double y = std::clamp(py - 0.5, 0.0, double(im.h - 1));
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const int x1 = std::min(x0 + 1, im.w - 1), y1 = std::min(y0 + 1, im.h - 1);
  const double fx = x - x0, fy = y - y0;
  Colour out{};
  for (int c = 0; c < 4; ++c)
    out[size_t(c)] = (1 - fy) * ((1 - fx) * im.at(x0, y0, c) + fx * im.at(x1, y0, c)) +
                     fy * ((1 - fx) * im.at(x0, y1, c) + fx * im.at(x1, y1, c));
  return out;
}

double luma(const Colour& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

// One 13-tap downsample by halves (ceil); destination texel (x, y) is centred on source
// position (2x+1, 2y+1).
Image ref_downsample(const Image& src, bool karis) {
  Image dst((src.w + 1) / 2, (src.h + 1) / 2);
  for (int y = 0; y < dst.h; ++y)
    for (int x = 0; x < dst.w; ++x) {
      auto tap = [&](int dx, int dy) { return bilinear(src, 2 * x + 1 + dx, 2 * y + 1 + dy); };
      // Groups: mean of four taps; inner at (+-1, +-1), outer boxes at {(ox, oy), (ox+2, oy),
      // (ox, oy+2), (ox+2, oy+2)} for ox, oy in {-2, 0}.
      std::vector<std::pair<double, Colour>> groups;  // (base weight, mean)
      auto add_group = [&](double weight, int ox, int oy, int step) {
        Colour a = tap(ox, oy), b = tap(ox + step, oy), c = tap(ox, oy + step),
               d = tap(ox + step, oy + step), mean{};
        for (size_t ch = 0; ch < 4; ++ch) mean[ch] = (a[ch] + b[ch] + c[ch] + d[ch]) / 4;
        groups.emplace_back(weight, mean);
      };
      add_group(0.5, -1, -1, 2);
      for (int oy : {-2, 0})
        for (int ox : {-2, 0}) add_group(0.125, ox, oy, 2);
      double wsum = 0;
      Colour sum{};
      for (auto& [weight, mean] : groups) {
        const double w = weight * (karis ? 1.0 / (1.0 + std::max(luma(mean), 0.0)) : 1.0);
        wsum += w;
        for (size_t ch = 0; ch < 4; ++ch) sum[ch] += w * mean[ch];
      }
      for (int ch = 0; ch < 4; ++ch) dst.at(x, y, ch) = sum[size_t(ch)] / wsum;
    }
  return dst;
}

// 3x3 tent of bilinear taps of `coarse` at +-1 texel of the w x h destination (0.5 coarse texel).
Image ref_upsample(const Image& coarse, int w, int h) {
  Image dst(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
          const double weight = (i == 0 ? 0.5 : 0.25) * (j == 0 ? 0.5 : 0.25);
          Colour s = bilinear(coarse, (x + 0.5 + i) / 2, (y + 0.5 + j) / 2);
          for (int c = 0; c < 4; ++c) dst.at(x, y, c) += weight * s[size_t(c)];
        }
  return dst;
}

Image add(Image a, const Image& b) {
  for (size_t i = 0; i < a.px.size(); ++i) a.px[i] += b.px[i];
  return a;
}

// Level sizes by the documented policy (up to 6 levels; after the first, smaller side >= 8).
std::vector<std::pair<int, int>> ref_level_sizes(int w, int h) {
  std::vector<std::pair<int, int>> sizes;
  for (int k = 1; k <= 6; ++k) {
    w = (w + 1) / 2;
    h = (h + 1) / 2;
    if (k > 1 && std::min(w, h) < 8) break;
    sizes.emplace_back(w, h);
  }
  return sizes;
}

// Whole pass: rgb = in * (1 - f) + up(U1) / N * f, alpha = in's.
Image ref_bloom(const Image& in, double f, bool karis) {
  const size_t n = ref_level_sizes(in.w, in.h).size();
  std::vector<Image> down{in};
  for (size_t k = 1; k <= n; ++k) down.push_back(ref_downsample(down.back(), karis && k == 1));
  Image u = down[n];
  for (size_t k = n - 1; k >= 1; --k) u = add(down[k], ref_upsample(u, down[k].w, down[k].h));
  Image bloom = ref_upsample(u, in.w, in.h);
  for (size_t i = 0; i < bloom.px.size(); ++i)
    bloom.px[i] = i % 4 == 3 ? in.px[i] : in.px[i] * (1 - f) + bloom.px[i] / double(n) * f;
  return bloom;
}

// ---- device helpers ----

::cl::Buffer upload(const Image& im) {
  auto& ctx = rp::test::context();
  std::vector<float> data(im.px.begin(), im.px.end());
  return ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                      data.size() * sizeof(float), data.data());
}

std::vector<float> read_floats(const ::cl::Buffer& buffer, size_t count) {
  std::vector<float> out(count);
  rp::test::context().queue.enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(float),
                                              out.data());
  return out;
}

Image read_image(const ::cl::Buffer& buffer, int w, int h) {
  Image im(w, h);
  std::vector<float> f = read_floats(buffer, im.px.size());
  std::copy(f.begin(), f.end(), im.px.begin());
  return im;
}

// A planar rgb level of the chain (3 planes of w x h floats) as an Image (alpha 0).
Image read_level(const ::cl::Buffer& buffer, int w, int h) {
  Image im(w, h);
  const size_t plane = size_t(w) * size_t(h);
  std::vector<float> f = read_floats(buffer, 3 * plane);
  for (size_t i = 0; i < plane; ++i)
    for (size_t c = 0; c < 3; ++c) im.px[4 * i + c] = f[c * plane + i];
  return im;
}

// Runs the pass on `in` and returns the output image.
Image run_pass(rp::passes::BloomPass& pass, const Image& in, float strength) {
  auto& ctx = rp::test::context();
  ::cl::Buffer src = upload(in);
  ::cl::Buffer dst(ctx.context, CL_MEM_READ_WRITE, in.px.size() * sizeof(float));
  rp::cl::Profiler profiler(ctx.queue);
  pass.run(profiler, src, uint32_t(in.w), uint32_t(in.h), strength, dst);
  profiler.collect();
  return read_image(dst, in.w, in.h);
}

// Positive random HDR image: mostly [0, 2), some texels up to 50 (alpha too).
Image random_image(int w, int h, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> base(0.0f, 2.0f), bright(2.0f, 50.0f), pick(0.0f, 1.0f);
  Image im(w, h);
  for (double& v : im.px) v = pick(rng) < 0.05f ? bright(rng) : base(rng);
  return im;
}

// Largest |got - want| / max(|want|, floor) over all elements (rgb only with `rgb_only`: the
// chain's levels carry no alpha).
double max_rel_error(const Image& got, const Image& want, double floor = 1e-3,
                     bool rgb_only = false) {
  EXPECT_EQ(got.px.size(), want.px.size());
  double worst = 0;
  for (size_t i = 0; i < got.px.size(); ++i)
    if (!rgb_only || i % 4 != 3)
      worst = std::max(worst,
                       std::abs(got.px[i] - want.px[i]) / std::max(std::abs(want.px[i]), floor));
  return worst;
}

double rgb_sum(const Image& im) {
  double s = 0;
  for (size_t i = 0; i < im.px.size(); ++i)
    if (i % 4 != 3) s += im.px[i];
  return s;
}

// Float accumulation of up to 36 positive terms: ~1e-7 typical, 1e-6 bound (stated).
constexpr double kStepTolerance = 1e-6;
constexpr double kChainTolerance = 1e-5;

class BloomSteps : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST(Bloom, LevelSizesFollowThePolicy) {
  rp::passes::BloomPass pass(rp::test::context(), rp::test::programs());
  const std::vector<std::tuple<int, int, std::vector<std::pair<int, int>>>> cases{
      {37, 29, {{19, 15}, {10, 8}}},
      {64, 64, {{32, 32}, {16, 16}, {8, 8}}},
      {160, 160, {{80, 80}, {40, 40}, {20, 20}, {10, 10}}},
      {3, 2, {{2, 1}}},
  };
  for (const auto& [w, h, sizes] : cases) {
    run_pass(pass, Image(w, h), 0.5f);
    ASSERT_EQ(pass.levels(), int(sizes.size())) << w << "x" << h;
    for (int k = 1; k <= pass.levels(); ++k) {
      EXPECT_EQ(int(pass.level_width(k)), sizes[size_t(k - 1)].first) << w << "x" << h << " " << k;
      EXPECT_EQ(int(pass.level_height(k)), sizes[size_t(k - 1)].second) << w << "x" << h << " " << k;
    }
  }
}

// Each step checked on its own: the reference step is fed the device's previous level.
TEST_P(BloomSteps, EachStepMatchesReference) {
  const auto [w, h] = GetParam();
  for (bool karis : {false, true}) {
    SCOPED_TRACE(karis ? "karis" : "plain");
    rp::passes::BloomPass pass(rp::test::context(), rp::test::programs());
    pass.set_karis_average(karis);
    const Image in = random_image(w, h, 7u + uint32_t(w));
    run_pass(pass, in, 0.1f);
    const int n = pass.levels();
    ASSERT_GE(n, 2);
    std::vector<Image> down{in}, up(size_t(n) + 1);
    for (int k = 1; k <= n; ++k) {
      down.push_back(read_level(pass.down(k), int(pass.level_width(k)), int(pass.level_height(k))));
      const Image want = ref_downsample(down[size_t(k - 1)], karis && k == 1);
      EXPECT_LT(max_rel_error(down[size_t(k)], want, 1e-3, true), kStepTolerance)
          << "downsample level " << k;
    }
    up[size_t(n)] = down[size_t(n)];
    for (int k = n - 1; k >= 1; --k) {
      up[size_t(k)] = read_level(pass.up(k), down[size_t(k)].w, down[size_t(k)].h);
      const Image want = add(down[size_t(k)], ref_upsample(up[size_t(k + 1)], down[size_t(k)].w,
                                                           down[size_t(k)].h));
      EXPECT_LT(max_rel_error(up[size_t(k)], want, 1e-3, true), kStepTolerance)
          << "upsample level " << k;
    }
  }
}

TEST_P(BloomSteps, WholeChainMatchesReference) {
  const auto [w, h] = GetParam();
  const Image in = random_image(w, h, 99u + uint32_t(h));
  for (bool karis : {false, true})
    for (float f : {0.1f, 1.0f}) {
      rp::passes::BloomPass pass(rp::test::context(), rp::test::programs());
      pass.set_karis_average(karis);
      EXPECT_LT(max_rel_error(run_pass(pass, in, f), ref_bloom(in, f, karis)), kChainTolerance)
          << "karis " << karis << " f " << f;
    }
}

// 37x29: odd sizes, partial work-items everywhere; 64x64: powers of two; 150x90: wide enough
// for the kernels' unclamped vector paths on levels 0 .. 2 (their clamped edge paths run too).
INSTANTIATE_TEST_SUITE_P(Sizes, BloomSteps,
                         ::testing::Values(std::make_pair(37, 29), std::make_pair(64, 64),
                                           std::make_pair(150, 90)),
                         [](const auto& param_info) {
                           return std::to_string(param_info.param.first) + "x" +
                                  std::to_string(param_info.param.second);
                         });

// A 2x2 bright block at the centre of a power-of-two image: the image is mirror symmetric about
// the centre, which is a texel corner on every level, so the chain (with Karis) is too; the
// bloom falls off monotonically from the centre along the centre row.
TEST(BloomBehaviour, CentredBlockBloomsSymmetrically) {
  Image in(64, 64);
  for (int y : {31, 32})
    for (int x : {31, 32})
      for (int c = 0; c < 3; ++c) in.at(x, y, c) = 100.0;
  rp::passes::BloomPass pass(rp::test::context(), rp::test::programs());
  const Image out = run_pass(pass, in, 1.0f);
  double peak = 0;
  for (double v : out.px) peak = std::max(peak, v);
  ASSERT_GT(peak, 0.0);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) {
        const double v = out.at(x, y, c);
        ASSERT_NEAR(out.at(63 - x, y, c), v, 1e-5 * peak) << x << "," << y;
        ASSERT_NEAR(out.at(x, 63 - y, c), v, 1e-5 * peak) << x << "," << y;
        ASSERT_NEAR(out.at(y, x, c), v, 1e-5 * peak) << x << "," << y;
      }
  for (int x = 32; x < 63; ++x) EXPECT_GE(out.at(x, 32, 0), out.at(x + 1, 32, 0)) << x;
  EXPECT_GT(out.at(50, 32, 0), 0.0);  // it spreads 18 px and more
}

// A single pixel on the diagonal of a square image: the chain is symmetric under transposition.
TEST(BloomBehaviour, SinglePixelBloomIsTransposeSymmetric) {
  Image in(64, 64);
  for (int c = 0; c < 3; ++c) in.at(29, 29, c) = 500.0;
  rp::passes::BloomPass pass(rp::test::context(), rp::test::programs());
  const Image out = run_pass(pass, in, 1.0f);
  double peak = 0;
  for (double v : out.px) peak = std::max(peak, v);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) ASSERT_NEAR(out.at(y, x, 1), out.at(x, y, 1), 1e-5 * peak);
}

// Without the Karis average the chain is linear and each step conserves energy away from the
// borders (weights of every source texel sum to the area ratio; bloom = up(U1) / N), so the
// bloom of a single pixel far from the borders (160x160, 4 levels, reach < 70 px) has the
// pixel's energy up to float rounding: stated tolerance 1e-4 relative.
TEST(BloomBehaviour, EnergyIsConservedAwayFromBorders) {
  Image in(160, 160);
  in.at(77, 83, 0) = 1000.0;
  in.at(77, 83, 1) = 250.0;
  in.at(81, 79, 2) = 40.0;
  rp::passes::BloomPass pass(rp::test::context(), rp::test::programs());
  pass.set_karis_average(false);
  const Image out = run_pass(pass, in, 1.0f);
  for (int c = 0; c < 3; ++c) {
    double in_sum = 0, out_sum = 0;
    for (size_t i = size_t(c); i < in.px.size(); i += 4) {
      in_sum += in.px[i];
      out_sum += out.px[i];
    }
    EXPECT_NEAR(out_sum, in_sum, 1e-4 * in_sum) << "channel " << c;
  }
  // The borders stay dark: the energy is not leaking into clamp-to-edge duplicates.
  EXPECT_LT(out.at(0, 0, 0) + out.at(159, 80, 0), 1e-6 * 1000.0);
}

// With the Karis average a flat field stays flat (all group weights are equal), odd size and
// borders included: the normalisation by N is right.
TEST(BloomBehaviour, FlatFieldStaysFlatWithKaris) {
  Image in(37, 29);
  for (size_t i = 0; i < in.px.size(); ++i) in.px[i] = (i % 4 == 0) ? 3.0 : (i % 4 == 1 ? 0.5 : 1.25);
  rp::passes::BloomPass pass(rp::test::context(), rp::test::programs());
  const Image out = run_pass(pass, in, 1.0f);
  EXPECT_LT(max_rel_error(out, in), 1e-6);
  EXPECT_NEAR(rgb_sum(out), rgb_sum(in), 1e-6 * rgb_sum(in));
}

// The Karis average is a normalised weighted average of the five groups, so it does not bound a
// single very bright pixel (a particle) outright: in the one level-1 texel centred on it, all
// five group means are v/16 and the weighted mean is v/16 too; in the neighbouring texels the
// groups containing it get weights ~16/v and it adds O(1). The bloom keeps 1/4 of its energy
// (the level-1 texel's area 4 x v/16) plus O(1) instead of all of it, relative to dim
// surroundings. Its energy does not depend on which of the 2x2 sub-positions it sits on (the
// filter is mirror symmetric), so a particle moving by one pixel does not make it flicker.
TEST(BloomBehaviour, KarisAverageDampsAFireflyWithoutFlicker) {
  auto bloom_energy = [](double value, bool karis, int x, int y) {
    Image in(64, 64);
    for (int c = 0; c < 3; ++c) in.at(x, y, c) = value;
    rp::passes::BloomPass pass(rp::test::context(), rp::test::programs());
    pass.set_karis_average(karis);
    return rgb_sum(run_pass(pass, in, 1.0f)) / (3 * value);
  };
  const double v = 1e4;
  const double karis = bloom_energy(v, true, 30, 33);
  EXPECT_GE(karis, 0.25 - 1e-5);
  EXPECT_LE(karis, 0.26);  // measured 0.2535 (0.2503 at 1e5, 0.283 at 1e3: -> 1/4 + O(1/v))
  EXPECT_NEAR(bloom_energy(v, false, 30, 33), 1.0, 1e-4);  // the plain chain keeps it all
  for (int dy : {0, 1})
    for (int dx : {0, 1})
      EXPECT_NEAR(bloom_energy(v, true, 30 + dx, 33 + dy), karis, 1e-5 * karis) << dx << dy;
}

TEST(BloomBehaviour, StrengthZeroReturnsTheInputExactly) {
  auto& ctx = rp::test::context();
  Image in = random_image(37, 29, 5u);
  in.px[17] = -3.0;
  in.px[18] = 1e30;
  ::cl::Buffer src = upload(in);
  ::cl::Buffer dst(ctx.context, CL_MEM_READ_WRITE, in.px.size() * sizeof(float));
  rp::passes::BloomPass pass(ctx, rp::test::programs());
  rp::cl::Profiler profiler(ctx.queue);
  pass.run(profiler, src, 37, 29, 0.0f, dst);
  EXPECT_EQ(profiler.collect().count(pass_name::kBloom), 1u);
  const std::vector<float> a = read_floats(src, in.px.size()), b = read_floats(dst, in.px.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
  pass.run(profiler, src, 37, 29, 0.0f, src);  // in place: nothing to do
  const std::vector<float> c = read_floats(src, in.px.size());
  EXPECT_EQ(std::memcmp(a.data(), c.data(), a.size() * sizeof(float)), 0);
}

// Same input, same result, bit for bit: repeated runs, a second pass object, and in place.
TEST(BloomBehaviour, DeterministicAndInPlace) {
  auto& ctx = rp::test::context();
  const Image in = random_image(64, 64, 11u);
  rp::passes::BloomPass pass(ctx, rp::test::programs()), other(ctx, rp::test::programs());
  const Image first = run_pass(pass, in, 0.1f);
  const Image again = run_pass(pass, in, 0.1f);
  const Image fresh = run_pass(other, in, 0.1f);
  EXPECT_EQ(first.px, again.px);
  EXPECT_EQ(first.px, fresh.px);
  ::cl::Buffer buffer = upload(in);
  rp::cl::Profiler profiler(ctx.queue);
  pass.run(profiler, buffer, 64, 64, 0.1f, buffer);
  EXPECT_EQ(read_image(buffer, 64, 64).px, first.px);
}

// run_chain + composite() describe the mix run() does: keep = 1 - f, scale = f / N, level 1 = U1.
TEST(BloomBehaviour, CompositeDescribesTheMix) {
  auto& ctx = rp::test::context();
  rp::passes::BloomPass pass(ctx, rp::test::programs());
  EXPECT_THROW(pass.composite(0.1f), rp::cl::Error);  // no chain yet
  const Image in = random_image(64, 48, 3u);
  ::cl::Buffer src = upload(in);
  rp::cl::Profiler profiler(ctx.queue);
  pass.run_chain(profiler, src, 64, 48);
  profiler.collect();
  ASSERT_EQ(pass.levels(), 2);  // 32x24, 16x12 (8x6 would be below the minimum side)
  const rp::passes::BloomPass::Composite c = pass.composite(0.25f);
  EXPECT_EQ(c.level1, &pass.up(1));
  EXPECT_EQ(c.level1_width, 32u);
  EXPECT_EQ(c.level1_height, 24u);
  EXPECT_EQ(c.keep, 0.75f);
  EXPECT_EQ(c.scale, 0.25f / 2.0f);
  for (float f : {-0.1f, 1.5f, std::numeric_limits<float>::quiet_NaN()})
    EXPECT_THROW(pass.composite(f), rp::cl::Error) << f;
  // The chain alone leaves the same levels as a whole run.
  const Image u1 = read_level(pass.up(1), 32, 24);
  run_pass(pass, in, 0.25f);
  EXPECT_EQ(read_level(pass.up(1), 32, 24).px, u1.px);
}

TEST(BloomBehaviour, RejectsBadArguments) {
  auto& ctx = rp::test::context();
  ::cl::Buffer small(ctx.context, CL_MEM_READ_WRITE, 16 * 16 * 16);
  ::cl::Buffer big(ctx.context, CL_MEM_READ_WRITE, 32 * 32 * 16);
  rp::passes::BloomPass pass(ctx, rp::test::programs());
  rp::cl::Profiler profiler(ctx.queue);
  for (float f : {-0.1f, 1.5f, std::numeric_limits<float>::quiet_NaN()})
    EXPECT_THROW(pass.run(profiler, big, 32, 32, f, big), rp::cl::Error) << f;
  EXPECT_THROW(pass.run(profiler, small, 32, 32, 0.1f, big), rp::cl::Error);
  EXPECT_THROW(pass.run(profiler, big, 32, 32, 0.1f, small), rp::cl::Error);
}

// 720x720 (six levels, 360 .. 12): per-frame device time of the pass, and the energy of the
// linear chain for a pixel in the middle (reach < 300 px: no border effect).
TEST(BloomBehaviour, Timing720) {
  auto& ctx = rp::test::context();
  Image in(720, 720);
  for (int c = 0; c < 3; ++c) in.at(360, 355, c) = 1000.0;
  ::cl::Buffer src = upload(in);
  ::cl::Buffer dst(ctx.context, CL_MEM_READ_WRITE, in.px.size() * sizeof(float));
  rp::passes::BloomPass pass(ctx, rp::test::programs());
  rp::cl::Profiler profiler(ctx.queue);
  pass.run(profiler, src, 720, 720, 0.1f, dst);  // warm-up (allocation, first launches)
  profiler.collect();
  ASSERT_EQ(pass.levels(), 6);
  EXPECT_EQ(pass.level_width(6), 12u);
  double best = std::numeric_limits<double>::infinity(), total = 0;
  const int runs = 5;
  for (int r = 0; r < runs; ++r) {
    pass.run(profiler, src, 720, 720, 0.1f, dst);
    const double ms = profiler.collect().at(pass_name::kBloom);
    best = std::min(best, ms);
    total += ms;
  }
  std::cout << "[bloom] 720x720 on " << ctx.info.name << ": mean " << total / runs
            << " ms, best " << best << " ms (device time, all launches)\n";
  pass.set_karis_average(false);
  pass.run(profiler, src, 720, 720, 1.0f, dst);
  profiler.collect();
  const Image out = read_image(dst, 720, 720);
  EXPECT_NEAR(rgb_sum(out), 3000.0, 3000.0 * 1e-4);
}

}  // namespace
