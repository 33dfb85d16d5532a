// `bench --accuracy` (see accuracy_report.h).
#include "app/accuracy_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "app/accuracy_metrics.h"
#include "app/commands.h"
#include "app/host_tone_map.h"
#include "app/interrupt.h"
#include "app/png_output.h"
#include "app/progress.h"
#include "app/truth_cache.h"
#include "scene/demo_scene.h"

namespace rp::app {
namespace {

// The linear images one mode or truth gives (3 floats per pixel).
struct Images {
  std::string name;
  std::vector<float> combined, direct, indirect, albedo;
};

Images from_truth(const std::string& name, const truth::PathTracedImage& t) {
  return {name, t.combined, t.direct, t.indirect, t.albedo};
}

// The real-time renderer on the demo frame at rest: `frames` frames (frame_index counting up,
// so the fast mode's interleaving and the shadow noise rotate as in the app), no post effects.
Images render_mode(const CommonOptions& common, render::Quality quality, uint32_t w, uint32_t h,
                   uint32_t frames) {
  CommonOptions c = common;
  c.quality = quality;
  c.view = {};
  c.effects.taa = c.effects.bloom = c.effects.motion_blur = false;
  RenderSession session(c, w, h);
  session.set_keep_components(true);
  std::vector<uint8_t> rgba;
  double ms = 0.0;
  for (uint32_t i = 0; i < frames; ++i) {
    if (InterruptGuard::interrupted()) throw truth::PathTracer::Cancelled();
    session.render(scene::make_demo_frame(session.assets(), i), rgba, ms);
  }
  render::LinearComponents lc;
  session.read_components(lc);
  return {quality == render::Quality::kFast ? "fast" : "reference", lc.combined, lc.direct,
          lc.indirect, lc.albedo};
}

nlohmann::json stats_json(const ErrorStats& s) {
  return {{"rel_l1", s.rel_l1}, {"bias", s.bias}, {"pixels", s.pixels}};
}

nlohmann::json rgb_json(const IncomingLight& in) {
  return {{"rgb", {in.rgb[0], in.rgb[1], in.rgb[2]}}, {"r_minus_b", in.r_minus_b()}};
}

// One mode against one truth.
nlohmann::json compare(const Images& rp, const Images& truth, const std::vector<uint16_t>& labels) {
  nlohmann::json j;
  j["final_psnr_db"] = tone_mapped_psnr(rp.combined, truth.combined);
  j["direct"] = stats_json(compare_region(rp.direct, truth.direct, labels, Region::kImage));
  nlohmann::json regions;
  for (size_t r = 0; r < kRegionCount; ++r)
    regions[region_name(Region(r))] =
        stats_json(compare_region(rp.indirect, truth.indirect, labels, Region(r)));
  j["indirect"] = regions;
  for (Region wall : {Region::kLeftWall, Region::kRightWall}) {
    const IncomingLight a = incoming_indirect(rp.indirect, rp.albedo, labels, wall);
    const IncomingLight t = incoming_indirect(truth.indirect, truth.albedo, labels, wall);
    nlohmann::json w = rgb_json(a);
    w["same_hue_sign_as_truth"] = (a.r_minus_b() > 0.0) == (t.r_minus_b() > 0.0);
    j["incoming_indirect"][region_name(wall)] = w;
  }
  const LeakStats leaks = leaks_and_misses(rp.indirect, truth.indirect, labels);
  j["leaks"] = {{"leak_pixels", leaks.leak_pixels},
                {"missing_pixels", leaks.missing_pixels},
                {"covered_pixels", leaks.covered_pixels},
                {"epsilon", leaks.epsilon}};
  return j;
}

// Tiles of w x h RGBA8 images, `columns` per row, in the order given.
std::vector<uint8_t> tile(const std::vector<std::vector<uint8_t>>& images, uint32_t w, uint32_t h,
                          uint32_t columns) {
  const uint32_t rows = uint32_t((images.size() + columns - 1) / columns);
  std::vector<uint8_t> out(size_t(w) * columns * h * rows * 4, 0);
  for (size_t k = 0; k < images.size(); ++k) {
    const size_t ox = (k % columns) * w, oy = (k / columns) * h;
    for (uint32_t y = 0; y < h; ++y)
      std::copy_n(&images[k][size_t(y) * w * 4], size_t(w) * 4,
                  &out[((oy + y) * size_t(w) * columns + ox) * 4]);
  }
  return out;
}

// "+12.3%" (signed: a bias) or "12.3%" (a magnitude), right-aligned in 8 characters.
std::string pct(double v, bool sign) {
  if (!std::isfinite(v)) return "     n/a";
  char b[32];
  std::snprintf(b, sizeof b, sign ? "%+7.1f%%" : "%7.1f%%", v * 100.0);
  return b;
}

}  // namespace

AccuracyResult measure_accuracy(const CommonOptions& common, const AccuracyOptions& options) {
  const uint32_t w = options.width, h = options.height;
  const scene::SceneAssets assets = scene::make_demo_assets(
      common.asset_dir.empty() ? scene::default_asset_dir() : common.asset_dir);
  const scene::FrameScene frame = scene::make_demo_frame(assets, 0);
  const std::filesystem::path cache =
      options.cache_dir.empty() ? default_truth_cache_dir() : options.cache_dir;
  ensure_directory(options.out_dir);  // before the long renders

  truth::PathTracer tracer(assets);
  const std::vector<uint16_t> labels = classify_regions(tracer.primary_hits(frame, w, h), w, h);
  nlohmann::json j;
  j["schema"] = "rolypoly-accuracy/1";
  j["command"] = options.command_line;
  j["scene"] = "demo frame at rest (scene::make_demo_frame)";
  j["width"] = w;
  j["height"] = h;

  // Truths at one gather (what the real-time passes model) and at many.
  std::vector<Images> truths;
  std::vector<truth::PathTracedImage> truth_raw;
  for (uint32_t bounces : {1u, options.many_bounces}) {
    truth::PathTraceSettings s;
    s.width = w;
    s.height = h;
    s.spp = options.spp;
    s.bounces = bounces;
    s.seed = options.seed;
    ProgressBar bar("path tracing (" + std::to_string(bounces) + " bounce" +
                        (bounces == 1 ? "" : "s") + ")",
                    h);
    std::atomic<bool> cancel{false};  // set from the progress callback on Ctrl-C / SIGTERM
    const CachedTruth t = cached_path_trace(
        tracer, assets, frame, s, cache,
        [&](uint32_t done, uint32_t) {
          if (InterruptGuard::interrupted()) cancel = true;
          bar.update(done);
        },
        &cancel);
    bar.finish();
    const std::string key = bounces == 1 ? "one" : "many";
    j["truth"][key] = {{"bounces", bounces},
                       {"spp", s.spp},
                       {"seed", s.seed},
                       {"seconds", t.image.seconds},
                       {"rays_per_second", t.image.rays_per_second()},
                       {"from_cache", t.from_cache},
                       {"file", t.file.string()}};
    truths.push_back(from_truth("truth_" + key, t.image));
    truth_raw.push_back(t.image);
  }

  const Images fast = render_mode(common, render::Quality::kFast, w, h, options.converge_frames);
  const Images reference = render_mode(common, render::Quality::kReference, w, h, 1);
  j["modes"]["fast"]["frames"] = options.converge_frames;
  j["modes"]["reference"]["frames"] = 1;
  for (const Images* mode : {&fast, &reference}) {
    j["modes"][mode->name]["vs_one_bounce"] = compare(*mode, truths[0], labels);
    j["modes"][mode->name]["vs_many_bounces"] = compare(*mode, truths[1], labels);
  }
  for (size_t k = 0; k < 2; ++k)
    for (Region wall : {Region::kLeftWall, Region::kRightWall})
      j["truth"][k == 0 ? "one" : "many"]["incoming_indirect"][region_name(wall)] =
          rgb_json(incoming_indirect(truths[k].indirect, truths[k].albedo, labels, wall));
  for (size_t r = 0; r < kRegionCount; ++r) {
    uint64_t n = 0;
    for (uint16_t l : labels) n += (l >> r) & 1u;
    j["region_pixels"][region_name(Region(r))] = n;
  }

  // Pictures: final and indirect of truth (1 bounce), fast, reference, truth (many); heat maps
  // of the indirect light, fast and reference against each truth.
  std::vector<std::vector<uint8_t>> tiles;
  const Images* order[] = {&truths[0], &fast, &reference, &truths[1]};
  for (int row = 0; row < 2; ++row)
    for (const Images* img : order) {
      tiles.emplace_back();
      encode_rgba8(row == 0 ? img->combined : img->indirect, true, tiles.back());
    }
  const std::filesystem::path side = options.out_dir / "accuracy_side_by_side.png";
  write_png_atomic(side, int(w * 4), int(h * 2), tile(tiles, w, h, 4));
  tiles.clear();
  for (const Images* t : {&truths[0], &truths[1]})
    for (const Images* mode : {&fast, &reference}) {
      tiles.emplace_back();
      const double eps = leaks_and_misses(mode->indirect, t->indirect, labels).epsilon;
      signed_heat_map(mode->indirect, t->indirect, labels, eps, tiles.back());
    }
  const std::filesystem::path heat = options.out_dir / "accuracy_indirect_heat.png";
  write_png_atomic(heat, int(w * 2), int(h * 2), tile(tiles, w, h, 2));
  j["images"] = {{"side_by_side", side.string()},
                 {"side_by_side_layout",
                  "columns: truth (1 bounce), fast, reference, truth (many bounces); rows: final "
                  "(combined radiance), indirect component; tone mapped x/(1+x), sRGB"},
                 {"heat_map", heat.string()},
                 {"heat_map_layout",
                  "rows: against the 1-bounce truth, against the many-bounce truth; columns: "
                  "fast, reference; (rp - truth) / (truth + eps) of indirect luminance: blue -1 "
                  "(too dark), white 0, red +1 (too bright)"}};

  // Thresholds: the fast mode (the default) against the truth at the bounce count it models.
  AccuracyResult result;
  const nlohmann::json& fast_one = j["modes"]["fast"]["vs_one_bounce"]["indirect"]["image"];
  if (options.max_indirect_l1) {
    const bool ok = fast_one["rel_l1"].get<double>() <= *options.max_indirect_l1;
    j["thresholds"]["max_indirect_l1"] = {{"limit", *options.max_indirect_l1}, {"passed", ok}};
    result.passed = result.passed && ok;
  }
  if (options.max_indirect_bias) {
    const bool ok = std::abs(fast_one["bias"].get<double>()) <= *options.max_indirect_bias;
    j["thresholds"]["max_indirect_bias"] = {{"limit", *options.max_indirect_bias}, {"passed", ok}};
    result.passed = result.passed && ok;
  }
  j["passed"] = result.passed;

  // The printed table.
  std::ostringstream t;
  char line[256];
  std::snprintf(line, sizeof line, "accuracy at %ux%u, demo frame at rest; truth %u spp, seed %llu\n",
                w, h, options.spp, static_cast<unsigned long long>(options.seed));
  t << line;
  for (const char* k : {"one", "many"}) {
    const nlohmann::json& tj = j["truth"][k];
    std::snprintf(line, sizeof line, "  truth, %u bounce(s): %.1f s, %.1f Mrays/s%s\n",
                  tj["bounces"].get<uint32_t>(), tj["seconds"].get<double>(),
                  tj["rays_per_second"].get<double>() / 1e6,
                  tj["from_cache"].get<bool>() ? " (from the cache)" : "");
    t << line;
  }
  std::snprintf(line, sizeof line, "\n%-32s %8s %8s %8s %8s\n", "(rolypoly vs truth)", "fast/1",
                "ref/1", "fast/N", "ref/N");
  t << line << "  (/1: against the 1-bounce truth, /N: against " << options.many_bounces
    << " bounces)\n";
  auto row = [&](const std::string& label, auto get) {
    std::snprintf(line, sizeof line, "%-32s", label.c_str());
    t << line;
    for (const char* vs : {"vs_one_bounce", "vs_many_bounces"})
      for (const char* mode : {"fast", "reference"}) t << ' ' << get(j["modes"][mode][vs]);
    t << '\n';
  };
  row("final PSNR (dB)", [](const nlohmann::json& m) {
    char b[16];
    std::snprintf(b, sizeof b, "%8.2f", m["final_psnr_db"].get<double>());
    return std::string(b);
  });
  row("direct bias", [](const nlohmann::json& m) {
    return pct(m["direct"]["bias"].get<double>(), true);
  });
  for (const char* what : {"rel_l1", "bias"})
    for (size_t r = 0; r < kRegionCount; ++r) {
      const std::string name = region_name(Region(r));
      row(std::string("indirect ") + (what[0] == 'r' ? "L1 " : "bias ") + name,
          [&](const nlohmann::json& m) {
            const nlohmann::json& v = m["indirect"][name][what];
            return pct(v.is_number() ? v.get<double>() : NAN, what[0] == 'b');
          });
    }
  for (const char* what : {"leak_pixels", "missing_pixels"})
    row(std::string(what[0] == 'l' ? "leak" : "missing") + " pixels (indirect)",
        [&](const nlohmann::json& m) {
          char b[16];
          std::snprintf(b, sizeof b, "%8llu",
                        static_cast<unsigned long long>(m["leaks"][what].get<uint64_t>()));
          return std::string(b);
        });
  t << "\nincoming indirect light on the side walls (indirect / albedo, R G B; R - B):\n";
  for (const char* wall : {"left_wall", "right_wall"}) {
    auto put = [&](const std::string& who, const nlohmann::json& in) {
      std::snprintf(line, sizeof line, "  %-10s %-16s %.3f %.3f %.3f  R-B %+.3f\n", wall,
                    who.c_str(), in["rgb"][0].get<double>(), in["rgb"][1].get<double>(),
                    in["rgb"][2].get<double>(), in["r_minus_b"].get<double>());
      t << line;
    };
    put("truth 1", j["truth"]["one"]["incoming_indirect"][wall]);
    put("truth N", j["truth"]["many"]["incoming_indirect"][wall]);
    put("fast", j["modes"]["fast"]["vs_one_bounce"]["incoming_indirect"][wall]);
    put("reference", j["modes"]["reference"]["vs_one_bounce"]["incoming_indirect"][wall]);
  }
  t << "wrote " << side.string() << " and " << heat.string() << "\n";
  result.table = t.str();
  result.json = j;
  if (!options.json_path.empty()) write_text_atomic(options.json_path, j.dump(2) + "\n");
  return result;
}

int accuracy_command(const CommonOptions& common, const BenchOptions& options) {
  InterruptGuard interrupt;
  AccuracyOptions o;
  o.width = options.size_given ? options.size.width : 360;
  o.height = options.size_given ? options.size.height : 360;
  o.spp = options.accuracy_spp;
  o.seed = options.sim.seed;
  o.cache_dir = options.truth_cache;
  o.out_dir = options.out_dir;
  o.json_path = options.json;
  o.max_indirect_l1 = options.max_indirect_l1;
  o.max_indirect_bias = options.max_indirect_bias;
  o.command_line = options.command_line;
  AccuracyResult r;
  try {
    r = measure_accuracy(common, o);
  } catch (const truth::PathTracer::Cancelled&) {
    std::fprintf(stderr,
                 "rolypoly: error: interrupted; no report was written (finished truths stay in "
                 "the cache)\n");
    return kInterruptedExitCode;
  }
  std::fputs(r.table.c_str(), stdout);
  for (const char* k : {"max_indirect_l1", "max_indirect_bias"})
    if (r.json.contains("thresholds") && r.json["thresholds"].contains(k)) {
      const nlohmann::json& th = r.json["thresholds"][k];
      std::printf("%s %.3f: %s\n", k, th["limit"].get<double>(),
                  th["passed"].get<bool>() ? "met" : "MISSED");
    }
  if (!options.json.empty()) std::printf("wrote %s\n", options.json.c_str());
  return r.passed ? 0 : 3;
}

}  // namespace rp::app
