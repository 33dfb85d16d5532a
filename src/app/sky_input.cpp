#include "app/sky_input.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>

#include "render/gpu_types.h"
#include "scene/asset_error.h"
#include "scene/clear_sky.h"
#include "scene/environment_glow.h"
#include "truth/environment.h"

namespace rp::app {
namespace {

// "%g" without a trailing zoo of digits: "90", "2.5".
std::string number(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(v));
  return text;
}

// The decoders' own messages for a missing file are unhelpful (stb: "can't fopen"), so the file
// is opened here first and the system's reason reported.
void check_readable(const std::string& file) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (!ec && std::filesystem::is_directory(status))
    throw scene::AssetError("--env: cannot read environment map " + file +
                            ": Is a directory");
  std::FILE* f = std::fopen(file.c_str(), "rb");
  if (f == nullptr)
    throw scene::AssetError("--env: cannot read environment map " + file + ": " +
                            std::strerror(errno));
  std::fclose(f);
}

// Takes up to `max_suns` suns out of the sky's map (scene/environment_suns.h): its residual
// and its lights, turned and scaled as the environment is now.
void take_suns(SkyLight& sky, int max_suns) {
  const scene::EnvironmentSuns suns =
      scene::find_environment_suns(*sky.environment.map, max_suns);
  sky.environment.residual = suns.residual;
  sky.environment.glow =
      suns.residual ? scene::find_environment_glow(*sky.environment.map, *suns.residual) : nullptr;
  sky.map_suns = suns.suns;
  sky.suns.clear();
  for (size_t i = 0; i < suns.suns.size(); ++i)
    sky.suns.push_back(scene::environment_sun_light(
        suns.suns[i], int(i), sky.environment.rotate_deg, sky.environment.strength));
}

}  // namespace

SkyLight load_sky(const SkyOptions& options) {
  SkyLight sky;
  if (!options.env_file.empty()) {
    check_readable(options.env_file);
    auto map = std::make_shared<scene::EnvironmentMap>();
    try {
      *map = truth::load_environment_map(options.env_file);
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {
      throw scene::AssetError(std::string("--env: ") + e.what());
    }
    sky.environment.map = std::move(map);
    sky.environment.rotate_deg = options.rotate_deg;
    sky.environment.strength = options.strength;
    take_suns(sky, options.env_suns);
  } else if (options.clear_sky) {
    scene::ClearSkySettings settings;
    settings.sun_azimuth_deg = options.sun_azimuth_deg;
    settings.sun_elevation_deg = options.sun_elevation_deg;
    scene::ClearSky clear = scene::make_clear_sky(settings);  // parse_cli checked the range
    sky.environment.map = std::move(clear.map);
    sky.environment.strength = options.strength;
    clear.sun.intensity *= options.strength;
    sky.suns.push_back(clear.sun);
  }
  return sky;
}

void add_sky(SkyLight& sky, scene::FrameScene& frame) {
  if (!sky.environment.enabled()) return;
  const size_t room =
      RP_MAX_PUNCTUAL_LIGHTS - std::min<size_t>(frame.lights.size(), RP_MAX_PUNCTUAL_LIGHTS);
  if (sky.map_suns.size() > room) {
    // the brightest `room` suns are the first `room` found: find them again with the rest
    // left in the map
    std::fprintf(stderr,
                 "rolypoly: note: the scene's %zu lights leave room for %zu of the map's %zu "
                 "suns; the others stay in the map\n",
                 frame.lights.size(), room, sky.map_suns.size());
    take_suns(sky, int(room));
  }
  frame.environment = sky.environment;
  frame.lights.insert(frame.lights.end(), sky.suns.begin(), sky.suns.end());
}

void turn_sky(SkyLight& sky, float degrees) {
  sky.environment.rotate_deg = std::fmod(sky.environment.rotate_deg + degrees, 360.0f);
  for (scene::PunctualLight& sun : sky.suns)
    sun.direction = scene::environment_to_world(sun.direction, degrees);
}

std::string describe_sky(const SkyOptions& options, const SkyLight& sky) {
  if (!sky.environment.enabled()) return "";
  std::string text;
  if (options.clear_sky) {
    text = "clear sky (Preetham, turbidity " + number(scene::ClearSkySettings{}.turbidity) +
           ") with its sun at azimuth " + number(options.sun_azimuth_deg) + ", elevation " +
           number(options.sun_elevation_deg) + " degrees";
  } else {
    text = "environment: " + options.env_file + " (" + std::to_string(sky.environment.map->width) +
           "x" + std::to_string(sky.environment.map->height) + ")";
    if (options.rotate_deg != 0.0f) text += ", turned " + number(options.rotate_deg) + " degrees";
  }
  if (options.strength != 1.0f) text += ", strength " + number(options.strength);
  for (size_t i = 0; i < sky.map_suns.size(); ++i) {
    const scene::EnvironmentSun& sun = sky.map_suns[i];
    const glm::vec3 towards = -sky.suns[i].direction;  // world, the map's turn applied
    const double azimuth = std::atan2(double(towards.x), -double(towards.z)) * 57.29577951;
    char line[200];
    std::snprintf(line, sizeof line,
                  "\n  sun %zu of the map: %.1f %% of its light from azimuth %.0f, elevation %.1f "
                  "degrees (%.3f sr), lit as a directional light with a shadow map",
                  i + 1, 100.0 * double(sun.share),
                  azimuth < 0.0 ? azimuth + 360.0 : azimuth,
                  std::asin(std::clamp(double(towards.y), -1.0, 1.0)) * 57.29577951,
                  double(sun.solid_angle));
    text += line;
  }
  return text;
}

}  // namespace rp::app
