// The path tracer's settings and report lines for `render` and `bench --quality pathtraced`.
#include "app/pathtrace_settings.h"

#include <algorithm>
#include <cstdio>
#include <thread>

#include "scene/demo_scene.h"

namespace rp::app {

rp::truth::PathTraceSettings pathtrace_settings(const CommonOptions& common, uint32_t width,
                                                uint32_t height, uint64_t seed) {
  rp::truth::PathTraceSettings s;
  s.width = width;
  s.height = height;
  s.spp = common.spp;
  s.bounces = common.render.bounces;
  s.seed = seed;  // the same streams every frame: a still scene gives the same image
  s.threads = 0;  // every hardware thread
  s.lamp = common.area_lamp ? rp::truth::LampModel::kArea : rp::truth::LampModel::kPoint;
  return s;
}

unsigned hardware_threads() { return std::max(1u, std::thread::hardware_concurrency()); }

scene::SceneAssets load_demo_assets(const CommonOptions& common) {
  return scene::make_demo_assets(
      common.asset_dir.empty() ? scene::default_asset_dir() : common.asset_dir, common.open_demo);
}

std::string describe_settings(const rp::truth::PathTraceSettings& s) {
  char text[112];
  std::snprintf(text, sizeof text, "%ux%u, %u spp, %u bounce%s%s", s.width, s.height, s.spp,
                s.bounces, s.bounces == 1 ? "" : "s",
                s.lamp == rp::truth::LampModel::kArea ? ", area lamp" : "");
  return text;
}

double mrays_per_second(uint64_t rays, double seconds) {
  return seconds > 0.0 ? double(rays) / seconds * 1e-6 : 0.0;
}

}  // namespace rp::app
