// `render --quality pathtraced` and `bench --quality pathtraced`: the frames of the simulated
// world, path traced on the host (truth/path_tracer.h) instead of rendered by OpenCL. No device
// is opened; the frames come from the same SimulationFrameSource as the real-time render.
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/frame_output.h"
#include "app/host_memory.h"
#include "app/host_tone_map.h"
#include "app/interrupt.h"
#include "bench/src/pass_stats.h"
#include "app/png_output.h"
#include "app/progress.h"
#include "app/scene_input.h"
#include "app/simulation_source.h"
#include "app/sky_input.h"
#include "app/video_output.h"
#include "scene/demo_scene.h"
#include "truth/path_tracer.h"

namespace rp::app {
namespace {

constexpr const char* kPathtraceBenchSchema = "rolypoly-pathtrace-bench/1";

rp::truth::PathTraceSettings settings_for(const CommonOptions& common, uint32_t width,
                                          uint32_t height, uint64_t seed) {
  rp::truth::PathTraceSettings s;
  s.width = width;
  s.height = height;
  s.spp = common.spp;
  s.bounces = common.bounces;
  s.seed = seed;  // the same streams every frame: a still scene gives the same image
  s.threads = 0;  // every hardware thread
  s.lamp = common.area_lamp ? rp::truth::LampModel::kArea : rp::truth::LampModel::kPoint;
  return s;
}

// What PathTraceSettings::threads = 0 means, for the report.
unsigned hardware_threads() { return std::max(1u, std::thread::hardware_concurrency()); }

scene::SceneAssets load_assets(const CommonOptions& common) {
  return scene::make_demo_assets(common.asset_dir.empty() ? scene::default_asset_dir()
                                                          : common.asset_dir);
}

// "360x360, 1024 spp, 1 bounce" (+ ", area lamp")
std::string describe_settings(const rp::truth::PathTraceSettings& s) {
  char text[112];
  std::snprintf(text, sizeof text, "%ux%u, %u spp, %u bounce%s%s", s.width, s.height, s.spp,
                s.bounces, s.bounces == 1 ? "" : "s",
                s.lamp == rp::truth::LampModel::kArea ? ", area lamp" : "");
  return text;
}

double mrays_per_second(uint64_t rays, double seconds) {
  return seconds > 0.0 ? double(rays) / seconds * 1e-6 : 0.0;
}

// The 8-bit image of `view`: final = combined, direct / indirect tone mapped like the final
// image, albedo sRGB-encoded without tone map (as the renderer's debug views).
void encode_view(const rp::truth::PathTracedImage& image, passes::DebugView view,
                 std::vector<uint8_t>& rgba) {
  switch (view) {
    case passes::DebugView::kDirect: encode_rgba8(image.direct, true, rgba); return;
    case passes::DebugView::kIndirect: encode_rgba8(image.indirect, true, rgba); return;
    case passes::DebugView::kAlbedo: encode_rgba8(image.albedo, false, rgba); return;
    default: encode_rgba8(image.combined, true, rgba); return;  // parse_cli allows no other
  }
}

}  // namespace

int pathtrace_render_command(const CommonOptions& common, const RenderOptions& options) {
  InterruptGuard interrupt;
  // Before anything is loaded or allocated: a size the host cannot hold fails at once.
  check_pathtrace_memory(options.size.width, options.size.height, host_memory());
  const std::filesystem::path out_dir(options.out_dir);
  ensure_directory(out_dir);
  // Cheap checks first (as the real-time render): the scene file or the replay log, ffmpeg,
  // then the assets.
  std::unique_ptr<FileScene> file;
  std::unique_ptr<FileFrameSource> file_source;
  std::unique_ptr<SimulationFrameSource> simulation;
  if (is_demo_scene(common.scene)) {
    simulation = std::make_unique<SimulationFrameSource>(
        make_simulation_options(options.sim, common.effects));
  } else {
    file = std::make_unique<FileScene>(open_scene_file(common.scene));
    file_source = std::make_unique<FileFrameSource>(*file);
  }
  uint32_t frames = options.frames;
  if (!options.frames_given && simulation && simulation->replay_frames() > 0)
    frames = simulation->replay_frames();
  const uint32_t w = options.size.width, h = options.size.height;
  std::unique_ptr<VideoPipe> video;
  if (!options.video.empty()) video = std::make_unique<VideoPipe>(options.video, w, h, 60);
  const scene::SceneAssets assets = file ? file->loaded.assets : load_assets(common);
  const SkyLight sky = load_sky(common.sky);
  auto next_frame = [&] {
    scene::FrameScene f = simulation ? simulation->next_frame() : file_source->next();
    add_sky(sky, f);
    return f;
  };
  rp::truth::PathTracer tracer(assets);
  if (file)
    std::printf("%s\nset-up: path tracer BVHs and textures %.0f ms\n",
                describe_file_scene(*file).c_str(), tracer.build_ms());
  if (const std::string line = describe_sky(common.sky, sky); !line.empty())
    std::printf("%s\n", line.c_str());
  const rp::truth::PathTraceSettings settings = settings_for(common, w, h, options.sim.seed);

  // The tracer calls `progress` from this thread about ten times a second: the place to turn
  // a Ctrl-C (a flag set by the signal handler) into the tracer's cancel flag.
  std::atomic<bool> cancel{false};
  ProgressBar bar("path tracing", size_t(frames) * h);
  uint32_t frame = 0;
  const rp::truth::ProgressFn progress = [&](uint32_t rows_done, uint32_t) {
    if (InterruptGuard::interrupted()) cancel = true;
    bar.update(size_t(frame) * h + rows_done);
  };
  double seconds = 0.0;
  uint64_t rays = 0;
  std::vector<uint8_t> rgba;
  bar.update(0);
  for (; frame < frames; ++frame) {
    if (interrupt.interrupted()) break;
    rp::truth::PathTracedImage image;
    try {
      image = tracer.render(next_frame(), settings, progress, &cancel);
    } catch (const rp::truth::PathTracer::Cancelled&) {
      break;  // nothing of this frame was written
    }
    seconds += image.seconds;
    rays += image.rays;
    write_frame_exr(out_dir / exr_file_name(frame), image.width, image.height, image.combined,
                    image.direct, image.indirect, image.emission, image.albedo);
    encode_view(image, common.view.view, rgba);
    write_png_atomic(out_dir / frame_file_name(frame), int(w), int(h), rgba);
    if (video) video->write(rgba);
    bar.update(size_t(frame + 1) * h);
  }
  bar.finish();
  if (frame < frames) return report_interrupted(frame, out_dir, ", each with its .exr");
  if (video) {
    video->finish();
    std::printf("wrote %s\n", options.video.c_str());
  }
  std::printf("path traced %s%s: %.*f s, %.1f Mrays/s (%u threads)\n",
              describe_settings(settings).c_str(),
              frames == 1 ? "" : (", " + std::to_string(frames) + " frames").c_str(),
              seconds < 10.0 ? 2 : 1, seconds, mrays_per_second(rays, seconds),
              hardware_threads());
  print_written(out_dir, frames, w, h, true);
  return 0;
}

int pathtrace_bench_command(const CommonOptions& common, const BenchOptions& options,
                            const FileScene* file, const nlohmann::ordered_json* scene_file) {
  InterruptGuard interrupt;
  check_pathtrace_memory(options.size.width, options.size.height, host_memory());
  std::unique_ptr<SimulationFrameSource> simulation;
  std::unique_ptr<FileFrameSource> file_source;
  if (file)
    file_source = std::make_unique<FileFrameSource>(*file);
  else
    simulation = std::make_unique<SimulationFrameSource>(
        make_simulation_options(options.sim, common.effects));
  // --json was checked by bench_command before this (the long renders).
  const uint32_t w = options.size.width, h = options.size.height;
  const scene::SceneAssets assets = file ? file->loaded.assets : load_assets(common);
  const SkyLight sky = load_sky(common.sky);
  auto next_frame = [&] {
    scene::FrameScene f = simulation ? simulation->next_frame() : file_source->next();
    add_sky(sky, f);
    return f;
  };
  rp::truth::PathTracer tracer(assets);
  const std::string sky_line = describe_sky(common.sky, sky);
  if (!sky_line.empty()) std::printf("%s\n", sky_line.c_str());
  const rp::truth::PathTraceSettings settings = settings_for(common, w, h, options.sim.seed);
  const uint32_t total = options.warmup + options.frames;
  std::printf("bench: path traced %s, seed %llu, %u warm-up + %u measured frames, %u threads\n",
              describe_settings(settings).c_str(),
              static_cast<unsigned long long>(options.sim.seed), options.warmup, options.frames,
              hardware_threads());
  std::fflush(stdout);

  ProgressBar bar("path tracing", size_t(total) * h);
  uint32_t frame = 0;
  // A signal stops the frame being traced; nothing is written (cli.cpp reports Interrupted).
  std::atomic<bool> cancel{false};
  const rp::truth::ProgressFn progress = [&](uint32_t rows_done, uint32_t) {
    if (InterruptGuard::interrupted()) cancel = true;
    bar.update(size_t(frame) * h + rows_done);
  };
  std::vector<double> seconds, mrays;
  std::vector<uint64_t> rays;
  bar.update(0);
  for (; frame < total; ++frame) {
    throw_if_interrupted("while path tracing; no file was written");
    rp::truth::PathTracedImage image;
    try {
      image = tracer.render(next_frame(), settings, progress, &cancel);
    } catch (const rp::truth::PathTracer::Cancelled&) {
      throw Interrupted("while path tracing; no file was written");
    }
    seconds.push_back(image.seconds);
    rays.push_back(image.rays);
    mrays.push_back(mrays_per_second(image.rays, image.seconds));
    bar.update(size_t(frame + 1) * h);
  }
  bar.finish();

  std::printf("frame        seconds    Mrays/s\n");
  for (uint32_t i = 0; i < total; ++i)
    std::printf("%5u%s %10.3f %10.2f\n", i, i < options.warmup ? " (w)" : "    ", seconds[i],
                mrays[i]);
  const std::vector<double> measured_s(seconds.begin() + options.warmup, seconds.end());
  const std::vector<double> measured_m(mrays.begin() + options.warmup, mrays.end());
  const TimeSummary s = summarize(measured_s), m = summarize(measured_m);
  std::printf("median    %10.3f %10.2f   (min %.3f s, max %.3f s; (w) = warm-up)\n",
              s.median_ms, m.median_ms, s.min_ms, s.max_ms);

  if (!options.json.empty()) {
    nlohmann::ordered_json j;
    j["schema"] = kPathtraceBenchSchema;
    j["command"] = options.command_line;
    if (scene_file) {
      j["scene"] = "file";
      j["scene_file"] = *scene_file;
    }
    j["size"] = {w, h};
    j["spp"] = settings.spp;
    j["bounces"] = settings.bounces;
    j["lamp"] = settings.lamp == rp::truth::LampModel::kArea ? "area" : "point";
    if (!sky_line.empty()) j["sky"] = sky_line;
    j["seed"] = options.sim.seed;
    j["threads"] = hardware_threads();
    j["warmup"] = options.warmup;
    j["frames"] = options.frames;
    nlohmann::ordered_json runs = nlohmann::ordered_json::array();
    for (uint32_t i = options.warmup; i < total; ++i)
      runs.push_back({{"frame", i},
                      {"seconds", seconds[i]},
                      {"rays", rays[i]},
                      {"mrays_per_s", mrays[i]}});
    j["runs"] = runs;
    j["median"] = {{"seconds", s.median_ms}, {"mrays_per_s", m.median_ms}};
    write_text_atomic(options.json, j.dump(2) + "\n");
    std::printf("wrote %s\n", options.json.c_str());
  }
  return 0;
}

}  // namespace rp::app
