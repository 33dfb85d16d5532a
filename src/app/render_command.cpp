#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/bench_report.h"
#include "app/commands.h"
#include "app/frame_output.h"
#include "app/frame_source.h"
#include "app/interrupt.h"
#include "app/pass_stats.h"
#include "app/png_output.h"
#include "app/progress.h"
#include "app/simulation_source.h"
#include "app/video_output.h"

namespace rp::app {

int render_command(const CommonOptions& common, const RenderOptions& options) {
  if (common.pathtraced) return pathtrace_render_command(common, options);
  InterruptGuard interrupt;
  std::filesystem::path out_dir(options.out_dir);
  ensure_directory(out_dir);  // fail before the (slow) kernel builds if the folder is unusable
  // Cheap checks first: a malformed replay log or a missing ffmpeg fail before kernel builds.
  SimulationFrameSource source(make_simulation_options(options.sim, common.effects));
  uint32_t frames = options.frames;
  if (!options.frames_given && source.replay_frames() > 0) frames = source.replay_frames();
  std::unique_ptr<VideoPipe> video;
  if (!options.video.empty())
    video = std::make_unique<VideoPipe>(options.video, options.size.width, options.size.height,
                                        60);

  RenderSession session(common, options.size.width, options.size.height, options.exr);
  std::printf("device %s\n", describe_device(session.device()).c_str());
  std::fflush(stdout);

  PassStats stats;
  std::vector<uint8_t> rgba;
  render::LinearComponents components;
  ProgressBar progress("rendering", frames);
  progress.update(0);
  for (uint32_t i = 0; i < frames; ++i) {
    // Between frames only: every frame before i is a complete PNG (written to a temporary name
    // and renamed), and no temporary file is open. The unfinished video is removed by ~VideoPipe.
    if (interrupt.interrupted()) {
      progress.finish();
      return report_interrupted(i, out_dir, options.exr ? ", each with its .exr" : "");
    }
    double frame_ms = 0.0;
    rp::cl::PassTimes times = render_next_frame(session, source, common.effects, rgba, frame_ms);
    stats.add(times, frame_ms);
    if (options.exr) {  // before the PNG: a frame counts as written once its PNG is there
      session.read_components(components);
      write_frame_exr(out_dir / exr_file_name(i), components.width, components.height,
                      components.combined, components.direct, components.indirect,
                      components.emission, components.albedo);
    }
    write_png_atomic(out_dir / frame_file_name(i), int(session.width()), int(session.height()),
                     rgba);
    if (video) video->write(rgba);
    progress.update(i + 1);
  }
  progress.finish();
  if (video) {
    video->finish();
    std::printf("wrote %s\n", options.video.c_str());
  }

  print_written(out_dir, frames, session.width(), session.height(), options.exr);
  std::printf("per-pass median: %s; frame %.2f ms\n", median_line(stats).c_str(),
              stats.frame().median_ms);
  return 0;
}

}  // namespace rp::app
