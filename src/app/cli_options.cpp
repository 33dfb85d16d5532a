#include "app/cli_options.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "render/renderer.h"

namespace rp::app {
namespace {

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

}  // namespace

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

void add_open_demo(CLI::App* cmd, CommonOptions& common) {
  cmd->add_flag("--open", common.open_demo,
                "the demo half open: a skylight in its ceiling, so a sky (--env FILE or --sky "
                "clear) lights the room through it and through the open front");
}

void add_common(CLI::App* cmd, CommonOptions& common, bool voxel_option, bool pathtraced) {
  cmd->add_option("--device", common.device,
                  "OpenCL device: index from `rolypoly devices` or part of its name "
                  "(case-insensitive); default: first GPU, else first CPU");
  cmd->add_option("--assets", common.asset_dir,
                  "folder with the scene's textures (default: the built-in asset folder)");
  add_open_demo(cmd, common);
  cmd->add_option("--shadow-size", common.render.shadow_size, "shadow map texels per side")
      ->capture_default_str()
      ->transform(whole_number(1, kMaxSize));
  if (voxel_option)
    cmd->add_option("--voxels", common.render.voxel_resolution,
                    "GI voxel volume resolution per side: 32, 64 or 128 for --gi-volume dense "
                    "(default " +
                        std::to_string(render::RenderSettings{}.voxel_resolution) +
                        "), 256 or 512 for --gi-volume svo (default " +
                        std::to_string(render::RenderSettings::kDefaultSvoResolution) + ")")
        ->check(CLI::IsMember({32u, 64u, 128u, 256u, 512u}));
  add_named_option(cmd, "--gi-volume", common.render.gi_volume,
                   "the volume the GI cones trace: dense (the anisotropic mip chain, 32^3 to "
                   "128^3; default) or svo (the sparse voxel octree with 3^3 bricks, 256^3 or "
                   "512^3: finer contacts for more build time, memory only where surfaces are)");
  add_named_option(cmd, "--visibility", common.render.visibility,
                   "where the visibility buffer comes from: raster (compute rasterizer on the "
                   "OpenCL device, default) or embree (Embree primary rays on the host's cores, "
                   "uploaded)");
  std::string quality_help =
      "indirect light: fast (real-time default: reduced resolution, interleaved cones, "
      "temporal accumulation), reference (per-pixel 16 cones at full resolution, twice the "
      "steps, no temporal reuse)";
  std::vector<std::string> qualities = name_list<render::Quality>();
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
           // pathtraced is not a render::Quality: the host path tracer replaces the renderer.
           common.pathtraced = name == "pathtraced";
           if (!common.pathtraced) common.render.quality = *parse_name<render::Quality>(name);
         },
         quality_help)
      ->check(CLI::IsMember(qualities));
  add_named_option(cmd, "--texture-filter", common.render.texture_filter,
                   "surface textures: bilinear (level 0 only: aliases in the distance), "
                   "trilinear (default: mipmaps, level from the pixel's footprint) or anisotropic "
                   "(up to 4 trilinear taps along the footprint's long axis: sharper at grazing "
                   "angles)");
  // --shadows: the light pass's shadow filter; key H cycles it in the window.
  add_named_option(cmd, "--shadows", common.render.shadows,
                   "how the lamp's shadow is filtered: hard (one tap: a point lamp's hard edge), "
                   "pcf (fixed-width soft edge), pcss (penumbra from the lamp's size and the "
                   "blocker and receiver depths; default) or vssm (the same from filtered depth "
                   "moments)");
  auto off = [&](const char* name, bool& flag, const char* what) {
    cmd->add_flag_callback(name, [&flag] { flag = false; }, what);
  };
  off("--no-taa", common.render.effects.taa, "temporal anti-aliasing off (key T toggles it)");
  off("--no-bloom", common.render.effects.bloom, "bloom off (key B toggles it)");
  off("--no-motion-blur", common.render.effects.motion_blur,
      "motion blur off (key M toggles it)");
  cmd->add_option("--bloom-strength", common.render.effects.bloom_strength,
                  "bloom mix factor f: colour * (1 - f) + bloom * f")
      ->capture_default_str()
      ->check(decimal_in(0.0, 1.0));
  cmd->add_option("--shutter", common.render.effects.shutter,
                  "motion blur: the fraction of the frame interval the shutter is open (0.5 = a "
                  "180 degree shutter; 0 = no blur)")
      ->capture_default_str()
      ->check(decimal_in(0.0, 1.0));
  cmd->add_option("--render-scale", common.render.render_scale,
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

std::string check_gi_volume(const CommonOptions& common, const std::vector<uint32_t>& voxels) {
  for (uint32_t v : voxels) {
    const bool svo_size = v == 256 || v == 512;  // the app's sizes (the renderer takes more)
    if (v == 0 || svo_size == (common.render.gi_volume == render::GiVolume::kSvo)) continue;
    if (common.render.gi_volume == render::GiVolume::kSvo)
      return "--gi-volume svo takes --voxels 256 or 512, not " + std::to_string(v);
    return "--voxels " + std::to_string(v) + " needs --gi-volume svo (the dense volume takes 32, "
           "64 or 128)";
  }
  return "";
}

std::string resolve_gi_volume(const CLI::App* cmd, CommonOptions& common) {
  if (common.render.gi_volume == render::GiVolume::kSvo && cmd->count("--voxels") == 0)
    common.render.voxel_resolution = render::RenderSettings::kDefaultSvoResolution;
  return check_gi_volume(common, {common.render.voxel_resolution});
}

std::string check_bounces(const CommonOptions& common) {
  if (!common.pathtraced && common.render.bounces == 0)
    return "--bounces 0 applies to --quality pathtraced; the fast and reference modes take 1 "
           "(single bounce) to 1000";
  return "";
}

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

void add_bounces(CLI::App* cmd, CommonOptions& common) {
  cmd->add_option("--bounces", common.render.bounces,
                  "indirect bounces: light that left an emitter or a lamp-lit surface reaches "
                  "the camera after at most N reflections besides the surface the camera sees. "
                  "fast and reference: 1 = single-bounce indirect light, any N >= 2 = "
                  "multi-bounce (the voxels' feedback converges to all bounces, compared with the "
                  "path-traced truth at 64); 1..1000. pathtraced: N gathers, 0..1000 (0 = direct "
                  "lamp light and seen emission only)")
      ->capture_default_str()
      ->transform(whole_number(0, 1000));
}

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
  cmd->add_option("--env-suns", sky.env_suns,
                  "--env: take up to N compact bright patches out of the map (its sun, a "
                  "studio's softboxes: at least 100x the map's mean, 5 % of its light within "
                  "0.1 sr) and light by them as directional lights with shadow maps, 0 to 4 "
                  "(default 4; 0: the cones and PRT gather the whole map)")
      ->transform(whole_number(0, 4));
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
  add_named_option(cmd, "--prt-transfer", prt.kind,
                   "--sky-light prt: unshadowed (the cosine lobe alone), shadowed (what the "
                   "scene hides of the sky) or interreflected (default: also the sky's light "
                   "bounced off the scene)");
  cmd->add_option_function<uint32_t>(
         "--prt-bounces", [&prt](uint32_t v) { prt.bounces = v; },
         "--prt-transfer interreflected: diffuse bounces, 1 to 16 (default 3)")
      ->transform(whole_number(1, 16));
  cmd->add_option_function<uint32_t>(
         "--prt-samples", [&prt](uint32_t v) { prt.samples = v; },
         "--sky-light prt: ray directions per vertex, 16 to 65536 (default 512)")
      ->transform(whole_number(16, 65536));
}

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
  if (cmd->count("--env-suns") && sky.clear_sky)
    return "--env-suns takes the suns out of an --env map; the clear sky's sun is its own light";
  for (const char* name : {"--env-rotate", "--env-strength", "--env-suns"})
    if (cmd->count(name) && !sky.given())
      return std::string(name) + " applies to --env FILE" +
             (std::string(name) == "--env-strength" ? " or --sky clear" : "");
  if (sky.given() && accuracy_demo)
    return std::string(sky.clear_sky ? "--sky" : "--env") +
           " with --accuracy needs --scene FILE or --open: the demo's report measures its "
           "closed box";
  return "";
}

std::string check_render_scale(const CommonOptions& common, const char* components_option) {
  if (common.render.render_scale >= 1.0f && common.target_ms <= 0.0) return "";
  const std::string name = common.target_ms > 0.0 ? "--target-ms" : "--render-scale";
  if (common.pathtraced)
    return name + " applies to the real-time modes (the path tracer renders every output pixel)";
  if (components_option != nullptr)
    return name + " applies to the final image; " + components_option +
           " reads the light pass's terms at the output size";
  return "";
}

std::string check_pathtrace(const CLI::App* cmd, const CommonOptions& common) {
  if (!common.pathtraced) {
    if (cmd->count("--spp")) return "--spp applies to --quality pathtraced";
    if (cmd->count("--lamp")) return "--lamp applies to --quality pathtraced";
    return check_bounces(common);
  }
  for (const char* name : {"--device", "--visibility", "--shadow-size", "--shadows",
                           "--texture-filter", "--bloom-strength", "--shutter", "--gi-volume"})
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

std::string ViewArgs::resolve(passes::DebugViewSettings& out) const {
  const auto view_kind = parse_name<passes::DebugView>(view);
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

void add_view(CLI::App* cmd, ViewArgs& args) {
  cmd->add_option("--view", args.view,
                  "what to show: final (the image), or a debug view: albedo, normal, depth, "
                  "velocity, shadow-map, direct, indirect, voxels")
      ->capture_default_str()
      ->check(CLI::IsMember(name_list<passes::DebugView>()));
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

std::string check_voxel_level(const CommonOptions& common) {
  if (common.view.view != passes::DebugView::kVoxels) return "";
  const bool svo = common.render.gi_volume == render::GiVolume::kSvo;
  const uint32_t r = common.render.voxel_resolution;
  uint32_t log2 = 0;
  while ((r >> log2) > 1) ++log2;
  const uint32_t top = svo ? log2 - 1 : log2;
  if (common.view.level <= top) return "";
  return "--level " + std::to_string(common.view.level) + ": --view voxels of the " +
         (svo ? "octree" : "dense volume") + " at " + std::to_string(r) + "^3 has levels 0 to " +
         std::to_string(top);
}

}  // namespace rp::app
