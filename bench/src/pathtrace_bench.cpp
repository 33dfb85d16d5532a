// `bench --quality pathtraced`: seconds and Mrays/s per frame of the path tracer on the host
// (truth/path_tracer.h), the demo's simulated frames or a scene file's; no OpenCL device.
#include <atomic>
#include <cstdio>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/host_memory.h"
#include "app/interrupt.h"
#include "app/pass_stats.h"
#include "app/pathtrace_settings.h"
#include "app/png_output.h"
#include "app/progress.h"
#include "app/simulation_source.h"
#include "app/sky_input.h"
#include "bench/src/bench_commands.h"
#include "truth/path_tracer.h"

namespace rp::bench {

using app::CommonOptions;
using app::FileFrameSource;
using app::FileScene;
using app::InterruptGuard;
using app::Interrupted;
using app::ProgressBar;
using app::SimulationFrameSource;
using app::SkyLight;
using app::TimeSummary;
using app::add_sky;
using app::check_pathtrace_memory;
using app::describe_settings;
using app::describe_sky;
using app::hardware_threads;
using app::host_memory;
using app::load_sky;
using app::make_simulation_options;
using app::mrays_per_second;
using app::summarize;
using app::throw_if_interrupted;
using app::write_text_atomic;

namespace {

constexpr const char* kPathtraceBenchSchema = "rolypoly-pathtrace-bench/1";

}  // namespace

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
        make_simulation_options(options.sim, common.render.effects));
  // --json was checked by bench_command before this (the long renders).
  const uint32_t w = options.size.width, h = options.size.height;
  const scene::SceneAssets assets = file ? file->loaded.assets : app::load_demo_assets(common);
  SkyLight sky = load_sky(common.sky);  // add_sky may put suns back into the map
  auto next_frame = [&] {
    scene::FrameScene f = simulation ? simulation->next_frame() : file_source->next();
    add_sky(sky, f);
    return f;
  };
  rp::truth::PathTracer tracer(assets);
  const std::string sky_line = describe_sky(common.sky, sky);
  if (!sky_line.empty()) std::printf("%s\n", sky_line.c_str());
  const rp::truth::PathTraceSettings settings =
      app::pathtrace_settings(common, w, h, options.sim.seed);
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

}  // namespace rp::bench
