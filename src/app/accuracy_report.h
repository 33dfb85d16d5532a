// `rolypoly bench --accuracy` (issue 13): the demo frame (scene::make_demo_frame, at rest)
// path traced as ground truth at one gather (what the real-time passes model today) and at many,
// against the fast mode after its temporal accumulation converged and the reference mode, all
// without TAA, bloom and motion blur (and so without jitter). For each mode and truth: the final
// image's PSNR after the tone map, the direct component's error, the indirect component's
// relative L1 and bias over the image and per named region (app/accuracy_metrics.h), the hue of
// the indirect light arriving on each side wall, and the leak / missing pixel counts. Writes a
// JSON (schema rolypoly-accuracy/1), a side-by-side PNG and signed difference heat maps.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "app/render_session.h"

namespace rp::app {

struct AccuracyOptions {
  uint32_t width = 360, height = 360;
  uint32_t spp = 1024;             // the truth's samples per pixel
  uint32_t many_bounces = 64;      // the "many" truth (Russian roulette ends paths long before)
  uint32_t converge_frames = 128;  // fast-mode frames before it is measured (blend 0.04)
  uint64_t seed = 1;               // the truth's random streams
  std::filesystem::path cache_dir;                  // empty: default_truth_cache_dir()
  std::filesystem::path out_dir = "out/accuracy";   // accuracy_side_by_side.png, _heat.png
  std::string json_path;                            // "" = no JSON file
  std::optional<double> max_indirect_l1, max_indirect_bias;  // thresholds (exit 3 when missed)
  std::string command_line;
};

struct AccuracyResult {
  nlohmann::json json;   // the whole report (schema rolypoly-accuracy/1)
  std::string table;     // what is printed
  bool passed = true;    // every given threshold met
};

// Renders everything, measures, writes the PNGs (and the JSON when asked). Throws what
// RenderSession and the path tracer throw; truth::PathTracer::Cancelled after Ctrl-C / SIGTERM
// (InterruptGuard, app/interrupt.h), before any report file is written.
AccuracyResult measure_accuracy(const CommonOptions& common, const AccuracyOptions& options);

}  // namespace rp::app
