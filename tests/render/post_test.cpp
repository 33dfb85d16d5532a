// The post-processing chain in the full renderer on the static demo: TAA settles within its
// 16-frame jitter cycle and stays close to the un-anti-aliased image; every effect can be
// switched off; the camera-cut rule resets the history.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "render/renderer.h"
#include "scene/demo_scene.h"
#include "support/cl_fixture.h"
#include "support/image_metrics.h"

namespace {

constexpr uint32_t kSize = 64;

double mean_abs_diff(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); i += 4)
    for (size_t c = 0; c < 3; ++c) sum += std::fabs(double(a[i + c]) - double(b[i + c]));
  return sum / double(a.size() / 4 * 3);
}

struct Demo {
  rp::scene::SceneAssets assets = rp::scene::make_demo_assets(rp::scene::default_asset_dir());
  rp::render::Renderer renderer;
  explicit Demo(rp::render::Effects fx)
      : renderer(rp::test::context(), rp::test::programs(), assets, settings(fx)) {}
  static rp::render::RenderSettings settings(rp::render::Effects fx) {
    rp::render::RenderSettings s;
    s.width = s.height = kSize;
    s.voxel_resolution = 32;
    s.effects = fx;
    return s;
  }
  std::vector<uint8_t> frame(uint32_t i) {
    renderer.render(rp::scene::make_demo_frame(assets, i));
    std::vector<uint8_t> px;
    renderer.read_rgba8(px);
    return px;
  }
};

TEST(PostProcessing, TaaSettlesOnAStaticSceneWithinItsJitterCycle) {
  rp::render::Effects taa_only;
  taa_only.bloom = taa_only.motion_blur = false;
  Demo taa(taa_only);
  std::vector<std::vector<uint8_t>> frames;
  for (uint32_t i = 0; i < 20; ++i) frames.push_back(taa.frame(i));
  double early = mean_abs_diff(frames[1], frames[2]);
  double late = mean_abs_diff(frames[18], frames[19]);
  std::printf("[ stats    ] consecutive-frame mean abs diff: frames 1-2 %.3f, 18-19 %.3f\n",
              early, late);
  // Dithering alone changes codes by ~0.5 on average from frame to frame.
  EXPECT_LT(late, 1.25) << "a static scene keeps changing after 16 frames";
  EXPECT_LE(late, early);

  rp::render::Effects none;
  none.taa = none.bloom = none.motion_blur = false;
  Demo plain(none);
  std::vector<uint8_t> reference = plain.frame(19);
  double psnr = rp::test::psnr_rgb8(frames[19], reference);
  std::printf("[ stats    ] TAA frame vs plain frame: %.2f dB\n", psnr);
  // At 64x64 the edges differ a lot (that is what TAA is for); the rest must not drift.
  EXPECT_GT(psnr, 22.0) << "TAA drifted far from the lit image";
  EXPECT_LT(psnr, 60.0) << "TAA had no effect at all";
}

TEST(PostProcessing, EffectsOffGiveTheSameImageAsBefore) {
  rp::render::Effects none;
  none.taa = none.bloom = none.motion_blur = false;
  Demo a(none), b(none);
  EXPECT_EQ(a.frame(5), b.frame(5));
}

TEST(PostProcessing, CameraCutResetsTheHistory) {
  Demo d({});
  for (uint32_t i = 0; i < 8; ++i) d.frame(i);
  // A cut: the camera jumps and prev_camera says so.
  rp::scene::FrameScene cut = rp::scene::make_demo_frame(d.assets, 8);
  cut.camera.position = cut.prev_camera.position = glm::vec3(0.3f, 0.2f, 2.6f);
  d.renderer.render(cut);
  std::vector<uint8_t> after_cut;
  d.renderer.read_rgba8(after_cut);
  // The same frame from a fresh renderer (no history at all).
  Demo fresh({});
  for (uint32_t i = 0; i < 8; ++i) fresh.frame(i);
  fresh.renderer.reset_history();
  fresh.renderer.render(cut);
  std::vector<uint8_t> expected;
  fresh.renderer.read_rgba8(expected);
  EXPECT_EQ(after_cut, expected);
}

}  // namespace
