#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "app/commands.h"
#include "app/fly_camera.h"
#include "app/frame_source.h"
#include "app/interrupt.h"
#include "app/pass_stats.h"
#include "app/png_output.h"
#include "app/scene_input.h"
#include "app/simulation_source.h"
#include "display/display_lost.h"
#include "display/window.h"
#include "io/output_path.h"

namespace rp::app {
namespace {

constexpr double kTitleIntervalMs = 500.0;  // window title refresh: about twice per second
constexpr char kShadowsKey = 'H';  // cycles --shadows: hard, pcf, pcss, vssm (not recorded)
constexpr char kSkyTurnKey = 'O';  // turns --env / --sky clear 15 degrees about +y (not recorded)
constexpr float kSkyTurnDeg = 15.0f;

// "rolypoly | 4.1 fps | shadows pcss | visibility 3.20 ms, gbuffer 1.10 ms, ..." (means over
// the interval); a debug view is named after the shadows: "... | view voxels 2 +x | ...".
// `label`: "rolypoly", or "rolypoly | FILE" for a scene file; `extra`: after the frame rate
// (" speed 2.5 m/s |") or "".
std::string title_text(const std::string& label, const std::string& extra,
                       const PassStats& interval, double elapsed_ms,
                       const passes::DebugViewSettings& view, render::ShadowMode shadows) {
  char fps[64];
  std::snprintf(fps, sizeof fps, " | %.1f fps |",
                elapsed_ms > 0.0 ? 1000.0 * double(interval.frames()) / elapsed_ms : 0.0);
  std::string title = label;
  title += fps;
  title += extra;
  title += " shadows ";
  title += name_of(shadows);
  title += " |";
  if (view.view != passes::DebugView::kFinal) {
    title += " view ";
    title += name_of(view.view);
    if (view.view == passes::DebugView::kVoxels) {
      title += ' ';  // appends, not operator+ chains: GCC 12 -Wrestrict false positive
      title += std::to_string(view.level);
      if (view.level > 0) {
        title += ' ';
        title += passes::voxel_dir_name(view.dir);
      }
    }
    title += " |";
  }
  std::map<std::string, double> means = interval.pass_means();
  const char* sep = " ";
  for (const std::string& name : interval.pass_names()) {
    char part[96];
    std::snprintf(part, sizeof part, "%s%s %.1f ms", sep, name.c_str(), means[name]);
    title += part;
    sep = ", ";
  }
  return title;
}

std::unique_ptr<display::Window> open_window(const ImageSize& size, const std::string& title) {
  try {
    return std::make_unique<display::Window>(int(size.width), int(size.height), title);
  } catch (const display::DisplayError& e) {
    throw display::DisplayError(std::string("cannot open a window: ") + e.what() +
                                ". Use `rolypoly render --out DIR` to render PNG files "
                                "without a display.");
  }
}

// The simulation's input for a window event; none for the fly camera's (Look, Scroll, Home).
std::optional<scene::InputEvent> to_input(const display::WindowEvent& e, glm::vec2 viewport) {
  using T = display::WindowEvent::Type;
  switch (e.type) {
    case T::Key: return scene::InputEvent::key_press(0, e.key);
    case T::MouseDown:
      return scene::InputEvent::mouse(0, scene::InputEventType::MouseDown, {e.x, e.y}, viewport);
    case T::MouseUp:
      return scene::InputEvent::mouse(0, scene::InputEventType::MouseUp, {e.x, e.y}, viewport);
    case T::MouseMove:
      return scene::InputEvent::mouse(0, scene::InputEventType::MouseMove, {e.x, e.y}, viewport);
    case T::Look:
    case T::Scroll:
    case T::Home:
      break;
  }
  return std::nullopt;
}

// A scene file in the window: the fly camera driven by the window's input, the render toggles
// the demo's simulation otherwise keeps (T, B, M), and the frames from FileFrameSource.
class FileSceneView {
 public:
  FileSceneView(const FileScene& scene, const render::Effects& effects)
      : scene_(scene),
        fly_(scene.camera, FlyCamera::base_speed_for(scene.loaded.bounds)),
        base_effects_(effects),
        toggles_{effects.taa, effects.bloom, effects.motion_blur} {
    source_.emplace(scene);
  }

  // One window event (H and the view keys are handled before).
  void handle(const display::WindowEvent& e) {
    using T = display::WindowEvent::Type;
    switch (e.type) {
      case T::Look: pending_.look += glm::vec2(e.x, e.y); return;
      case T::Scroll: pending_.scroll += e.y; return;
      case T::Home: pending_.home = true; return;
      case T::MouseDown: note_simulation_input("dragging with the left button"); return;
      case T::MouseUp:
      case T::MouseMove: return;
      case T::Key: break;
    }
    // A press shorter than a frame moves for that frame: on a slow device it would be lost to
    // the held-key poll.
    if (float* axis = axis_for(pending_, e.key)) {
      *axis = 1.0f;
      return;
    }
    switch (e.key) {
      case scene::keys::kTaa: toggles_.taa = !toggles_.taa; break;
      case scene::keys::kBloom: toggles_.bloom = !toggles_.bloom; break;
      case scene::keys::kMotionBlur: toggles_.motion_blur = !toggles_.motion_blur; break;
      case scene::keys::kFireball: note_simulation_input("F (fireball)"); break;
      case scene::keys::kReset: note_simulation_input("R (reset)"); break;
      case scene::keys::kPause: note_simulation_input("P (pause)"); break;
      case scene::keys::kSingleStep: note_simulation_input("Space (single step)"); break;
      default: break;
    }
  }

  // The next frame, the camera moved for `dt_seconds` by the keys held now and the input
  // since the last frame.
  rp::cl::PassTimes render(RenderSession& session, const display::Window& window,
                           double dt_seconds, std::vector<uint8_t>& rgba, double& frame_ms) {
    FlyInput input = std::exchange(pending_, FlyInput{});
    for (char key : {'W', 'S', 'A', 'D', 'Q', 'E'})
      if (window.key_held(key)) *axis_for(input, key) = 1.0f;
    fly_.update(input, float(dt_seconds));
    // Home jumps: a fresh source's previous camera is the file's, so the jump is no motion
    // (no blur streak across the frame) and the renderer sees a camera cut (its view histories
    // start over).
    if (input.home) source_.emplace(scene_);
    source_->set_camera(fly_.camera());
    session.set_effects(effects_with(base_effects_, toggles_));
    return session.render(source_->next(), rgba, frame_ms);
  }

  // " speed 2.5 m/s |" for the window title (glTF's world unit is the metre).
  std::string title_part() const {
    char text[64];
    std::snprintf(text, sizeof text, " speed %.3g m/s |", double(fly_.speed()));
    return text;
  }

 private:
  // The movement axis a key drives (W S A D Q E), else nullptr.
  static float* axis_for(FlyInput& input, char key) {
    switch (key) {
      case 'W': return &input.forward;
      case 'S': return &input.back;
      case 'A': return &input.left;
      case 'D': return &input.right;
      case 'Q': return &input.down;
      case 'E': return &input.up;
      default: return nullptr;
    }
  }

  // Once per session: the demo's simulation keys do nothing here, say why.
  void note_simulation_input(const char* what) {
    if (noted_) return;
    noted_ = true;
    std::fprintf(stderr,
                 "rolypoly: note: %s acts on the simulated demo; a scene file has no simulation "
                 "(fly with W A S D Q E, look with the right mouse button, Home resets)\n",
                 what);
  }

  const FileScene& scene_;
  FlyCamera fly_;
  std::optional<FileFrameSource> source_;
  render::Effects base_effects_;
  ViewToggles toggles_;
  FlyInput pending_;
  bool noted_ = false;
};

// --record's log: every input event and frame mark so far.
// `source`: nullptr for a scene file (parse_cli refuses --record there).
void write_recording(const RunOptions& options, const SimulationFrameSource* source) {
  if (options.record.empty() || !source) return;
  std::ostringstream log;
  source->recording().write(log);
  write_text_atomic(options.record, log.str());
  std::printf("recorded %zu input events and frames to %s\n", source->recording().events().size(),
              options.record.c_str());
  std::fflush(stdout);
}

// Keeps the display-lost handler (which refers to this run's locals) for one run only.
struct DisplayLostScope {
  explicit DisplayLostScope(std::function<void()> save) {
    display::on_display_lost(std::move(save));
  }
  ~DisplayLostScope() { display::on_display_lost({}); }
  DisplayLostScope(const DisplayLostScope&) = delete;
  DisplayLostScope& operator=(const DisplayLostScope&) = delete;
};

}  // namespace

int run_command(const CommonOptions& common, const RunOptions& options) {
  // SIGINT / SIGTERM end the loop like closing the window, so --record's log is written.
  InterruptGuard interrupt;
  // What is shown: the simulated demo, or a scene file (a malformed one fails here, before the
  // window and the kernel builds).
  std::unique_ptr<SimulationFrameSource> simulation;
  std::unique_ptr<FileScene> file;
  std::string label = "rolypoly";
  if (is_demo_scene(common.scene)) {
    SimulationOptions sim = make_simulation_options(options.sim, common.render.effects);
    sim.record = !options.record.empty();
    simulation = std::make_unique<SimulationFrameSource>(std::move(sim));
  } else {
    file = std::make_unique<FileScene>(open_scene_file(common.scene));
    label += " | " + std::filesystem::path(common.scene).filename().string();
  }
  // Fail now, not after the session, if a file cannot be written.
  if (!options.record.empty()) io::check_output_file(options.record, "--record");
  if (!options.capture.empty()) io::check_output_file(options.capture, "--capture");
  // The window first: without a display, fail at once rather than after the kernel builds.
  std::unique_ptr<display::Window> window = open_window(options.size, label);
  RenderSession session(common, options.size.width, options.size.height, false,
                        file ? &file->loaded.assets : nullptr);
  std::optional<FileSceneView> file_view;
  if (file) {
    file_view.emplace(*file, common.render.effects);
    window->set_look_drag(true);
  }
  std::printf("device %s\n", describe_device(session.device()).c_str());
  if (!session.sky_description().empty()) std::printf("%s\n", session.sky_description().c_str());
  std::fflush(stdout);

  PassStats all, interval;
  std::vector<uint8_t> rgba;
  uint32_t presented = 0;
  // A lost X connection ends the process inside Xlib (exit 1): save the log first.
  DisplayLostScope lost([&] {
    std::fflush(stdout);
    std::fprintf(stderr, "rolypoly: error: lost the connection to the display after %u frames%s\n",
                 presented, options.record.empty() ? "" : "; writing the --record log");
    try {
      write_recording(options, simulation.get());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "rolypoly: error: %s\n", e.what());
    }
  });
  auto interval_start = std::chrono::steady_clock::now();
  const glm::vec2 viewport(float(session.width()), float(session.height()));
  auto last_frame = std::chrono::steady_clock::now();
  window->poll_events();
  while (!window->should_close() && !interrupt.interrupted() &&
         (options.frames == 0 || presented < options.frames)) {
    for (const display::WindowEvent& e : window->take_events()) {
      if (e.type == display::WindowEvent::Type::Key && e.key == kShadowsKey) {
        session.set_shadows(render::next_shadow_mode(session.shadows()));
        std::printf("shadows %s\n", name_of(session.shadows()).data());
        std::fflush(stdout);
        continue;
      }
      if (e.type == display::WindowEvent::Type::Key && e.key == kSkyTurnKey) {
        if (const std::optional<float> turn = session.turn_sky(kSkyTurnDeg))
          std::printf("sky turned to %g degrees\n", double(*turn));
        else
          std::printf("no sky to turn (--env FILE or --sky clear)\n");
        std::fflush(stdout);
        continue;
      }
      // Number keys switch the view (not simulation input, so not recorded).
      if (auto view = e.type == display::WindowEvent::Type::Key
                          ? passes::debug_view_for_key(e.key)
                          : std::nullopt) {
        passes::DebugViewSettings settings = session.view();
        settings.view = *view;
        try {
          session.set_view(settings);
        } catch (const std::exception& error) {  // keep showing the current view
          std::fprintf(stderr, "rolypoly: view %s: %s\n", name_of(*view).data(),
                       error.what());
        }
        continue;
      }
      if (file_view)
        file_view->handle(e);
      else if (std::optional<scene::InputEvent> input = to_input(e, viewport))
        simulation->input(*input);
    }
    auto now = std::chrono::steady_clock::now();
    // The first frame and scripted runs (--frames) advance by the nominal frame time, so a
    // short test run does not depend on how long kernel builds took.
    const double elapsed_s = presented == 0 || options.frames != 0
                                 ? 1.0 / 60.0
                                 : std::chrono::duration<double>(now - last_frame).count();
    last_frame = now;
    double frame_ms = 0.0;
    rp::cl::PassTimes times;
    if (file_view) {
      times = file_view->render(session, *window, elapsed_s, rgba, frame_ms);
    } else {
      simulation->set_elapsed_seconds(elapsed_s);
      times = render_next_frame(session, *simulation, common.render.effects, rgba, frame_ms);
    }
    window->present(rgba.data(), int(session.width()), int(session.height()));
    ++presented;
    all.add(times, frame_ms);
    interval.add(times, frame_ms);
    window->poll_events();
    if (double elapsed = ms_since(interval_start); elapsed >= kTitleIntervalMs) {
      std::string extra = file_view ? file_view->title_part() : "";
      // " 720x720 scale 0.70 (504x504) |": output size, render scale and render size
      if (session.render_width() != session.width() || session.frame_scale() != nullptr) {
        char scale[96];
        std::snprintf(scale, sizeof scale, " %ux%u scale %.2f (%ux%u) |", session.width(),
                      session.height(), double(session.render_scale()), session.render_width(),
                      session.render_height());
        extra += scale;
      }
      window->set_title(
          title_text(label, extra, interval, elapsed, session.view(), session.shadows()));
      interval.clear();
      interval_start = std::chrono::steady_clock::now();
    }
  }

  // Closing the window (its close button or Esc) is the normal end of `run --frames 0` and an
  // early end otherwise: not an error, and --capture / --record below still happen. SIGINT and
  // SIGTERM end it the same way, then exit 130 / 143.
  const bool closed_early = !interrupt.interrupted() && window->should_close() &&
                            (options.frames == 0 || presented < options.frames);
  if (closed_early) std::printf("window closed after %u frames\n", presented);
  // The log first: it is wanted even when --capture fails below (no frame shown).
  write_recording(options, simulation.get());
  if (interrupt.interrupted()) {
    std::fflush(stdout);
    std::fprintf(stderr, "rolypoly: error: interrupted by %s after %u frames%s\n",
                 interrupt_signal_name(), presented,
                 options.record.empty() ? "" : " (the --record log is complete)");
    return interrupted_exit_code();
  }
  if (!options.capture.empty()) {
    if (presented == 0) throw std::runtime_error("--capture: the window closed before any frame");
    std::vector<uint8_t> shown;
    int w = 0, h = 0;
    window->read_back(shown, w, h);
    write_png_atomic(options.capture, w, h, shown);
    std::printf("captured the window (%dx%d) to %s\n", w, h, options.capture.c_str());
  }
  if (presented > 0)
    std::printf("%u frames; per-pass median: %s; frame %.2f ms\n", presented,
                median_line(all).c_str(), all.frame().median_ms);
  return 0;
}

}  // namespace rp::app
