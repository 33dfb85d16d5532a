#include "bench/src/quality_report.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "app/png_output.h"
#include "app/simulation_source.h"
#include "bench/src/bench_commands.h"
#include "scene/demo_scene.h"

namespace rp::bench {

using app::CommonOptions;
using app::RenderSession;
using app::SimulationArgs;
using app::SimulationFrameSource;
using app::make_simulation_options;
using app::render_next_frame;
using app::write_text_atomic;

namespace {

void check_same_size(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  if (a.size() != b.size() || a.size() % 4 != 0)
    throw std::invalid_argument("image comparison: the images differ in size");
}

CommonOptions with_quality(const CommonOptions& common, render::Quality quality) {
  CommonOptions c = common;
  c.render.quality = quality;
  c.view = {};  // the final image
  return c;
}

struct StaticRun {
  std::vector<uint8_t> last;
  double flicker = 0.0;
};

// The demo at rest for options.static_frames frames.
StaticRun render_static(const CommonOptions& common, uint32_t width, uint32_t height,
                        const QualityOptions& options) {
  RenderSession session(common, width, height);
  StaticRun run;
  std::vector<uint8_t> rgba, previous;
  double frame_ms = 0.0, flicker_sum = 0.0;
  uint32_t flicker_count = 0;
  for (uint32_t i = 0; i < options.static_frames; ++i) {
    session.render(scene::make_demo_frame(session.assets(), i), rgba, frame_ms);
    if (i > 0 && i + options.flicker_frames >= options.static_frames) {
      flicker_sum += mean_abs_diff_rgb8(rgba, previous);
      ++flicker_count;
    }
    previous.swap(rgba);
  }
  run.last = std::move(previous);
  run.flicker = flicker_count > 0 ? flicker_sum / flicker_count : 0.0;
  return run;
}

}  // namespace

double psnr_rgb8(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  check_same_size(a, b);
  double sum = 0.0;
  size_t count = 0;
  for (size_t i = 0; i < a.size(); i += 4)
    for (size_t c = 0; c < 3; ++c) {
      const double d = double(a[i + c]) - double(b[i + c]);
      sum += d * d;
      ++count;
    }
  if (sum == 0.0 || count == 0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(255.0 * 255.0 / (sum / double(count)));
}

double mean_abs_diff_rgb8(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  check_same_size(a, b);
  uint64_t sum = 0;
  size_t count = 0;
  for (size_t i = 0; i < a.size(); i += 4)
    for (size_t c = 0; c < 3; ++c) {
      sum += uint64_t(std::abs(int(a[i + c]) - int(b[i + c])));
      ++count;
    }
  return count > 0 ? double(sum) / double(count) : 0.0;
}

QualityReport measure_quality(const CommonOptions& common, uint32_t width, uint32_t height,
                              const QualityOptions& options) {
  return measure_quality(with_quality(common, render::Quality::kFast),
                         with_quality(common, render::Quality::kReference), width, height,
                         options);
}

QualityReport measure_quality(const CommonOptions& fast, const CommonOptions& reference,
                              uint32_t width, uint32_t height, const QualityOptions& options) {
  const CommonOptions& common = fast;
  QualityReport report;
  report.width = width;
  report.height = height;

  const StaticRun fast_static = render_static(fast, width, height, options);
  const StaticRun ref_static = render_static(reference, width, height, options);
  report.static_psnr_db = psnr_rgb8(fast_static.last, ref_static.last);
  report.flicker_fast = fast_static.flicker;
  report.flicker_reference = ref_static.flicker;

  // Busy: both modes side by side, one frame each in turn (two sessions, two identical worlds).
  SimulationArgs args;
  args.seed = options.seed;
  args.marbles = true;
  args.fireball = true;
  RenderSession fast_session(fast, width, height);
  RenderSession ref_session(reference, width, height);
  SimulationFrameSource fast_source(make_simulation_options(args, common.render.effects));
  SimulationFrameSource ref_source(make_simulation_options(args, common.render.effects));
  std::vector<uint8_t> fast_rgba, ref_rgba;
  double frame_ms = 0.0;
  for (uint32_t i = 0; i < options.busy_warmup + options.busy_frames; ++i) {
    render_next_frame(fast_session, fast_source, common.render.effects, fast_rgba, frame_ms);
    render_next_frame(ref_session, ref_source, common.render.effects, ref_rgba, frame_ms);
    if (i >= options.busy_warmup) report.busy_psnr_db.push_back(psnr_rgb8(fast_rgba, ref_rgba));
  }
  if (!report.busy_psnr_db.empty()) {
    std::vector<double> sorted = report.busy_psnr_db;
    std::sort(sorted.begin(), sorted.end());
    report.busy_min_psnr_db = sorted.front();
    const size_t n = sorted.size();
    report.busy_median_psnr_db =
        n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  }
  return report;
}

// The fast mode's quality criteria at the bench size: both quality modes render the static demo and
// the busy animation; prints the figures and the pass/fail of each threshold, and writes them
// as JSON with --json.
// With --render-scale below 1 or --target-ms, the fast mode as given against the fast mode at
// full scale instead (the render scale's criteria: static >= 33 dB, busy >= 28 dB).
int quality_report_command(const CommonOptions& common, const BenchOptions& options) {
  const uint32_t w = options.size.width, h = options.size.height;
  QualityOptions q;
  q.seed = options.sim.seed;
  const bool scaled = common.render.render_scale < 1.0f || common.target_ms > 0.0;
  char what[96];
  if (scaled && common.target_ms > 0.0)
    std::snprintf(what, sizeof what, "the scale holding %.1f ms vs full scale", common.target_ms);
  else if (scaled)
    std::snprintf(what, sizeof what, "render scale %.2f vs full scale",
                  double(common.render.render_scale));
  else
    std::snprintf(what, sizeof what, "fast vs reference");
  std::printf("quality: %s at %ux%u (static demo %u frames, busy animation %u + %u frames, seed "
              "%llu)\n",
              what, w, h, q.static_frames, q.busy_warmup, q.busy_frames,
              static_cast<unsigned long long>(q.seed));
  std::fflush(stdout);
  QualityReport r;
  if (scaled) {
    CommonOptions full = with_quality(common, render::Quality::kFast);
    full.render.render_scale = 1.0f;
    full.target_ms = 0.0;
    r = measure_quality(with_quality(common, render::Quality::kFast), full, w, h, q);
  } else {
    r = measure_quality(common, w, h, q);
  }
  const bool static_ok = r.static_psnr_db >= (scaled ? 33.0 : 35.0);
  const bool busy_ok = r.busy_min_psnr_db >= (scaled ? 28.0 : 30.0);
  const bool flicker_ok = r.flicker_fast <= r.flicker_reference;
  std::printf("  static PSNR after TAA converged  %7.2f dB   (>= %d: %s)\n", r.static_psnr_db,
              scaled ? 33 : 35, static_ok ? "yes" : "NO");
  std::printf("  busy PSNR per frame, min/median  %7.2f / %.2f dB   (min >= %d: %s)\n",
              r.busy_min_psnr_db, r.busy_median_psnr_db, scaled ? 28 : 30,
              busy_ok ? "yes" : "NO");
  std::printf("  static flicker %s  %7.3f / %.3f codes   (first <= second: %s)\n",
              scaled ? "scaled / full" : "fast / reference", r.flicker_fast, r.flicker_reference,
              flicker_ok ? "yes" : "NO");
  if (!options.json.empty()) {
    std::string busy = "[";
    for (size_t i = 0; i < r.busy_psnr_db.size(); ++i) {
      char v[32];
      std::snprintf(v, sizeof v, "%s%.3f", i ? ", " : "", r.busy_psnr_db[i]);
      busy += v;
    }
    busy += "]";
    char text[1024];
    std::snprintf(text, sizeof text,
                  "{\n  \"schema\": \"rolypoly-quality/1\",\n  \"command\": \"%s\",\n"
                  "  \"width\": %u, \"height\": %u, \"bounces\": %u,\n"
                  "  \"compared\": \"%s\",\n"
                  "  \"static_psnr_db\": %.3f,\n"
                  "  \"busy_min_psnr_db\": %.3f, \"busy_median_psnr_db\": %.3f,\n"
                  "  \"flicker_fast\": %.4f, \"flicker_reference\": %.4f,\n"
                  "  \"busy_psnr_db\": ",
                  options.command_line.c_str(), w, h, common.render.bounces, what, r.static_psnr_db,
                  r.busy_min_psnr_db,
                  r.busy_median_psnr_db, r.flicker_fast, r.flicker_reference);
    write_text_atomic(options.json, std::string(text) + busy + "\n}\n");
    std::printf("wrote %s\n", options.json.c_str());
  }
  return static_ok && busy_ok && flicker_ok ? 0 : 3;
}

}  // namespace rp::bench
