// Global illumination on the demo frame, measured on the light pass's indirect term: colour
// bleeds from the walls onto the floor, and shadowed floor still receives bounce light. Both
// quality modes: the fast one (one frame: the spatially filtered low-resolution cones,
// upsampled) and the reference (16 cones per pixel).
#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "render/renderer.h"
#include "scene/demo_scene.h"
#include "support/cl_fixture.h"

namespace {

constexpr uint32_t kSize = 128;

struct Pixel {
  float px, py, pz, nx, ny, nz;
  float albedo[3], direct[3], indirect[3];
};

std::vector<Pixel> render_indirect(rp::render::Quality quality) {
  rp::scene::SceneAssets assets = rp::scene::make_demo_assets(rp::scene::default_asset_dir());
  rp::render::RenderSettings settings;
  settings.width = settings.height = kSize;
  settings.quality = quality;
  rp::render::Renderer renderer(rp::test::context(), rp::test::programs(), assets, settings);
  renderer.set_debug_view({rp::passes::DebugView::kIndirect, 0, 0});
  renderer.render(rp::scene::make_demo_frame(assets, 0));
  const size_t n = size_t(kSize) * kSize;
  std::vector<float> pos(n * 4), nrm(n * 4), alb(n * 4), dir(n * 4), ind(n * 4);
  auto& q = rp::test::context().queue;
  q.enqueueReadBuffer(renderer.gbuffer().position, CL_TRUE, 0, n * 16, pos.data());
  q.enqueueReadBuffer(renderer.gbuffer().normal_depth, CL_TRUE, 0, n * 16, nrm.data());
  q.enqueueReadBuffer(renderer.gbuffer().albedo, CL_TRUE, 0, n * 16, alb.data());
  q.enqueueReadBuffer(renderer.light_components().direct, CL_TRUE, 0, n * 16, dir.data());
  q.enqueueReadBuffer(renderer.light_components().indirect, CL_TRUE, 0, n * 16, ind.data());
  std::vector<Pixel> out;
  for (size_t i = 0; i < n; ++i) {
    if (pos[4 * i + 3] == 0.0f) continue;
    Pixel p{pos[4 * i], pos[4 * i + 1], pos[4 * i + 2], nrm[4 * i], nrm[4 * i + 1], nrm[4 * i + 2],
            {}, {}, {}};
    for (int c = 0; c < 3; ++c) {
      p.albedo[c] = alb[4 * i + c];
      p.direct[c] = dir[4 * i + c];
      p.indirect[c] = ind[4 * i + c];
    }
    out.push_back(p);
  }
  return out;
}

class GlobalIllumination : public ::testing::TestWithParam<rp::render::Quality> {
 protected:
  const std::vector<Pixel>& pixels() const {
    static const std::vector<Pixel> fast = render_indirect(rp::render::Quality::kFast);
    static const std::vector<Pixel> reference = render_indirect(rp::render::Quality::kReference);
    return GetParam() == rp::render::Quality::kFast ? fast : reference;
  }
  double incoming_red_over_blue(float x0, float x1) const;
};

bool on_floor(const Pixel& p) { return p.ny > 0.99f && p.py < -0.99f; }

// Red / blue of the light arriving at floor pixels with x in [x0, x1) (indirect / albedo, so the
// wood's own colour drops out), summed over the visible floor of that strip.
double GlobalIllumination::incoming_red_over_blue(float x0, float x1) const {
  double red = 0.0, blue = 0.0;
  int count = 0;
  for (const Pixel& p : pixels()) {
    if (!on_floor(p) || p.px < x0 || p.px >= x1) continue;
    red += p.indirect[0] / std::max(p.albedo[0], 1e-3f);
    blue += p.indirect[2] / std::max(p.albedo[2], 1e-3f);
    ++count;
  }
  EXPECT_GT(count, 10) << "too few floor pixels in x [" << x0 << ", " << x1 << ")";
  return red / std::max(blue, 1e-9);
}

TEST_P(GlobalIllumination, FloorIsWarmerByTheOrangeWallAndCoolerByTheBlueWall) {
  double left = incoming_red_over_blue(-1.0f, -0.75f);
  double centre = incoming_red_over_blue(-0.15f, 0.15f);
  double right = incoming_red_over_blue(0.75f, 1.0f);
  EXPECT_GT(left, centre * 1.15) << "left " << left << " centre " << centre;
  EXPECT_LT(right, centre / 1.15) << "right " << right << " centre " << centre;
}

TEST_P(GlobalIllumination, ShadowedFloorReceivesBounceLight) {
  int shadowed = 0, lifted = 0;
  double sum = 0.0, lit_sum = 0.0;
  int lit = 0;
  for (const Pixel& p : pixels()) {
    if (!on_floor(p)) continue;
    float direct = p.direct[0] + p.direct[1] + p.direct[2];
    float indirect = p.indirect[0] + p.indirect[1] + p.indirect[2];
    if (direct > 1e-4f) {  // lit by the lamp
      lit_sum += indirect;
      ++lit;
      continue;
    }
    ++shadowed;
    lifted += indirect > 0.0f;
    sum += indirect;
  }
  ASSERT_GT(shadowed, 20) << "the tumblers should shadow some floor";
  ASSERT_GT(lit, 20);
  EXPECT_EQ(lifted, shadowed) << "every shadowed floor pixel gets some bounce light";
  // On average a shadowed floor pixel gets at least a third of what lit floor gets indirectly
  // (the tumbler above it hides part of the sky of bounce light, not all of it).
  EXPECT_GT(sum / shadowed, (lit_sum / lit) / 3.0);
}

TEST_P(GlobalIllumination, CeilingFacingAwayFromTheLampIsLitOnlyByBounceLight) {
  double direct = 0.0, indirect = 0.0;
  int count = 0;
  for (const Pixel& p : pixels()) {
    if (p.ny > -0.99f || p.py < 0.99f || std::max(std::abs(p.px), std::abs(p.pz)) < 0.5f) continue;
    direct += p.direct[0] + p.direct[1] + p.direct[2];
    indirect += p.indirect[0] + p.indirect[1] + p.indirect[2];
    ++count;
  }
  ASSERT_GT(count, 20);
  EXPECT_EQ(direct, 0.0);
  EXPECT_GT(indirect / count, 0.05);
}

INSTANTIATE_TEST_SUITE_P(Modes, GlobalIllumination,
                         ::testing::Values(rp::render::Quality::kFast,
                                           rp::render::Quality::kReference),
                         [](const ::testing::TestParamInfo<rp::render::Quality>& mode) {
                           return mode.param == rp::render::Quality::kFast ? "Fast" : "Reference";
                         });

}  // namespace
