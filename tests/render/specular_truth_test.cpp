// The specular indirect light against the path tracer on a mirror-like floor. The
// demo's room without tumblers, its floor a polished grey metal (roughness 0.15, F0 0.9: every bit
// of its indirect light is the coat's reflection), the back wall emitting (the bright object it
// mirrors), walls and ceiling black, the lamp off, one bounce in both (the floor sees the emitting
// wall directly; nothing else reflects). The floor's indirect light, real time (reference and fast
// mode) against the path-traced truth (128 x 128, 64 spp, the BRDF's own sampler), in three bands
// of the floor: far (rows 92-99: mirroring the wall's foot), middle and near (mirroring the wall's
// upper part and, at the sides, the black side walls). The reference mode's first frame has the
// reflection cone only; its second and the fast mode (24 frames) have screen-space reflections
// (they read the previous frame) where the floor's roughness allows (0.15: full weight) and the
// wall is on screen, the cone elsewhere. 128 x 128: at 64 x 64 the fast mode's 4 x 4 blocks blur
// the reflection's edges (the side walls) over a large part of the floor (+10..+13 % there).
// Tolerance: 12 % per band, 5 % over the floor; the reference mode with SSR 5 % and 3 % (the cone
// alone fails that). Measured: reference -9.6 / -3.7 / +0.6 % (floor -2.7 %), with SSR +1.0 / +0.6
// / +0.5 % (+0.6 %), fast (SSR + cone) -0.4 / +2.5 / +0.5 % (+1.0 %); the fast mode with the cone
// only -8.5 / -0.5 / +2.0 % at 64 x 64. The truth's 64-spp noise averages out over a band's 390+
// pixels. The placeholder this replaced (E_spec * irradiance / pi: the wall's light averaged over
// the whole hemisphere) fails by -66 to -81 %.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "render/renderer.h"
#include "scene/demo_scene.h"
#include "support/cl_fixture.h"
#include "truth/path_tracer.h"

namespace {

constexpr uint32_t kSize = 128;

rp::scene::SceneAssets mirror_room() {
  rp::scene::SceneAssets assets = rp::scene::make_demo_assets(rp::scene::default_asset_dir());
  rp::scene::Material& floor = assets.materials[rp::scene::demo::kFloorMaterial];
  floor.albedo = glm::vec3(0.9f);
  floor.texture = -1;
  floor.specular = rp::scene::Specular{0.15f, 0.0f, true};
  assets.materials[rp::scene::demo::kBackMaterial].emission = glm::vec3(2.0f, 1.6f, 1.2f);
  // Black walls and ceiling: nothing but the floor reflects, so one gather is all the light
  // there is, and the screen-space reflections' radiance (the hit's whole lit radiance, every
  // bounce) means the same as the one-gather truth's.
  for (uint32_t m : {rp::scene::demo::kCeilingMaterial, rp::scene::demo::kBackMaterial,
                     rp::scene::demo::kLeftMaterial, rp::scene::demo::kRightMaterial})
    assets.materials[m].albedo = glm::vec3(0.0f);
  return assets;
}

rp::scene::FrameScene mirror_frame() {
  rp::scene::FrameScene frame;
  rp::scene::add_room_instances(frame);
  frame.light.intensity = glm::vec3(0.0f);  // only the wall's light
  frame.prev_camera = frame.camera;
  return frame;
}

// Sum of the indirect light over the floor pixels of rows [y0, y1) (the floor: its albedo).
struct Band {
  uint32_t y0, y1;
  const char* name;
};
double floor_sum(const std::vector<float>& indirect, const std::vector<float>& albedo,
                 const Band& b, uint32_t* pixels = nullptr) {
  double sum = 0.0;
  uint32_t n = 0;
  for (uint32_t y = b.y0; y < b.y1; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      const size_t i = 3 * (size_t(y) * kSize + x);
      // the floor's albedo is 0.9 grey; the walls' and the ceiling's 0
      if (std::abs(albedo[i] - 0.9f) > 0.01f || std::abs(albedo[i + 2] - 0.9f) > 0.01f) continue;
      sum += indirect[i] + indirect[i + 1] + indirect[i + 2];
      ++n;
    }
  if (pixels) *pixels = n;
  return sum;
}

rp::render::LinearComponents render(rp::render::Quality quality, uint32_t frames) {
  const rp::scene::SceneAssets assets = mirror_room();
  rp::render::RenderSettings s;
  s.width = s.height = kSize;
  s.voxel_resolution = 64;
  s.quality = quality;
  s.bounces = 1;
  s.effects.taa = s.effects.bloom = s.effects.motion_blur = false;
  rp::render::Renderer r(rp::test::context(), rp::test::programs(), assets, s);
  r.set_keep_light_components(true);
  rp::scene::FrameScene frame = mirror_frame();
  for (uint32_t f = 0; f < frames; ++f) {
    frame.frame_index = f;
    r.render(frame);
  }
  rp::render::LinearComponents out;
  r.read_components(out);
  return out;
}

TEST(SpecularTruth, MirrorFloorReflectsTheBrightWallLikeThePathTracer) {
  const rp::scene::SceneAssets assets = mirror_room();
  rp::truth::PathTracer tracer(assets);
  rp::truth::PathTraceSettings ts;
  ts.width = ts.height = kSize;
  ts.spp = 64;
  ts.bounces = 1;
  ts.seed = 3;
  const rp::truth::PathTracedImage truth = tracer.render(mirror_frame(), ts);
  // one frame: the cone alone (the screen-space reflections need the previous frame); two:
  // the reference mode's per-pixel screen-space reflections, the cone where they miss
  const rp::render::LinearComponents ref = render(rp::render::Quality::kReference, 1);
  const rp::render::LinearComponents ref_ssr = render(rp::render::Quality::kReference, 2);
  const rp::render::LinearComponents fast = render(rp::render::Quality::kFast, 24);

  const Band bands[] = {{92, 100, "far"}, {100, 112, "middle"}, {112, 128, "near"}};
  double t_all = 0.0, r_all = 0.0, s_all = 0.0, f_all = 0.0;
  for (const Band& b : bands) {
    uint32_t n = 0;
    const double t = floor_sum(truth.indirect, truth.albedo, b, &n);
    const double r = floor_sum(ref.indirect, ref.albedo, b);
    const double rs = floor_sum(ref_ssr.indirect, ref_ssr.albedo, b);
    const double f = floor_sum(fast.indirect, fast.albedo, b);
    // the floor's specular layer is all of its indirect light (a metal: no diffuse base)
    EXPECT_NEAR(floor_sum(truth.specular, truth.albedo, b), t, 1e-3 * t) << b.name;
    std::printf("%-6s band (%u floor pixels): truth %.4f, reference %.4f (%+.1f%%), with SSR "
                "%.4f (%+.1f%%), fast %.4f (%+.1f%%) per pixel\n",
                b.name, n, t / n, r / n, (r / t - 1.0) * 100.0, rs / n, (rs / t - 1.0) * 100.0,
                f / n, (f / t - 1.0) * 100.0);
    ASSERT_GT(n, 200u) << b.name;
    ASSERT_GT(t / n, 0.3) << b.name << ": the floor must mirror the bright wall";
    EXPECT_NEAR(r / t, 1.0, 0.12) << "reference mode, " << b.name;
    EXPECT_NEAR(rs / t, 1.0, 0.05) << "reference mode with SSR, " << b.name;
    EXPECT_NEAR(f / t, 1.0, 0.12) << "fast mode, " << b.name;
    t_all += t;
    r_all += r;
    s_all += rs;
    f_all += f;
  }
  EXPECT_NEAR(r_all / t_all, 1.0, 0.05) << "reference mode, whole floor";
  EXPECT_NEAR(s_all / t_all, 1.0, 0.03) << "reference mode with SSR, whole floor";
  EXPECT_NEAR(f_all / t_all, 1.0, 0.05) << "fast mode, whole floor";
  std::printf("whole floor: reference %+.1f%%, with SSR %+.1f%%, fast %+.1f%%\n",
              (r_all / t_all - 1.0) * 100.0, (s_all / t_all - 1.0) * 100.0,
              (f_all / t_all - 1.0) * 100.0);
}


// Stability under motion (temporal reuse must not smear reflections). The fast mode's
// reflections are this frame's: cones traced from this frame's GBuffer, never accumulated, and
// screen-space reflections that read the previous frame's radiance at the hit (moved back by
// the hit's own velocity). With the camera moving (a dolly and pan over 8 frames, the demo with
// its tumblers, one bounce, TAA off), the last frame's specular component is compared with a
// fresh renderer's that saw only the last two frames (one frame: the history SSR needs). A
// reflection dragged along by temporal reuse would differ there by about as much as the
// reflections change from one frame to the next; the ghost metric, mean |moving - fresh| over
// the mean |frame 7 - frame 6| of the moving run, must stay below 0.2 (measured 0.001 at
// 128 x 128; the diffuse indirect light's 0.44). The diffuse indirect light, which is accumulated, differs more (the check can see
// history).
double mean_abs_diff(const std::vector<float>& a, const std::vector<float>& b) {
  double d = 0.0;
  for (size_t i = 0; i < a.size(); ++i) d += std::abs(double(a[i]) - double(b[i]));
  return d / double(a.size());
}

TEST(SpecularMotion, ReflectionsCarryNoTrailUnderCameraMotion) {
  const rp::scene::SceneAssets assets = rp::scene::make_demo_assets(rp::scene::default_asset_dir());
  rp::render::RenderSettings s;
  s.width = s.height = kSize;
  s.voxel_resolution = 64;
  s.quality = rp::render::Quality::kFast;
  s.bounces = 1;
  s.effects.taa = s.effects.bloom = s.effects.motion_blur = false;
  auto camera_at = [](uint32_t f) {
    rp::scene::Camera c;
    c.position = glm::vec3(-0.3f + 0.08f * float(f), 0.1f - 0.03f * float(f), 2.7f - 0.1f * float(f));
    c.target = glm::vec3(0.05f * float(f), -0.2f, 0.0f);
    return c;
  };
  auto frame_at = [&](uint32_t f) {
    rp::scene::FrameScene frame = rp::scene::make_demo_frame(assets, f);
    frame.camera = camera_at(f);
    frame.prev_camera = camera_at(f == 0 ? 0 : f - 1);
    return frame;
  };
  rp::render::Renderer moving(rp::test::context(), rp::test::programs(), assets, s);
  moving.set_keep_light_components(true);
  rp::render::LinearComponents prev, last, fresh;
  for (uint32_t f = 0; f < 8; ++f) {
    moving.render(frame_at(f));
    if (f == 6) moving.read_components(prev);
  }
  moving.read_components(last);
  rp::render::Renderer once(rp::test::context(), rp::test::programs(), assets, s);
  once.set_keep_light_components(true);
  once.render(frame_at(6));
  once.render(frame_at(7));
  once.read_components(fresh);

  double spec = 0.0;
  for (float v : last.specular) spec += v;
  ASSERT_GT(spec / double(last.specular.size()), 1e-3) << "the frame must show reflections";
  const double motion = mean_abs_diff(last.specular, prev.specular);
  const double ghost = mean_abs_diff(last.specular, fresh.specular);
  const double diffuse_ghost = mean_abs_diff(last.indirect, fresh.indirect) /
                               mean_abs_diff(last.indirect, prev.indirect);
  std::printf("specular: frame-to-frame change %.5f, moving vs fresh %.5f (ghost metric %.3f); "
              "diffuse indirect's ghost metric %.3f\n",
              motion, ghost, ghost / motion, diffuse_ghost);
  ASSERT_GT(motion, 1e-4) << "the reflections should move with the camera";
  EXPECT_LT(ghost / motion, 0.2) << "the reflections carry a trail of earlier frames";
  EXPECT_GT(diffuse_ghost, ghost / motion) << "the diffuse history should show more";
}

}  // namespace
