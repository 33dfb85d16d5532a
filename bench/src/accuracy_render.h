// What the sections of `bench --accuracy` share (bench/src/accuracy_report.h, the marble section
// bench/src/accuracy_marbles.h): the linear images of one real-time mode or truth, the
// real-time renderer on a frame at rest, and a cached truth with a progress bar.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/render_session.h"
#include "app/truth_cache.h"
#include "bench/src/accuracy_metrics.h"
#include "scene/demo_scene.h"
#include "truth/path_tracer.h"

namespace rp::bench {

// One real-time configuration of the report (accuracy_report.h): a quality mode at many
// bounces against the many-bounce truth, or at --bounces 1 against the 1-bounce truth.
struct AccuracyConfig {
  const char* key;     // JSON key under "configurations"
  const char* column;  // the table's column
  render::Quality quality;
  bool many;           // AccuracyOptions::many_bounces against the many-bounce truth
};
inline constexpr AccuracyConfig kAccuracyConfigs[] = {
    {"fast_many", "fast/N", render::Quality::kFast, true},
    {"reference_many", "ref/N", render::Quality::kReference, true},
    {"fast_one", "fast/1", render::Quality::kFast, false},
    {"reference_one", "ref/1", render::Quality::kReference, false},
};
// The fifth render: fast at many bounces with TAA, its finished 8-bit frame.
inline constexpr const char* kTaaConfigKey = "fast_many_taa";
// The sixth: the same session's first frame, which no history averages (what `render --frames
// 1`, a camera cut or R show).
inline constexpr const char* kFirstFrameConfigKey = "fast_first_frame";
// The seventh (scene files): fast at many bounces, its light averaged over TAA's jitter cycle
// (render_jittered_average).
inline constexpr const char* kJitteredConfigKey = "fast_many_jittered";

// {"rel_l1", "bias", "pixels"} (NaN figures, a region without light, are written as null).
nlohmann::json stats_json(const ErrorStats& s);
// "+12.3%" (signed: a bias) or "12.3%" (a magnitude), right-aligned in 8 characters; "n/a"
// for NaN.
std::string percent_cell(double v, bool sign);
// "   12.34" (8 characters); "     n/a" for NaN.
std::string db_cell(double v);
// The table's lines on the truths of truths_one_and_many's JSON ("  truth, N bounce(s): S s,
// R Mrays/s", and whether it came from the cache).
std::string truth_lines(const nlohmann::json& truth_json);
// The configurations' table head: "(rolypoly vs truth)" in a label column `label_width` wide,
// one column per configuration, and the line that says what /N and /1 mean (N = n bounces).
std::string config_table_head(int label_width, const std::string& n);
// A JSON number as a double, NaN for null (a figure without pixels).
inline double json_number(const nlohmann::json& v) {
  return v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN();
}

// The linear images one mode or truth gives (3 floats per pixel).
struct Images {
  std::string name;
  std::vector<float> combined, direct, indirect, albedo;
  std::vector<float> specular;  // the coat's part of direct + indirect
};

Images from_truth(const std::string& name, const truth::PathTracedImage& t);

// A render scale for the JSON as the user typed it (0.85, not the float's 0.8500000238).
inline double json_scale(float scale) { return std::round(double(scale) * 1.0e4) / 1.0e4; }

// The frame a section measures: frame `frame_index` of a scene at rest (scene::make_demo_frame,
// the marble section's marble_frame, a scene file's still frame).
using FrameFn =
    std::function<scene::FrameScene(const scene::SceneAssets&, uint32_t frame_index)>;

// The real-time renderer on `frame_fn`'s frames: `frames` frames (frame_index counting up, so
// the fast mode's interleaving, the shadow noise and TAA's jitter rotate as in the app), no
// bloom or motion blur, TAA only when asked. `final_rgba` gets the last finished frame. Only
// the TAA render takes common's render scale (the others render at the output size); its light
// terms are returned at scale 1 and left empty below it.
// `assets`: what the frames draw from (a scene file's); nullptr = the demo's (--assets).
Images render_mode(const app::CommonOptions& common, const std::string& name,
                   render::Quality quality, uint32_t bounces, bool taa, uint32_t w, uint32_t h,
                   uint32_t frames, std::vector<uint8_t>& final_rgba,
                   const FrameFn& frame_fn = scene::make_demo_frame,
                   const scene::SceneAssets* assets = nullptr);

// The fast mode at `bounces` with TAA's camera jitter on (no bloom or motion blur), `frames`
// frames, its light terms averaged over the last `average_frames` of them (one cycle of TAA's
// 16-sample Halton jitter): what TAA converges to without its history clamp and blend, so
// sub-pixel geometry and texture detail resolve as the truth's pixel averages do. Separates the
// light's error from a single unjittered frame's aliasing (render_mode). At the output size.
Images render_jittered_average(const app::CommonOptions& common, const std::string& name,
                               uint32_t bounces, uint32_t w, uint32_t h, uint32_t frames,
                               uint32_t average_frames, const FrameFn& frame_fn,
                               const scene::SceneAssets* assets);

// The fast mode's finished frames with TAA at `bounces` (no bloom or motion blur) against
// `truth` (the many-bounce truth's combined radiance): converged after `frames` frames
// (configurations[kTaaConfigKey]) and a fresh session's first frame, which no history averages
// (configurations[kFirstFrameConfigKey], with its gap to the converged frame's PSNR). Returns
// the converged frame's RGBA8.
std::vector<uint8_t> render_finished_frames(const app::CommonOptions& common, uint32_t bounces,
                                            uint32_t w, uint32_t h, uint32_t frames,
                                            const std::vector<float>& truth,
                                            nlohmann::json& configurations,
                                            const FrameFn& frame_fn = scene::make_demo_frame,
                                            const scene::SceneAssets* assets = nullptr);

// cached_path_trace with a progress bar named `label`; Ctrl-C / SIGTERM (InterruptGuard) stops
// the render between rows (truth::PathTracer::Cancelled).
app::CachedTruth cached_truth_with_progress(truth::PathTracer& tracer,
                                       const scene::SceneAssets& assets,
                                       const scene::FrameScene& frame,
                                       const truth::PathTraceSettings& settings,
                                       const std::filesystem::path& cache,
                                       const std::string& label);

// The truths of `frame` at one gather ([0], "one") and at `many_bounces` ([1], "many"), w x h,
// `spp` samples, `seed`, each from the cache when it holds it; each one's facts (bounces, spp,
// seed, seconds, rays per second, from the cache, file) go into truth_json["one"] / ["many"].
// with_one false: the many-bounce truth alone ([0]).
std::vector<Images> truths_one_and_many(truth::PathTracer& tracer,
                                        const scene::SceneAssets& assets,
                                        const scene::FrameScene& frame, uint32_t w, uint32_t h,
                                        uint32_t spp, uint32_t many_bounces, uint64_t seed,
                                        const std::filesystem::path& cache,
                                        nlohmann::json& truth_json, bool with_one = true);

// The report's three PNGs in out/: accuracy_side_by_side.png (truth, fast, reference at 1 and
// at `many` bounces; rows final and indirect), accuracy_indirect_heat.png (the indirect light's
// signed error against the truth at the same bounces, over the pixels of image_labels) and
// accuracy_final_taa.png (truth and the fast mode's TAA frame). truths: {one, many};
// rendered: kAccuracyConfigs' order (fast many, reference many, fast one, reference one).
// Returns the JSON "images" object (paths and layouts).
nlohmann::json write_accuracy_pictures(const std::filesystem::path& out, uint32_t w, uint32_t h,
                                       const std::vector<Images>& truths,
                                       const std::vector<Images>& rendered,
                                       const std::vector<uint16_t>& image_labels,
                                       const std::vector<uint8_t>& taa_rgba, uint32_t many);

}  // namespace rp::bench
