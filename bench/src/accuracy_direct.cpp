// The direct-light section of `bench --accuracy` (see accuracy_direct.h).
#include "bench/src/accuracy_direct.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "app/host_tone_map.h"
#include "app/interrupt.h"
#include "app/png_output.h"
#include "app/progress.h"
#include "app/truth_cache.h"
#include "bench/src/accuracy_metrics.h"
#include "bench/src/accuracy_penumbra.h"
#include "scene/demo_scene.h"

namespace rp::bench {

using app::CachedTruth;
using app::CommonOptions;
using app::InterruptGuard;
using app::ProgressBar;
using app::RenderSession;
using app::cached_path_trace;
using app::encode_rgba8;
using app::ensure_directory;
using app::write_png_atomic;

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

// The marbles of the direct section: world_constants::kMarbleRadius (0.04) resting on the floor
// (centre 0.04 above y = -1), in front of the tumblers where their shadows fall on visible floor
// and no tumbler's shadow reaches; albedos are saturated "glass" colours like the simulated
// marbles' (scene/world.cpp glass_colour: hue 0 red, hue 0.6 blue).
struct MarbleSpot {
  glm::vec2 xz;
  glm::vec3 albedo;
};
constexpr float kMarbleRadius = 0.04f;
constexpr MarbleSpot kMarbles[] = {
    {{0.25f, 0.72f}, {0.9f, 0.225f, 0.225f}},
    {{-0.30f, 0.70f}, {0.225f, 0.495f, 0.9f}},
};
// The tumbler whose shadow is measured: demo_tumbler_placements()[4], front right, whose shadow
// falls towards the camera and the right wall.
constexpr size_t kMeasuredTumbler = 4;

double luminance(glm::vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// A line on the floor from a contact point directly away from the lamp's foot.
struct EdgeLine {
  const char* name;
  glm::vec3 start, dir;
  double length;
};
EdgeLine away_from_lamp(const char* name, glm::vec2 contact, double length) {
  const glm::vec2 d = glm::normalize(contact);
  // Stay 2 cm inside the side walls and the open front (x, z in [-0.98, 0.98]).
  double reach = length;
  for (int a = 0; a < 2; ++a)
    if (std::abs(d[a]) > 1e-6f)
      reach = std::min(reach, (0.98 * (d[a] > 0 ? 1.0 : -1.0) - contact[a]) / d[a]);
  return {name, glm::vec3(contact.x, -1.0f, contact.y), glm::vec3(d.x, 0.0f, d.y), reach};
}

// Pixel coordinates (x right, y down, centres at +0.5) of a world point.
glm::dvec2 project(const scene::Camera& cam, uint32_t w, uint32_t h, glm::vec3 p) {
  const glm::vec4 clip = cam.projection(float(w) / float(h)) * cam.view() * glm::vec4(p, 1.0f);
  const double nx = clip.x / clip.w, ny = clip.y / clip.w;
  return {(nx * 0.5 + 0.5) * w, (0.5 - ny * 0.5) * h};
}

// The unshadowed light factor of a lamp model on the floor (normal +y): albedo * I * this.
double point_unshadowed(const scene::PointLight& light, glm::vec3 p) {
  const glm::vec3 to = light.position - p;
  const double d2 = glm::dot(to, to);
  const glm::vec3 l = to / float(std::sqrt(d2));
  const double s = std::clamp(double(l.y), 0.0, 1.0);
  return std::max(0.0, double(l.y)) / d2 * (0.35 + s * (0.446 + 0.204 * s));
}

// Visible-fraction profile of an image (direct, albedo) along `line`, at samples whose four
// surrounding pixel centres see the floor.
std::vector<ProfileSample> profile(const EdgeLine& line, const std::vector<float>& direct,
                                   const std::vector<float>& albedo, bool area_model,
                                   const scene::FrameScene& frame,
                                   const std::vector<truth::PrimaryHit>& hits, uint32_t w,
                                   uint32_t h) {
  std::vector<ProfileSample> out;
  const double step = 0.002;  // world units: ~1/4 pixel at 360x360 on the front floor
  const double intensity = luminance(frame.light.intensity);
  for (double s = 0.0; s <= line.length; s += step) {
    const glm::vec3 p = line.start + float(s) * line.dir;
    const glm::dvec2 px = project(frame.camera, w, h, p);
    const int x0 = int(std::floor(px.x - 0.5)), y0 = int(std::floor(px.y - 0.5));
    bool floor = x0 >= 0 && y0 >= 0 && x0 + 1 < int(w) && y0 + 1 < int(h);
    for (int dy = 0; floor && dy < 2; ++dy)
      for (int dx = 0; floor && dx < 2; ++dx)
        floor = hits[size_t(y0 + dy) * w + size_t(x0 + dx)].material == scene::demo::kFloorMaterial;
    if (!floor) continue;
    const double a = bilinear_luma(albedo, w, h, px.x, px.y);
    const double u = area_model ? truth::area_lamp_unshadowed(frame.light, p, {0, 1, 0})
                                : point_unshadowed(frame.light, p);
    if (!(a > 0.0) || !(u > 0.0)) continue;
    out.push_back({s, bilinear_luma(direct, w, h, px.x, px.y) / (a * intensity * u)});
  }
  return out;
}

// Real-time images of one shadow mode (accuracy_direct.h).
struct RealTime {
  std::vector<float> direct_avg, albedo_avg;  // mean over the jittered frames
  std::vector<float> direct_one, albedo_one;  // the unjittered first frame
  double median_frame_ms = 0.0;
};
RealTime render_real_time(const CommonOptions& common, render::ShadowMode mode, uint32_t w,
                          uint32_t h, uint32_t jitter_frames, const std::string& label) {
  CommonOptions c = common;
  c.render.quality = render::Quality::kFast;
  c.render.bounces = 1;
  c.render.shadows = mode;
  c.view = {};
  c.render.effects.bloom = c.render.effects.motion_blur = false;
  c.render.effects.taa = false;
  c.render.render_scale = 1.0f;  // the direct term at the output size
  RenderSession session(c, w, h, true);
  RealTime rt;
  std::vector<uint8_t> rgba;
  render::LinearComponents lc;
  std::vector<double> ms;
  ProgressBar bar(label, jitter_frames + 1);
  for (uint32_t i = 0; i <= jitter_frames; ++i) {
    if (InterruptGuard::interrupted()) throw truth::PathTracer::Cancelled();
    if (i == 1) {
      render::Effects e = c.render.effects;
      e.taa = true;  // from now on the projection is jittered (Halton, 16 per cycle)
      session.set_effects(e);
    }
    double frame_ms = 0.0;
    session.render(direct_frame(session.assets(), i), rgba, frame_ms);
    ms.push_back(frame_ms);
    session.read_components(lc);
    if (i == 0) {
      rt.direct_one = lc.direct;
      rt.albedo_one = lc.albedo;
      rt.direct_avg.assign(lc.direct.size(), 0.0f);
      rt.albedo_avg.assign(lc.albedo.size(), 0.0f);
      continue;
    }
    for (size_t k = 0; k < lc.direct.size(); ++k) {
      rt.direct_avg[k] += lc.direct[k] / float(jitter_frames);
      rt.albedo_avg[k] += lc.albedo[k] / float(jitter_frames);
    }
    bar.update(i + 1);
  }
  bar.finish();
  std::sort(ms.begin(), ms.end());
  rt.median_frame_ms = ms[ms.size() / 2];
  return rt;
}


double bias(const std::vector<float>& a, const std::vector<float>& t,
            const std::vector<uint8_t>& mask) {
  double sa = 0.0, st = 0.0;
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i])
      for (size_t c = 0; c < 3; ++c) sa += a[3 * i + c], st += t[3 * i + c];
  return st > 0.0 ? sa / st - 1.0 : kNan;
}

nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }
// [[s, v], ...] with 4 decimals (world units, visible fraction).
nlohmann::json profile_json(const std::vector<ProfileSample>& p) {
  nlohmann::json a = nlohmann::json::array();
  for (const ProfileSample& q : p)
    a.push_back({std::round(q.s * 1e4) / 1e4, std::round(q.v * 1e4) / 1e4});
  return a;
}
double dnum(const nlohmann::json& v) { return v.is_number() ? v.get<double>() : kNan; }

}  // namespace

scene::FrameScene direct_frame(const scene::SceneAssets& assets, uint32_t frame_index) {
  scene::FrameScene frame = scene::make_demo_frame(assets, frame_index);
  for (const MarbleSpot& m : kMarbles)
    frame.spheres.push_back(scene::resting_marble(m.xz, kMarbleRadius, m.albedo));
  return frame;
}

DirectResult measure_direct(const CommonOptions& common, const scene::SceneAssets& assets,
                            truth::PathTracer& tracer, const DirectOptions& o) {
  const uint32_t w = o.width, h = o.height;
  const scene::FrameScene frame = direct_frame(assets, 0);
  nlohmann::json j;
  j["scene"] = "demo frame at rest + 2 marbles (r 0.04) resting on the floor at (0.25, 0.72) and "
               "(-0.30, 0.70) (app/accuracy_direct.h)";

  const auto start = std::chrono::steady_clock::now();
  // The truth (two seeds: the second only to state the first's noise), then the point lamp's
  // truth at a quarter of the samples (its only noise is the pixel filter's): what a perfect
  // shadow of the point model would score, the ceiling of the real-time light model.
  std::vector<truth::PathTracedImage> truths;
  for (int k = 0; k < 3; ++k) {
    truth::PathTraceSettings s;
    s.width = w;
    s.height = h;
    s.spp = k < 2 ? o.spp : std::max(1u, o.spp / 4);
    s.bounces = 0;
    s.seed = k == 1 ? o.seed + 1 : o.seed;
    s.lamp = k < 2 ? truth::LampModel::kArea : truth::LampModel::kPoint;
    const uint64_t seed = s.seed;
    ProgressBar bar(std::string("path tracing (") + (k < 2 ? "area" : "point") +
                        " lamp, direct, seed " + std::to_string(seed) + ")",
                    h);
    std::atomic<bool> cancel{false};
    CachedTruth t = cached_path_trace(
        tracer, assets, frame, s, o.cache_dir,
        [&](uint32_t done, uint32_t) {
          if (InterruptGuard::interrupted()) cancel = true;
          bar.update(done);
        },
        &cancel);
    bar.finish();
    if (truths.empty())
      j["truth"] = {{"lamp", "area"},       {"bounces", 0},
                    {"spp", s.spp},         {"seed", seed},
                    {"seconds", t.image.seconds}, {"from_cache", t.from_cache},
                    {"file", t.file.string()}};
    truths.push_back(std::move(t.image));
  }
  const truth::PathTracedImage& truth = truths[0];

  // Regions from the truth: floor (eroded labels), covered pixels, penumbra.
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<truth::PrimaryHit> hits = tracer.primary_hits(frame, w, h, 16);
  const std::vector<uint16_t> labels = classify_regions(hits, w, h);
  const uint16_t floor_bits =
      uint16_t((1u << unsigned(Region::kFloorLit)) | (1u << unsigned(Region::kFloorShadow)));
  std::vector<uint8_t> floor(labels.size()), image(labels.size()), penumbra(labels.size());
  // "image": every covered pixel but the ceiling, the lamp cap and the pixels beside them: the
  // area lamp lights the ceiling (brightly beside the cap, whose side it sees from close by),
  // the point model cannot (its centre is above the ceiling), and pixels that straddle the
  // ceiling's edge or the cap's rim would swamp every other difference.
  std::vector<uint8_t> ceiling(labels.size());
  for (size_t i = 0; i < labels.size(); ++i)
    ceiling[i] = hits[i].material == scene::demo::kCeilingMaterial ||
                 hits[i].material == scene::demo::kLampMaterial;
  ceiling = dilate(ceiling, w, h, 1);
  for (size_t i = 0; i < labels.size(); ++i) {
    floor[i] = (labels[i] & floor_bits) ? 1 : 0;
    image[i] = labels[i] && !ceiling[i] ? 1 : 0;
    penumbra[i] = hits[i].lamp_fraction > 0.05f && hits[i].lamp_fraction < 0.95f;
  }
  penumbra = dilate(penumbra, w, h, 1);
  for (size_t i = 0; i < labels.size(); ++i) penumbra[i] = penumbra[i] && image[i];
  // The penumbra taken apart (accuracy_penumbra.h): by where the floor shows, and by the
  // truth's lamp fraction.
  std::vector<uint8_t> floor_material(labels.size());
  std::vector<float> lamp_fraction(labels.size());
  for (size_t i = 0; i < labels.size(); ++i) {
    floor_material[i] = hits[i].material == scene::demo::kFloorMaterial ? 1 : 0;
    lamp_fraction[i] = hits[i].lamp_fraction;
  }
  const PenumbraParts parts = penumbra_parts(penumbra, floor_material, w, h);
  // The normaliser: the truth's mean direct luminance over floor pixels the whole lamp reaches.
  double lit_sum = 0.0;
  uint64_t lit_n = 0, floor_n = 0, penumbra_n = 0;
  for (size_t i = 0; i < labels.size(); ++i) {
    floor_n += floor[i];
    penumbra_n += penumbra[i];
    if (floor[i] && hits[i].lamp_fraction >= 0.999f) {
      lit_sum += 0.2126 * truth.direct[3 * i] + 0.7152 * truth.direct[3 * i + 1] +
                 0.0722 * truth.direct[3 * i + 2];
      ++lit_n;
    }
  }
  const double scale = lit_n ? double(lit_n) / lit_sum : 1.0;
  j["psnr_definition"] = {
      {"direct_psnr_db",
       "10 log10(1 / MSE) over RGB of the direct component after the renderer's tone map x/(1+x) "
       "and the exact sRGB encode (peak 1), the jittered average against the truth"},
      {"direct_psnr_db_lit_floor_scale",
       "the same on the linear direct component divided by the truth's mean direct luminance "
       "on the fully lit floor (peak 1 = the lit floor's level)"},
      {"lit_floor_luminance", lit_n ? lit_sum / double(lit_n) : kNan}};
  j["pixels"] = {{"floor", floor_n}, {"penumbra", penumbra_n}, {"lit_floor", lit_n}};
  // The truth's own noise: the two seeds' PSNR, both scales (its error against the exact image
  // is 3 dB better than this).
  j["truth"]["noise_psnr_db"] = {
      {"floor", num(masked_tone_mapped_psnr(truths[1].direct, truth.direct, floor))},
      {"penumbra", num(masked_tone_mapped_psnr(truths[1].direct, truth.direct, penumbra))},
      {"image", num(masked_tone_mapped_psnr(truths[1].direct, truth.direct, image))}};
  j["truth"]["noise_psnr_db_lit_floor_scale"] = {
      {"floor", num(masked_psnr(truths[1].direct, truth.direct, floor, scale))},
      {"penumbra", num(masked_psnr(truths[1].direct, truth.direct, penumbra, scale))},
      {"image", num(masked_psnr(truths[1].direct, truth.direct, image, scale))}};
  {
    const truth::PathTracedImage& point = truths[2];
    nlohmann::json pj = {{"lamp", "point"}, {"bounces", 0}, {"spp", std::max(1u, o.spp / 4)}};
    pj["direct_psnr_db"] = {
        {"floor", num(masked_tone_mapped_psnr(point.direct, truth.direct, floor))},
        {"penumbra", num(masked_tone_mapped_psnr(point.direct, truth.direct, penumbra))},
        {"image", num(masked_tone_mapped_psnr(point.direct, truth.direct, image))}};
    pj["direct_bias_floor"] = num(bias(point.direct, truth.direct, floor));
    j["point_lamp_truth"] = pj;
  }
  j["truth"]["noise_note"] = "PSNR between the truths of seeds " + std::to_string(o.seed) +
                             " and " + std::to_string(o.seed + 1) +
                             "; the truth's own error is 3 dB better";

  // Measurement lines.
  const auto placements = scene::demo_tumbler_placements();
  const EdgeLine lines[] = {away_from_lamp("tumbler", placements[kMeasuredTumbler].xz, 0.5),
                            away_from_lamp("marble", kMarbles[0].xz, 0.15)};
  double truth_width[2];
  for (int k = 0; k < 2; ++k) {
    const EdgeLine& l = lines[k];
    const std::vector<ProfileSample> tp =
        profile(l, truth.direct, truth.albedo, true, frame, hits, w, h);
    truth_width[k] = transition_width(tp);
    j["profiles"][l.name]["truth"] = profile_json(tp);
    // World size of a pixel at the line's start, along the line: the widths' resolution.
    const double pixel = 0.01 / glm::length(project(frame.camera, w, h, l.start + 0.01f * l.dir) -
                                            project(frame.camera, w, h, l.start));
    j["lines"][l.name] = {{"start", {l.start.x, l.start.y, l.start.z}},
                          {"direction", {l.dir.x, l.dir.y, l.dir.z}},
                          {"length", l.length},
                          {"pixel_world_size", pixel},
                          {"truth_width", num(truth_width[k])},
                          {"point_lamp_truth_width",
                           num(transition_width(profile(l, truths[2].direct, truths[2].albedo,
                                                        false, frame, hits, w, h)))}};
  }
  j["setup_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Every shadow mode.
  const render::ShadowMode default_mode = render::RenderSettings{}.shadows;
  const char* default_name = "";
  std::vector<std::vector<uint8_t>> top, bottom;
  top.emplace_back();
  encode_rgba8(truth.direct, true, top.back());
  {  // the measurement lines in green on the truth's tile
    std::vector<uint8_t>& img = top.back();
    for (const EdgeLine& l : lines)
      for (double s = 0.0; s <= l.length; s += 0.001) {
        const glm::dvec2 px = project(frame.camera, w, h, l.start + float(s) * l.dir);
        const int x = int(px.x), y = int(px.y);
        if (x < 0 || y < 0 || x >= int(w) || y >= int(h)) continue;
        uint8_t* p = &img[(size_t(y) * w + size_t(x)) * 4];
        p[0] = 0, p[1] = 255, p[2] = 0;
      }
  }
  bottom.emplace_back(size_t(w) * h * 4, 0);  // the penumbra mask over the truth, in red
  for (size_t i = 0; i < labels.size(); ++i) {
    uint8_t* p = &bottom.back()[4 * i];
    const uint8_t g = top.back()[4 * i + 1];
    p[0] = penumbra[i] ? 255 : g / 2;
    p[1] = penumbra[i] ? 0 : g / 2;
    p[2] = penumbra[i] ? 0 : g / 2;
    p[3] = 255;
  }
  double lum_sum = 0.0;
  for (size_t i = 0; i < labels.size(); ++i)
    if (image[i])
      lum_sum += 0.2126 * truth.direct[3 * i] + 0.7152 * truth.direct[3 * i + 1] +
                 0.0722 * truth.direct[3 * i + 2];
  const double heat_eps = 0.05 * lum_sum / double(std::max<uint64_t>(1, penumbra_n + floor_n));

  char line[256];
  std::string table;
  std::snprintf(line, sizeof line,
                "\ndirect light against the area-lamp truth (%u spp, 0 bounces; demo + 2 marbles; "
                "real time: %u jittered frames averaged); PSNR of the direct component after the "
                "tone map, widths in world units (10-90 %%)\n",
                o.spp, o.jitter_frames);
  table += line;
  std::snprintf(line, sizeof line, "%-8s %9s %9s %9s %9s %9s %9s %9s %9s\n", "shadows",
                "floor dB", "penum dB", "image dB", "floor bias", "tumbler w", "ratio",
                "marble w", "ratio");
  table += line;
  std::snprintf(line, sizeof line, "%-8s %9.2f %9.2f %9.2f %9s %9.4f %9s %9.4f %9s\n",
                "(truth noise)", dnum(j["truth"]["noise_psnr_db"]["floor"]),
                dnum(j["truth"]["noise_psnr_db"]["penumbra"]),
                dnum(j["truth"]["noise_psnr_db"]["image"]), "", truth_width[0], "",
                truth_width[1], "");
  table += line;
  {
    const nlohmann::json& pj = j["point_lamp_truth"];
    std::snprintf(line, sizeof line, "%-8s %9.2f %9.2f %9.2f %+8.1f%%   (the point lamp's perfect "
                  "hard shadow)\n", "(point)", dnum(pj["direct_psnr_db"]["floor"]),
                  dnum(pj["direct_psnr_db"]["penumbra"]), dnum(pj["direct_psnr_db"]["image"]),
                  100.0 * dnum(pj["direct_bias_floor"]));
    table += line;
  }
  for (const NamedValue<render::ShadowMode>& mode : names(render::ShadowMode{})) {
    // The table's names are string literals: .data() is NUL-terminated.
    const char* mode_name = mode.name.data();
    if (mode.value == default_mode) default_name = mode_name;
    const RealTime rt = render_real_time(common, mode.value, w, h, o.jitter_frames,
                                         std::string("fast, shadows ") + mode_name);
    nlohmann::json mj;
    mj["frames"] = o.jitter_frames;
    mj["median_frame_ms"] = rt.median_frame_ms;
    auto psnrs = [&](const std::vector<float>& a, bool tone_mapped) {
      nlohmann::json p;
      for (const auto& [name, mask] : {std::pair{"floor", &floor}, std::pair{"penumbra", &penumbra},
                                       std::pair{"image", &image}})
        p[name] = num(tone_mapped ? masked_tone_mapped_psnr(a, truth.direct, *mask)
                                  : masked_psnr(a, truth.direct, *mask, scale));
      return p;
    };
    mj["direct_psnr_db"] = psnrs(rt.direct_avg, true);
    mj["direct_psnr_db_unjittered"] = psnrs(rt.direct_one, true);
    mj["direct_psnr_db_lit_floor_scale"] = psnrs(rt.direct_avg, false);
    mj["direct_bias_floor"] = num(bias(rt.direct_avg, truth.direct, floor));
    mj["penumbra_breakdown"] = penumbra_breakdown(rt.direct_avg, truth.direct, parts,
                                                  lamp_fraction);
    double ratio[2];
    for (int k = 0; k < 2; ++k) {
      const std::vector<ProfileSample> p =
          profile(lines[k], rt.direct_avg, rt.albedo_avg, false, frame, hits, w, h);
      const double width = transition_width(p);
      j["profiles"][lines[k].name][mode_name] = profile_json(p);
      ratio[k] = width / truth_width[k];
      mj["penumbra"][lines[k].name] = {{"width", num(width)},
                                       {"ratio_to_truth", num(ratio[k])},
                                       {"error", num(std::abs(ratio[k] - 1.0))}};
    }
    mj["albedo_psnr_db"] = {{"image", num(srgb_psnr(rt.albedo_one, truth.albedo, image))},
                            {"floor", num(srgb_psnr(rt.albedo_one, truth.albedo, floor))}};
    mj["albedo_psnr_db_jittered_average"] = {
        {"image", num(srgb_psnr(rt.albedo_avg, truth.albedo, image))},
        {"floor", num(srgb_psnr(rt.albedo_avg, truth.albedo, floor))}};
    const auto& d = dnum;
    std::snprintf(line, sizeof line, "%-8s %9.2f %9.2f %9.2f %+8.1f%% %9.4f %9.2f %9.4f %9.2f\n",
                  mode_name, d(mj["direct_psnr_db"]["floor"]), d(mj["direct_psnr_db"]["penumbra"]),
                  d(mj["direct_psnr_db"]["image"]), 100.0 * d(mj["direct_bias_floor"]),
                  d(mj["penumbra"]["tumbler"]["width"]), ratio[0],
                  d(mj["penumbra"]["marble"]["width"]), ratio[1]);
    table += line;
    j["modes"][mode_name] = mj;
    top.emplace_back();
    encode_rgba8(rt.direct_avg, true, top.back());
    bottom.emplace_back();
    signed_heat_map(rt.direct_avg, truth.direct, labels, heat_eps, bottom.back());
  }
  j["default_shadows"] = default_name;
  j["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  j["texture_filter"] = name_of(common.render.texture_filter).data();
  const nlohmann::json& dm = j["modes"][default_name];
  table += penumbra_breakdown_text(default_name, dm["penumbra_breakdown"]);
  std::snprintf(line, sizeof line,
                "albedo view (%s, one unjittered frame) against the truth's pixel-averaged "
                "albedo: %.2f dB image, %.2f dB floor (jittered average: %.2f / %.2f dB)\n",
                name_of(common.render.texture_filter).data(),
                dnum(dm["albedo_psnr_db"]["image"]), dnum(dm["albedo_psnr_db"]["floor"]),
                dnum(dm["albedo_psnr_db_jittered_average"]["image"]),
                dnum(dm["albedo_psnr_db_jittered_average"]["floor"]));
  table += line;

  ensure_directory(o.out_dir);
  std::vector<std::vector<uint8_t>> tiles = top;
  tiles.insert(tiles.end(), bottom.begin(), bottom.end());
  const std::filesystem::path side = o.out_dir / "accuracy_direct_side_by_side.png";
  write_png_atomic(side, int(w * 5), int(h * 2), tile_rgba8(tiles, w, h, 5));
  j["images"] = {
      {"side_by_side", side.string()},
      {"side_by_side_layout",
       "top: the direct component, tone mapped x/(1+x), sRGB: area-lamp truth (the measurement "
       "lines in green), then the fast mode with shadows hard, pcf, pcss, vssm (jittered "
       "average); bottom: the truth's penumbra pixels in red, then each mode's heat map "
       "(rp - truth) / (truth + eps) of direct luminance: blue -1, white 0, red +1"}};
  table += "wrote " + side.string() + "\n";
  return {j, table};
}

}  // namespace rp::bench
