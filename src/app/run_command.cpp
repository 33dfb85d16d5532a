#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

#include "bench/src/bench_report.h"
#include "app/commands.h"
#include "app/frame_source.h"
#include "app/interrupt.h"
#include "bench/src/pass_stats.h"
#include "app/png_output.h"
#include "app/simulation_source.h"
#include "display/display_lost.h"
#include "display/window.h"
#include "io/output_path.h"

namespace rp::app {
namespace {

constexpr double kTitleIntervalMs = 500.0;  // window title refresh: about twice per second
constexpr char kShadowsKey = 'H';  // cycles --shadows: hard, pcf, pcss, vssm (not recorded)

// "rolypoly | 4.1 fps | shadows pcss | visibility 3.20 ms, gbuffer 1.10 ms, ..." (means over
// the interval); a debug view is named after the shadows: "... | view voxels 2 +x | ...".
std::string title_text(const PassStats& interval, double elapsed_ms,
                       const passes::DebugViewSettings& view, render::ShadowMode shadows) {
  char head[96];
  std::snprintf(head, sizeof head, "rolypoly | %.1f fps | shadows %s |",
                elapsed_ms > 0.0 ? 1000.0 * double(interval.frames()) / elapsed_ms : 0.0,
                render::shadow_mode_name(shadows));
  std::string title = head;
  if (view.view != passes::DebugView::kFinal) {
    title += " view ";
    title += passes::debug_view_name(view.view);
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

std::unique_ptr<display::Window> open_window(const ImageSize& size) {
  try {
    return std::make_unique<display::Window>(int(size.width), int(size.height), "rolypoly");
  } catch (const display::DisplayError& e) {
    throw display::DisplayError(std::string("cannot open a window: ") + e.what() +
                                ". Use `rolypoly render --out DIR` to render PNG files "
                                "without a display.");
  }
}

scene::InputEvent to_input(const display::WindowEvent& e, glm::vec2 viewport) {
  using T = display::WindowEvent::Type;
  switch (e.type) {
    case T::Key: return scene::InputEvent::key_press(0, e.key);
    case T::MouseDown:
      return scene::InputEvent::mouse(0, scene::InputEventType::MouseDown, {e.x, e.y}, viewport);
    case T::MouseUp:
      return scene::InputEvent::mouse(0, scene::InputEventType::MouseUp, {e.x, e.y}, viewport);
    case T::MouseMove:
      break;
  }
  return scene::InputEvent::mouse(0, scene::InputEventType::MouseMove, {e.x, e.y}, viewport);
}

// --record's log: every input event and frame mark so far.
void write_recording(const RunOptions& options, const SimulationFrameSource& source) {
  if (options.record.empty()) return;
  std::ostringstream log;
  source.recording().write(log);
  write_text_atomic(options.record, log.str());
  std::printf("recorded %zu input events and frames to %s\n", source.recording().events().size(),
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
  SimulationOptions sim = make_simulation_options(options.sim, common.effects);
  sim.record = !options.record.empty();
  SimulationFrameSource source(std::move(sim));
  // Fail now, not after the session, if a file cannot be written.
  if (!options.record.empty()) io::check_output_file(options.record, "--record");
  if (!options.capture.empty()) io::check_output_file(options.capture, "--capture");
  // The window first: without a display, fail at once rather than after the kernel builds.
  std::unique_ptr<display::Window> window = open_window(options.size);
  RenderSession session(common, options.size.width, options.size.height);
  std::printf("device %s\n", describe_device(session.device()).c_str());
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
      write_recording(options, source);
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
        std::printf("shadows %s\n", render::shadow_mode_name(session.shadows()));
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
          std::fprintf(stderr, "rolypoly: view %s: %s\n", passes::debug_view_name(*view),
                       error.what());
        }
        continue;
      }
      source.input(to_input(e, viewport));
    }
    auto now = std::chrono::steady_clock::now();
    // The first frame and scripted runs (--frames) advance by the nominal frame time, so a
    // short test run does not depend on how long kernel builds took.
    source.set_elapsed_seconds(presented == 0 || options.frames != 0
                                   ? 1.0 / 60.0
                                   : std::chrono::duration<double>(now - last_frame).count());
    last_frame = now;
    double frame_ms = 0.0;
    rp::cl::PassTimes times = render_next_frame(session, source, common.effects, rgba, frame_ms);
    window->present(rgba.data(), int(session.width()), int(session.height()));
    ++presented;
    all.add(times, frame_ms);
    interval.add(times, frame_ms);
    window->poll_events();
    if (double elapsed = ms_since(interval_start); elapsed >= kTitleIntervalMs) {
      window->set_title(title_text(interval, elapsed, session.view(), session.shadows()));
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
  write_recording(options, source);
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
