#include <cstdio>

#include "app/bench_report.h"
#include "app/commands.h"
#include "app/frame_source.h"
#include "app/pass_stats.h"
#include "app/png_output.h"
#include "app/progress.h"
#include "app/simulation_source.h"

namespace rp::app {

namespace {

// Visibility cost of one backend: the raster pass's device time, or Embree's host tracing plus
// the device time of uploading its buffer.
double visibility_ms(const PassStats& stats) {
  double ms = 0.0;
  for (const std::string& name : stats.pass_names())
    if (name == "visibility" || name == "visibility_host") ms += stats.pass(name).median_ms;
  return ms;
}

// Renders the simulated frames of `options` (same seed, toggles and replay every time) and
// returns the measured frames' statistics.
PassStats measure(const CommonOptions& common, const BenchOptions& options,
                  rp::cl::DeviceInfo& info) {
  SimulationFrameSource source(make_simulation_options(options.sim, common.effects));
  RenderSession session(common, options.size.width, options.size.height);
  info = session.device();
  PassStats stats;
  std::vector<uint8_t> rgba;
  ProgressBar progress("bench", size_t(options.warmup) + options.frames);
  progress.update(0);
  for (uint32_t i = 0; i < options.warmup + options.frames; ++i) {
    double frame_ms = 0.0;
    rp::cl::PassTimes times = render_next_frame(session, source, common.effects, rgba, frame_ms);
    if (i >= options.warmup) stats.add(times, frame_ms);
    progress.update(i + 1);
  }
  progress.finish();
  return stats;
}

}  // namespace

int bench_command(const CommonOptions& common, const BenchOptions& options) {
  std::printf("%ux%u, %u warm-up + %u measured frames\n", options.size.width,
              options.size.height, options.warmup, options.frames);
  rp::cl::DeviceInfo info;
  if (options.compare_visibility) {
    // Both backends render the same frames one after the other; everything but the visibility
    // buffer's source is shared.
    CommonOptions raster = common, embree = common;
    raster.visibility = render::VisibilityBackend::kRaster;
    embree.visibility = render::VisibilityBackend::kEmbree;
    PassStats r = measure(raster, options, info);
    std::printf("device %s\n", describe_device(info).c_str());
    PassStats e = measure(embree, options, info);
    std::printf("visibility backend     median ms (frame median ms)\n");
    std::printf("raster (device)      %9.3f   (%.3f)\n", visibility_ms(r), r.frame().median_ms);
    std::printf("embree (host+upload) %9.3f   (%.3f)\n", visibility_ms(e), e.frame().median_ms);
    std::printf("embree / raster      %9.2fx\n", visibility_ms(e) / visibility_ms(r));
    return 0;
  }
  PassStats stats = measure(common, options, info);
  std::printf("device %s\n", describe_device(info).c_str());
  std::fflush(stdout);

  std::printf("%s", timing_table(stats).c_str());
  std::printf("(passes: device time from OpenCL profiling events; frame: wall clock of one "
              "Renderer::render call)\n");
  if (!options.json.empty()) {
    BenchDevice device{info.name, info.type, info.platform_name, info.compute_units};
    write_text_atomic(options.json,
                      bench_json(device, options.size.width, options.size.height, stats));
    std::printf("wrote %s\n", options.json.c_str());
  }
  return 0;
}

}  // namespace rp::app
