// Tone map pass and the colour helpers of kernels/common/colour.h against double-precision C++
// references: T(x) = x / (1 + x) per channel, the exact piecewise sRGB curve, round to nearest.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "cl/program_cache.h"
#include "passes/pass_names.h"
#include "passes/tone_map.h"
#include "render/gpu_scene.h"
#include "support/cl_fixture.h"

namespace {

double srgb_encode_ref(double y) {
  y = std::clamp(y, 0.0, 1.0);
  return y <= 0.0031308 ? 12.92 * y : 1.055 * std::pow(y, 1.0 / 2.4) - 0.055;
}
double srgb_decode_ref(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
double tone_map_ref(double x) { return std::max(x, 0.0) / (1.0 + std::max(x, 0.0)); }
uint32_t quantize_ref(double v) { return static_cast<uint32_t>(std::floor(v * 255.0 + 0.5)); }

// Runs the tone map pass over `hdr` (one row of pixels) and returns the packed RGBA8 words.
std::vector<uint32_t> run_tone_map(const std::vector<float>& hdr_rgba, bool dither = false,
                                   uint32_t frame = 0) {
  auto& ctx = rp::test::context();
  const uint32_t n = static_cast<uint32_t>(hdr_rgba.size() / 4);
  rp::render::GpuScene scene(ctx.context, ctx.queue, rp::scene::SceneAssets{});
  scene.constants.width = n;
  scene.constants.height = 1;
  scene.constants.frame_index = frame;
  ::cl::Buffer hdr(ctx.context, CL_MEM_READ_WRITE, hdr_rgba.size() * sizeof(float));
  ::cl::Buffer out(ctx.context, CL_MEM_READ_WRITE, n * sizeof(uint32_t));
  ctx.queue.enqueueWriteBuffer(hdr, CL_TRUE, 0, hdr_rgba.size() * sizeof(float), hdr_rgba.data());
  rp::cl::Profiler profiler(ctx.queue);
  rp::passes::ToneMapPass pass(ctx, rp::test::programs(), dither);
  pass.run(profiler, scene, hdr, uint32_t(n), out);
  auto times = profiler.collect();
  EXPECT_EQ(times.count(rp::passes::pass_name::kToneMap), 1u);
  std::vector<uint32_t> result(n);
  ctx.queue.enqueueReadBuffer(out, CL_TRUE, 0, n * sizeof(uint32_t), result.data());
  return result;
}

// HDR ramp: 0, then geometric steps from 1e-4 to 1000 (covers the linear sRGB toe, mid-tones and
// highlights), the three channels at different scales.
std::vector<float> hdr_ramp(size_t count) {
  std::vector<float> rgba;
  for (size_t i = 0; i < count; ++i) {
    double x = i == 0 ? 0.0 : 1e-4 * std::pow(1e7, double(i - 1) / double(count - 2));
    rgba.insert(rgba.end(), {float(x), float(x * 0.37), float(x * 2.9), 0.5f});
  }
  return rgba;
}

TEST(ToneMap, MatchesReferenceWithinOneStep) {
  std::vector<float> hdr = hdr_ramp(4096);
  std::vector<uint32_t> out = run_tone_map(hdr);
  int exact = 0, total = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      uint32_t got = (out[i] >> (8 * c)) & 0xFFu;
      uint32_t want = quantize_ref(srgb_encode_ref(tone_map_ref(hdr[i * 4 + c])));
      ASSERT_LE(std::abs(int(got) - int(want)), 1) << "pixel " << i << " channel " << c
                                                   << " hdr " << hdr[i * 4 + c];
      exact += got == want;
      ++total;
    }
    ASSERT_EQ(out[i] >> 24, 255u) << "alpha of pixel " << i;
  }
  // The polynomial sRGB curve is accurate to 0.002 of a step: off-by-one only at rounding ties.
  EXPECT_GE(exact, total - total / 200) << exact << " of " << total << " exact";
}

TEST(ToneMap, DitheringRemovesBandingOnASlowGradient) {
  // 4096 pixels whose encoded value rises by 1.5 codes in total: rounding gives 2-3 flat bands,
  // dithering gives codes whose local average follows the gradient.
  const size_t n = 4096;
  std::vector<double> exact(n);
  std::vector<float> hdr;
  for (size_t i = 0; i < n; ++i) {
    double code = 100.2 + 1.5 * double(i) / double(n - 1);
    double srgb = code / 255.0;
    double lin = srgb_decode_ref(srgb);
    double x = lin / (1.0 - lin);  // inverse of T
    exact[i] = code;
    hdr.insert(hdr.end(), {float(x), float(x), float(x), 1.0f});
  }
  for (uint32_t frame : {0u, 1u}) {
    std::vector<uint32_t> rounded = run_tone_map(hdr, false, frame);
    std::vector<uint32_t> dithered = run_tone_map(hdr, true, frame);
    double worst_rounded = 0.0, worst_dithered = 0.0;
    const size_t block = 256;
    for (size_t b = 0; b < n; b += block) {
      double sum_r = 0.0, sum_d = 0.0, sum_e = 0.0;
      for (size_t i = b; i < b + block; ++i) {
        sum_r += double(rounded[i] & 0xFF);
        sum_d += double(dithered[i] & 0xFF);
        sum_e += exact[i];
        // Each dithered code is one of the two codes around the exact value.
        EXPECT_LE(std::fabs(double(dithered[i] & 0xFF) - exact[i]), 1.0) << i;
      }
      worst_rounded = std::max(worst_rounded, std::fabs(sum_r - sum_e) / block);
      worst_dithered = std::max(worst_dithered, std::fabs(sum_d - sum_e) / block);
    }
    EXPECT_GT(worst_rounded, 0.2) << "the test gradient should band when rounded";
    EXPECT_LT(worst_dithered, 0.1) << "block means of dithered codes follow the gradient";
  }
  // The noise differs from frame to frame, and is the same for the same frame.
  EXPECT_NE(run_tone_map(hdr, true, 0), run_tone_map(hdr, true, 1));
  EXPECT_EQ(run_tone_map(hdr, true, 3), run_tone_map(hdr, true, 3));
}

TEST(ToneMap, MonotonicPerChannel) {
  std::vector<float> hdr = hdr_ramp(4096);
  std::vector<uint32_t> out = run_tone_map(hdr);
  for (size_t i = 1; i < out.size(); ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_GE((out[i] >> (8 * c)) & 0xFFu, (out[i - 1] >> (8 * c)) & 0xFFu) << "pixel " << i;
  EXPECT_EQ(out.front(), 0xFF000000u);  // black stays black
}

TEST(ToneMap, NonFiniteAndNegativeInputs) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<uint32_t> out = run_tone_map({-1.0f, nan, inf, 0.0f, 1e30f, -inf, 1.0f, 0.0f});
  EXPECT_EQ(out[0], 0xFFFF0000u);  // r: -1 -> 0, g: NaN -> 0, b: inf -> 255
  // r: 1e30 -> 255, g: -inf -> 0, b: 1 -> T = 0.5 -> sRGB 0.7354 -> 188.
  EXPECT_EQ(out[1], 0xFF000000u | (quantize_ref(srgb_encode_ref(0.5)) << 16) | 255u);
}

// The kernel resolves 16 pixels per work-item; a pixel count that is not a multiple of 16 ends
// in a partial block, which must write exactly its own pixels (the words after them keep their
// sentinel) with the same codes as in a whole block.
TEST(ToneMap, PartialLastBlockWritesOnlyItsPixels) {
  auto& ctx = rp::test::context();
  std::vector<float> hdr = hdr_ramp(64);
  const std::vector<uint32_t> whole = run_tone_map(hdr);  // 64 pixels: whole blocks only
  for (uint32_t n : {1u, 15u, 17u, 37u}) {
    rp::render::GpuScene scene(ctx.context, ctx.queue, rp::scene::SceneAssets{});
    scene.constants.width = n;
    scene.constants.height = 1;
    ::cl::Buffer in(ctx.context, CL_MEM_READ_WRITE, hdr.size() * sizeof(float));
    ctx.queue.enqueueWriteBuffer(in, CL_TRUE, 0, hdr.size() * sizeof(float), hdr.data());
    std::vector<uint32_t> out(64, 0x12345678u);
    ::cl::Buffer buf(ctx.context, CL_MEM_READ_WRITE, out.size() * sizeof(uint32_t));
    ctx.queue.enqueueWriteBuffer(buf, CL_TRUE, 0, out.size() * sizeof(uint32_t), out.data());
    rp::cl::Profiler profiler(ctx.queue);
    rp::passes::ToneMapPass pass(ctx, rp::test::programs(), false);
    pass.run(profiler, scene, in, n, buf);
    profiler.collect();
    ctx.queue.enqueueReadBuffer(buf, CL_TRUE, 0, out.size() * sizeof(uint32_t), out.data());
    for (uint32_t i = 0; i < 64; ++i) {
      if (i < n)
        ASSERT_EQ(out[i], whole[i]) << "pixel " << i << " of " << n;
      else
        ASSERT_EQ(out[i], 0x12345678u) << "word " << i << " past " << n << " pixels was written";
    }
  }
}

// A probe kernel over colour.h: tone map, inverse, sRGB encode and the decode table.
class ColourProbe : public ::testing::Test {
 protected:
  void SetUp() override {
    auto& ctx = rp::test::context();
    std::string source = rp::cl::kernel_source("common/colour.h") + R"CLC(
__kernel void colour_probe(__global const float* x, __global float* mapped, __global float* back,
                           __global float* srgb, __global float4* decoded, __global float* inverse,
                           uint n) {
  uint i = get_global_id(0);
  if (i >= n) return;
  mapped[i] = rp_tone_map1(x[i]);
  back[i] = rp_tone_map_inverse1(mapped[i]);
  srgb[i] = rp_linear_to_srgb(x[i]);
  inverse[i] = rp_tone_map_inverse1(x[i]);
  uint code = i & 255u;
  decoded[i] = rp_unpack_rgba8_srgb(code | (code << 8) | (code << 16) | (code << 24));
}
)CLC";
    program_ = ::cl::Program(ctx.context, source);
    try {
      program_.build(std::vector<::cl::Device>{ctx.info.device});
    } catch (const ::cl::Error&) {
      FAIL() << program_.getBuildInfo<CL_PROGRAM_BUILD_LOG>(ctx.info.device);
    }
  }

  // Runs the probe over inputs x; fills the four outputs.
  void run(const std::vector<float>& x) {
    auto& ctx = rp::test::context();
    const size_t n = x.size();
    ::cl::Buffer in(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * 4,
                    const_cast<float*>(x.data()));
    ::cl::Buffer m(ctx.context, CL_MEM_WRITE_ONLY, n * 4), b(ctx.context, CL_MEM_WRITE_ONLY, n * 4),
        s(ctx.context, CL_MEM_WRITE_ONLY, n * 4), d(ctx.context, CL_MEM_WRITE_ONLY, n * 16),
        inv(ctx.context, CL_MEM_WRITE_ONLY, n * 4);
    ::cl::Kernel k(program_, "colour_probe");
    k.setArg(0, in);
    k.setArg(1, m);
    k.setArg(2, b);
    k.setArg(3, s);
    k.setArg(4, d);
    k.setArg(5, inv);
    k.setArg(6, static_cast<cl_uint>(n));
    ctx.queue.enqueueNDRangeKernel(k, ::cl::NullRange, ::cl::NDRange(n));
    mapped.resize(n);
    back.resize(n);
    srgb.resize(n);
    decoded.resize(n * 4);
    inverse.resize(n);
    ctx.queue.enqueueReadBuffer(m, CL_TRUE, 0, n * 4, mapped.data());
    ctx.queue.enqueueReadBuffer(b, CL_TRUE, 0, n * 4, back.data());
    ctx.queue.enqueueReadBuffer(s, CL_TRUE, 0, n * 4, srgb.data());
    ctx.queue.enqueueReadBuffer(d, CL_TRUE, 0, n * 16, decoded.data());
    ctx.queue.enqueueReadBuffer(inv, CL_TRUE, 0, n * 4, inverse.data());
  }

  ::cl::Program program_;
  std::vector<float> mapped, back, srgb, decoded, inverse;
};

TEST_F(ColourProbe, InverseToneMapRoundTrip) {
  std::vector<float> x{0.0f};
  for (int i = 0; i <= 2000; ++i) x.push_back(float(1e-4 * std::pow(1e6, i / 2000.0)));  // to 100
  run(x);
  for (size_t i = 0; i < x.size(); ++i) {
    // OpenCL's x / y may be off by 2.5 ulp (GPUs use that freedom), plus 0.5 ulp for 1 + x:
    // 3 ulp of a result below 1 is under 2e-7.
    EXPECT_NEAR(mapped[i], tone_map_ref(x[i]), 2e-7) << "x = " << x[i];
    // float rounding of T(x) is amplified by 1/(1-y) = 1+x in the inverse: ~6e-8 (1+x) relative.
    EXPECT_NEAR(back[i], x[i], 1e-5 * x[i]) << "x = " << x[i];
  }
}

TEST_F(ColourProbe, InverseClampsOutsideTheImageOfT) {
  run({1.0f, 2.0f, -0.5f, 0.5f, 0.75f});
  EXPECT_FLOAT_EQ(inverse[0], 65535.0f);  // T never reaches 1: clamped to a finite radiance
  EXPECT_FLOAT_EQ(inverse[1], 65535.0f);
  EXPECT_EQ(inverse[2], 0.0f);
  EXPECT_FLOAT_EQ(inverse[3], 1.0f);
  EXPECT_FLOAT_EQ(inverse[4], 3.0f);
}

TEST_F(ColourProbe, SrgbEncodeAccurateAndMonotonic) {
  std::vector<float> y;
  for (int i = 0; i <= 65536; ++i) y.push_back(float(i / 65536.0));
  run(y);
  double max_err = 0.0;
  for (size_t i = 0; i < y.size(); ++i) {
    max_err = std::max(max_err, std::abs(srgb[i] - srgb_encode_ref(y[i])));
    if (i > 0) {
      ASSERT_GE(srgb[i], srgb[i - 1]) << "y = " << y[i];
    }
  }
  EXPECT_LT(max_err, 2e-5);  // fit error 7e-6 plus float evaluation
  EXPECT_EQ(srgb[0], 0.0f);
  EXPECT_NEAR(srgb.back(), 1.0f, 1e-5);
}

TEST_F(ColourProbe, SrgbDecodeTableIsExact) {
  std::vector<float> x(256, 0.0f);
  run(x);
  for (int code = 0; code < 256; ++code) {
    float want = float(srgb_decode_ref(code / 255.0));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(decoded[code * 4 + c], want) << "code " << code;
    EXPECT_FLOAT_EQ(decoded[code * 4 + 3], float(code) / 255.0f) << "alpha code " << code;
  }
}

}  // namespace
