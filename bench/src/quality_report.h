// How close the fast quality mode (reduced-resolution, temporally accumulated indirect light)
// comes to the reference mode (16 cones per pixel at full resolution, no temporal reuse):
// the fast mode's quality criteria, measured on final 8-bit images rendered through RenderSession.
//   static:  the demo at rest (scene::make_demo_frame, camera and scene still, frame_index
//            counting up so TAA jitter, shadow noise and the fast mode's interleaving rotate);
//            PSNR of the last frame (TAA converged), fast against reference; and the flicker
//            of each mode: mean absolute difference of consecutive frames over the last
//            `flicker_frames` frames, in 8-bit codes averaged over the RGB channels.
//   busy:    the simulated world with marbles and a fireball (its fire particles), the same seed
//            in both modes (SimulationFrameSource: identical frames); PSNR per frame after the
//            first `busy_warmup` frames.
// Both modes use the command line's other options (device, effects, voxels, shadow size).
#pragma once

#include <cstdint>
#include <vector>

#include "app/render_session.h"

namespace rp::bench {

struct QualityOptions {
  uint32_t static_frames = 48;   // frames of the static scene (TAA converges in ~30 at f = 0.9)
  uint32_t flicker_frames = 16;  // the last frames the flicker is measured over
  uint32_t busy_warmup = 16;     // busy frames before the per-frame PSNR counts
  uint32_t busy_frames = 16;     // busy frames measured after the warm-up
  uint64_t seed = 1;             // the busy world's seed
};

struct QualityReport {
  uint32_t width = 0, height = 0;
  double static_psnr_db = 0.0;            // fast vs reference, last static frame
  double flicker_fast = 0.0;              // 8-bit codes, static scene
  double flicker_reference = 0.0;
  std::vector<double> busy_psnr_db;       // per measured busy frame (frame busy_warmup + 1, ...)
  double busy_min_psnr_db = 0.0;
  double busy_median_psnr_db = 0.0;
};

// PSNR in dB of two RGBA8 images of equal size over the RGB channels (peak 255); +infinity when
// identical. Throws std::invalid_argument for different sizes.
double psnr_rgb8(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

// Mean absolute difference of two RGBA8 images over the RGB channels, in 8-bit codes.
double mean_abs_diff_rgb8(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

// Renders both modes (common.render.quality is ignored; common.view must be the final image) at
// width x height and measures the criteria above. Throws what RenderSession throws.
QualityReport measure_quality(const app::CommonOptions& common, uint32_t width, uint32_t height,
                              const QualityOptions& options = {});
// The same criteria for any two configurations: `fast` takes the report's "fast" figures,
// `reference` the other's (the render scale: scaled against full scale).
QualityReport measure_quality(const app::CommonOptions& fast, const app::CommonOptions& reference,
                              uint32_t width, uint32_t height, const QualityOptions& options);

struct BenchOptions;
// `bench --quality-report`: measure_quality at the bench size, the figures and the pass/fail of
// each criterion printed (and written as JSON with --json). Exit code 0 when all are met, 3
// when not.
int quality_report_command(const app::CommonOptions& common, const BenchOptions& options);

}  // namespace rp::bench
