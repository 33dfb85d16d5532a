// The path tracer's bench on a scene file (see pathtrace_file_bench.h).
#include "bench/src/pathtrace_file_bench.h"

#include <algorithm>
#include <cstdio>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/png_output.h"
#include "app/progress.h"
#include "bench/src/pass_stats.h"
#include "bench/src/scene_file_facts.h"
#include "truth/path_tracer.h"

namespace rp::app {

int pathtrace_file_bench_command(const CommonOptions& common, const BenchOptions& options,
                                 const FileScene& scene, const SceneFileFacts& facts) {
  // --json was checked by bench_command before this (the long renders).
  const uint32_t w = options.size.width, h = options.size.height;
  truth::PathTraceSettings settings;
  settings.width = w;
  settings.height = h;
  settings.spp = common.spp;
  settings.bounces = common.bounces;
  settings.seed = options.sim.seed;  // the same streams every frame: the same image
  settings.threads = 0;              // every hardware thread
  settings.lamp = common.area_lamp ? truth::LampModel::kArea : truth::LampModel::kPoint;
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  truth::PathTracer tracer(scene.loaded.assets);
  FileFrameSource source(scene);
  const uint32_t total = options.warmup + options.frames;
  std::printf("bench: path traced %ux%u, %u spp, %u bounce%s%s, %u warm-up + %u measured "
              "frames, %u threads\n",
              w, h, settings.spp, settings.bounces, settings.bounces == 1 ? "" : "s",
              common.area_lamp ? ", area lamp" : "", options.warmup, options.frames, threads);
  std::fflush(stdout);

  ProgressBar bar("path tracing", size_t(total) * h);
  uint32_t frame = 0;
  const truth::ProgressFn progress = [&](uint32_t rows_done, uint32_t) {
    bar.update(size_t(frame) * h + rows_done);
  };
  std::vector<double> seconds, mrays;
  std::vector<uint64_t> rays;
  bar.update(0);
  for (; frame < total; ++frame) {
    const truth::PathTracedImage image = tracer.render(source.next(), settings, progress);
    seconds.push_back(image.seconds);
    rays.push_back(image.rays);
    mrays.push_back(image.rays_per_second() * 1e-6);
    bar.update(size_t(frame + 1) * h);
  }
  bar.finish();

  std::printf("frame        seconds    Mrays/s\n");
  for (uint32_t i = 0; i < total; ++i)
    std::printf("%5u%s %10.3f %10.2f\n", i, i < options.warmup ? " (w)" : "    ", seconds[i],
                mrays[i]);
  const std::vector<double> measured_s(seconds.begin() + options.warmup, seconds.end());
  const std::vector<double> measured_m(mrays.begin() + options.warmup, mrays.end());
  // summarize() names its fields in ms; here they hold seconds and Mrays/s.
  const TimeSummary s = summarize(measured_s), m = summarize(measured_m);
  std::printf("median    %10.3f %10.2f   (min %.3f s, max %.3f s; (w) = warm-up)\n",
              s.median_ms, m.median_ms, s.min_ms, s.max_ms);

  if (!options.json.empty()) {
    nlohmann::ordered_json j;
    j["schema"] = "rolypoly-pathtrace-bench/1";
    j["command"] = options.command_line;
    j["scene"] = "file";
    j["scene_file"] = scene_file_json<nlohmann::ordered_json>(facts);
    j["size"] = {w, h};
    j["spp"] = settings.spp;
    j["bounces"] = settings.bounces;
    j["lamp"] = common.area_lamp ? "area" : "point";
    j["seed"] = settings.seed;
    j["threads"] = threads;
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
