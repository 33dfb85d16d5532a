// The options of `rolypoly bench` (bench/src/bench_cli.h declares and checks them).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.h"

namespace rp::bench {

struct BenchOptions {
  app::ImageSize size;        // --size / --width / --height: the one size when --sizes is not given
  app::SimulationArgs sim;
  uint32_t frames = 10;  // measured frames
  uint32_t warmup = 3;   // frames rendered first and not measured
  std::string json;      // "" = no JSON file
  bool compare_visibility = false;  // --compare-visibility: raster and Embree on the same frames
  // --quality-report: fast vs reference quality mode at the bench size (bench/src/quality_report.h)
  bool quality_report = false;
  // --accuracy: every real-time mode against the path-traced truth (bench/src/accuracy_report.h);
  // its size defaults to 360 (size_given: --size/--width/--height on the command line).
  bool accuracy = false;
  bool size_given = false;
  uint32_t accuracy_spp = 1024;         // --spp with --accuracy: the truth's samples per pixel
  std::string out_dir = "out/accuracy";  // --out: the report's PNGs
  std::string truth_cache;              // --truth-cache DIR ("" = the default cache folder)
  // Thresholds (exit 3 when missed; bench/src/accuracy_report.h): fractions, PSNR in dB.
  std::optional<double> max_indirect_l1, max_indirect_bias, max_region_bias;
  std::optional<double> max_indirect_l1_single, min_psnr_taa, max_first_frame_gap;
  std::optional<double> min_direct_psnr_floor, max_penumbra_error, min_albedo_psnr;
  bool require_wall_hue = false;
  bool truth_noise = false;  // --truth-noise: a second truth (next seed) to state the first's noise
  // The matrix: every device x size x voxel resolution.
  std::string devices;           // --devices all|LIST ("" = the one --device, or the default)
  std::vector<uint32_t> sizes;   // --sizes: square sizes (empty = `size`)
  std::vector<uint32_t> voxels;  // --voxels: resolutions (empty = the renderer's default)
  // --scene default|demo|busy|FILE (busy: bench/src/bench_scene.h; FILE: a glTF scene)
  std::string scene = "default";
  std::string chart;     // --chart FILE.svg ("" = none)
  std::string markdown;  // --markdown FILE.md: the summary table ("" = none)
  std::string command_line;  // how the bench was invoked (recorded in the JSON)
};

}  // namespace rp::bench
