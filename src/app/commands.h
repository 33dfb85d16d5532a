// The subcommands of `rolypoly`. Each returns the process exit code and throws on errors
// (rp::cl::Error, rp::scene::AssetError, rp::display::DisplayError, std::exception); cli.cpp
// turns exceptions into "rolypoly: error: <message>" and exit code 1.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

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
// Writes the demo's first frame (room, lamp, tumblers, marbles and fireball when asked) with
// its materials and textures embedded and its lamp as a light (scene/gltf_export.h).
int export_command(const CommonOptions& common, const ExportOptions& options);

}  // namespace rp::app
