#include <cstdio>

#include "app/bench_report.h"
#include "app/commands.h"
#include "app/frame_source.h"
#include "app/pass_stats.h"
#include "app/png_output.h"
#include "app/progress.h"
#include "app/simulation_source.h"

namespace rp::app {

int bench_command(const CommonOptions& common, const BenchOptions& options) {
  SimulationFrameSource source(make_simulation_options(options.sim, common.effects));
  RenderSession session(common, options.size.width, options.size.height);
  const rp::cl::DeviceInfo& info = session.device();
  std::printf("device %s\n", describe_device(info).c_str());
  std::printf("%ux%u, %u warm-up + %u measured frames\n", session.width(), session.height(),
              options.warmup, options.frames);
  std::fflush(stdout);

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

  std::printf("%s", timing_table(stats).c_str());
  std::printf("(passes: device time from OpenCL profiling events; frame: wall clock of one "
              "Renderer::render call)\n");
  if (!options.json.empty()) {
    BenchDevice device{info.name, info.type, info.platform_name, info.compute_units};
    write_text_atomic(options.json,
                      bench_json(device, session.width(), session.height(), stats));
    std::printf("wrote %s\n", options.json.c_str());
  }
  return 0;
}

}  // namespace rp::app
