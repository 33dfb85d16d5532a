#include <chrono>
#include <cstdio>
#include <memory>

#include "app/bench_report.h"
#include "app/commands.h"
#include "app/frame_source.h"
#include "app/pass_stats.h"
#include "app/png_output.h"
#include "display/window.h"

namespace rp::app {
namespace {

constexpr double kTitleIntervalMs = 500.0;  // window title refresh: about twice per second

// "rolypoly | 4.1 fps | visibility 3.20 ms, gbuffer 1.10 ms, ..." (means over the interval).
std::string title_text(const PassStats& interval, double elapsed_ms) {
  char head[64];
  std::snprintf(head, sizeof head, "rolypoly | %.1f fps |",
                elapsed_ms > 0.0 ? 1000.0 * double(interval.frames()) / elapsed_ms : 0.0);
  std::string title = head;
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

}  // namespace

int run_command(const CommonOptions& common, const RunOptions& options) {
  // The window first: without a display, fail at once rather than after the kernel builds.
  std::unique_ptr<display::Window> window = open_window(options.size);
  RenderSession session(common, options.size.width, options.size.height);
  std::printf("device %s\n", describe_device(session.device()).c_str());
  std::fflush(stdout);

  DemoFrameSource source(session.assets());
  PassStats all, interval;
  std::vector<uint8_t> rgba;
  uint32_t presented = 0;
  auto interval_start = std::chrono::steady_clock::now();
  window->poll_events();
  while (!window->should_close() && (options.frames == 0 || presented < options.frames)) {
    double frame_ms = 0.0;
    rp::cl::PassTimes times = session.render(source.next(), rgba, frame_ms);
    window->present(rgba.data(), int(session.width()), int(session.height()));
    ++presented;
    all.add(times, frame_ms);
    interval.add(times, frame_ms);
    window->poll_events();
    if (double elapsed = ms_since(interval_start); elapsed >= kTitleIntervalMs) {
      window->set_title(title_text(interval, elapsed));
      interval.clear();
      interval_start = std::chrono::steady_clock::now();
    }
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
