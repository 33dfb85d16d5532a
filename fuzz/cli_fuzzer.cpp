// libFuzzer target: the whole command line, cli::parse_cli (src/cli/cli_parse.cpp): the real
// CLI11 option definitions, validators and usage checks of every subcommand. parse_cli opens no
// device or file, so this runs the program's own parser, not a copy.
//
// Input: the argument words after "rolypoly", separated by '\n' (argv cannot hold NUL, so
// inputs with NUL are skipped). Findings beyond crashes, sanitizer reports, leaks and hangs:
// - an exception escapes parse_cli;
// - the same argv parses to a different result the second time (parse_cli keeps no state);
// - an exit that is not 0 (help text, only when a word asks for help) or 2 (a usage message
//   "rolypoly...: ...\nRun with --help for more information.\n", its lines at most 3000 bytes
//   and free of control bytes whatever the words echoed);
// - a parsed command whose values break what the commands rely on: sizes 1..16384, voxels
//   32/64/128 for the dense volume and 256/512 for the octree, shadow map 1..16384, bloom
//   strength in [0, 1], a debug
//   view that exists with --level/--dir only for voxels, render/bench frames >= 1, a bench scene
//   that exists, no conflicting bench options, command_line = "rolypoly" + the words; --spp
//   1..1000000, at its default unless --quality pathtraced (or bench --accuracy), which only
//   render and bench take (render: views final/direct/indirect/albedo, EXR on; bench: one
//   size, default scene, no matrix, comparison or report options; neither: --device);
//   --bounces in every mode, 1..1000 in the real-time modes and 0..1000 path traced; bench
//   --accuracy alone on one device and size at its own bounce counts (--spp its truth's
//   samples), its --out, --truth-cache and thresholds (finite, 0..1000) only with it.
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <cstdlib>
#include <exception>
#include <string>
#include <variant>
#include <vector>

#include "cli/cli.h"

namespace {

using rp::cli::CliExit;
using rp::cli::CliParse;
using rp::cli::ParsedCommand;

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_cli: %s\n", what.c_str());
  std::abort();
}

void require(bool ok, const char* what) {
  if (!ok) finding(what);
}

bool valid_size(uint32_t side) { return side >= 1 && side <= 16384; }

bool valid_voxels(uint32_t r) { return r == 32 || r == 64 || r == 128 || r == 256 || r == 512; }
// The octree takes 256 or 512, the dense volume 32, 64 or 128.
bool voxels_fit_volume(uint32_t r, rp::render::GiVolume volume) {
  return (r >= 256) == (volume == rp::render::GiVolume::kSvo);
}

// Every field a command reads, as text: two parses of one argv must give the same string.
std::string describe(const CliParse& result) {
  if (const CliExit* e = std::get_if<CliExit>(&result))
    return "exit " + std::to_string(e->exit_code) + " " + e->message;
  const ParsedCommand& p = std::get<ParsedCommand>(result);
  const rp::app::CommonOptions& c = p.common;
  std::string s = "kind " + std::to_string(int(p.kind));
  auto add = [&s](const std::string& name, const std::string& value) {
    s += "|" + name + "=" + value;
  };
  auto sim = [&add](const rp::app::SimulationArgs& a) {
    add("seed", std::to_string(a.seed));
    add("marbles", std::to_string(a.marbles));
    add("fireball", std::to_string(a.fireball));
    add("replay", a.replay);
  };
  add("device", c.device);
  add("assets", c.asset_dir);
  add("shadow", std::to_string(c.render.shadow_size));
  add("voxels", std::to_string(c.render.voxel_resolution));
  add("fx", std::to_string(c.render.effects.taa) + std::to_string(c.render.effects.bloom) +
                std::to_string(c.render.effects.motion_blur) + " " +
                std::to_string(c.render.effects.bloom_strength));
  add("view", std::to_string(int(c.view.view)) + " " + std::to_string(c.view.level) + " " +
                  std::to_string(c.view.dir));
  add("visibility", std::to_string(int(c.render.visibility)));
  add("quality", std::to_string(int(c.render.quality)));
  add("pathtraced", std::to_string(c.pathtraced) + " " + std::to_string(c.spp) + " " +
                        std::to_string(c.render.bounces));
  add("render", std::to_string(p.render.size.width) + "x" + std::to_string(p.render.size.height) +
                    " " + std::to_string(p.render.frames) + " " +
                    std::to_string(p.render.frames_given) + " " + p.render.out_dir + " " +
                    p.render.video + " " + std::to_string(p.render.exr));
  sim(p.render.sim);
  add("run", std::to_string(p.run.size.width) + "x" + std::to_string(p.run.size.height) + " " +
                 std::to_string(p.run.frames) + " " + p.run.capture + " " + p.run.record);
  sim(p.run.sim);
  const rp::bench::BenchOptions& b = p.bench;
  add("bench", std::to_string(b.size.width) + "x" + std::to_string(b.size.height) + " " +
                   std::to_string(b.frames) + " " + std::to_string(b.warmup) + " " + b.json +
                   " " + std::to_string(b.compare_visibility) + " " + b.devices + " " +
                   b.scene + " " + b.chart + " " + b.markdown + " " + b.command_line);
  add("accuracy", std::to_string(b.accuracy) + " " + std::to_string(b.size_given) + " " +
                      std::to_string(b.accuracy_spp) + " " + b.out_dir + " " + b.truth_cache +
                      " " + std::to_string(b.require_wall_hue));
  for (const std::optional<double>& t : {b.max_indirect_l1, b.max_indirect_bias,
                                         b.max_region_bias, b.max_indirect_l1_single,
                                         b.min_psnr_taa})
    add("threshold", t ? std::to_string(*t) : "-");
  for (uint32_t v : b.sizes) add("sizes", std::to_string(v));
  for (uint32_t v : b.voxels) add("bvoxels", std::to_string(v));
  sim(b.sim);
  return s;
}

void check_exit(const CliExit& e, const std::vector<std::string>& words) {
  require(!e.message.empty() && e.message.back() == '\n', "exit message empty or no newline");
  if (e.exit_code == 0) {
    bool asked = false;
    for (const std::string& w : words) asked = asked || w.rfind("-h", 0) == 0 || w.rfind("--help", 0) == 0;
    require(asked, "exit code 0 without -h/--help");
    return;
  }
  require(e.exit_code == 2, "exit code is neither 0 nor 2");
  require(e.message.rfind("rolypoly", 0) == 0, "usage message does not start with 'rolypoly'");
  require(e.message.find("Run with --help for more information.\n") != std::string::npos,
          "usage message does not point to --help");
  // Echoed values are cut and escaped (app/printable.h): short lines, no control bytes.
  size_t line = 0;
  for (const char c : e.message) {
    line = c == '\n' ? 0 : line + 1;
    require(line <= 3000, "usage message line longer than 3000 bytes");
    require(c == '\n' || static_cast<unsigned char>(c) >= 0x20, "control byte in usage message");
    require(c != 0x7f, "DEL byte in usage message");
  }
}

void check_view(const rp::passes::DebugViewSettings& v) {
  require(int(v.view) >= 0 && v.view <= rp::passes::DebugView::kVoxels, "view out of range");
  require(v.dir < 6, "voxel direction out of range");
  if (v.view != rp::passes::DebugView::kVoxels)
    require(v.level == 0 && v.dir == 0, "--level/--dir accepted without --view voxels");
}

void check_command(const ParsedCommand& p, const std::vector<std::string>& words) {
  const rp::app::CommonOptions& c = p.common;
  require(valid_size(c.render.shadow_size), "--shadow-size out of range");
  require(valid_voxels(c.render.voxel_resolution), "--voxels not 32/64/128/256/512");
  if (p.kind == ParsedCommand::Kind::kRender || p.kind == ParsedCommand::Kind::kRun)
    require(voxels_fit_volume(c.render.voxel_resolution, c.render.gi_volume),
            "--voxels that the --gi-volume does not take");
  const float f = c.render.effects.bloom_strength;
  require(f >= 0.0f && f <= 1.0f, "--bloom-strength outside [0, 1] (or NaN)");
  require(c.render.visibility == rp::render::VisibilityBackend::kRaster ||
              c.render.visibility == rp::render::VisibilityBackend::kEmbree,
          "--visibility out of range");
  require(c.render.quality == rp::render::Quality::kFast ||
              c.render.quality == rp::render::Quality::kReference,
          "--quality out of range");
  require(c.spp >= 1 && c.spp <= 1000000, "--spp out of range");
  require(c.render.bounces <= 1000, "--bounces out of range");
  const bool accuracy = p.kind == ParsedCommand::Kind::kBench && p.bench.accuracy;
  if (accuracy)
    require(c.render.bounces == rp::render::RenderSettings::kDefaultBounces,
            "bench --accuracy took --bounces (it renders 1 and 64 itself)");
  if (!c.pathtraced)
    require((c.spp == 256 || accuracy) && c.render.bounces >= 1,
            "--spp without --quality pathtraced or --accuracy, or --bounces 0 in a real-time mode");
  else
    require(c.device.empty() && (p.kind == ParsedCommand::Kind::kRender ||
                                 p.kind == ParsedCommand::Kind::kBench),
            "--quality pathtraced with --device or outside render and bench");
  switch (p.kind) {
    case ParsedCommand::Kind::kDevices: break;
    case ParsedCommand::Kind::kRender:
      require(valid_size(p.render.size.width) && valid_size(p.render.size.height),
              "render size out of range");
      require(p.render.frames >= 1 && p.render.frames <= 1000000, "render --frames out of range");
      check_view(c.view);
      if (c.pathtraced) {
        using rp::passes::DebugView;
        require(c.view.view == DebugView::kFinal || c.view.view == DebugView::kDirect ||
                    c.view.view == DebugView::kIndirect || c.view.view == DebugView::kAlbedo,
                "--quality pathtraced with a view the path tracer has no image for");
        require(p.render.exr, "--quality pathtraced without its EXR");
      }
      break;
    case ParsedCommand::Kind::kRun:
      require(valid_size(p.run.size.width) && valid_size(p.run.size.height),
              "run size out of range");
      check_view(c.view);
      break;
    case ParsedCommand::Kind::kExport: {
      // a .glb or .gltf name, the demo only
      const std::string& name = p.exporting.file;
      std::string tail = name.size() >= 5 ? name.substr(name.size() - 5) : name;
      for (char& ch : tail) ch = char(std::tolower(static_cast<unsigned char>(ch)));
      require(c.scene == "demo" && (tail == ".gltf" || tail.substr(1) == ".glb"),
              "export of something other than the demo, or to a name not .glb / .gltf");
      break;
    }
    case ParsedCommand::Kind::kBench: {
      const rp::bench::BenchOptions& b = p.bench;
      require(valid_size(b.size.width) && valid_size(b.size.height), "bench size out of range");
      for (uint32_t s : b.sizes) require(valid_size(s), "bench --sizes entry out of range");
      for (uint32_t v : b.voxels)
        require(valid_voxels(v) && voxels_fit_volume(v, c.render.gi_volume),
                "bench --voxels entry not one the --gi-volume takes");
      require(b.frames >= 1 && b.frames <= 1000000, "bench --frames out of range");
      require(b.warmup <= 1000000, "bench --warmup out of range");
      // default, busy or a scene file's path ("demo" reads as default)
      require(!b.scene.empty() && b.scene != "demo", "bench --scene empty or not resolved");
      require(b.devices.empty() || c.device.empty(), "bench took both --devices and --device");
      if (b.compare_visibility)
        require(b.devices.empty() && b.sizes.empty() && b.voxels.size() <= 1,
                "--compare-visibility with several devices, sizes or voxel resolutions");
      if (c.pathtraced)
        require(b.devices.empty() && b.sizes.empty() && b.voxels.empty() &&
                    !b.compare_visibility && !b.quality_report && b.scene != "busy" &&
                    b.chart.empty() && b.markdown.empty(),
                "bench --quality pathtraced with matrix, comparison or report options");
      if (b.accuracy) {
        require(b.devices.empty() && b.sizes.empty() && b.voxels.size() <= 1 &&
                    !b.compare_visibility && !b.quality_report && !c.pathtraced &&
                    b.scene != "busy" && b.chart.empty() && b.markdown.empty(),
                "bench --accuracy with matrix, comparison, report or path-tracer options");
        require(b.accuracy_spp >= 1 && b.accuracy_spp <= 1000000, "--accuracy --spp out of range");
      } else {
        require(b.out_dir == "out/accuracy" && b.truth_cache.empty() && !b.max_indirect_l1 &&
                    !b.max_indirect_bias && !b.max_region_bias && !b.max_indirect_l1_single &&
                    !b.min_psnr_taa && !b.require_wall_hue,
                "--accuracy's options accepted without --accuracy");
      }
      for (const std::optional<double>& t : {b.max_indirect_l1, b.max_indirect_bias,
                                             b.max_region_bias, b.max_indirect_l1_single,
                                             b.min_psnr_taa})
        require(!t || (std::isfinite(*t) && *t >= 0.0 && *t <= 1000.0),
                "--accuracy threshold out of range");
      std::string line = "rolypoly";
      for (const std::string& w : words) line += " " + w;
      require(b.command_line == line, "bench command_line is not the arguments");
      break;
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (text.find('\0') != std::string::npos) return 0;
  std::vector<std::string> words;
  for (size_t start = 0; start <= text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    words.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  if (words.size() == 1 && words[0].empty()) words.clear();  // empty input: no arguments
  std::vector<const char*> argv = {"rolypoly"};
  for (const std::string& w : words) argv.push_back(w.c_str());
  argv.push_back(nullptr);
  const int argc = static_cast<int>(argv.size() - 1);

  CliParse first, second;
  try {
    first = rp::cli::parse_cli(argc, argv.data());
    second = rp::cli::parse_cli(argc, argv.data());
  } catch (const std::exception& e) {
    finding(std::string("parse_cli threw: ") + e.what());
  } catch (...) {
    finding("parse_cli threw a non-std exception");
  }
  if (describe(first) != describe(second)) finding("the same argv parsed differently twice");
  if (const CliExit* e = std::get_if<CliExit>(&first))
    check_exit(*e, words);
  else
    check_command(std::get<ParsedCommand>(first), words);
  return 0;
}
