#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/bench_report.h"
#include "app/commands.h"
#include "app/frame_source.h"
#include "app/pass_stats.h"
#include "app/png_output.h"
#include "app/progress.h"
#include "app/simulation_source.h"
#include "app/video_output.h"

namespace rp::app {

int render_command(const CommonOptions& common, const RenderOptions& options) {
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

  RenderSession session(common, options.size.width, options.size.height);
  std::printf("device %s\n", describe_device(session.device()).c_str());
  std::fflush(stdout);

  PassStats stats;
  std::vector<uint8_t> rgba;
  ProgressBar progress("rendering", frames);
  progress.update(0);
  for (uint32_t i = 0; i < frames; ++i) {
    double frame_ms = 0.0;
    rp::cl::PassTimes times = render_next_frame(session, source, common.effects, rgba, frame_ms);
    stats.add(times, frame_ms);
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

  std::string first = (out_dir / frame_file_name(0)).string();
  if (frames == 1)
    std::printf("wrote %s (%ux%u)\n", first.c_str(), session.width(), session.height());
  else
    std::printf("wrote %u frames (%ux%u): %s ... %s\n", frames, session.width(),
                session.height(), first.c_str(),
                frame_file_name(frames - 1).c_str());
  std::printf("per-pass median: %s; frame %.2f ms\n", median_line(stats).c_str(),
              stats.frame().median_ms);
  return 0;
}

}  // namespace rp::app
