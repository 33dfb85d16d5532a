// Loader, exporter and renderer agree: the demo's first frame written by `rolypoly export`
// (scene/gltf_export.h) and opened again as a scene file (scene/gltf_loader.h, app/scene_input.h)
// renders the same image as the built-in demo, in both real-time quality modes and in the path
// tracer, at 128x128.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <vector>

#include "app/commands.h"
#include "app/host_tone_map.h"
#include "app/render_session.h"
#include "app/scene_input.h"
#include "app/simulation_source.h"
#include "cl/context.h"
#include "scene/demo_scene.h"
#include "scene/gltf_export.h"
#include "support/image_metrics.h"
#include "truth/path_tracer.h"

namespace rp::test {
namespace {

constexpr uint32_t kSize = 128;
constexpr double kMinPsnr = 45.0;  // dB over the 8-bit final image

struct Exported {
  std::filesystem::path dir, file;
  Exported() {
    dir = std::filesystem::temp_directory_path() /
          ("rolypoly_round_trip_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    file = dir / "demo.glb";
  }
  ~Exported() {
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
  }
};

scene::FrameScene demo_first_frame() {
  app::SimulationFrameSource source(app::make_simulation_options(app::SimulationArgs{}, render::Effects{}));
  return source.next_frame();
}

void export_demo(const std::filesystem::path& file) {
  const scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  scene::ExportOptions options;
  options.volume = scene::Bounds{glm::vec3(-1.0f), glm::vec3(1.0f)};
  scene::export_gltf(assets, demo_first_frame(), file, options);
}

std::vector<uint8_t> render_realtime(render::Quality quality, const app::FileScene* file) {
  app::CommonOptions common;
  common.render.quality = quality;
  std::vector<uint8_t> rgba;
  double ms = 0.0;
  if (file) {
    app::RenderSession session(common, kSize, kSize, false, &file->loaded.assets);
    app::FileFrameSource source(*file);
    session.render(source.next(), rgba, ms);
  } else {
    app::RenderSession session(common, kSize, kSize);
    session.render(demo_first_frame(), rgba, ms);
  }
  return rgba;
}

TEST(GltfRoundTrip, ExportedDemoRendersLikeTheBuiltInDemoInBothRealTimeModes) {
  rp::cl::ensure_pocl_cache_dir();
  Exported exported;
  export_demo(exported.file);
  const app::FileScene file = app::open_scene_file(exported.file.string());
  EXPECT_TRUE(file.loaded.lamp.has_value());
  EXPECT_FLOAT_EQ(file.fit.scale, 1.0f);
  for (render::Quality q : {render::Quality::kFast, render::Quality::kReference}) {
    const double psnr = psnr_rgb8(render_realtime(q, nullptr), render_realtime(q, &file));
    EXPECT_GE(psnr, kMinPsnr) << (q == render::Quality::kFast ? "fast" : "reference");
  }
}

TEST(GltfRoundTrip, ExportedDemoPathTracesLikeTheBuiltInDemo) {
  Exported exported;
  export_demo(exported.file);
  const app::FileScene file = app::open_scene_file(exported.file.string());
  truth::PathTraceSettings settings;
  settings.width = settings.height = kSize;
  settings.spp = 8;
  settings.bounces = 2;
  const scene::SceneAssets demo = scene::make_demo_assets(scene::default_asset_dir());
  truth::PathTracer demo_tracer(demo), file_tracer(file.loaded.assets);
  const truth::PathTracedImage a = demo_tracer.render(demo_first_frame(), settings);
  app::FileFrameSource source(file);
  const truth::PathTracedImage b = file_tracer.render(source.next(), settings);
  // Same random streams, same surfaces: the final images agree up to float rounding of the
  // transformed geometry (a differently rounded hit can send one path elsewhere).
  std::vector<uint8_t> demo_rgba, file_rgba;
  app::encode_rgba8(a.combined, true, demo_rgba);
  app::encode_rgba8(b.combined, true, file_rgba);
  const double psnr = psnr_rgb8(demo_rgba, file_rgba);
  EXPECT_GE(psnr, kMinPsnr);
}

}  // namespace
}  // namespace rp::test
