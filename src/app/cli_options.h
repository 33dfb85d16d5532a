// The options that several subcommands share (device, quality, effects, sky, sizes, the
// simulation, debug views), their validators and their usage checks, declared on a CLI11
// subcommand. The command line (src/cli/cli_parse.cpp) and the bench's options
// (bench/src/bench_cli.cpp) are built from these. Nothing here opens a device, a file or the
// terminal.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "passes/debug_view.h"
#include "util/named_enum.h"

namespace rp::app {

constexpr uint32_t kMaxSize = 16384;  // pixels per side; far above any sensible render

// Pixel counts: checks the text before CLI11 converts it, so that 0, negative and non-numeric
// values get a message that says what is allowed (CLI11's own would be "Value -5 not in range
// 1 to 16384"), and rewrites it as plain decimal: CLI11 converts integers with base 0, so
// "0720" would otherwise become octal 464. Whether the size fits the device's memory is checked
// later, once the device is known (render_session.cpp).
CLI::Validator pixel_count();

// Any other whole number in [lo, hi], decimal only and rewritten as such (see pixel_count).
CLI::Validator whole_number(uint64_t lo, uint64_t hi);

// A decimal number in [lo, hi] ("0.25", "1", "5e-1"). CLI11's float conversion also takes "nan",
// "inf" and hex floats, and its Range check lets NaN through (every comparison with NaN is
// false), so --bloom-strength nan used to be accepted.
CLI::Validator decimal_in(double lo, double hi);

// An option whose value is one of E's names (util/named_enum.h): CLI11 lists and checks the
// choices, then the callback stores the value in `field`.
template <typename E>
CLI::Option* add_named_option(CLI::App* cmd, const std::string& flag, E& field,
                              const std::string& help) {
  return cmd
      ->add_option_function<std::string>(
          flag, [&field](const std::string& name) { field = *parse_name<E>(name); }, help)
      ->check(CLI::IsMember(name_list<E>()));
}

// --size sets both sides; --width / --height override one of them.
struct SizeArgs {
  uint32_t size = 720;
  uint32_t width = 0, height = 0;  // 0 = take --size
  ImageSize resolve() const { return {width ? width : size, height ? height : size}; }
};

// `voxel_option`: false for bench, which takes a list of resolutions instead. `pathtraced`:
// --quality also offers pathtraced (render and bench; the window shows only real-time frames).
void add_common(CLI::App* cmd, CommonOptions& common, bool voxel_option, bool pathtraced);
// --open (CommonOptions::open_demo): in add_common, and for `export`.
void add_open_demo(CLI::App* cmd, CommonOptions& common);

// --voxels against --gi-volume (each resolution list entry): "" when fine.
std::string check_gi_volume(const CommonOptions& common, const std::vector<uint32_t>& voxels);

// render and run: --gi-volume svo without --voxels takes the octree's default resolution
// (render::RenderSettings::kDefaultSvoResolution); then check_gi_volume. "" when fine.
std::string resolve_gi_volume(const CLI::App* cmd, CommonOptions& common);

// --bounces 0 (no indirect light at all) exists only in the path tracer: "" when fine.
std::string check_bounces(const CommonOptions& common);

// --spp (render and bench): the path tracer's samples per pixel (and bench --accuracy's truth).
// --lamp: the path tracer's lamp model (truth/path_tracer.h).
void add_spp(CLI::App* cmd, CommonOptions& common);

// --bounces (render, run and bench): every mode's bounce count, so each can be compared with
// the path tracer at the same count.
void add_bounces(CLI::App* cmd, CommonOptions& common);

// --env / --sky clear and their settings (render, run, bench): light from afar.
void add_sky_options(CLI::App* cmd, CommonOptions& common);

// Usage checks of --env / --sky, --sky-light and their settings: "" when fine (`demo_scene`:
// the simulated demo, whose moving toys PRT cannot hold). Every mode lights with the
// sky; `accuracy_demo`: bench --accuracy on the demo, whose sections (the lamp's direct light,
// the marbles) are measured without one.
std::string check_sky(const CLI::App* cmd, const CommonOptions& common, bool accuracy_demo,
                      bool demo_scene);

// --render-scale and --target-ms change how the real-time final image is made: "" when fine.
// `components_option`: the option of this command that reads the light pass's terms at the
// output size (render --exr, bench --accuracy), which the render scale does not reconstruct;
// nullptr when none.
std::string check_render_scale(const CommonOptions& common, const char* components_option);

// Usage checks of --quality pathtraced and its options (render and bench): "" when fine.
// Options that pick the OpenCL device or change the real-time image cannot apply to the host
// path tracer, so they are refused rather than silently ignored; the --no-* switches ask for
// less post-processing than the path tracer already has none of, and pass. --bounces applies to
// every mode, but the real-time modes always model at least one bounce.
std::string check_pathtrace(const CLI::App* cmd, const CommonOptions& common);

// --size, --width, --height.
void add_size(CLI::App* cmd, SizeArgs& size);

// --seed, --marbles, --fireball, --replay: what the simulated demo starts with.
void add_simulation(CLI::App* cmd, SimulationArgs& sim);

// --view / --level / --dir (render and run): a debug view instead of the final image.
struct ViewArgs {
  std::string view = "final";
  uint32_t level = 0;
  std::string dir = "+x";
  CLI::Option* level_option = nullptr;
  CLI::Option* dir_option = nullptr;

  // The settings, or a usage message when --level / --dir come without --view voxels. The
  // names were checked by CLI11 (IsMember); a name that slipped through is reported, not
  // dereferenced.
  std::string resolve(passes::DebugViewSettings& out) const;
};

// --view, --level, --dir.
void add_view(CLI::App* cmd, ViewArgs& args);

// --level against the volume --view voxels shows: the dense chain has levels 0 .. log2 R (1^3
// at the top), the octree 0 .. log2 R - 1. Checked here rather than when the renderer sets the
// view, after the device and the kernels (exit 1 there). "" when fine.
std::string check_voxel_level(const CommonOptions& common);

}  // namespace rp::app
