// `rolypoly bench --accuracy` (issues 13 and 14): the demo frame (scene::make_demo_frame, at rest)
// path traced as ground truth at one gather and at many (64), against four real-time
// configurations, each at the truth's bounce count and all without TAA, bloom and motion blur
// (and so without jitter):
//   fast_many       the fast mode at 64 bounces (the default) after its temporal accumulation
//                   converged, against the many-bounce truth ("fast/N");
//   reference_many  the reference mode at 64 bounces, after the voxels' bounce feedback
//                   converged, against the many-bounce truth ("ref/N");
//   fast_one        the fast mode at --bounces 1, converged, against the 1-bounce truth ("fast/1");
//   reference_one   the reference mode at --bounces 1 (one frame), against the 1-bounce truth
//                   ("ref/1");
// and a fifth render, fast_many_taa: the fast mode at 64 bounces with TAA on (bloom and motion
// blur off) for `converge_frames` frames, whose finished 8-bit image is held against the
// many-bounce truth (final PSNR only). For each of the four: the final image's PSNR after the
// tone map, the direct component's error, the indirect component's relative L1 and bias over the
// image and per named region (bench/src/accuracy_metrics.h), the hue of the indirect light arriving on
// each side wall, the leak / missing pixel counts, and the specular component (the coat's part
// of direct + indirect: relative L1 and bias over the image, the floor and the
// tumblers). Then the direct-light section
// (bench/src/accuracy_direct.h): every shadow mode's direct component against the area-lamp truth,
// penumbra widths, the albedo view. With `marbles` (--marbles), the marble section
// (bench/src/accuracy_marbles.h): a second frame with 16 marbles at rest, fast/N and ref/N
// against its many-bounce truth, per region (marbles and the floor beside them included);
// the main section's frame, regions and figures stay as without it. Writes a JSON (schema rolypoly-accuracy/4: /3 plus
// "specular" per configuration, and "marbles" only with --marbles; /3 was /2 plus "direct";
// README "Accuracy against the ground truth"), side-by-side PNGs and signed difference heat maps.
// With --scene FILE the report is a scene file's instead, its materials as the regions
// (bench/src/accuracy_file.h); AccuracyOptions and AccuracyResult serve both.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "app/render_session.h"

namespace rp::bench {

struct AccuracyOptions {
  uint32_t width = 360, height = 360;
  uint32_t spp = 1024;             // the truth's samples per pixel
  // The "many" truth and the real-time modes' bounces against it (Russian roulette ends the
  // truth's paths long before 64; the real-time feedback converges to all bounces).
  uint32_t many_bounces = render::RenderSettings::kDefaultBounces;
  uint32_t converge_frames = 128;  // fast-mode frames before it is measured (blend 0.04),
                                   // also the TAA render's frames
  // Reference-mode frames at many bounces: the voxels carry the previous frame's indirect light,
  // one more bounce per frame (at 1 bounce the reference mode needs one frame).
  uint32_t reference_many_frames = 32;
  uint64_t seed = 1;               // the truth's random streams
  std::filesystem::path cache_dir;                  // empty: default_truth_cache_dir()
  std::filesystem::path out_dir = "out/accuracy";   // accuracy_{side_by_side,indirect_heat,
                                                    // final_taa}.png
  std::string json_path;                            // "" = no JSON file
  // Thresholds (exit 3 when one is missed), each on the fast mode: fractions, PSNR in dB.
  std::optional<double> max_indirect_l1;         // fast_many: indirect relative L1, image
  std::optional<double> max_indirect_bias;       // fast_many: |indirect bias|, image
  std::optional<double> max_region_bias;         // fast_many: |indirect bias|, every named region
  std::optional<double> max_indirect_l1_single;  // fast_one: indirect relative L1, image
  std::optional<double> min_psnr_taa;            // fast_many_taa: final PSNR (dB)
  std::optional<double> max_first_frame_gap;     // fast_many_taa's PSNR - fast_first_frame's
  bool require_wall_hue = false;  // both walls: sign(R - B) of fast_many and fast_one as truth's
  // A scene file's report: also the many-bounce truth with seed + 1, and the indirect light's
  // relative L1 and bias between the two truths per region (JSON truth.noise): what the truth's
  // own noise adds to every L1 of the report (a noiseless image reads about 1 / sqrt 2 of it).
  bool truth_noise = false;
  // The direct section (accuracy_direct.h): its truth's samples per pixel are direct_spp_factor
  // x spp (a 0-bounce sample costs about a quarter of a 64-bounce one); its thresholds are on
  // the default shadow mode (RenderSettings::shadows) and texture filter.
  uint32_t direct_spp_factor = 4;
  uint32_t direct_jitter_frames = 16;
  std::optional<double> min_direct_psnr_floor;   // direct PSNR (dB) on the floor
  std::optional<double> max_penumbra_error;      // |width / truth's - 1|, tumbler and marble
  std::optional<double> min_albedo_psnr;         // albedo view PSNR (dB), image
  // The marble section (bench/src/accuracy_marbles.h; `bench --accuracy --marbles`): the
  // marble frame's truth at many bounces and fast/N, ref/N on it; JSON "marbles".
  bool marbles = false;
  std::string command_line;
};

struct AccuracyResult {
  nlohmann::json json;   // the whole report (schema rolypoly-accuracy/4)
  std::string table;     // what is printed, thresholds included
  bool passed = true;    // every given threshold met
};

// Renders everything, measures, writes the PNGs (and the JSON when asked). Throws what
// RenderSession and the path tracer throw; truth::PathTracer::Cancelled after Ctrl-C / SIGTERM
// (InterruptGuard, app/interrupt.h), before any report file is written.
AccuracyResult measure_accuracy(const app::CommonOptions& common, const AccuracyOptions& options);

// The demo at rest (the report's frame; with common.open_demo its skylight) written as glTF to
// OUT_DIR/demo.glb or OUT_DIR/demo_open.glb (created); returns the path. `bench --accuracy
// --open` with a sky measures this file as a scene file.
std::string export_demo_at_rest(const app::CommonOptions& common, const std::string& out_dir);

}  // namespace rp::bench
