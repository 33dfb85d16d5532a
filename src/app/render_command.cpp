#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>

#include "app/commands.h"
#include "app/frame_output.h"
#include "app/frame_source.h"
#include "app/interrupt.h"
#include "app/pass_stats.h"
#include "app/png_output.h"
#include "app/progress.h"
#include "app/scene_input.h"
#include "app/simulation_source.h"
#include "app/video_output.h"

namespace rp::app {
namespace {

// A replayed frame mark far ahead (`step 100000000 frame`) is minutes of simulation for one
// frame: say how far it got on stderr, at most once a second, and stop on SIGINT / SIGTERM
// (next_frame throws SimulationStopped; render_command reports the interruption).
void show_long_steps(SimulationFrameSource& source) {
  using Clock = std::chrono::steady_clock;
  source.set_step_progress([&source, last = Clock::now()](uint64_t done,
                                                          uint64_t total) mutable {
    if (InterruptGuard::interrupted()) return false;
    if (const auto now = Clock::now(); now - last >= std::chrono::seconds(1)) {
      last = now;
      std::fprintf(stderr, "rolypoly: replay: frame %u: %llu of %llu steps simulated (%.1f %%)\n",
                   source.frames_produced(), static_cast<unsigned long long>(done),
                   static_cast<unsigned long long>(total), 100.0 * double(done) / double(total));
    }
    return true;
  });
}

// The device, the kernels and the frames; `written` counts the complete PNGs as they appear.
// `simulation` or `file` (the other nullptr) gives the frames.
int render_frames(const CommonOptions& common, const RenderOptions& options,
                  SimulationFrameSource* simulation, FileScene* file, uint32_t frames,
                  VideoPipe* video, uint32_t& written) {
  const std::filesystem::path out_dir(options.out_dir);
  RenderSession session(common, options.size.width, options.size.height, options.exr,
                        file ? &file->loaded.assets : nullptr);
  std::unique_ptr<FileFrameSource> file_source;
  if (file) file_source = std::make_unique<FileFrameSource>(*file);
  std::printf("device %s\n", describe_device(session.device()).c_str());
  if (!session.sky_description().empty()) std::printf("%s\n", session.sky_description().c_str());
  if (file) {
    const render::SetupTimes& t = session.renderer().setup_times();
    std::printf("%s\nset-up: scene upload %.0f ms (mip chains %.0f, buffers %.0f), ",
                describe_file_scene(*file).c_str(), t.scene_ms, t.mips_ms,
                t.scene_ms - t.mips_ms);
    if (t.bvh_ms > 0.0) std::printf("Embree BVHs %.0f ms, ", t.bvh_ms);
    std::printf("kernels %.0f ms\n", t.kernels_ms);
  }
  std::fflush(stdout);

  PassStats stats;
  std::vector<uint8_t> rgba;
  render::LinearComponents components;
  ProgressBar progress("rendering", frames);
  progress.update(0);
  for (uint32_t i = 0; i < frames; ++i) {
    // Between frames only: every frame before i is a complete PNG (written to a temporary name
    // and renamed), and no temporary file is open. The unfinished video is removed by ~VideoPipe.
    if (InterruptGuard::interrupted()) {
      progress.finish();
      return report_interrupted(i, out_dir, options.exr ? ", each with its .exr" : "");
    }
    double frame_ms = 0.0;
    rp::cl::PassTimes times =
        simulation ? render_next_frame(session, *simulation, common.render.effects, rgba, frame_ms)
                   : session.render(file_source->next(), rgba, frame_ms);
    stats.add(times, frame_ms);
    if (options.exr) {  // before the PNG: a frame counts as written once its PNG is there
      session.read_components(components);
      write_frame_exr(out_dir / exr_file_name(i), components.width, components.height,
                      components.combined, components.direct, components.indirect,
                      components.emission, components.albedo);
    }
    write_png_atomic(out_dir / frame_file_name(i), int(session.width()), int(session.height()),
                     rgba);
    written = i + 1;
    if (video) video->write(rgba);
    progress.update(i + 1);
  }
  progress.finish();
  if (video) {
    video->finish();
    std::printf("wrote %s\n", options.video.c_str());
  }

  print_written(out_dir, frames, session.width(), session.height(), options.exr);
  std::printf("%s; device memory: about %.0f MiB (estimate)\n", describe_host_memory().c_str(),
              double(session.device_memory_estimate()) / double(1 << 20));
  std::printf("per-pass median: %s; frame %.2f ms\n", median_line(stats).c_str(),
              stats.frame().median_ms);
  return 0;
}

}  // namespace

int render_command(const CommonOptions& common, const RenderOptions& options) {
  if (common.pathtraced) return pathtrace_render_command(common, options);
  InterruptGuard interrupt;
  std::filesystem::path out_dir(options.out_dir);
  ensure_directory(out_dir);  // fail before the (slow) kernel builds if the folder is unusable
  // Cheap checks first: a malformed scene file or replay log, or a missing ffmpeg fail before
  // kernel builds.
  std::unique_ptr<SimulationFrameSource> simulation;
  std::unique_ptr<FileScene> file;
  uint32_t frames = options.frames;
  if (is_demo_scene(common.scene)) {
    simulation = std::make_unique<SimulationFrameSource>(
        make_simulation_options(options.sim, common.render.effects));
    if (!options.frames_given && simulation->replay_frames() > 0)
      frames = simulation->replay_frames();
    show_long_steps(*simulation);
  } else {
    file = std::make_unique<FileScene>(open_scene_file(common.scene));
  }
  std::unique_ptr<VideoPipe> video;
  if (!options.video.empty())
    video = std::make_unique<VideoPipe>(options.video, options.size.width, options.size.height,
                                        60);
  uint32_t written = 0;
  try {
    return render_frames(common, options, simulation.get(), file.get(), frames, video.get(),
                         written);
  } catch (const std::exception&) {
    // A signal can make the work fail before the loop sees it (LLVM deletes its temporary
    // files on SIGINT / SIGTERM, so a kernel build in progress fails; a long replay stops):
    // report the interruption, not its consequence. ~VideoPipe removes the unfinished video.
    if (!interrupt.interrupted()) throw;
    return report_interrupted(written, out_dir, options.exr ? ", each with its .exr" : "");
  }
}

}  // namespace rp::app
