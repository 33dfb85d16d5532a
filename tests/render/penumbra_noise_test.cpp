// Soft shadows on a frame that no history averages (the first frame, TAA off, after a cut):
// pcss filters each pixel with LightPass::kPcssTapsWithoutHistory taps there, so its penumbrae
// are not the stipple that TAA smooths over later frames (6 taps). The noise measure: the
// high-frequency energy of the floor's irradiance (direct light / albedo) in the tumblers'
// penumbrae, the mean |E - mean of its 4 neighbours| over penumbra pixels (the 16-frame average
// between 10 % and 90 % of the lit floor), at 128x128.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/renderer.h"
#include "scene/demo_scene.h"
#include "support/cl_fixture.h"

namespace {

constexpr uint32_t kSize = 128;
constexpr uint32_t kFrames = 16;

struct Frames {
  std::vector<std::vector<float>> irradiance;  // per frame: red direct / albedo per pixel
  std::vector<uint8_t> floor;                  // 1: the floor (y = -1)
};

Frames render_frames() {
  const rp::scene::SceneAssets assets = rp::scene::make_demo_assets(rp::scene::default_asset_dir());
  rp::render::RenderSettings s;
  s.width = s.height = kSize;
  s.shadows = rp::render::ShadowMode::kPcss;
  rp::render::Renderer r(rp::test::context(), rp::test::programs(), assets, s);
  r.set_keep_light_components(true);
  Frames out;
  for (uint32_t f = 0; f < kFrames; ++f) {
    r.render(rp::scene::make_demo_frame(assets, f));
    rp::render::LinearComponents c;
    r.read_components(c);
    std::vector<float> e(size_t(kSize) * kSize, 0.0f);
    for (size_t i = 0; i < e.size(); ++i)
      e[i] = c.albedo[3 * i] > 1e-3f ? c.direct[3 * i] / c.albedo[3 * i] : 0.0f;
    const size_t n = e.size();
    out.irradiance.push_back(std::move(e));
    if (f == 0) {
      std::vector<float> position(size_t(kSize) * kSize * 4);
      rp::test::context().queue.enqueueReadBuffer(r.gbuffer().position, CL_TRUE, 0,
                                                  position.size() * sizeof(float),
                                                  position.data());
      out.floor.resize(n);
      for (size_t i = 0; i < n; ++i)
        out.floor[i] = position[4 * i + 3] != 0.0f && std::abs(position[4 * i + 1] + 1.0f) < 1e-3f;
    }
  }
  return out;
}

// Mean |E - mean of the 4 neighbours| over the pixels in `region` whose neighbours are floor.
double high_frequency(const std::vector<float>& e, const std::vector<uint8_t>& floor,
                      const std::vector<uint8_t>& region) {
  double sum = 0.0;
  int n = 0;
  for (uint32_t y = 1; y + 1 < kSize; ++y)
    for (uint32_t x = 1; x + 1 < kSize; ++x) {
      const size_t i = size_t(y) * kSize + x;
      if (!region[i] || !floor[i - 1] || !floor[i + 1] || !floor[i - kSize] || !floor[i + kSize])
        continue;
      const double m = 0.25 * (e[i - 1] + e[i + 1] + e[i - kSize] + e[i + kSize]);
      sum += std::abs(e[i] - m);
      ++n;
    }
  EXPECT_GT(n, 50) << "too few penumbra pixels";
  return n > 0 ? sum / n : 0.0;
}

TEST(PenumbraNoise, AFrameWithoutHistoryIsAsSmoothAsTheConvergedOne) {
  const Frames f = render_frames();
  const size_t n = size_t(kSize) * kSize;
  std::vector<float> mean(n, 0.0f);
  for (const std::vector<float>& e : f.irradiance)
    for (size_t i = 0; i < n; ++i) mean[i] += e[i] / float(kFrames);
  std::vector<float> lit;
  for (size_t i = 0; i < n; ++i)
    if (f.floor[i]) lit.push_back(mean[i]);
  ASSERT_FALSE(lit.empty());
  std::sort(lit.begin(), lit.end());
  const float full = lit[lit.size() * 9 / 10];  // the lit floor's level
  std::vector<uint8_t> penumbra(n, 0);
  for (size_t i = 0; i < n; ++i)
    penumbra[i] = f.floor[i] && mean[i] > 0.1f * full && mean[i] < 0.9f * full;
  const double converged = high_frequency(mean, f.floor, penumbra);
  const double first = high_frequency(f.irradiance[0], f.floor, penumbra);
  const double later = high_frequency(f.irradiance[1], f.floor, penumbra);
  std::printf("penumbra high-frequency energy: first frame %.4f, second %.4f, 16-frame mean %.4f "
              "(lit floor %.3f)\n", first, later, converged, full);
  EXPECT_LT(first, 0.6 * later) << "the frame without history is no smoother than one with it";
  EXPECT_LT(first, 1.6 * converged) << "the first frame's penumbrae are a stipple";
}

}  // namespace
