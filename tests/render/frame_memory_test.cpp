// The device memory the app's estimate counts for the image (render::frame_memory, summed from
// each pass's frame_bytes) is what the renderer holds after real frames, part by part and
// byte for byte (Renderer::frame_device_memory, the buffers' CL_MEM_SIZE): in the fast and
// reference modes, under each shadow mode, with and without the light components, at odd
// sizes, with temporal upsampling at a fixed scale and with the scale following the frame
// time. A buffer a pass adds without stating it in its frame_bytes fails here.
#include <string>

#include <gtest/gtest.h>

#include "render/frame_memory.h"
#include "render/renderer.h"
#include "scene/demo_scene.h"
#include "support/cl_fixture.h"

namespace rp::test {
namespace {

struct Case {
  const char* name;
  render::RenderSettings settings;
  bool components = false;
};

render::RenderSettings base(uint32_t width, uint32_t height) {
  render::RenderSettings s;
  s.width = width;
  s.height = height;
  s.shadow_size = 200;  // not a multiple of the raster's tile
  s.voxel_resolution = 32;
  return s;
}

std::string describe(const render::FrameMemory& m) {
  std::string text;
  for (const auto& [name, bytes] : m.parts)
    text += std::string(name) + "=" + std::to_string(bytes) + " ";
  return text;
}

void expect_frame_memory_matches(const Case& c) {
  SCOPED_TRACE(c.name);
  const scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  render::Renderer renderer(context(), programs(), assets, c.settings);
  if (c.components) renderer.set_keep_light_components(true);
  for (uint32_t i = 0; i < 2; ++i) renderer.render(scene::make_demo_frame(assets, i));
  render::FrameMemoryOptions options;
  options.light_components = c.components;
  const render::FrameMemory stated = render::frame_memory(c.settings, options);
  const render::FrameMemory held = renderer.frame_device_memory();
  for (const auto& [name, bytes] : held.parts)
    EXPECT_EQ(stated.of(name), bytes) << "part " << name;
  for (const auto& [name, bytes] : stated.parts)
    EXPECT_EQ(held.of(name), bytes) << "part " << name;
  EXPECT_EQ(stated.total(), held.total()) << "stated " << describe(stated) << "\nheld "
                                          << describe(held);
  EXPECT_GT(held.total(), uint64_t(c.settings.width) * c.settings.height * 100)
      << "fewer than 100 bytes per pixel: buffers were not counted";
}

TEST(FrameMemory, FastModeWithEveryEffectUnderPcss) {
  expect_frame_memory_matches({"fast pcss", base(161, 97)});
}

TEST(FrameMemory, ReferenceModeWithComponentsUnderVssmOnEmbree) {
  Case c{"reference vssm embree", base(203, 151), true};
  c.settings.quality = render::Quality::kReference;
  c.settings.shadows = render::ShadowMode::kVssm;
  c.settings.visibility = render::VisibilityBackend::kEmbree;
  c.settings.effects.taa = false;
  c.settings.effects.motion_blur = false;
  expect_frame_memory_matches(c);
}

TEST(FrameMemory, TemporalUpsamplingAtAFixedScaleUnderHardShadows) {
  Case c{"scale 0.7 hard", base(203, 151)};
  c.settings.render_scale = 0.7f;
  c.settings.shadows = render::ShadowMode::kHard;
  expect_frame_memory_matches(c);
}

TEST(FrameMemory, ScaleFollowingTimeWithoutEffectsUnderPcf) {
  Case c{"follows time pcf", base(97, 65)};
  c.settings.scale_follows_time = true;
  c.settings.shadows = render::ShadowMode::kPcf;
  c.settings.effects.taa = c.settings.effects.bloom = c.settings.effects.motion_blur = false;
  expect_frame_memory_matches(c);
}

TEST(FrameMemory, TakeMaxKeepsTheLargerOfEachPart) {
  render::FrameMemory a, b;
  a.add("light", 10);
  a.add("taa", 5);
  b.add("light", 7);
  b.add("bloom", 3);
  b.add("taa", 9);
  a.take_max(b);
  EXPECT_EQ(a.of("light"), 10u);
  EXPECT_EQ(a.of("taa"), 9u);
  EXPECT_EQ(a.of("bloom"), 3u);
  EXPECT_EQ(a.total(), 22u);
  a.add("light", 1);  // adds to the existing part
  EXPECT_EQ(a.of("light"), 11u);
  EXPECT_EQ(a.parts.size(), 3u);
}

}  // namespace
}  // namespace rp::test
