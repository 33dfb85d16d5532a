// Disk cache of path-traced truths (see truth_cache.h).
#include "app/truth_cache.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/png_output.h"
#include "io/fnv1a.h"
#include "truth/exr_io.h"

namespace rp::app {
namespace {

using io::Fnv1a;

const char* const kLayers[] = {"", "direct", "indirect", "emission", "albedo", "specular"};
constexpr int kLayerCount = 6;  // an entry without the specular layer (older)
                                // does not load and is rendered anew

std::vector<float>* layer(truth::PathTracedImage& img, int i) {
  std::vector<float>* planes[] = {&img.combined, &img.direct, &img.indirect, &img.emission,
                                  &img.albedo, &img.specular};
  return planes[i];
}

bool load(const std::filesystem::path& exr, const std::filesystem::path& meta,
          const truth::PathTraceSettings& s, truth::PathTracedImage& img) {
  std::error_code ec;
  if (!std::filesystem::exists(exr, ec) || !std::filesystem::exists(meta, ec)) return false;
  try {
    std::ifstream in(meta);
    const nlohmann::json j = nlohmann::json::parse(in);
    img.seconds = j.at("seconds").get<double>();
    img.rays = j.at("rays").get<uint64_t>();
    for (int i = 0; i < kLayerCount; ++i) {
      uint32_t w = 0, h = 0;
      *layer(img, i) = truth::read_exr_layer(exr, kLayers[i], w, h);
      if (w != s.width || h != s.height) return false;
    }
    img.width = s.width;
    img.height = s.height;
    return true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rolypoly: the cached truth %s is unreadable (%s); rendering it anew\n",
                 exr.string().c_str(), e.what());
    return false;
  }
}

}  // namespace

std::string truth_key(const scene::SceneAssets& assets, const scene::FrameScene& frame,
                      const truth::PathTraceSettings& settings) {
  Fnv1a h;
  h.text(kPathTracerVersion);
  h.value(settings.width);
  h.value(settings.height);
  h.value(settings.spp);
  h.value(settings.bounces);
  h.value(settings.seed);
  // Only the area lamp adds to the key, so the point-lamp truths keep their keys (and caches).
  if (settings.lamp == truth::LampModel::kArea) h.text("lamp=area");
  for (const scene::Mesh& m : assets.meshes) {
    h.text(m.name);
    for (const scene::Vertex& v : m.vertices) {
      h.vec(v.position);
      h.vec(v.normal);
      h.bytes(&v.uv.x, 2 * sizeof(float));
    }
    h.bytes(m.triangles.data(), m.triangles.size() * sizeof(glm::uvec3));
    h.bytes(m.materials.data(), m.materials.size() * sizeof(uint32_t));
  }
  // The surface model: a coated surface adds its coat and the model's name, so a
  // scene of matte surfaces keeps its key; a change to the model's formulas must rename it.
  auto coat = [&h](const scene::Specular& sp) {
    if (!sp.metal && !(sp.f0 > 0.0f)) return;
    h.text(kSurfaceModel);
    h.value(sp.roughness);
    h.value(sp.f0);
    h.value(uint8_t(sp.metal));
  };
  for (const scene::Material& m : assets.materials) {
    h.vec(m.albedo);
    h.vec(m.emission);
    h.value(m.texture);
    coat(m.specular);
  }
  for (const scene::Texture& t : assets.textures) {
    h.value(t.width);
    h.value(t.height);
    h.bytes(t.rgba.data(), t.rgba.size());
  }
  const scene::Camera& c = frame.camera;
  h.vec(c.position);
  h.vec(c.target);
  h.vec(c.up);
  h.value(c.fov_y_deg);
  h.value(c.near_plane);
  h.value(c.far_plane);
  h.vec(frame.light.position);
  h.vec(frame.light.intensity);
  h.value(frame.light.lamp_radius);
  for (const scene::MeshInstance& i : frame.instances) {
    h.value(i.mesh);
    h.mat(i.model);
    h.value(uint8_t(i.casts_shadow));
    h.value(uint8_t(i.voxelize));
  }
  // Instances that shade only the sky and the punctual lights (the demo's box) matter only
  // under those: other frames keep their keys.
  const bool light_casters = std::any_of(
      frame.instances.begin(), frame.instances.end(),
      [](const scene::MeshInstance& i) { return i.casts_light_shadow && !i.casts_shadow; });
  if (light_casters && (frame.environment.enabled() || !frame.lights.empty())) {
    h.text("light-casters");
    for (const scene::MeshInstance& i : frame.instances) h.value(uint8_t(i.casts_light_shadow));
  }
  for (const scene::Sphere& s : frame.spheres) {
    h.vec(s.center);
    h.value(s.radius);
    h.vec(s.albedo);
    h.vec(s.emission);
    coat(s.specular);
    h.value(uint8_t(s.casts_shadow));
  }
  // An environment light adds its map and settings; frames without one keep their keys.
  if (frame.environment.enabled()) {
    const scene::EnvironmentMap& map = *frame.environment.map;
    h.text("environment/2");  // /2: its light at the seen surface counts as indirect
    h.value(map.width);
    h.value(map.height);
    h.bytes(map.rgb.data(), map.rgb.size() * sizeof(float));
    h.value(frame.environment.strength);
    h.value(frame.environment.rotate_deg);
    // suns taken out of the map (scene/environment_suns.h): their part is direct light at
    // the first vertex; the whole map stays what is sampled, so the images' sum is the same
    if (const auto& residual = frame.environment.residual) {
      h.text("environment-suns");
      h.bytes(residual->rgb.data(), residual->rgb.size() * sizeof(float));
    }
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h.get()));
  return hex;
}

std::filesystem::path default_truth_cache_dir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return std::filesystem::path(xdg) / "rolypoly" / "truth";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::filesystem::path(home) / ".cache" / "rolypoly" / "truth";
  return std::filesystem::path(".rolypoly-cache") / "truth";
}

CachedTruth cached_path_trace(truth::PathTracer& tracer, const scene::SceneAssets& assets,
                              const scene::FrameScene& frame,
                              const truth::PathTraceSettings& settings,
                              const std::filesystem::path& dir, const truth::ProgressFn& progress,
                              const std::atomic<bool>* cancel) {
  const std::string key = truth_key(assets, frame, settings);
  CachedTruth out;
  out.file = dir / ("truth-" + key + ".exr");
  const std::filesystem::path meta = dir / ("truth-" + key + ".json");
  if (load(out.file, meta, settings, out.image)) {
    out.from_cache = true;
    return out;
  }
  out.image = tracer.render(frame, settings, progress, cancel);
  try {
    ensure_directory(dir);
    std::vector<truth::ExrLayer> layers;
    for (int i = 0; i < kLayerCount; ++i) layers.push_back({kLayers[i], layer(out.image, i)});
    truth::write_exr_atomic(out.file, settings.width, settings.height, layers);
    nlohmann::json j;
    j["key"] = key;
    j["version"] = kPathTracerVersion;
    j["width"] = settings.width;
    j["height"] = settings.height;
    j["spp"] = settings.spp;
    j["bounces"] = settings.bounces;
    j["lamp"] = settings.lamp == truth::LampModel::kArea ? "area" : "point";
    j["seed"] = settings.seed;
    j["seconds"] = out.image.seconds;
    j["rays"] = out.image.rays;
    write_text_atomic(meta, j.dump(2) + "\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rolypoly: warning: could not store the truth in the cache: %s\n",
                 e.what());
  }
  return out;
}

}  // namespace rp::app
