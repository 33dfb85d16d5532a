// A loaded scene's real-time frame against its path-traced truth at 128x128: the test room of
// tools/gen_load_scene (a red wall, two boxes, a cube with an emission map, a floor with
// normal and metallic-roughness maps, a trellis cut out by an alpha mask, a sun, a spot and a
// point light), written as glTF and opened as a scene file like `render --scene FILE`. The
// thresholds guard what was measured on the 2-core EPYC with PoCL (fast mode, 64^3, 8 frames,
// no TAA): direct 29.6 dB (the punctual lights' light and shadows, the material maps, the
// trellis's holes and its shadow; the difference is on edges, one raster sample per pixel
// against 256 jittered ones, the trellis's bars adding most of them), final 27.8 dB,
// indirect relative L1 52.5 % and bias -6.9 % (the truth's 256 samples leave noise in the
// polished metal stripes' indirect light; the wall's indirect light is still 40 % short, the
// glossy floor's reflections too bright). The open room's indirect light is far from the
// demo box's (L1 9-11 %); the thresholds keep it from getting worse until it is tuned.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "app/host_tone_map.h"
#include "app/render_session.h"
#include "app/scene_input.h"
#include "cl/context.h"
#include "support/image_metrics.h"
#include "truth/path_tracer.h"

namespace rp::test {
namespace {

constexpr uint32_t kSize = 128;

// The test room of tools/gen_load_scene (--room): sun, spot and point light, a floor with
// normal and metallic-roughness maps, a cube with an emission map, 10 m across.
void write_room(const std::filesystem::path& file) {
  const std::string command = std::string(ROLYPOLY_GEN_LOAD_SCENE) + " '" + file.string() +
                              "' --room > /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
}

// The test room, written into a temporary folder and opened as `render --scene` opens it.
app::FileScene open_room() {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("rolypoly_room_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  write_room(dir / "room.glb");
  app::FileScene file = app::open_scene_file((dir / "room.glb").string());
  std::filesystem::remove_all(dir);
  return file;
}

// Mean |a - b| / mean b over the pixels (rgb), and mean (a - b) / mean b.
void relative_l1_bias(const std::vector<float>& a, const std::vector<float>& b, double& l1,
                      double& bias) {
  double diff = 0.0, signed_diff = 0.0, ref = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    diff += std::abs(double(a[i]) - double(b[i]));
    signed_diff += double(a[i]) - double(b[i]);
    ref += double(b[i]);
  }
  l1 = diff / ref;
  bias = signed_diff / ref;
}

TEST(FileSceneTruth, LoadedRoomMatchesItsPathTracedTruth) {
  rp::cl::ensure_pocl_cache_dir();
  const app::FileScene file = open_room();
  ASSERT_EQ(file.loaded.lights.size(), 3u);

  truth::PathTraceSettings settings;
  settings.width = settings.height = kSize;
  settings.spp = 256;
  settings.bounces = 8;
  truth::PathTracer tracer(file.loaded.assets);
  app::FileFrameSource truth_source(file);
  const truth::PathTracedImage truth = tracer.render(truth_source.next(), settings);

  app::CommonOptions common;
  common.render.effects.taa = false;  // one frame against the truth: no history to converge
  common.render.effects.bloom = false;
  common.render.effects.motion_blur = false;
  app::RenderSession session(common, kSize, kSize, true, &file.loaded.assets);
  app::FileFrameSource source(file);
  std::vector<uint8_t> rgba;
  double ms = 0.0;
  render::LinearComponents rt;
  for (int i = 0; i < 8; ++i) session.render(source.next(), rgba, ms);  // bounces converge
  session.read_components(rt);

  std::vector<uint8_t> rt_direct, pt_direct;
  app::encode_rgba8(rt.direct, true, rt_direct);
  app::encode_rgba8(truth.direct, true, pt_direct);
  const double direct_psnr = psnr_rgb8(rt_direct, pt_direct);
  std::vector<uint8_t> rt_final, pt_final;
  app::encode_rgba8(rt.combined, true, rt_final);
  app::encode_rgba8(truth.combined, true, pt_final);
  const double final_psnr = psnr_rgb8(rt_final, pt_final);
  double l1 = 0.0, bias = 0.0;
  relative_l1_bias(rt.indirect, truth.indirect, l1, bias);
  RecordProperty("direct_psnr", std::to_string(direct_psnr));
  RecordProperty("final_psnr", std::to_string(final_psnr));
  std::printf("loaded room vs truth: direct %.2f dB, final %.2f dB, indirect L1 %.1f %%, "
              "bias %+.1f %%\n", direct_psnr, final_psnr, 100.0 * l1, 100.0 * bias);
  EXPECT_GE(direct_psnr, 29.0);
  EXPECT_GE(final_psnr, 27.0);
  EXPECT_LE(l1, 0.62);
  EXPECT_LE(std::abs(bias), 0.30);
}

// The lights' shadow views are counted in the device memory estimate before they are drawn:
// the room's sun and spot take two planes of 256^2 floats each, its point light six faces of
// two planes at half the size, all after the lamp's two planes in one depth buffer.
TEST(FileSceneTruth, TheLightsShadowViewsAreCountedInTheDeviceMemory) {
  rp::cl::ensure_pocl_cache_dir();
  const app::FileScene file = open_room();
  ASSERT_EQ(file.loaded.lights.size(), 3u);

  app::CommonOptions common;
  common.render.shadow_size = 256;
  app::RenderSession session(common, 32, 32, false, &file.loaded.assets);
  const uint64_t before = session.device_memory_estimate();
  app::FileFrameSource source(file);
  std::vector<uint8_t> rgba;
  double ms = 0.0;
  session.render(source.next(), rgba, ms);
  const uint64_t lamp = 2 * 256 * 256, views = 2 * (2 * 256 * 256) + 6 * 2 * (128 * 128);
  EXPECT_EQ(session.renderer().shadow_map().depth_floats, lamp + views);
  EXPECT_EQ(session.device_memory_estimate() - before, 4 * views);
  session.render(source.next(), rgba, ms);  // counted once
  EXPECT_EQ(session.device_memory_estimate() - before, 4 * views);
}

}  // namespace
}  // namespace rp::test
