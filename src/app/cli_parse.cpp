// parse_cli (app/cli.h): the options of every subcommand, CLI11's parse and the usage checks.
// Nothing here opens a device, a file or the terminal, so fuzz/cli_fuzzer.cpp compiles this file
// alone (with passes/debug_view.cpp for the view names) and fuzzes the real command line.
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/cli.h"
#include "app/printable.h"
#include "app/scene_input.h"
#include "passes/debug_view.h"

namespace rp::app {
namespace {

constexpr uint32_t kMaxSize = 16384;  // pixels per side; far above any sensible render
constexpr const char* kMoreHelp = "Run with --help for more information.\n";

// Reads optional sign + decimal digits (nothing else: no spaces, no base prefix). Values beyond
// +-10^18 saturate there, which is out of every range below. False when `text` is not of
// that form.
bool read_decimal(const std::string& text, long long& value) {
  size_t i = 0;
  bool negative = false;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) negative = text[i++] == '-';
  if (i == text.size()) return false;
  constexpr long long kSaturate = 1000000000000000000LL;
  long long v = 0;
  for (; i < text.size(); ++i) {
    if (text[i] < '0' || text[i] > '9') return false;
    // v >= 10^17 would reach 10^18 with this digit (and v * 10 overflows from 9.3 10^17 on,
    // which the CLI fuzzer found): saturate before multiplying.
    v = v >= kSaturate / 10 ? kSaturate : v * 10 + (text[i] - '0');
  }
  value = negative ? -v : v;
  return true;
}

// Pixel counts: checks the text before CLI11 converts it, so that 0, negative and non-numeric
// values get a message that says what is allowed (CLI11's own would be "Value -5 not in range
// 1 to 16384"), and rewrites it as plain decimal: CLI11 converts integers with base 0, so
// "0720" would otherwise become octal 464. Whether the size fits the device's memory is checked
// later, once the device is known (render_session.cpp).
CLI::Validator pixel_count() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        long long value = 0;
        const std::string range = "give 1 to " + std::to_string(kMaxSize) + " pixels";
        if (!read_decimal(text, value))
          return "'" + text + "' is not a whole number of pixels; " + range;
        if (value < 1)
          return text + " pixels is not a size: an image needs at least 1 pixel per side; " +
                 range;
        if (value > kMaxSize)
          return text + " pixels is above the limit of " + std::to_string(kMaxSize) +
                 " per side; " + range;
        text = std::to_string(value);
        return "";
      },
      "PIXELS in 1.." + std::to_string(kMaxSize));
}

// Any other whole number in [lo, hi], decimal only and rewritten as such (see pixel_count).
CLI::Validator whole_number(uint64_t lo, uint64_t hi) {
  const std::string range = std::to_string(lo) + " to " + std::to_string(hi);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        // Up to 20 digits: uint64 values above 10^18 (--seed) are read digit by digit.
        size_t first = text.size() > 1 && text[0] == '+' ? 1 : 0;
        bool digits = first < text.size() && text.size() - first <= 20;
        uint64_t value = 0;
        for (size_t i = first; digits && i < text.size(); ++i) {
          const uint64_t d = uint64_t(text[i] - '0');
          if (text[i] < '0' || text[i] > '9' ||
              value > (std::numeric_limits<uint64_t>::max() - d) / 10)
            digits = false;  // not a digit, or above 2^64 - 1
          else
            value = value * 10 + d;
        }
        if (!digits || value < lo || value > hi)
          return "'" + text + "' is not a whole number from " + range;
        text = std::to_string(value);
        return "";
      },
      "INT in " + range);
}

// A decimal number in [lo, hi] ("0.25", "1", "5e-1"). CLI11's float conversion also takes "nan",
// "inf" and hex floats, and its Range check lets NaN through (every comparison with NaN is
// false), so --bloom-strength nan used to be accepted.
CLI::Validator decimal_in(double lo, double hi) {
  char range[64];
  std::snprintf(range, sizeof range, "%g to %g", lo, hi);
  return CLI::Validator(
      [lo, hi, text_range = std::string(range)](std::string& text) -> std::string {
        bool ok = !text.empty() && text.size() < 64 &&
                  text.find_first_not_of("0123456789+-.eE") == std::string::npos;
        double value = 0.0;
        if (ok) {
          char* end = nullptr;
          value = std::strtod(text.c_str(), &end);
          ok = end == text.c_str() + text.size() && std::isfinite(value) && value >= lo &&
               value <= hi;
        }
        return ok ? "" : "'" + text + "' is not a number from " + text_range;
      },
      "NUMBER in " + std::string(range));
}

// --size sets both sides; --width / --height override one of them.
struct SizeArgs {
  uint32_t size = 720;
  uint32_t width = 0, height = 0;  // 0 = take --size
  ImageSize resolve() const { return {width ? width : size, height ? height : size}; }
};

// `voxel_option`: false for bench, which takes a list of resolutions instead. `pathtraced`:
// --quality also offers pathtraced (render and bench; the window shows only real-time frames).
void add_common(CLI::App* cmd, CommonOptions& common, bool voxel_option, bool pathtraced) {
  cmd->add_option("--device", common.device,
                  "OpenCL device: index from `rolypoly devices` or part of its name "
                  "(case-insensitive); default: first GPU, else first CPU");
  cmd->add_option("--assets", common.asset_dir,
                  "folder with the scene's textures (default: the built-in asset folder)");
  cmd->add_option("--shadow-size", common.shadow_size,
                  "shadow map texels per side (default: the renderer's, " +
                      std::to_string(render::RenderSettings{}.shadow_size) + ")")
      ->transform(whole_number(1, kMaxSize));
  if (voxel_option)
    cmd->add_option("--voxels", common.voxels,
                    "GI voxel volume resolution per side: 32, 64 or 128 for --gi-volume dense "
                    "(default " +
                        std::to_string(render::RenderSettings{}.voxel_resolution) +
                        "), 256 or 512 for --gi-volume svo (default " +
                        std::to_string(CommonOptions::kDefaultSvoVoxels) + ")")
        ->check(CLI::IsMember({32u, 64u, 128u, 256u, 512u}));
  cmd->add_option_function<std::string>(
         "--gi-volume",
         [&common](const std::string& name) {
           common.gi_volume = *render::parse_gi_volume(name);  // IsMember checked the name
         },
         "the volume the GI cones trace: dense (the anisotropic mip chain, 32^3 to 128^3; "
         "default) or svo (the sparse voxel octree with 3^3 bricks, 256^3 or 512^3: finer "
         "contacts for more build time, memory only where surfaces are)")
      ->check(CLI::IsMember({"dense", "svo"}));
  cmd->add_option_function<std::string>(
         "--visibility",
         [&common](const std::string& name) {
           common.visibility = name == "embree" ? render::VisibilityBackend::kEmbree
                                                : render::VisibilityBackend::kRaster;
         },
         "where the visibility buffer comes from: raster (compute rasterizer on the OpenCL "
         "device, default) or embree (Embree primary rays on the host's cores, uploaded)")
      ->check(CLI::IsMember({"raster", "embree"}));
  std::string quality_help =
      "indirect light: fast (real-time default: reduced resolution, interleaved cones, "
      "temporal accumulation), reference (per-pixel 16 cones at full resolution, twice the "
      "steps, no temporal reuse)";
  std::vector<std::string> qualities = {"fast", "reference"};
  if (pathtraced) {
    quality_help += " or pathtraced (the ground truth: Monte Carlo path tracing of the same "
                    "frame on the host's cores with Embree, no OpenCL device; --spp, --bounces)";
    qualities.push_back("pathtraced");
  } else {
    quality_help += " (render and bench also take pathtraced)";
  }
  cmd->add_option_function<std::string>(
         "--quality",
         [&common](const std::string& name) {
           common.quality =
               name == "reference" ? render::Quality::kReference : render::Quality::kFast;
           common.pathtraced = name == "pathtraced";
         },
         quality_help)
      ->check(CLI::IsMember(qualities));
  cmd->add_option_function<std::string>(
         "--texture-filter",
         [&common](const std::string& name) {
           common.texture_filter = name == "bilinear"    ? render::TextureFilter::kBilinear
                                   : name == "anisotropic" ? render::TextureFilter::kAnisotropic
                                                           : render::TextureFilter::kTrilinear;
         },
         "surface textures: bilinear (level 0 only: aliases in the distance), trilinear "
         "(default: mipmaps, level from the pixel's footprint) or anisotropic (up to 4 "
         "trilinear taps along the footprint's long axis: sharper at grazing angles)")
      ->check(CLI::IsMember({"bilinear", "trilinear", "anisotropic"}));
  // --shadows: the light pass's shadow filter; key H cycles it in the window.
  cmd->add_option_function<std::string>(
         "--shadows",
         [&common](const std::string& name) {
           common.shadows = *render::parse_shadow_mode(name);  // IsMember checked the name
         },
         "how the lamp's shadow is filtered: hard (one tap: a point lamp's hard edge), pcf "
         "(fixed-width soft edge), pcss (penumbra from the lamp's size and the blocker and "
         "receiver depths; default) or vssm (the same from filtered depth moments)")
      ->check(CLI::IsMember({"hard", "pcf", "pcss", "vssm"}));
  auto off = [&](const char* name, bool& flag, const char* what) {
    cmd->add_flag_callback(name, [&flag] { flag = false; }, what);
  };
  off("--no-taa", common.effects.taa, "temporal anti-aliasing off (key T toggles it)");
  off("--no-bloom", common.effects.bloom, "bloom off (key B toggles it)");
  off("--no-motion-blur", common.effects.motion_blur, "motion blur off (key M toggles it)");
  cmd->add_option("--bloom-strength", common.effects.bloom_strength,
                  "bloom mix factor f: colour * (1 - f) + bloom * f")
      ->capture_default_str()
      ->check(decimal_in(0.0, 1.0));
  cmd->add_option("--render-scale", common.render_scale,
                  "render pixels per output pixel along each axis, 0.5 to 1: below 1 the frame "
                  "is rendered smaller and temporal upsampling reconstructs the output size "
                  "from the jittered frames (bloom, motion blur and tone map at output size)")
      ->capture_default_str()
      ->check(decimal_in(render::RenderSettings::kMinRenderScale, 1.0));
  cmd->add_option("--target-ms", common.target_ms,
                  "hold this frame time (ms): the render scale follows the measured frame time "
                  "(between 0.5 and 1, smoothly, with hysteresis), starting at --render-scale")
      ->check(decimal_in(1.0, 10000.0));
}

// --bounces 0 (no indirect light at all) exists only in the path tracer: "" when fine.
// --voxels against --gi-volume (each resolution list entry): "" when fine.
std::string check_gi_volume(const CommonOptions& common, const std::vector<uint32_t>& voxels) {
  for (uint32_t v : voxels) {
    const bool svo_size = v == 256 || v == 512;  // the app's sizes (the renderer takes more)
    if (v == 0 || svo_size == (common.gi_volume == render::GiVolume::kSvo)) continue;
    if (common.gi_volume == render::GiVolume::kSvo)
      return "--gi-volume svo takes --voxels 256 or 512, not " + std::to_string(v);
    return "--voxels " + std::to_string(v) + " needs --gi-volume svo (the dense volume takes 32, "
           "64 or 128)";
  }
  return "";
}

std::string check_bounces(const CommonOptions& common) {
  if (!common.pathtraced && common.bounces == 0)
    return "--bounces 0 applies to --quality pathtraced; the fast and reference modes take 1 "
           "(single bounce) to 1000";
  return "";
}

// --spp (render and bench): the path tracer's samples per pixel (and bench --accuracy's truth).
// --lamp: the path tracer's lamp model (truth/path_tracer.h).
void add_spp(CLI::App* cmd, CommonOptions& common) {
  cmd->add_option("--spp", common.spp, "--quality pathtraced: samples per pixel")
      ->capture_default_str()
      ->transform(whole_number(1, 1000000));
  cmd->add_option_function<std::string>(
         "--lamp", [&common](const std::string& v) { common.area_lamp = v == "area"; },
         "--quality pathtraced: point (default: the real-time passes' point light) or area (the "
         "lamp cap emits: soft shadows)")
      ->check(CLI::IsMember({"point", "area"}));
}

// --bounces (render, run and bench): every mode's bounce count, so each can be compared with
// the path tracer at the same count.
void add_bounces(CLI::App* cmd, CommonOptions& common) {
  cmd->add_option("--bounces", common.bounces,
                  "indirect bounces: light that left an emitter or a lamp-lit surface reaches "
                  "the camera after at most N reflections besides the surface the camera sees. "
                  "fast and reference: 1 = single-bounce indirect light, any N >= 2 = "
                  "multi-bounce (the voxels' feedback converges to all bounces, compared with the "
                  "path-traced truth at 64); 1..1000. pathtraced: N gathers, 0..1000 (0 = direct "
                  "lamp light and seen emission only)")
      ->capture_default_str()
      ->transform(whole_number(0, 1000));
}

// --sun AZ,EL: two decimal numbers, azimuth 0 to 360 and elevation 1 to 90 (the clear sky
// model's range: scene::make_clear_sky), written back as the two numbers for the callback.
CLI::Validator sun_position() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const std::string why = "'" + text + "' is not AZ,EL in degrees: azimuth 0 to 360 "
                                "(from -z towards +x), elevation 1 to 90 above the horizon";
        const size_t comma = text.find(',');
        if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos)
          return why;
        double values[2] = {0.0, 0.0};
        const std::string parts[2] = {text.substr(0, comma), text.substr(comma + 1)};
        for (int i = 0; i < 2; ++i) {
          const std::string& part = parts[i];
          if (part.empty() || part.size() >= 32 ||
              part.find_first_not_of("0123456789+-.eE") != std::string::npos)
            return why;
          char* end = nullptr;
          values[i] = std::strtod(part.c_str(), &end);
          if (end != part.c_str() + part.size() || !std::isfinite(values[i])) return why;
        }
        if (values[0] < 0.0 || values[0] > 360.0 || values[1] < 1.0 || values[1] > 90.0)
          return why;
        return "";
      },
      "AZ,EL");
}

// --env / --sky clear and their settings (render, run, bench): light from afar.
void add_sky_options(CLI::App* cmd, CommonOptions& common) {
  SkyOptions& sky = common.sky;
  cmd->add_option("--env", sky.env_file,
                  "light the scene from afar with this equirectangular environment map "
                  "(.exr or .hdr, width = 2 x height; its top row is +y, its centre towards "
                  "+z), seen as the background and through the cones (every mode)");
  cmd->add_option("--env-rotate", sky.rotate_deg,
                  "--env: turn the map about +y by DEG degrees (counter-clockwise seen from "
                  "above), -360 to 360")
      ->check(decimal_in(-360.0, 360.0));
  cmd->add_option("--env-strength", sky.strength,
                  "--env or --sky clear: multiply the map's radiance (and the clear sky's sun) "
                  "by K >= 0 (default 1)")
      ->check(decimal_in(0.0, 1000000.0));
  cmd->add_option_function<std::string>(
         "--sky", [&sky](const std::string&) { sky.clear_sky = true; },
         "clear: a built-in Preetham clear sky with its sun as a directional light (--sun "
         "places the sun; every mode)")
      ->check(CLI::IsMember({"clear"}));
  cmd->add_option_function<std::string>(
         "--sun",
         [&sky](const std::string& text) {
           const size_t comma = text.find(',');  // the validator checked the form
           sky.sun_azimuth_deg = std::strtof(text.substr(0, comma).c_str(), nullptr);
           sky.sun_elevation_deg = std::strtof(text.substr(comma + 1).c_str(), nullptr);
         },
         "--sky clear: the sun's azimuth (0 to 360 degrees from -z towards +x) and elevation "
         "(1 to 90 degrees above the horizon), default 135,45")
      ->check(sun_position());
  cmd->add_option_function<std::string>(
         "--sky-light", [&sky](const std::string& v) { sky.prt = v == "prt"; },
         "how the sky's diffuse light reaches surfaces: cones (default: through the voxel "
         "cones, with what they pass by) or prt (precomputed radiance transfer: per-vertex "
         "transfer of a still scene file, computed on the first frame and cached on disk, "
         "dotted with the sky's spherical harmonics; reflections keep the cones)")
      ->check(CLI::IsMember({"cones", "prt"}));
  truth::PrtSettings& prt = sky.prt_settings;
  cmd->add_option_function<int>(
         "--prt-bands", [&prt](int v) { prt.bands = v; },
         "--sky-light prt: spherical-harmonic bands, 3 (9 coefficients, default) or 5 (25)")
      ->check(CLI::IsMember({3, 5}));
  cmd->add_option_function<std::string>(
         "--prt-transfer",
         [&prt](const std::string& v) {
           prt.kind = v == "unshadowed" ? truth::PrtKind::kUnshadowed
                      : v == "shadowed" ? truth::PrtKind::kShadowed
                                        : truth::PrtKind::kInterreflected;
         },
         "--sky-light prt: unshadowed (the cosine lobe alone), shadowed (what the scene hides "
         "of the sky) or interreflected (default: also the sky's light bounced off the scene)")
      ->check(CLI::IsMember({"unshadowed", "shadowed", "interreflected"}));
  cmd->add_option_function<uint32_t>(
         "--prt-bounces", [&prt](uint32_t v) { prt.bounces = v; },
         "--prt-transfer interreflected: diffuse bounces, 1 to 16 (default 3)")
      ->transform(whole_number(1, 16));
  cmd->add_option_function<uint32_t>(
         "--prt-samples", [&prt](uint32_t v) { prt.samples = v; },
         "--sky-light prt: ray directions per vertex, 16 to 65536 (default 512)")
      ->transform(whole_number(16, 65536));
}

// Usage checks of --env / --sky, --sky-light and their settings: "" when fine (`demo_scene`:
// the simulated demo, whose moving toys PRT cannot hold). Every mode lights with the
// sky; `accuracy_demo`: bench --accuracy on the demo, whose sections (the lamp's direct light,
// the marbles) are measured without one.
std::string check_sky(const CLI::App* cmd, const CommonOptions& common, bool accuracy_demo,
                      bool demo_scene) {
  const SkyOptions& sky = common.sky;
  for (const char* name : {"--prt-bands", "--prt-transfer", "--prt-bounces", "--prt-samples"})
    if (cmd->count(name) && !sky.prt) return std::string(name) + " applies to --sky-light prt";
  if (cmd->count("--prt-bounces") && sky.prt_settings.kind != truth::PrtKind::kInterreflected)
    return "--prt-bounces applies to --prt-transfer interreflected";
  if (sky.prt && !sky.given())
    return "--sky-light prt lights with the sky of --env FILE or --sky clear; give one";
  if (sky.prt && demo_scene)
    return "--sky-light prt needs a still scene file (--scene FILE or atrium): its transfer is "
           "computed once, and the demo's toys move";
  if (sky.prt && common.pathtraced)
    return "--sky-light applies to the real-time modes (the path tracer samples the sky itself)";
  if (!sky.env_file.empty() && sky.clear_sky)
    return "--env and --sky clear are two skies; give one";
  if (cmd->count("--sun") && !sky.clear_sky)
    return "--sun places the sun of --sky clear (an --env map's sun is part of the map)";
  if (cmd->count("--env-rotate") && sky.clear_sky)
    return "--env-rotate turns an --env map; the clear sky's sun is placed with --sun AZ,EL";
  for (const char* name : {"--env-rotate", "--env-strength"})
    if (cmd->count(name) && !sky.given())
      return std::string(name) + " applies to --env FILE" +
             (std::string(name) == "--env-strength" ? " or --sky clear" : "");
  if (sky.given() && accuracy_demo)
    return std::string(sky.clear_sky ? "--sky" : "--env") +
           " with --accuracy needs --scene FILE: the demo's report measures its closed box";
  return "";
}

// --render-scale and --target-ms change how the real-time final image is made: "" when fine.
// `components_option`: the option of this command that reads the light pass's terms at the
// output size (render --exr, bench --accuracy), which the render scale does not reconstruct;
// nullptr when none.
std::string check_render_scale(const CommonOptions& common, const char* components_option) {
  if (common.render_scale >= 1.0f && common.target_ms <= 0.0) return "";
  const std::string name = common.target_ms > 0.0 ? "--target-ms" : "--render-scale";
  if (common.pathtraced)
    return name + " applies to the real-time modes (the path tracer renders every output pixel)";
  if (components_option != nullptr)
    return name + " applies to the final image; " + components_option +
           " reads the light pass's terms at the output size";
  return "";
}

// Usage checks of --quality pathtraced and its options (render and bench): "" when fine.
// Options that pick the OpenCL device or change the real-time image cannot apply to the host
// path tracer, so they are refused rather than silently ignored; the --no-* switches ask for
// less post-processing than the path tracer already has none of, and pass. --bounces applies to
// every mode, but the real-time modes always model at least one bounce.
std::string check_pathtrace(const CLI::App* cmd, const CommonOptions& common) {
  if (!common.pathtraced) {
    if (cmd->count("--spp")) return "--spp applies to --quality pathtraced";
    if (cmd->count("--lamp")) return "--lamp applies to --quality pathtraced";
    return check_bounces(common);
  }
  for (const char* name : {"--device", "--visibility", "--shadow-size", "--shadows",
                           "--texture-filter", "--bloom-strength", "--gi-volume"})
    if (cmd->count(name))
      return std::string(name) + " does not apply to --quality pathtraced (the path tracer "
                                 "runs on the host's cores, without post-processing)";
  return "";
}

void add_size(CLI::App* cmd, SizeArgs& size) {
  cmd->add_option("--size", size.size, "square image size in pixels")
      ->capture_default_str()
      ->transform(pixel_count());
  cmd->add_option("--width", size.width, "image width in pixels (overrides --size)")
      ->transform(pixel_count());
  cmd->add_option("--height", size.height, "image height in pixels (overrides --size)")
      ->transform(pixel_count());
}

void add_simulation(CLI::App* cmd, SimulationArgs& sim) {
  cmd->add_option("--seed", sim.seed, "random seed of the simulation")
      ->capture_default_str()
      ->transform(whole_number(0, std::numeric_limits<uint64_t>::max()));
  cmd->add_flag("--marbles", sim.marbles, "start with the 30 marbles (key S toggles them)");
  cmd->add_flag("--fireball", sim.fireball, "start with a fireball (key F toggles it)");
  cmd->add_option("--replay", sim.replay,
                  "replay an input log written by `rolypoly run --record FILE`");
}

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
  std::string resolve(passes::DebugViewSettings& out) const {
    const auto view_kind = passes::parse_debug_view(view);
    const auto dir_index = passes::parse_voxel_dir(dir);
    if (!view_kind) return "unknown --view '" + view + "'";
    if (!dir_index) return "unknown --dir '" + dir + "'";
    out.view = *view_kind;
    out.level = level;
    out.dir = *dir_index;
    const bool voxel_args = level_option->count() > 0 || dir_option->count() > 0;
    if (voxel_args && out.view != passes::DebugView::kVoxels)
      return "--level and --dir choose the volume of --view voxels";
    return "";
  }
};

void add_view(CLI::App* cmd, ViewArgs& args) {
  cmd->add_option("--view", args.view,
                  "what to show: final (the image), or a debug view: albedo, normal, depth, "
                  "velocity, shadow-map, direct, indirect, voxels")
      ->capture_default_str()
      ->check(CLI::IsMember(passes::debug_view_names()));
  args.level_option =
      cmd->add_option("--level", args.level,
                      "--view voxels: mip level (0 = the isotropic level 0, up to log2 of the "
                      "voxel resolution)")
          ->capture_default_str()
          ->transform(whole_number(0, 31));
  args.dir_option = cmd->add_option("--dir", args.dir,
                                    "--view voxels: which directional volume of levels >= 1 "
                                    "(+x, -x, +y, -y, +z, -z: what a cone travelling that way "
                                    "sees)")
                        ->capture_default_str()
                        ->check(CLI::IsMember({"+x", "-x", "+y", "-y", "+z", "-z"}));
}

// --level against the volume --view voxels shows: the dense chain has levels 0 .. log2 R (1^3
// at the top), the octree 0 .. log2 R - 1. Checked here rather than when the renderer sets the
// view, after the device and the kernels (exit 1 there). "" when fine.
std::string check_voxel_level(const CommonOptions& common) {
  if (common.view.view != passes::DebugView::kVoxels) return "";
  const bool svo = common.gi_volume == render::GiVolume::kSvo;
  const uint32_t r = common.voxels != 0 ? common.voxels
                     : svo              ? CommonOptions::kDefaultSvoVoxels
                                        : render::RenderSettings{}.voxel_resolution;
  uint32_t log2 = 0;
  while ((r >> log2) > 1) ++log2;
  const uint32_t top = svo ? log2 - 1 : log2;
  if (common.view.level <= top) return "";
  return "--level " + std::to_string(common.view.level) + ": --view voxels of the " +
         (svo ? "octree" : "dense volume") + " at " + std::to_string(r) + "^3 has levels 0 to " +
         std::to_string(top);
}

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
  SizeArgs render_size, run_size, bench_size;
  ViewArgs render_view, run_view;
  RenderOptions& render_opts = parsed.render;
  RunOptions& run_opts = parsed.run;
  BenchOptions& bench_opts = parsed.bench;

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
  export_cmd->add_option("--assets", common.asset_dir,
                         "folder with the demo's textures (default: the built-in asset folder)");
  add_simulation(export_cmd, parsed.exporting.sim);
  export_cmd->remove_option(export_cmd->get_option("--replay"));

  CLI::App* bench = app.add_subcommand(
      "bench", "time every pass over many frames, on one or many devices, sizes and voxel "
               "resolutions");
  add_common(bench, common, false, true);
  add_sky_options(bench, common);
  add_spp(bench, common);
  add_bounces(bench, common);
  add_size(bench, bench_size);
  bench->add_option("--frames", bench_opts.frames, "measured frames")
      ->capture_default_str()
      ->transform(whole_number(1, 1000000));
  bench->add_option("--warmup", bench_opts.warmup, "frames rendered first, not measured")
      ->capture_default_str()
      ->transform(whole_number(0, 1000000));
  bench->add_option("--json", bench_opts.json, "also write the results as JSON to this file");
  bench->add_flag("--compare-visibility", bench_opts.compare_visibility,
                  "render the same frames with the compute rasterizer and with Embree and "
                  "compare the visibility cost side by side");
  bench->add_flag("--quality-report", bench_opts.quality_report,
                  "measure how close the fast quality mode comes to the reference mode at the "
                  "bench size: PSNR on the static demo after TAA converged, per frame on the "
                  "busy animation, and the flicker of both");
  bench->add_flag("--accuracy", bench_opts.accuracy,
                  "hold the fast and reference modes against the path-traced truth of the demo "
                  "frame or the --scene file's (cached on disk): each at 64 bounces against the 64-bounce truth and at "
                  "--bounces 1 against the 1-bounce truth, plus the fast mode's final image with "
                  "TAA; PSNR, indirect L1 and bias per region (a file's: per material), "
                  "side-wall hue, leaks; default size 360, --spp 1024");
  bench->add_option("--out", bench_opts.out_dir,
                    "--accuracy: folder for the side-by-side PNGs and the heat maps")
      ->capture_default_str();
  bench->add_option("--truth-cache", bench_opts.truth_cache,
                    "--accuracy: folder of cached path-traced truths (default "
                    "$XDG_CACHE_HOME/rolypoly/truth or ~/.cache/rolypoly/truth)");
  // --accuracy's thresholds: exit 3 when one is missed. Fractions (0.15 = 15 %), PSNR in dB.
  auto threshold = [&](const char* name, std::optional<double>& value, const std::string& what) {
    bench->add_option_function<std::string>(
             name, [&value](const std::string& v) { value = std::strtod(v.c_str(), nullptr); },
             "--accuracy: exit 3 when " + what)
        ->check(decimal_in(0.0, 1000.0));
  };
  threshold("--max-indirect-l1", bench_opts.max_indirect_l1,
            "the fast mode's indirect relative L1 over the image (64 bounces against the "
            "64-bounce truth) exceeds this fraction (e.g. 0.15)");
  threshold("--max-indirect-bias", bench_opts.max_indirect_bias,
            "the fast mode's |indirect bias| over the image (64 bounces against the 64-bounce "
            "truth) exceeds this fraction (e.g. 0.10)");
  threshold("--max-region-bias", bench_opts.max_region_bias,
            "the fast mode's |indirect bias| (64 bounces against the 64-bounce truth) in any "
            "named region exceeds this fraction (e.g. 0.15)");
  threshold("--max-indirect-l1-single", bench_opts.max_indirect_l1_single,
            "the fast mode's indirect relative L1 over the image at --bounces 1 against the "
            "1-bounce truth exceeds this fraction (e.g. 0.12)");
  threshold("--min-psnr-taa", bench_opts.min_psnr_taa,
            "the PSNR (dB) of the fast mode's final image with TAA (no bloom or motion blur, "
            "64 bounces) against the 64-bounce truth is below this (e.g. 30)");
  threshold("--min-direct-psnr-floor", bench_opts.min_direct_psnr_floor,
            "the default shadow mode's direct PSNR (dB) on the floor against the area-lamp truth "
            "is below this (e.g. 35)");
  threshold("--max-penumbra-error", bench_opts.max_penumbra_error,
            "the default shadow mode's penumbra width under the tumbler or the marble differs "
            "from the area-lamp truth's by more than this fraction (e.g. 0.25)");
  threshold("--min-albedo-psnr", bench_opts.min_albedo_psnr,
            "the albedo view's PSNR (dB) against the truth's pixel-averaged albedo is below this");
  bench->add_flag("--require-wall-hue", bench_opts.require_wall_hue,
                  "--accuracy: exit 3 unless on each side wall the incoming indirect light's "
                  "sign of R - B is the truth's: fast at 64 bounces as the 64-bounce truth, fast "
                  "at 1 bounce as the 1-bounce truth");
  add_simulation(bench, bench_opts.sim);
  bench->get_option("--marbles")
      ->description("start with the 30 marbles (key S toggles them); with --accuracy: also "
                    "measure the marble frame (16 marbles at rest: fast and reference mode "
                    "against its truth, the marbles and the floor beside them as regions)");
  CLI::Option* devices_opt = bench->add_option(
      "--devices", bench_opts.devices,
      "devices to bench one after the other: all, or a comma-separated list of indices from "
      "`rolypoly devices` and/or parts of device names (instead of --device)");
  CLI::Option* sizes_opt =
      bench->add_option("--sizes", bench_opts.sizes,
                        "comma-separated square image sizes, e.g. 256,512,720 (instead of --size)")
          ->delimiter(',')
          ->transform(pixel_count());
  bench->add_option("--voxels", bench_opts.voxels,
                    "comma-separated GI voxel resolutions per side, each 32, 64 or 128 (default " +
                        std::to_string(render::RenderSettings{}.voxel_resolution) +
                        "), or 256 or 512 with --gi-volume svo (default " +
                        std::to_string(CommonOptions::kDefaultSvoVoxels) + ")")
      ->delimiter(',')
      ->check(CLI::IsMember({32u, 64u, 128u, 256u, 512u}));
  bench->add_option("--scene", bench_opts.scene,
                    "default or demo (the simulated demo, the simulation options as given), busy "
                    "(30 marbles, a fireball and the particle budget kept full), atrium (a "
                    "generated courtyard, opened as a file), or a glTF 2.0 "
                    "file (.gltf or .glb: its still frame from the file's camera; with "
                    "--accuracy its materials are the regions)")
      ->capture_default_str();
  bench->add_option("--chart", bench_opts.chart,
                    "also write an SVG chart: per-pass time per device, frame time against "
                    "resolution and voxel count");
  bench->add_option("--markdown", bench_opts.markdown,
                    "also write the summary table as Markdown to this file");

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
    if (std::string why = check_gi_volume(common, {common.voxels}); !why.empty())
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
      for (const char* name : {"--seed", "--marbles", "--fireball", "--replay", "--assets"})
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
    if (std::string why = check_gi_volume(common, {common.voxels}); !why.empty())
      return usage("rolypoly run", why);
    if (std::string why = check_voxel_level(common); !why.empty())
      return usage("rolypoly run", why);
    if (!is_demo_scene(common.scene)) {
      for (const char* name :
           {"--seed", "--marbles", "--fireball", "--replay", "--record", "--assets"})
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
    if (bench_opts.scene == kDemoScene) bench_opts.scene = "default";
    // Neither demo name: a scene file (bench/src/bench_scene.h), static and with its own
    // materials, so the simulation's options and the demo-only reports cannot apply.
    if (bench_opts.scene != "default" && bench_opts.scene != "busy") {
      std::string why;
      for (const char* name : {"--seed", "--marbles", "--fireball", "--replay", "--assets"})
        if (why.empty() && bench->count(name))
          why = std::string(name) + " applies to the simulated demo, not to a scene file";
      if (why.empty() && bench_opts.quality_report)
        why = "--quality-report measures the demo (at rest and the busy animation), not a "
              "scene file";
      for (const char* name :
           {"--require-wall-hue", "--min-direct-psnr-floor", "--max-penumbra-error"})
        if (why.empty() && bench->count(name))
          why = std::string(name) + " measures the demo's box (its side walls, the floor's "
                "shadows under its lamp); a scene file's report has its materials as regions";
      if (!why.empty())
        return usage("rolypoly bench", why + " (--scene " + bench_opts.scene + ")");
    }
    const char* why = nullptr;
    if (devices_opt->count() && bench->count("--device"))
      why = "--devices and --device both choose devices; use one";
    else if (sizes_opt->count() && (bench->count("--size") || bench->count("--width") ||
                                    bench->count("--height")))
      why = "--sizes and --size/--width/--height both choose sizes; use one";
    else if (bench_opts.compare_visibility &&
             (devices_opt->count() || sizes_opt->count() || bench_opts.voxels.size() > 1))
      why = "--compare-visibility runs one device, size and voxel resolution";
    else if (bench_opts.quality_report &&
             (devices_opt->count() || sizes_opt->count() || bench_opts.voxels.size() > 1 ||
              bench_opts.compare_visibility))
      why = "--quality-report runs one device, size and voxel resolution";
    else if (common.pathtraced &&
             (devices_opt->count() || sizes_opt->count() || bench->count("--voxels") ||
              bench_opts.compare_visibility || bench_opts.quality_report ||
              bench->count("--chart") || bench->count("--markdown") ||
              bench_opts.scene == "busy"))
      why = "--quality pathtraced benches the path tracer on the host at one size on the "
            "demo or a scene file (no --devices, --sizes, --voxels, --compare-visibility, "
            "--quality-report, --chart, --markdown or --scene busy)";
    else if (bench_opts.accuracy &&
             (devices_opt->count() || sizes_opt->count() || bench_opts.voxels.size() > 1 ||
              bench_opts.compare_visibility || bench_opts.quality_report || common.pathtraced ||
              bench->count("--bounces") || bench->count("--chart") ||
              bench->count("--markdown") || bench_opts.scene == "busy"))
      why = "--accuracy runs one device and voxel resolution on the demo frame or a scene "
            "file, at 1 and 64 bounces (no --devices, --sizes, --compare-visibility, "
            "--quality-report, --quality pathtraced, --bounces, --chart, --markdown or --scene "
            "busy)";
    else if (!bench_opts.accuracy &&
             (bench->count("--out") || bench->count("--truth-cache") ||
              bench->count("--max-indirect-l1") || bench->count("--max-indirect-bias") ||
              bench->count("--max-region-bias") || bench->count("--max-indirect-l1-single") ||
              bench->count("--min-psnr-taa") || bench_opts.require_wall_hue ||
              bench->count("--min-direct-psnr-floor") || bench->count("--max-penumbra-error") ||
              bench->count("--min-albedo-psnr")))
      why = "--out, --truth-cache and the thresholds (--max-indirect-l1, --max-indirect-bias, "
            "--max-region-bias, --max-indirect-l1-single, --min-psnr-taa, --require-wall-hue, "
            "--min-direct-psnr-floor, --max-penumbra-error, --min-albedo-psnr) belong to "
            "--accuracy";
    if (why) return usage("rolypoly bench", why);
    const bool demo_scene = bench_opts.scene == "default" || bench_opts.scene == "busy" ||
                            is_demo_scene(bench_opts.scene);
    if (std::string sky = check_sky(bench, common, bench_opts.accuracy && demo_scene, demo_scene);
        !sky.empty())
      return usage("rolypoly bench", sky);
    if (std::string scale =
            check_render_scale(common, bench_opts.accuracy ? "--accuracy" : nullptr);
        !scale.empty())
      return usage("rolypoly bench", scale);
    if (std::string gi = check_gi_volume(common, bench_opts.voxels); !gi.empty())
      return usage("rolypoly bench", gi);
    if (common.gi_volume == render::GiVolume::kSvo && bench_opts.voxels.empty())
      bench_opts.voxels = {CommonOptions::kDefaultSvoVoxels};
    if (bench_opts.accuracy) {
      if (bench->count("--lamp"))
        return usage("rolypoly bench", "--lamp applies to --quality pathtraced (--accuracy uses "
                                       "both lamp models)");
      if (bench->count("--spp")) bench_opts.accuracy_spp = common.spp;
    } else if (std::string pt = check_pathtrace(bench, common); !pt.empty()) {
      return usage("rolypoly bench", pt);
    }
    parsed.kind = ParsedCommand::Kind::kBench;
    bench_opts.size = bench_size.resolve();
    bench_opts.size_given =
        bench->count("--size") || bench->count("--width") || bench->count("--height");
    bench_opts.command_line = "rolypoly";
    for (int i = 1; i < argc; ++i) {
      bench_opts.command_line += ' ';
      bench_opts.command_line += argv[i];
    }
  } else {
    return usage("rolypoly: error", "no subcommand given (try --help)");  // CLI11 requires one
  }
  return parsed;
}

}  // namespace rp::app
