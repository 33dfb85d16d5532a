#include <csignal>
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
namespace {

// Set by SIGINT / SIGTERM; the render loop checks it between frames. A signal handler can only
// talk to the program through a variable like this, hence the one file-local global. The
// handler does nothing else, and SA_RESETHAND makes a second Ctrl-C kill at once (e.g. while
// kernels build).
volatile std::sig_atomic_t g_interrupted = 0;

extern "C" void on_interrupt(int) { g_interrupted = 1; }

// Installs the handler for one render and restores the previous ones afterwards.
class InterruptGuard {
 public:
  InterruptGuard() {
    g_interrupted = 0;
    struct sigaction action {};
    action.sa_handler = on_interrupt;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART | SA_RESETHAND;  // restart interrupted writes
    sigaction(SIGINT, &action, &old_int_);
    sigaction(SIGTERM, &action, &old_term_);
  }
  ~InterruptGuard() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  bool interrupted() const { return g_interrupted != 0; }

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

// Exit code of a process ended by SIGINT, as shells report it (128 + 2).
constexpr int kInterruptedExitCode = 130;

}  // namespace

int render_command(const CommonOptions& common, const RenderOptions& options) {
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

  RenderSession session(common, options.size.width, options.size.height);
  std::printf("device %s\n", describe_device(session.device()).c_str());
  std::fflush(stdout);

  PassStats stats;
  std::vector<uint8_t> rgba;
  ProgressBar progress("rendering", frames);
  progress.update(0);
  for (uint32_t i = 0; i < frames; ++i) {
    // Between frames only: every frame before i is a complete PNG (written to a temporary name
    // and renamed), and no temporary file is open. The unfinished video is removed by ~VideoPipe.
    if (interrupt.interrupted()) {
      progress.finish();
      std::fflush(stdout);
      std::string done;  // appends, not operator+ chains: GCC 12 -Wrestrict false positive
      if (i == 0) {
        done = "no frame was written";
      } else {
        if (i > 1) {
          done += frame_file_name(0);
          done += " ... ";
        }
        done += frame_file_name(i - 1);
        done += " in ";
        done += out_dir.string();
        done += i == 1 ? " is complete" : " are complete";
      }
      std::fprintf(stderr, "rolypoly: error: interrupted after %u frame%s (%s)\n", i,
                   i == 1 ? "" : "s", done.c_str());
      return kInterruptedExitCode;
    }
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
