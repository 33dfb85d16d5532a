// Whole-frame checks of the demo scene: a committed golden image (PSNR threshold) and
// bit-exact determinism. Regenerate the golden only on purpose:
//   ROLYPOLY_UPDATE_GOLDEN=1 build/tests/test_render --gtest_filter=DemoFrame.*
// and say why in the commit message.
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/renderer.h"
#include "scene/demo_scene.h"
#include "support/cl_fixture.h"
#include "support/image_metrics.h"

namespace {

constexpr uint32_t kSize = 256;
const std::string kGolden = std::string(ROLYPOLY_TEST_DATA_DIR) + "/golden/demo_256.png";

std::vector<uint8_t> render_demo(uint32_t frames) {
  rp::scene::SceneAssets assets = rp::scene::make_demo_assets(rp::scene::default_asset_dir());
  rp::render::RenderSettings settings;
  settings.width = settings.height = kSize;
  rp::render::Renderer renderer(rp::test::context(), rp::test::programs(), assets, settings);
  for (uint32_t i = 0; i < frames; ++i) renderer.render(rp::scene::make_demo_frame(assets, i));
  std::vector<uint8_t> pixels;
  renderer.read_rgba8(pixels);
  return pixels;
}

TEST(DemoFrame, MatchesGoldenImage) {
  std::vector<uint8_t> pixels = render_demo(1);
  if (std::getenv("ROLYPOLY_UPDATE_GOLDEN")) {
    std::filesystem::create_directories(std::filesystem::path(kGolden).parent_path());
    rp::test::save_png(kGolden, {int(kSize), int(kSize), pixels});
    GTEST_SKIP() << "golden image rewritten: " << kGolden;
  }
  rp::test::Rgba8Image golden = rp::test::load_png(kGolden);
  ASSERT_EQ(golden.width, int(kSize));
  ASSERT_EQ(golden.height, int(kSize));
  double psnr = rp::test::psnr_rgb8(pixels, golden.rgba);
  if (psnr < 40.0)
    rp::test::save_png(std::filesystem::temp_directory_path() / "rolypoly_demo_256_actual.png",
                       {int(kSize), int(kSize), pixels});
  EXPECT_GE(psnr, 40.0) << "actual frame saved to /tmp/rolypoly_demo_256_actual.png";
}

TEST(DemoFrame, RenderingTwiceIsBitIdentical) {
  std::vector<uint8_t> a = render_demo(1);
  std::vector<uint8_t> b = render_demo(1);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_TRUE(a == b);
}

TEST(DemoFrame, ShowsTheLitBoxNotABlankImage) {
  std::vector<uint8_t> pixels = render_demo(1);
  // The lamp cap near the top centre is the brightest thing in the frame, the floor is lit and
  // the left wall is orange (more red than blue), the right wall blue (more blue than red).
  auto at = [&](uint32_t x, uint32_t y, int c) { return int(pixels[(y * kSize + x) * 4 + c]); };
  int max_lum = 0;
  for (uint32_t y = 0; y < kSize / 4; ++y)
    for (uint32_t x = kSize / 3; x < 2 * kSize / 3; ++x)
      max_lum = std::max(max_lum, at(x, y, 0) + at(x, y, 1) + at(x, y, 2));
  EXPECT_GT(max_lum, 3 * 230) << "no bright lamp near the top centre";
  uint32_t mid = kSize / 2;
  EXPECT_GT(at(kSize / 16, mid, 0), at(kSize / 16, mid, 2) + 20) << "left wall not orange";
  EXPECT_GT(at(kSize - 1 - kSize / 16, mid, 2), at(kSize - 1 - kSize / 16, mid, 0) + 20)
      << "right wall not blue";
}

}  // namespace
