// The demo's box and a sky's sun (scene::MeshInstance::casts_light_shadow): the box is in the
// punctual lights' shadow views but not in the lamp's map. A sun that can reach the inside only
// through the walls adds no direct light anywhere inside (the lamp's light and shadows are the
// scene's without the sun, within the shadow maps' filtering); through the open demo's skylight
// (demo::kSkylight) it lights a patch of the floor.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/renderer.h"
#include "scene/demo_scene.h"
#include "support/cl_fixture.h"

namespace {

constexpr uint32_t kSize = 96;

struct Frame {
  std::vector<float> direct;    // rgb per pixel, 0 on the background
  std::vector<float> position;  // world xyz, w = 1 covered
};

// The demo's first frame with an optional directional light shining along `sun` (unit,
// pointing down).
Frame render(bool open, const glm::vec3* sun) {
  const rp::scene::SceneAssets assets =
      rp::scene::make_demo_assets(rp::scene::default_asset_dir(), open);
  rp::render::RenderSettings s;
  s.width = s.height = kSize;
  s.bounces = 1;
  s.shadows = rp::render::ShadowMode::kHard;
  s.effects.taa = s.effects.bloom = s.effects.motion_blur = false;
  rp::render::Renderer r(rp::test::context(), rp::test::programs(), assets, s);
  r.set_keep_light_components(true);
  rp::scene::FrameScene frame = rp::scene::make_demo_frame(assets, 0);
  if (sun) {
    rp::scene::PunctualLight l;
    l.type = rp::scene::LightType::kDirectional;
    l.direction = *sun;
    l.intensity = glm::vec3(3.0f);
    frame.lights.push_back(l);
  }
  r.render(frame);
  rp::render::LinearComponents out;
  r.read_components(out);
  Frame f;
  f.direct = out.direct;
  f.position.resize(size_t(kSize) * kSize * 4);
  rp::test::context().queue.enqueueReadBuffer(r.gbuffer().position, CL_TRUE, 0,
                                              f.position.size() * sizeof(float),
                                              f.position.data());
  return f;
}

// Mean red direct light of the floor points (y = -1) inside the rectangle [x0, x1] x [z0, z1].
double floor_mean(const Frame& f, float x0, float x1, float z0, float z1) {
  double sum = 0.0;
  int n = 0;
  for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
    const float* p = &f.position[4 * i];
    if (p[3] == 0.0f || std::abs(p[1] + 1.0f) > 1e-3f) continue;
    if (p[0] < x0 || p[0] > x1 || p[2] < z0 || p[2] > z1) continue;
    sum += f.direct[3 * i];
    ++n;
  }
  EXPECT_GT(n, 20) << "too few floor pixels in the rectangle";
  return n > 0 ? sum / n : 0.0;
}

TEST(DemoSun, TheWallsKeepASideSunOutAndTheSkylightLetsAHighOneIn) {
  const Frame lamp_only = render(false, nullptr);
  // from +x, 30 degrees above the horizon: only through the right wall and the ceiling
  const glm::vec3 side = glm::normalize(glm::vec3(-std::cos(0.5236f), -std::sin(0.5236f), 0.0f));
  const Frame side_sun = render(false, &side);
  double most = 0.0;
  for (size_t i = 0; i < side_sun.direct.size(); ++i)
    most = std::max(most, double(side_sun.direct[i] - lamp_only.direct[i]));
  EXPECT_LT(most, 1e-3) << "the sun came through the walls";

  // from behind the back wall, 70 degrees up (travelling towards +z): through the skylight
  // (z -1 .. -0.5 at y = 1) it reaches the floor at z -0.27 .. 0.23; the band in front of the
  // tumblers' line, x in [-0.45, 0.45], z in [0.05, 0.2], is in that patch
  const glm::vec3 high = glm::normalize(glm::vec3(0.0f, -std::sin(1.2217f), std::cos(1.2217f)));
  const Frame closed = render(false, &high), open = render(true, &high);
  const Frame open_lamp_only = render(true, nullptr);
  const auto patch = [](const Frame& f) { return floor_mean(f, -0.45f, 0.45f, 0.05f, 0.2f); };
  EXPECT_NEAR(patch(closed), patch(lamp_only), 1e-4) << "the closed ceiling let the sun in";
  // sun: 3 x cos 20 degrees x the wood's albedo (about 0.5 in red); less where a tumbler's
  // shadow falls
  EXPECT_GT(patch(open) - patch(open_lamp_only), 0.5) << "the skylight's patch of sun is missing";
}

}  // namespace
