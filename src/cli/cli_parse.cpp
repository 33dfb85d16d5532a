// parse_cli (cli/cli.h): every subcommand's options, CLI11's parse and the usage checks. The
// options shared by several subcommands are app/cli_options.h; the bench's are
// bench/src/bench_cli.h. Nothing here opens a device, a file or the terminal, so
// fuzz/cli_fuzzer.cpp compiles these files alone and fuzzes the real command line.
#include <cctype>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/cli_options.h"
#include "app/printable.h"
#include "app/scene_input.h"
#include "bench/src/bench_cli.h"
#include "cli/cli.h"
#include "passes/debug_view.h"

namespace rp::cli {
namespace {

using app::add_bounces;
using app::add_common;
using app::add_simulation;
using app::add_size;
using app::add_sky_options;
using app::add_spp;
using app::add_view;
using app::check_bounces;
using app::check_pathtrace;
using app::check_render_scale;
using app::check_sky;
using app::check_voxel_level;
using app::resolve_gi_volume;
using app::CommonOptions;
using app::is_demo_scene;
using app::printable;
using app::RenderOptions;
using app::RunOptions;
using app::SizeArgs;
using app::ViewArgs;
using app::whole_number;

constexpr const char* kMoreHelp = "Run with --help for more information.\n";

// `why` often echoes the user's value (CLI11's messages too): printable() cuts a long one and
// escapes control bytes.
CliExit usage(const std::string& who, const std::string& why) {
  return {2, who + ": " + printable(why) + "\n" + kMoreHelp};
}

// The first option of `cmd` given an empty value ("--voxels ''", "--json=", "--sizes 256,,512"),
// or nullptr. CLI11 takes "" as a value: numbers became 0 or their default, paths the current
// folder or nothing, so `--record ""` silently recorded nothing. Flags (no value) are skipped.
const CLI::Option* option_with_empty_value(const CLI::App* cmd) {
  for (const CLI::Option* opt : cmd->get_options()) {
    if (opt->get_type_size_max() == 0 || opt->count() == 0) continue;
    for (const std::string& value : opt->results())
      if (value.empty()) return opt;
  }
  return nullptr;
}

// A comma-separated list with an empty entry ("256,,512", ",32"): CLI11 drops the entry, so
// such a list used to run with fewer items than written; `--devices ,` failed only once the
// device list was read (exit 1). "" when fine.
std::string check_list_entries(int argc, const char* const* argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    for (const std::string name : {"--sizes", "--voxels", "--devices"}) {
      std::string list;
      if (word == name && i + 1 < argc)
        list = argv[i + 1];
      else if (word.rfind(name + "=", 0) == 0)
        list = word.substr(name.size() + 1);
      else
        continue;
      if (!list.empty() && (list.front() == ',' || list.back() == ',' ||
                            list.find(",,") != std::string::npos))
        return name + ": empty entry in '" + list + "'";
    }
  }
  return "";
}

// --device is an index from `rolypoly devices` or part of a name: an index too large for any
// device list used to reach std::stoul and fail with its bare message "stoul".
std::string check_device_index(const std::string& spec) {
  if (spec.empty() || spec.find_first_not_of("0123456789") != std::string::npos) return "";
  if (spec.size() <= 9) return "";  // up to 999999999: "no such device" lists the devices
  return "--device: " + spec + " is not a device index (`rolypoly devices` lists them, from 0)";
}

}  // namespace

CliParse parse_cli(int argc, const char* const* argv) {
  CLI::App app{"rolypoly: a Cornell box of roly-poly toys, rendered entirely by OpenCL kernels",
               "rolypoly"};
  app.require_subcommand(1);

  ParsedCommand parsed;
  CommonOptions& common = parsed.common;
  SizeArgs render_size, run_size;
  ViewArgs render_view, run_view;
  RenderOptions& render_opts = parsed.render;
  RunOptions& run_opts = parsed.run;

  CLI::App* devices = app.add_subcommand("devices", "list every OpenCL platform and device");

  CLI::App* render = app.add_subcommand("render", "render frames headless into numbered PNGs");
  add_common(render, common, true, true);
  add_sky_options(render, common);
  add_spp(render, common);
  add_bounces(render, common);
  add_size(render, render_size);
  render->add_option("--scene", common.scene,
                     "what to draw: demo (the simulated Cornell box), atrium (a generated "
                     "courtyard, 250k triangles) or a glTF 2.0 file (.gltf or .glb)")
      ->capture_default_str();
  render->add_option("--frames", render_opts.frames, "number of frames")
      ->capture_default_str()
      ->transform(whole_number(1, 1000000));
  render->add_option("--out", render_opts.out_dir, "output folder (created if missing)")
      ->capture_default_str();
  render->add_option("--video", render_opts.video,
                     "also encode the frames into this video file with ffmpeg (60 fps)");
  render->add_flag("--exr", render_opts.exr,
                   "also write frame_NNNN.exr: the linear combined image and its direct, "
                   "indirect, emission and albedo layers (always with --quality pathtraced)");
  add_simulation(render, render_opts.sim);
  add_view(render, render_view);

  CLI::App* run = app.add_subcommand("run", "show the frames in a window (Esc quits)");
  add_common(run, common, true, false);
  add_sky_options(run, common);
  add_bounces(run, common);
  add_size(run, run_size);
  run->add_option("--scene", common.scene,
                  "what to show: demo (the simulated Cornell box), atrium (a generated "
                  "courtyard) or a glTF 2.0 file (.gltf or .glb) to fly through")
      ->capture_default_str();
  run->add_option("--frames", run_opts.frames, "frames to show, 0 = until the window is closed")
      ->capture_default_str()
      ->transform(whole_number(0, std::numeric_limits<uint32_t>::max()));
  run->add_option("--capture", run_opts.capture,
                  "after the last frame, save what the window shows to this PNG");
  run->add_option("--record", run_opts.record,
                  "write every input event and frame to this log on exit (replay it with "
                  "`rolypoly render --replay FILE`)");
  add_simulation(run, run_opts.sim);
  add_view(run, run_view);

  CLI::App* export_cmd = app.add_subcommand(
      "export", "write the demo's frame as a glTF 2.0 file (.glb, or .gltf with the data "
                "embedded) that --scene FILE opens again");
  export_cmd->add_option("FILE", parsed.exporting.file, "the file to write (.glb or .gltf)")
      ->required();
  export_cmd->add_option("--scene", common.scene, "what to export: demo (the only choice)")
      ->capture_default_str();
  app::add_open_demo(export_cmd, common);
  export_cmd->add_option("--assets", common.asset_dir,
                         "folder with the demo's textures (default: the built-in asset folder)");
  add_simulation(export_cmd, parsed.exporting.sim);
  export_cmd->remove_option(export_cmd->get_option("--replay"));

  bench::BenchCli bench_cli(app, common, parsed.bench);
  CLI::App* bench = bench_cli.command();

  // CLI11 reports an unknown first word only as "A subcommand is required"; name it instead.
  if (argc > 1 && argv[1][0] != '-') {
    std::string word = argv[1], known;
    bool found = false;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      found = found || sub->get_name() == word;
      known += (known.empty() ? "" : ", ") + sub->get_name();
    }
    if (!found)
      return usage("rolypoly", "unknown subcommand '" + word + "' (expected one of: " + known +
                                   ")");
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    return CliExit{0, app.help()};
  } catch (const CLI::CallForAllHelp&) {
    return CliExit{0, app.help("", CLI::AppFormatMode::All)};
  } catch (const CLI::ParseError& e) {
    return usage("rolypoly: error", e.what());
  }
  if (std::string why = check_list_entries(argc, argv); !why.empty())
    return usage("rolypoly: error", why);
  for (const CLI::App* cmd : {render, run, bench, export_cmd}) {
    if (!cmd->parsed()) continue;
    if (const CLI::Option* empty = option_with_empty_value(cmd))
      return usage("rolypoly " + cmd->get_name(),
                   empty->get_name() + " needs a value; an empty one is not allowed");
    if (std::string why = check_device_index(common.device); !why.empty())
      return usage("rolypoly " + cmd->get_name(), why);
  }
  for (const auto& [cmd, args] : {std::pair{render, &render_view}, std::pair{run, &run_view}}) {
    if (!cmd->parsed()) continue;
    if (std::string why = args->resolve(common.view); !why.empty())
      return usage("rolypoly " + cmd->get_name(), why);
  }

  if (devices->parsed()) {
    parsed.kind = ParsedCommand::Kind::kDevices;
  } else if (render->parsed()) {
    if (std::string why = resolve_gi_volume(render, common); !why.empty())
      return usage("rolypoly render", why);
    if (std::string why = check_voxel_level(common); !why.empty())
      return usage("rolypoly render", why);
    if (std::string why = check_pathtrace(render, common); !why.empty())
      return usage("rolypoly render", why);
    if (std::string why = check_sky(render, common, false, is_demo_scene(common.scene));
        !why.empty())
      return usage("rolypoly render", why);
    if (std::string why = check_render_scale(common, render_opts.exr ? "--exr" : nullptr);
        !why.empty())
      return usage("rolypoly render", why);
    if (!is_demo_scene(common.scene)) {
      for (const char* name :
           {"--seed", "--marbles", "--fireball", "--replay", "--assets", "--open"})
        if (render->count(name))
          return usage("rolypoly render",
                       std::string(name) + " applies to the simulated demo, not to a scene "
                       "file (--scene " + common.scene + ")");
    }
    if (common.pathtraced) {
      const passes::DebugView v = common.view.view;
      if (v != passes::DebugView::kFinal && v != passes::DebugView::kDirect &&
          v != passes::DebugView::kIndirect && v != passes::DebugView::kAlbedo)
        return usage("rolypoly render",
                     "--view " + render_view.view +
                         " is not available with --quality pathtraced; use final, direct, "
                         "indirect or albedo");
      render_opts.exr = true;  // the path-traced frames always come with their EXR
    }
    parsed.kind = ParsedCommand::Kind::kRender;
    render_opts.size = render_size.resolve();
    render_opts.frames_given = render->count("--frames") > 0;
  } else if (run->parsed()) {
    if (std::string why = check_bounces(common); !why.empty()) return usage("rolypoly run", why);
    if (std::string why = check_sky(run, common, false, is_demo_scene(common.scene));
        !why.empty())
      return usage("rolypoly run", why);
    if (std::string why = resolve_gi_volume(run, common); !why.empty())
      return usage("rolypoly run", why);
    if (std::string why = check_voxel_level(common); !why.empty())
      return usage("rolypoly run", why);
    if (!is_demo_scene(common.scene)) {
      for (const char* name :
           {"--seed", "--marbles", "--fireball", "--replay", "--record", "--assets", "--open"})
        if (run->count(name))
          return usage("rolypoly run",
                       std::string(name) + " applies to the simulated demo, not to a scene "
                       "file (--scene " + common.scene + ")");
    }
    parsed.kind = ParsedCommand::Kind::kRun;
    run_opts.size = run_size.resolve();
  } else if (export_cmd->parsed()) {
    if (!is_demo_scene(common.scene))
      return usage("rolypoly export", "--scene takes only demo (a scene file is already glTF)");
    const std::string& f = parsed.exporting.file;
    const auto ends_with = [&f](const char* ext) {
      const std::string e(ext);
      if (f.size() <= e.size()) return false;
      std::string tail = f.substr(f.size() - e.size());
      for (char& c : tail) c = char(std::tolower(static_cast<unsigned char>(c)));
      return tail == e;
    };
    if (!ends_with(".glb") && !ends_with(".gltf"))
      return usage("rolypoly export", "FILE must end in .glb or .gltf, not '" + f + "'");
    parsed.kind = ParsedCommand::Kind::kExport;
  } else if (bench->parsed()) {
    if (std::string why = bench_cli.finish(argc, argv); !why.empty())
      return usage("rolypoly bench", why);
    parsed.kind = ParsedCommand::Kind::kBench;
  } else {
    return usage("rolypoly: error", "no subcommand given (try --help)");  // CLI11 requires one
  }
  return parsed;
}

}  // namespace rp::cli
