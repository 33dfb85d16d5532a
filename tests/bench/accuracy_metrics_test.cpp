// The accuracy report's measures (bench/src/accuracy_metrics.h) on synthetic images whose answers
// are worked out by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "bench/src/accuracy_metrics.h"
#include "scene/demo_scene.h"

namespace rp::bench {
namespace {

uint16_t bit(Region r) { return uint16_t(1u << unsigned(r)); }

// A 5x5 image: a 3x3 block of back wall in the middle, ringed by left wall; one background pixel.
std::vector<truth::PrimaryHit> hits_5x5() {
  std::vector<truth::PrimaryHit> hits(25);
  for (uint32_t y = 0; y < 5; ++y)
    for (uint32_t x = 0; x < 5; ++x) {
      truth::PrimaryHit& h = hits[y * 5 + x];
      h.instance = 0;
      const bool inner = x >= 1 && x <= 3 && y >= 1 && y <= 3;
      h.material = inner ? scene::demo::kBackMaterial : scene::demo::kLeftMaterial;
    }
  hits[0] = truth::PrimaryHit{};  // background
  return hits;
}

TEST(AccuracyMetrics, RegionsAreErodedByOnePixel) {
  const std::vector<uint16_t> labels = classify_regions(hits_5x5(), 5, 5);
  EXPECT_EQ(labels[0], 0);                    // background: in no region
  EXPECT_EQ(labels[1], bit(Region::kImage));  // left wall on the border: image only
  // Only the centre of the 3x3 back-wall block has four back-wall neighbours.
  EXPECT_EQ(labels[12], bit(Region::kImage) | bit(Region::kBackWall));
  EXPECT_EQ(labels[6], bit(Region::kImage));
  int back = 0;
  for (uint16_t l : labels) back += (l & bit(Region::kBackWall)) ? 1 : 0;
  EXPECT_EQ(back, 1);
}

TEST(AccuracyMetrics, FloorAndTumblersSplitByTheLamp) {
  std::vector<truth::PrimaryHit> hits(9);
  for (auto& h : hits) {
    h.instance = 0;
    h.material = scene::demo::kFloorMaterial;
    h.lamp_visible = false;
    h.lamp_cos = 0.5f;
  }
  EXPECT_TRUE(classify_regions(hits, 3, 3)[4] & bit(Region::kFloorShadow));
  for (auto& h : hits) h.lamp_visible = true;
  EXPECT_TRUE(classify_regions(hits, 3, 3)[4] & bit(Region::kFloorLit));
  for (auto& h : hits) h.material = scene::demo::kTumblerMaterial, h.lamp_cos = -0.2f;
  EXPECT_TRUE(classify_regions(hits, 3, 3)[4] & bit(Region::kTumblerShadowed));
}

TEST(AccuracyMetrics, RelativeL1AndBias) {
  // Two covered pixels: truth (1, 1, 1) and (3, 3, 3); a = (2, 2, 2) and (3, 3, 0).
  const std::vector<uint16_t> labels = {bit(Region::kImage), bit(Region::kImage), 0};
  const std::vector<float> truth = {1, 1, 1, 3, 3, 3, 9, 9, 9};
  const std::vector<float> a = {2, 2, 2, 3, 3, 0, 0, 0, 0};
  const ErrorStats s = compare_region(a, truth, labels, Region::kImage);
  EXPECT_EQ(s.pixels, 2u);
  EXPECT_DOUBLE_EQ(s.sum_truth, 12.0);
  EXPECT_DOUBLE_EQ(s.rel_l1, (1 + 1 + 1 + 0 + 0 + 3) / 12.0);
  EXPECT_DOUBLE_EQ(s.bias, (6 + 6) / 12.0 - 1.0);
  EXPECT_TRUE(std::isnan(compare_region(a, truth, labels, Region::kCeiling).rel_l1));
}

TEST(AccuracyMetrics, IncomingLightDividesByAlbedoAndGivesTheHue) {
  const std::vector<uint16_t> labels = {uint16_t(bit(Region::kImage) | bit(Region::kLeftWall)),
                                        uint16_t(bit(Region::kImage) | bit(Region::kLeftWall))};
  const std::vector<float> albedo = {0.8f, 0.35f, 0.05f, 0.8f, 0.35f, 0.05f};
  // Bluish light arriving: (0.2, 0.3, 0.4) times the albedo.
  std::vector<float> indirect(6);
  const float in[3] = {0.2f, 0.3f, 0.4f};
  for (int i = 0; i < 6; ++i) indirect[size_t(i)] = albedo[size_t(i)] * in[i % 3];
  const IncomingLight l = incoming_indirect(indirect, albedo, labels, Region::kLeftWall);
  EXPECT_NEAR(l.rgb[0], 0.2, 1e-6);
  EXPECT_NEAR(l.rgb[2], 0.4, 1e-6);
  EXPECT_LT(l.r_minus_b(), 0.0);
}

TEST(AccuracyMetrics, LeaksAndMissingPixels) {
  // Truth luminance 1 everywhere (grey 1); eps = 0.05.
  const std::vector<uint16_t> labels(4, bit(Region::kImage));
  const std::vector<float> truth(12, 1.0f);
  const std::vector<float> a = {2, 2, 2, 1.5f, 1.5f, 1.5f, 0.5f, 0.5f, 0.5f, 0.7f, 0.7f, 0.7f};
  const LeakStats s = leaks_and_misses(a, truth, labels);
  EXPECT_NEAR(s.epsilon, 0.05, 1e-9);
  EXPECT_EQ(s.leak_pixels, 1u);     // 2 > 1.55; 1.5 is not
  EXPECT_EQ(s.missing_pixels, 1u);  // 0.5 < 0.95 / 1.5 = 0.633; 0.7 is not
  EXPECT_EQ(s.covered_pixels, 4u);
  // Counted in one region: the leak pixel and one plain pixel are marbles; eps stays the
  // image's (a region of dark truth does not get a smaller eps).
  std::vector<uint16_t> marbles = labels;
  marbles[0] |= bit(Region::kMarble);
  marbles[1] |= bit(Region::kMarble);
  const LeakStats m = leaks_and_misses(a, truth, marbles, Region::kMarble);
  EXPECT_NEAR(m.epsilon, 0.05, 1e-9);
  EXPECT_EQ(m.leak_pixels, 1u);
  EXPECT_EQ(m.missing_pixels, 0u);
  EXPECT_EQ(m.covered_pixels, 2u);
}

TEST(AccuracyMetrics, PsnrAfterToneMap) {
  const std::vector<float> a = {1.0f, 1.0f, 1.0f};
  EXPECT_TRUE(std::isinf(tone_mapped_psnr(a, a)));
  // Tone map 1 -> 0.5, 3 -> 0.75; sRGB 0.5 -> 0.7353569, 0.75 -> 0.8808250.
  const std::vector<float> b = {3.0f, 3.0f, 3.0f};
  const double d = 0.8808250 - 0.7353569;
  EXPECT_NEAR(tone_mapped_psnr(a, b), 10.0 * std::log10(1.0 / (d * d)), 1e-3);
}

TEST(AccuracyMetrics, PsnrOfAnEightBitFrame) {
  // Tone map 1 -> 0.5 -> sRGB 0.7353569; code 188 = 0.7372549; alpha is ignored.
  const std::vector<float> radiance = {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f};
  const std::vector<uint8_t> rgba = {188, 188, 188, 0, 188, 188, 188, 255};
  const double d = 188.0 / 255.0 - 0.7353569;
  EXPECT_NEAR(rgba8_psnr(rgba, radiance), 10.0 * std::log10(1.0 / (d * d)), 1e-2);
  const std::vector<uint8_t> black = {0, 0, 0, 255, 0, 0, 0, 255};
  EXPECT_TRUE(std::isinf(rgba8_psnr(black, std::vector<float>(6, 0.0f))));
  EXPECT_THROW(rgba8_psnr(black, std::vector<float>(3, 0.0f)), std::invalid_argument);
}

TEST(AccuracyMetrics, HeatMapSigns) {
  const std::vector<uint16_t> labels = {bit(Region::kImage), bit(Region::kImage),
                                        bit(Region::kImage), 0};
  const std::vector<float> truth(12, 1.0f);
  const std::vector<float> a = {1, 1, 1, 3, 3, 3, 0, 0, 0, 5, 5, 5};
  std::vector<uint8_t> rgba;
  signed_heat_map(a, truth, labels, 0.0, rgba);
  EXPECT_EQ(rgba[0], 255); EXPECT_EQ(rgba[1], 255); EXPECT_EQ(rgba[2], 255);  // equal: white
  EXPECT_EQ(rgba[4], 255); EXPECT_EQ(rgba[5], 0); EXPECT_EQ(rgba[6], 0);      // too bright: red
  EXPECT_EQ(rgba[8], 0); EXPECT_EQ(rgba[9], 0); EXPECT_EQ(rgba[10], 255);     // too dark: blue
  EXPECT_EQ(rgba[12], 0); EXPECT_EQ(rgba[13], 0); EXPECT_EQ(rgba[14], 0);     // background
}


// ---- The direct section's measures ----

// A linear ramp from 0 at s = a to 1 at s = b (flat outside), sampled every `step`: its 10-90 %
// width is 0.8 (b - a) wherever the samples fall, since the crossings are interpolated linearly.
std::vector<ProfileSample> ramp(double a, double b, double step, double end) {
  std::vector<ProfileSample> p;
  for (double s = 0.0; s <= end; s += step) p.push_back({s, std::clamp((s - a) / (b - a), 0.0, 1.0)});
  return p;
}

TEST(AccuracyMetrics, TransitionWidthOfARamp) {
  EXPECT_NEAR(transition_width(ramp(0.1, 0.3, 0.01, 0.5)), 0.16, 1e-9);
  EXPECT_NEAR(transition_width(ramp(0.1037, 0.2291, 0.0013, 0.5)), 0.8 * (0.2291 - 0.1037), 1e-9);
  // A step (hard shadow) sampled every 0.01 reads 0.8 of a sample spacing.
  EXPECT_NEAR(transition_width(ramp(0.2, 0.2000001, 0.01, 0.5)), 0.008, 1e-4);
  // A dip back into shadow before the edge does not count: the last rise through 10 % does.
  std::vector<ProfileSample> p = ramp(0.3, 0.4, 0.01, 0.6);
  p[5].v = 0.5;  // s = 0.05: a lit speck inside the umbra
  EXPECT_NEAR(transition_width(p), 0.08, 1e-9);
  // Undefined: never lit enough, or lit from the start.
  EXPECT_TRUE(std::isnan(transition_width(ramp(0.1, 0.3, 0.01, 0.2))));
  EXPECT_TRUE(std::isnan(transition_width(ramp(-0.3, -0.1, 0.01, 0.2))));
  // Wider transition in the other sense of the words: 5-95 %.
  EXPECT_NEAR(transition_width(ramp(0.1, 0.3, 0.01, 0.5), 0.05, 0.95), 0.18, 1e-9);
}

TEST(AccuracyMetrics, MaskedPsnrOfKnownImages) {
  // Two pixels in the mask, one out: differences 0.1 in every channel of the first, 0 in the
  // second: MSE = 0.01 * 3 / 6 = 0.005 -> 23.01 dB; scaled by 2 the MSE is 4x: 16.99 dB.
  const std::vector<float> t = {1, 1, 1, 0.5f, 0.5f, 0.5f, 9, 9, 9};
  const std::vector<float> a = {1.1f, 1.1f, 1.1f, 0.5f, 0.5f, 0.5f, 0, 0, 0};
  const std::vector<uint8_t> mask = {1, 1, 0};
  EXPECT_NEAR(masked_psnr(a, t, mask, 1.0), 10.0 * std::log10(1.0 / 0.005), 1e-4);
  EXPECT_NEAR(masked_psnr(a, t, mask, 2.0), 10.0 * std::log10(1.0 / 0.02), 1e-4);
  EXPECT_TRUE(std::isinf(masked_psnr(t, t, mask, 1.0)));
  EXPECT_TRUE(std::isnan(masked_psnr(a, t, {0, 0, 0}, 1.0)));
  EXPECT_THROW(masked_psnr(a, t, {1, 1}, 1.0), std::invalid_argument);
}

TEST(AccuracyMetrics, ToneMappedErrorByKeyBins) {
  // Tone map and sRGB: 1 -> 0.7353569, 3 -> 0.8808250, 0 -> 0. Four pixels, the last masked
  // out; keys 0.05 and -1 fall into bin 0 of 2, key 1 into bin 1.
  const std::vector<float> truth = {1, 1, 1, 1, 1, 1, 3, 3, 3, 0, 0, 0};
  const std::vector<float> a = {3, 3, 3, 1, 1, 1, 1, 1, 1, 9, 9, 9};
  const std::vector<uint8_t> mask = {1, 1, 1, 0};
  const std::vector<float> key = {0.05f, -1.0f, 1.0f, 0.5f};
  const std::vector<ErrorBin> bins = tone_mapped_error_by_key(a, truth, mask, key, 2);
  ASSERT_EQ(bins.size(), 2u);
  const double d = 0.8808250 - 0.7353569;
  EXPECT_EQ(bins[0].pixels, 2u);  // +d on three channels, 0 on three
  EXPECT_NEAR(bins[0].mean, d / 2.0, 1e-6);
  EXPECT_NEAR(bins[0].rms, d / std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(bins[0].squared_sum, 3.0 * d * d, 1e-6);
  EXPECT_EQ(bins[1].pixels, 1u);  // -d on three channels
  EXPECT_NEAR(bins[1].mean, -d, 1e-6);
  EXPECT_NEAR(bins[1].rms, d, 1e-6);
  // The bins' squared sums make the masked PSNR.
  const double mse = (bins[0].squared_sum + bins[1].squared_sum) / 9.0;
  EXPECT_NEAR(masked_tone_mapped_psnr(a, truth, mask), 10.0 * std::log10(1.0 / mse), 1e-6);
  EXPECT_EQ(tone_mapped_error_by_key(a, truth, {0, 0, 0, 0}, key, 3)[2].pixels, 0u);
  EXPECT_THROW(tone_mapped_error_by_key(a, truth, mask, {0.0f}, 2), std::invalid_argument);
  EXPECT_THROW(tone_mapped_error_by_key(a, truth, mask, key, 0), std::invalid_argument);
}

TEST(AccuracyMetrics, SrgbPsnrEncodesEachChannel) {
  // Linear 0.5 -> sRGB 0.735357; linear 0.2 -> 0.484529; one pixel, three equal channels.
  const std::vector<float> a = {0.5f, 0.5f, 0.5f}, t = {0.2f, 0.2f, 0.2f};
  const double d = 0.735357 - 0.484529;
  EXPECT_NEAR(srgb_psnr(a, t, {1}), 10.0 * std::log10(1.0 / (d * d)), 1e-3);
  // Clamped to [0, 1] before the encode.
  EXPECT_TRUE(std::isinf(srgb_psnr({2, 2, 2}, {1, 1, 1}, {1})));
}

TEST(AccuracyMetrics, DilateGrowsBySquare) {
  std::vector<uint8_t> m(25, 0);
  m[2 * 5 + 2] = 1;
  const std::vector<uint8_t> d = dilate(m, 5, 5, 1);
  int n = 0;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x) {
      const bool inside = std::abs(x - 2) <= 1 && std::abs(y - 2) <= 1;
      EXPECT_EQ(d[size_t(y) * 5 + size_t(x)], inside ? 1 : 0) << x << "," << y;
      n += d[size_t(y) * 5 + size_t(x)];
    }
  EXPECT_EQ(n, 9);
  m.assign(25, 0);
  m[0] = 1;  // at the corner: clipped
  EXPECT_EQ(dilate(m, 5, 5, 1)[6], 1);
  EXPECT_EQ(dilate(m, 5, 5, 1)[2], 0);
}

TEST(AccuracyMetrics, BilinearLumaBetweenPixelCentres) {
  // 2x1 image, luminance 0 and 1 (grey): centres at x = 0.5 and 1.5.
  const std::vector<float> img = {0, 0, 0, 1, 1, 1};
  EXPECT_NEAR(bilinear_luma(img, 2, 1, 0.5, 0.5), 0.0, 1e-12);
  EXPECT_NEAR(bilinear_luma(img, 2, 1, 1.0, 0.5), 0.5, 1e-12);
  EXPECT_NEAR(bilinear_luma(img, 2, 1, 1.25, 0.5), 0.75, 1e-12);
  EXPECT_NEAR(bilinear_luma(img, 2, 1, 7.0, 0.5), 1.0, 1e-12);  // clamped at the edge
}

}  // namespace
}  // namespace rp::bench
