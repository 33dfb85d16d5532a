// The subcommands of `rolypoly`. Each returns the process exit code and throws on errors
// (rp::cl::Error, rp::scene::AssetError, rp::display::DisplayError, std::exception); cli.cpp
// turns exceptions into "rolypoly: error: <message>" and exit code 1.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "app/render_session.h"

namespace rp::app {

struct ImageSize {
  uint32_t width = 720, height = 720;
};

// What the simulated world starts with (render, run and bench).
struct SimulationArgs {
  uint64_t seed = 1;       // --seed: marbles' and particles' random streams
  bool marbles = false;    // --marbles: start with the 30 marbles (key S); bench --accuracy:
                           // also the marble section (bench/src/accuracy_marbles.h)
  bool fireball = false;   // --fireball: start with a fireball (key F)
  std::string replay;      // --replay FILE: input log to replay ("" = none)
};

struct RenderOptions {
  ImageSize size;
  uint32_t frames = 1;
  bool frames_given = false;  // --frames on the command line (else a replay's frame count)
  std::string out_dir = "out";
  std::string video;          // --video FILE.mp4: also pipe the frames to ffmpeg
  bool exr = false;           // --exr: also frame_NNNN.exr (linear components; always when
                              // path traced)
  SimulationArgs sim;
};

struct RunOptions {
  ImageSize size;
  uint32_t frames = 0;   // 0 = until the window is closed
  std::string capture;   // PNG of the window's content after the last frame ("" = none)
  std::string record;    // --record FILE: write the session's input log on exit ("" = none)
  SimulationArgs sim;
};

struct BenchOptions {
  ImageSize size;        // --size / --width / --height: the one size when --sizes is not given
  SimulationArgs sim;
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
  std::optional<double> max_indirect_l1_single, min_psnr_taa;
  std::optional<double> min_direct_psnr_floor, max_penumbra_error, min_albedo_psnr;
  bool require_wall_hue = false;
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

// `rolypoly export`: the demo's frame as a glTF 2.0 file.
struct ExportOptions {
  std::string file;  // FILE.glb (binary) or FILE.gltf (JSON with the buffer as a data URI)
  SimulationArgs sim;  // --seed, --marbles, --fireball: which frame of the demo
};

// Prints every OpenCL platform/device.
int devices_command();
// Headless: frame_0000.png ... into out_dir (with common.pathtraced: pathtrace_render_command).
int render_command(const CommonOptions& common, const RenderOptions& options);
// --quality pathtraced: the same frames path traced on the host (no OpenCL), frame_NNNN.png
// and frame_NNNN.exr (app/pathtrace_command.cpp).
int pathtrace_render_command(const CommonOptions& common, const RenderOptions& options);
// Window (GLFW); throws rp::display::DisplayError when no window can be opened.
int run_command(const CommonOptions& common, const RunOptions& options);
// Timing tables per device and run, optional JSON, chart and Markdown. Exit code 0 when at
// least one device completed, 1 when every device was skipped.
int bench_command(const CommonOptions& common, const BenchOptions& options);
// The files a bench writes: `given`, with out/bench.json and out/bench.svg for --json and
// --chart when a device sweep (--devices) named none (bench/src/bench_command.cpp).
BenchOptions with_default_outputs(const BenchOptions& given);
// bench --accuracy: the real-time modes against the path-traced truth (bench/src/accuracy_report.h);
// exit 3 when a threshold (--max-indirect-l1 ... --require-wall-hue) is missed, 130 when
// interrupted.
int accuracy_command(const CommonOptions& common, const BenchOptions& options);
// bench --quality pathtraced: seconds and Mrays/s per path-traced frame, optional JSON (schema
// "rolypoly-pathtrace-bench/1"). file: a loaded scene file instead of the demo, with
// scene_file: its facts for the JSON ("scene_file").
struct FileScene;
int pathtrace_bench_command(const CommonOptions& common, const BenchOptions& options,
                           const FileScene* file = nullptr,
                           const nlohmann::ordered_json* scene_file = nullptr);

// Writes the demo's first frame (room, lamp, tumblers, marbles and fireball when asked) with
// its materials and textures embedded and its lamp as a light (scene/gltf_export.h).
int export_command(const CommonOptions& common, const ExportOptions& options);

}  // namespace rp::app
