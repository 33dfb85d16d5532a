// Timing of the PRT transfer on the demo room (box, lamp cap, five tumblers at rest: 6833
// vertices) and the atrium. Disabled by default (seconds to minutes); run with
//   test_truth --gtest_also_run_disabled_tests --gtest_filter='PrtTiming.*'
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>

#include "scene/atrium.h"
#include "scene/demo_scene.h"
#include "truth/prt_transfer.h"

namespace rp::truth {
namespace {

TEST(PrtTiming, DISABLED_DemoRoomAndTumblers) {
  const scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  const scene::FrameScene frame = scene::make_demo_frame(assets);
  struct Case {
    PrtKind kind;
    int bands;
    uint32_t samples, bounces;
    uint32_t matrix_mb = 1024;
  };
  const Case cases[] = {
      {PrtKind::kUnshadowed, 5, 0, 0},         {PrtKind::kShadowed, 3, 512, 0},
      {PrtKind::kShadowed, 5, 512, 0},         {PrtKind::kInterreflected, 5, 512, 1},
      {PrtKind::kInterreflected, 5, 512, 3},   {PrtKind::kInterreflected, 5, 512, 10},
      {PrtKind::kInterreflected, 5, 512, 3, 0},  // no memory for the bounce matrix
      {PrtKind::kInterreflected, 5, 1024, 3}};
  for (const Case& c : cases) {
    PrtSettings s;
    s.kind = c.kind;
    s.bands = c.bands;
    s.samples = c.samples;
    s.bounces = c.bounces;
    s.bounce_matrix_mb = c.matrix_mb;
    const auto t0 = std::chrono::steady_clock::now();
    const PrtTransfer t = compute_prt_transfer(assets, frame, s);
    const double sec =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%s bands %d samples %u bounces %u%s: %u vertices, %.2f s (%.2f Mrays/s)\n",
                name_of(c.kind).data(), c.bands, c.samples, c.bounces,
                c.matrix_mb ? "" : " (rays again per bounce)", t.vertex_count(), sec,
                double(t.vertex_count()) * c.samples / sec * 1e-6);
  }
}

TEST(PrtTiming, DISABLED_Atrium) {
  const scene::Atrium atrium = scene::make_atrium();
  PrtSettings s;
  s.kind = PrtKind::kShadowed;
  s.bands = 3;
  s.samples = 256;
  const auto t0 = std::chrono::steady_clock::now();
  const PrtTransfer t = compute_prt_transfer(atrium.assets, atrium.frame, s);
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("atrium shadowed bands 3 samples 256: %u vertices, %.2f s (%.2f Mrays/s)\n",
              t.vertex_count(), sec, double(t.vertex_count()) * s.samples / sec * 1e-6);
}

}  // namespace
}  // namespace rp::truth
