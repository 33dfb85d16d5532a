// The shared parts of `bench --accuracy` (see accuracy_render.h).
#include "bench/src/accuracy_render.h"

#include <atomic>
#include <cmath>
#include <cstdio>

#include "app/interrupt.h"
#include "app/progress.h"

namespace rp::app {

nlohmann::json stats_json(const ErrorStats& s) {
  return {{"rel_l1", s.rel_l1}, {"bias", s.bias}, {"pixels", s.pixels}};
}

std::string percent_cell(double v, bool sign) {
  if (!std::isfinite(v)) return "     n/a";
  char b[32];
  std::snprintf(b, sizeof b, sign ? "%+7.1f%%" : "%7.1f%%", v * 100.0);
  return b;
}

std::string config_table_head(int label_width, const std::string& n) {
  char line[128];
  std::snprintf(line, sizeof line, "\n%-*s", label_width, "(rolypoly vs truth)");
  std::string t = line;
  for (const AccuracyConfig& c : kAccuracyConfigs) {
    std::snprintf(line, sizeof line, " %8s", c.column);
    t += line;
  }
  return t + "\n  (/N: " + n + " bounces against the " + n +
         "-bounce truth; /1: --bounces 1 against the 1-bounce truth)\n";
}

std::string db_cell(double v) {
  if (std::isnan(v)) return "     n/a";
  char b[32];
  std::snprintf(b, sizeof b, "%8.2f", v);
  return b;
}

Images from_truth(const std::string& name, const truth::PathTracedImage& t) {
  return {name, t.combined, t.direct, t.indirect, t.albedo, t.specular};
}

Images render_mode(const CommonOptions& common, const std::string& name, render::Quality quality,
                   uint32_t bounces, bool taa, uint32_t w, uint32_t h, uint32_t frames,
                   std::vector<uint8_t>& final_rgba, const FrameFn& frame_fn,
                   const scene::SceneAssets* assets) {
  CommonOptions c = common;
  c.quality = quality;
  c.bounces = bounces;
  c.view = {};
  c.effects.bloom = c.effects.motion_blur = false;
  c.effects.taa = taa;
  RenderSession session(c, w, h, false, assets);
  session.set_keep_components(true);
  ProgressBar bar(name, frames);
  double ms = 0.0;
  for (uint32_t i = 0; i < frames; ++i) {
    if (InterruptGuard::interrupted()) throw truth::PathTracer::Cancelled();
    session.render(frame_fn(session.assets(), i), final_rgba, ms);
    bar.update(i + 1);
  }
  bar.finish();
  render::LinearComponents lc;
  session.read_components(lc);
  return {name, lc.combined, lc.direct, lc.indirect, lc.albedo, lc.specular};
}

CachedTruth cached_truth_with_progress(truth::PathTracer& tracer,
                                       const scene::SceneAssets& assets,
                                       const scene::FrameScene& frame,
                                       const truth::PathTraceSettings& settings,
                                       const std::filesystem::path& cache,
                                       const std::string& label) {
  ProgressBar bar(label, settings.height);
  std::atomic<bool> cancel{false};  // set from the progress callback on Ctrl-C / SIGTERM
  CachedTruth t = cached_path_trace(
      tracer, assets, frame, settings, cache,
      [&](uint32_t done, uint32_t) {
        if (InterruptGuard::interrupted()) cancel = true;
        bar.update(done);
      },
      &cancel);
  bar.finish();
  return t;
}

std::vector<Images> truths_one_and_many(truth::PathTracer& tracer,
                                        const scene::SceneAssets& assets,
                                        const scene::FrameScene& frame, uint32_t w, uint32_t h,
                                        uint32_t spp, uint32_t many_bounces, uint64_t seed,
                                        const std::filesystem::path& cache,
                                        nlohmann::json& truth_json) {
  std::vector<Images> truths;
  for (uint32_t bounces : {1u, many_bounces}) {
    truth::PathTraceSettings s;
    s.width = w;
    s.height = h;
    s.spp = spp;
    s.bounces = bounces;
    s.seed = seed;
    const CachedTruth t = cached_truth_with_progress(
        tracer, assets, frame, s, cache,
        "path tracing (" + std::to_string(bounces) + " bounce" + (bounces == 1 ? "" : "s") + ")");
    const std::string key = bounces == 1 ? "one" : "many";
    truth_json[key] = {{"bounces", bounces},
                       {"spp", s.spp},
                       {"seed", s.seed},
                       {"seconds", t.image.seconds},
                       {"rays_per_second", t.image.rays_per_second()},
                       {"from_cache", t.from_cache},
                       {"file", t.file.string()}};
    truths.push_back(from_truth("truth_" + key, t.image));
  }
  return truths;
}

}  // namespace rp::app
