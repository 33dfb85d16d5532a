#include "app/sky_input.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>

#include "scene/asset_error.h"
#include "scene/clear_sky.h"
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
  } else if (options.clear_sky) {
    scene::ClearSkySettings settings;
    settings.sun_azimuth_deg = options.sun_azimuth_deg;
    settings.sun_elevation_deg = options.sun_elevation_deg;
    scene::ClearSky clear = scene::make_clear_sky(settings);  // parse_cli checked the range
    sky.environment.map = std::move(clear.map);
    sky.environment.strength = options.strength;
    clear.sun.intensity *= options.strength;
    sky.sun = clear.sun;
  }
  return sky;
}

void add_sky(const SkyLight& sky, scene::FrameScene& frame) {
  if (!sky.environment.enabled()) return;
  frame.environment = sky.environment;
  if (sky.sun) frame.lights.push_back(*sky.sun);
}

void turn_sky(SkyLight& sky, float degrees) {
  sky.environment.rotate_deg = std::fmod(sky.environment.rotate_deg + degrees, 360.0f);
  if (!sky.sun) return;
  // the path tracer's map-to-world turn (truth::EnvironmentSampler::to_world) by `degrees`
  const float a = degrees * 0.0174532925f, c = std::cos(a), s = std::sin(a);
  const glm::vec3 d = sky.sun->direction;
  sky.sun->direction = glm::vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
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
  return text;
}

}  // namespace rp::app
