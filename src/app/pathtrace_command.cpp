// `render --quality pathtraced`: the frames of the simulated
// world, path traced on the host (truth/path_tracer.h) instead of rendered by OpenCL. No device
// is opened; the frames come from the same SimulationFrameSource as the real-time render.
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.h"
#include "app/frame_output.h"
#include "app/host_memory.h"
#include "app/host_tone_map.h"
#include "app/interrupt.h"
#include "app/pathtrace_settings.h"
#include "app/png_output.h"
#include "app/progress.h"
#include "app/scene_input.h"
#include "app/simulation_source.h"
#include "app/sky_input.h"
#include "app/video_output.h"
#include "truth/path_tracer.h"

namespace rp::app {
namespace {

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
        make_simulation_options(options.sim, common.render.effects));
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
  const scene::SceneAssets assets = file ? file->loaded.assets : load_demo_assets(common);
  SkyLight sky = load_sky(common.sky);  // add_sky may put suns back into the map
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
  const rp::truth::PathTraceSettings settings = pathtrace_settings(common, w, h, options.sim.seed);

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

}  // namespace rp::app
