// The shared parts of `bench --accuracy` (see accuracy_render.h).
#include "bench/src/accuracy_render.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <utility>

#include "app/host_tone_map.h"
#include "app/interrupt.h"
#include "app/png_output.h"
#include "app/progress.h"

namespace rp::bench {

using app::CachedTruth;
using app::CommonOptions;
using app::InterruptGuard;
using app::ProgressBar;
using app::RenderSession;
using app::cached_path_trace;
using app::encode_rgba8;
using app::write_png_atomic;

nlohmann::json stats_json(const ErrorStats& s) {
  return {{"rel_l1", s.rel_l1}, {"bias", s.bias}, {"pixels", s.pixels}};
}

std::string percent_cell(double v, bool sign) {
  if (!std::isfinite(v)) return "     n/a";
  char b[32];
  std::snprintf(b, sizeof b, sign ? "%+7.1f%%" : "%7.1f%%", v * 100.0);
  return b;
}

std::string truth_lines(const nlohmann::json& truth_json) {
  std::string t;
  char line[160];
  for (const char* k : {"one", "many"}) {
    const nlohmann::json& tj = truth_json[k];
    std::snprintf(line, sizeof line, "  truth, %u bounce(s): %.1f s, %.1f Mrays/s%s\n",
                  tj["bounces"].get<uint32_t>(), tj["seconds"].get<double>(),
                  tj["rays_per_second"].get<double>() / 1e6,
                  tj["from_cache"].get<bool>() ? " (from the cache)" : "");
    t += line;
  }
  return t;
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

namespace {

// The options a measured render runs with: the user's device and scene settings, the given
// quality, bounces and TAA, the final view, no bloom or motion blur.
CommonOptions measured_options(const CommonOptions& common, render::Quality quality,
                               uint32_t bounces, bool taa) {
  CommonOptions c = common;
  c.render.quality = quality;
  c.render.bounces = bounces;
  c.view = {};
  c.render.effects.bloom = c.render.effects.motion_blur = false;
  c.render.effects.taa = taa;
  return c;
}

}  // namespace

Images render_mode(const CommonOptions& common, const std::string& name, render::Quality quality,
                   uint32_t bounces, bool taa, uint32_t w, uint32_t h, uint32_t frames,
                   std::vector<uint8_t>& final_rgba, const FrameFn& frame_fn,
                   const scene::SceneAssets* assets) {
  CommonOptions c = measured_options(common, quality, bounces, taa);
  // The light pass's terms are compared at the output size; only the finished frame with TAA
  // is reconstructed from the render scale (--render-scale), as the user would see it.
  if (!taa) c.render.render_scale = 1.0f;
  const bool components = c.render.render_scale >= 1.0f;
  RenderSession session(c, w, h, false, assets);
  session.set_keep_components(components);
  ProgressBar bar(name, frames);
  double ms = 0.0;
  for (uint32_t i = 0; i < frames; ++i) {
    if (InterruptGuard::interrupted()) throw truth::PathTracer::Cancelled();
    session.render(frame_fn(session.assets(), i), final_rgba, ms);
    bar.update(i + 1);
  }
  bar.finish();
  if (!components) return {name, {}, {}, {}, {}, {}};  // at the render size: not comparable
  render::LinearComponents lc;
  session.read_components(lc);
  return {name, lc.combined, lc.direct, lc.indirect, lc.albedo, lc.specular};
}

Images render_jittered_average(const CommonOptions& common, const std::string& name,
                               uint32_t bounces, uint32_t w, uint32_t h, uint32_t frames,
                               uint32_t average_frames, const FrameFn& frame_fn,
                               const scene::SceneAssets* assets) {
  // TAA on for its jittered projection (Halton, 16 per cycle); the terms at the output size
  CommonOptions c = measured_options(common, render::Quality::kFast, bounces, true);
  c.render.render_scale = 1.0f;
  RenderSession session(c, w, h, false, assets);
  session.set_keep_components(true);
  average_frames = std::min(std::max(average_frames, 1u), std::max(frames, 1u));
  frames = std::max(frames, average_frames);
  Images avg{name, {}, {}, {}, {}, {}};
  std::vector<std::vector<float>*> sums = {&avg.combined, &avg.direct, &avg.indirect,
                                           &avg.albedo, &avg.specular};
  std::vector<uint8_t> rgba;
  render::LinearComponents lc;
  ProgressBar bar(name, frames);
  double ms = 0.0;
  for (uint32_t i = 0; i < frames; ++i) {
    if (InterruptGuard::interrupted()) throw truth::PathTracer::Cancelled();
    session.render(frame_fn(session.assets(), i), rgba, ms);
    bar.update(i + 1);
    if (i + average_frames < frames) continue;
    session.read_components(lc);
    const std::vector<float>* terms[] = {&lc.combined, &lc.direct, &lc.indirect, &lc.albedo,
                                         &lc.specular};
    for (size_t t = 0; t < sums.size(); ++t) {
      std::vector<float>& sum = *sums[t];
      sum.resize(terms[t]->size(), 0.0f);
      for (size_t k = 0; k < sum.size(); ++k) sum[k] += (*terms[t])[k];
    }
  }
  bar.finish();
  for (std::vector<float>* sum : sums)
    for (float& v : *sum) v /= float(average_frames);
  return avg;
}

std::vector<uint8_t> render_finished_frames(const CommonOptions& common, uint32_t bounces,
                                            uint32_t w, uint32_t h, uint32_t frames,
                                            const std::vector<float>& truth,
                                            nlohmann::json& configurations,
                                            const FrameFn& frame_fn,
                                            const scene::SceneAssets* assets) {
  auto facts = [&](uint32_t n, double psnr) {
    return nlohmann::json{{"quality", "fast"},
                          {"bounces", bounces},
                          {"frames", n},
                          {"taa", true},
                          {"render_scale", json_scale(common.render.render_scale)},
                          {"bloom", false},
                          {"motion_blur", false},
                          {"truth", "many"},
                          {"final_psnr_db", psnr}};
  };
  std::vector<uint8_t> converged, first;
  render_mode(common, kTaaConfigKey, render::Quality::kFast, bounces, true, w, h, frames,
              converged, frame_fn, assets);
  render_mode(common, kFirstFrameConfigKey, render::Quality::kFast, bounces, true, w, h, 1, first,
              frame_fn, assets);
  const double converged_db = rgba8_psnr(converged, truth), first_db = rgba8_psnr(first, truth);
  configurations[kTaaConfigKey] = facts(frames, converged_db);
  configurations[kFirstFrameConfigKey] = facts(1, first_db);
  configurations[kFirstFrameConfigKey]["gap_to_taa_db"] = converged_db - first_db;
  return converged;
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
                                        nlohmann::json& truth_json, bool with_one) {
  std::vector<Images> truths;
  for (uint32_t bounces : {1u, many_bounces}) {
    if (bounces == 1u && !with_one) continue;
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

nlohmann::json write_accuracy_pictures(const std::filesystem::path& out, uint32_t w, uint32_t h,
                                       const std::vector<Images>& truths,
                                       const std::vector<Images>& rendered,
                                       const std::vector<uint16_t>& image_labels,
                                       const std::vector<uint8_t>& taa_rgba, uint32_t many) {
  const Images& truth_one = truths[0];
  const Images& truth_many = truths[1];
  const Images& fast_many = rendered[0];
  const Images& ref_many = rendered[1];
  const Images& fast_one = rendered[2];
  const Images& ref_one = rendered[3];
  std::vector<std::vector<uint8_t>> tiles;
  const Images* order[] = {&truth_one, &fast_one, &ref_one, &truth_many, &fast_many, &ref_many};
  for (int row = 0; row < 2; ++row)
    for (const Images* img : order) {
      tiles.emplace_back();
      encode_rgba8(row == 0 ? img->combined : img->indirect, true, tiles.back());
    }
  const std::filesystem::path side = out / "accuracy_side_by_side.png";
  write_png_atomic(side, int(w * 6), int(h * 2), tile_rgba8(tiles, w, h, 6));
  tiles.clear();
  for (const auto& [mode, t] : {std::pair{&fast_one, &truth_one}, std::pair{&ref_one, &truth_one},
                                std::pair{&fast_many, &truth_many},
                                std::pair{&ref_many, &truth_many}}) {
    tiles.emplace_back();
    const double eps = leaks_and_misses(mode->indirect, t->indirect, image_labels).epsilon;
    signed_heat_map(mode->indirect, t->indirect, image_labels, eps, tiles.back());
  }
  const std::filesystem::path heat = out / "accuracy_indirect_heat.png";
  write_png_atomic(heat, int(w * 2), int(h * 2), tile_rgba8(tiles, w, h, 2));
  tiles.assign(1, {});
  encode_rgba8(truth_many.combined, true, tiles.back());
  tiles.push_back(taa_rgba);
  const std::filesystem::path taa_png = out / "accuracy_final_taa.png";
  write_png_atomic(taa_png, int(w * 2), int(h), tile_rgba8(tiles, w, h, 2));
  const std::string n = std::to_string(many);
  return {
      {"side_by_side", side.string()},
      {"side_by_side_layout",
       "columns: truth (1 bounce), fast (1), reference (1), truth (" + n + " bounces), fast (" +
           n + "), reference (" + n + "); rows: final (combined radiance), indirect component; "
           "tone mapped x/(1+x), sRGB"},
      {"heat_map", heat.string()},
      {"heat_map_layout",
       "rows: 1 bounce against the 1-bounce truth, " + n + " against the " + n +
           "-bounce truth; columns: fast, reference; (rp - truth) / (truth + eps) of indirect "
           "luminance: blue -1 (too dark), white 0, red +1 (too bright)"},
      {"final_taa", taa_png.string()},
      {"final_taa_layout", "truth (" + n + " bounces, tone mapped x/(1+x), sRGB), the fast "
                           "mode's finished frame with TAA (" + n + " bounces, no bloom or "
                           "motion blur)"}};
}

}  // namespace rp::bench
