// The direct section's penumbra breakdown (bench/src/accuracy_penumbra.h) on small images.
#include "bench/src/accuracy_penumbra.h"

#include <cmath>

#include <gtest/gtest.h>

#include "bench/src/accuracy_metrics.h"

namespace {

using rp::bench::PenumbraParts;

// 5 x 3 pixels, all in the penumbra but the top-right one; pixel (1, 1) shows an object.
constexpr uint32_t kW = 5, kH = 3;

std::vector<uint8_t> floor_mask() {
  std::vector<uint8_t> f(kW * kH, 1);
  f[1 * kW + 1] = 0;
  return f;
}

std::vector<uint8_t> penumbra_mask() {
  std::vector<uint8_t> p(kW * kH, 1);
  p[4] = 0;
  return p;
}

TEST(AccuracyPenumbra, PartsSplitTheMaskByTheFloorsOutlines) {
  const PenumbraParts parts = rp::bench::penumbra_parts(penumbra_mask(), floor_mask(), kW, kH);
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const size_t i = size_t(y) * kW + x;
      const bool in = penumbra_mask()[i] != 0;
      const bool object = x == 1 && y == 1;
      const bool beside = !object && x <= 2;  // the object's 3x3 neighbourhood
      EXPECT_EQ(parts.objects[i], in && object ? 1 : 0) << x << "," << y;
      EXPECT_EQ(parts.floor_beside_objects[i], in && beside ? 1 : 0) << x << "," << y;
      EXPECT_EQ(parts.open_floor[i], in && !object && !beside ? 1 : 0) << x << "," << y;
    }
  EXPECT_THROW(rp::bench::penumbra_parts(penumbra_mask(), {1, 1}, kW, kH),
               std::invalid_argument);
}

TEST(AccuracyPenumbra, BreakdownAddsUpToTheWholeMask) {
  const std::vector<uint8_t> penumbra = penumbra_mask();
  const PenumbraParts parts = rp::bench::penumbra_parts(penumbra, floor_mask(), kW, kH);
  // The truth 1 everywhere; the real time 3 on the open floor pixel (3, 1) (lamp fraction
  // 0.85) and on the object, 0.5 on the open floor pixel (4, 2) (lamp fraction 0.31).
  std::vector<float> truth(3 * kW * kH, 1.0f), a = truth;
  std::vector<float> fraction(kW * kH, 0.5f);
  for (int c = 0; c < 3; ++c) {
    a[3 * (1 * kW + 3) + c] = 3.0f;
    a[3 * (1 * kW + 1) + c] = 3.0f;
    a[3 * (2 * kW + 4) + c] = 0.5f;
  }
  fraction[1 * kW + 3] = 0.85f;
  fraction[2 * kW + 4] = 0.31f;
  const nlohmann::json j = rp::bench::penumbra_breakdown(a, truth, parts, fraction);
  const nlohmann::json& p = j["parts"];
  EXPECT_EQ(p["open_floor"]["pixels"], 5);  // x 3..4 but (4, 0), outside the mask
  EXPECT_EQ(p["floor_beside_objects"]["pixels"], 8);
  EXPECT_EQ(p["objects"]["pixels"], 1);
  EXPECT_TRUE(p["floor_beside_objects"]["direct_psnr_db"].is_null());  // equal there: +inf
  // The parts' squared errors make the whole mask's PSNR.
  auto mse = [](double db, double pixels) { return pixels * std::pow(10.0, -db / 10.0); };
  const double whole = rp::bench::masked_tone_mapped_psnr(a, truth, penumbra);
  const double sum = mse(p["open_floor"]["direct_psnr_db"].get<double>(), 5.0) +
                     mse(p["objects"]["direct_psnr_db"].get<double>(), 1.0);
  EXPECT_NEAR(10.0 * std::log10(14.0 / sum), whole, 1e-9);
  // The open floor's bins: the two differing pixels in bins 8 and 3, the rest (0.5) in bin 5.
  const nlohmann::json& bins = j["open_floor_by_lamp_fraction"];
  ASSERT_EQ(bins.size(), 10u);
  EXPECT_EQ(bins[8]["pixels"], 1);
  EXPECT_EQ(bins[3]["pixels"], 1);
  EXPECT_EQ(bins[5]["pixels"], 3);
  EXPECT_GT(bins[8]["mean"].get<double>(), 0.0);  // too bright
  EXPECT_LT(bins[3]["mean"].get<double>(), 0.0);  // too dark
  EXPECT_EQ(bins[5]["mean"].get<double>(), 0.0);
  EXPECT_TRUE(bins[0]["mean"].is_null());
  EXPECT_NEAR(bins[8]["share"].get<double>() + bins[3]["share"].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(bins[3]["from"].get<double>(), 0.3, 1e-12);
  const std::string text = rp::bench::penumbra_breakdown_text("pcss", j);
  EXPECT_NE(text.find("pcss penumbra by part: open floor 5 px"), std::string::npos) << text;
  EXPECT_NE(text.find(" 0.8-0.9 +"), std::string::npos) << text;
  EXPECT_EQ(text.find(" 0.0-0.1"), std::string::npos) << text;  // empty bins are left out
}

}  // namespace
