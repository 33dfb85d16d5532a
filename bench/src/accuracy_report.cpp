// `bench --accuracy` (see accuracy_report.h).
#include "bench/src/accuracy_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "app/host_tone_map.h"
#include "app/interrupt.h"
#include "app/pathtrace_settings.h"
#include "app/png_output.h"
#include "app/truth_cache.h"
#include "bench/src/accuracy_direct.h"
#include "bench/src/accuracy_file.h"
#include "bench/src/accuracy_marbles.h"
#include "bench/src/accuracy_metrics.h"
#include "bench/src/accuracy_render.h"
#include "bench/src/bench_commands.h"
#include "bench/src/bench_scene.h"
#include "bench/src/scene_file_facts.h"
#include "render/renderer.h"
#include "scene/demo_scene.h"
#include "scene/gltf_export.h"

namespace rp::bench {

using app::CommonOptions;
using app::FileScene;
using app::InterruptGuard;
using app::default_truth_cache_dir;
using app::ensure_directory;
using app::interrupted_exit_code;
using app::open_scene_file;
using app::write_text_atomic;

namespace {

// The regions whose surfaces are coated in the demo (the floor, the tumblers): the specular
// component's rows.
constexpr Region kCoatedRegions[] = {Region::kImage, Region::kFloorLit, Region::kFloorShadow,
                                     Region::kTumblerLit, Region::kTumblerShadowed};

nlohmann::json rgb_json(const IncomingLight& in) {
  return {{"rgb", {in.rgb[0], in.rgb[1], in.rgb[2]}}, {"r_minus_b", in.r_minus_b()}};
}

// One mode against one truth.
nlohmann::json compare(const Images& rp, const Images& truth, const std::vector<uint16_t>& labels) {
  nlohmann::json j;
  j["final_psnr_db"] = tone_mapped_psnr(rp.combined, truth.combined);
  j["direct"] = stats_json(compare_region(rp.direct, truth.direct, labels, Region::kImage));
  nlohmann::json regions;
  for (size_t r = 0; r < kDemoRegionCount; ++r)
    regions[region_name(Region(r))] =
        stats_json(compare_region(rp.indirect, truth.indirect, labels, Region(r)));
  j["indirect"] = regions;
  for (Region r : kCoatedRegions)
    j["specular"][region_name(r)] =
        stats_json(compare_region(rp.specular, truth.specular, labels, r));
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


}  // namespace

std::string export_demo_at_rest(const CommonOptions& common, const std::string& out_dir) {
  ensure_directory(out_dir);
  const std::string path =
      (std::filesystem::path(out_dir) / (common.open_demo ? "demo_open.glb" : "demo.glb"))
          .string();
  const scene::SceneAssets assets = app::load_demo_assets(common);
  scene::ExportOptions exporting;
  exporting.volume = scene::Bounds{glm::vec3(-1.0f), glm::vec3(1.0f)};  // the demo's GI volume
  scene::export_gltf(assets, scene::make_demo_frame(assets, 0), path, exporting);
  return path;
}

AccuracyResult measure_accuracy(const CommonOptions& common, const AccuracyOptions& options) {
  const uint32_t w = options.width, h = options.height;
  const scene::SceneAssets assets = app::load_demo_assets(common);
  const scene::FrameScene frame = scene::make_demo_frame(assets, 0);
  const std::filesystem::path cache =
      options.cache_dir.empty() ? default_truth_cache_dir() : options.cache_dir;
  ensure_directory(options.out_dir);  // before the long renders

  truth::PathTracer tracer(assets);
  const std::vector<uint16_t> labels = classify_regions(tracer.primary_hits(frame, w, h), w, h);
  nlohmann::json j;
  j["schema"] = "rolypoly-accuracy/4";
  j["command"] = options.command_line;
  j["gi_volume"] = name_of(common.render.gi_volume);
  j["scene"] = "demo frame at rest (scene::make_demo_frame)";
  j["width"] = w;
  j["height"] = h;

  // Truths at one gather and at many: truths[0] "one", truths[1] "many".
  const std::vector<Images> truths =
      truths_one_and_many(tracer, assets, frame, w, h, options.spp, options.many_bounces,
                          options.seed, cache, j["truth"]);
  const Images& truth_one = truths[0];
  const Images& truth_many = truths[1];
  for (const char* key : {"one", "many"})
    for (Region wall : {Region::kLeftWall, Region::kRightWall}) {
      const Images& t = key[0] == 'o' ? truth_one : truth_many;
      j["truth"][key]["incoming_indirect"][region_name(wall)] =
          rgb_json(incoming_indirect(t.indirect, t.albedo, labels, wall));
    }
  // How much of the light one bounce leaves out.
  j["truth"]["one"]["indirect_vs_many"] =
      stats_json(compare_region(truth_one.indirect, truth_many.indirect, labels, Region::kImage));

  // The four configurations, each against the truth at its bounce count, then the TAA render.
  std::vector<Images> rendered;
  std::vector<uint8_t> rgba;
  for (const AccuracyConfig& c : kAccuracyConfigs) {
    const uint32_t bounces = c.many ? options.many_bounces : 1u;
    const uint32_t frames = c.quality == render::Quality::kFast ? options.converge_frames
                            : c.many                            ? options.reference_many_frames
                                                                : 1u;
    rendered.push_back(render_mode(common, c.key, c.quality, bounces, false, w, h, frames, rgba));
    nlohmann::json m = compare(rendered.back(), c.many ? truth_many : truth_one, labels);
    m["quality"] = name_of(c.quality);
    m["bounces"] = bounces;
    m["frames"] = frames;
    m["taa"] = false;
    m["truth"] = c.many ? "many" : "one";
    j["configurations"][c.key] = m;
  }
  const std::vector<uint8_t> taa_rgba =
      render_finished_frames(common, options.many_bounces, w, h, options.converge_frames,
                             truth_many.combined, j["configurations"]);
  for (size_t r = 0; r < kDemoRegionCount; ++r) {
    uint64_t n = 0;
    for (uint16_t l : labels) n += (l >> r) & 1u;
    j["region_pixels"][region_name(Region(r))] = n;
  }
  j["images"] = write_accuracy_pictures(options.out_dir, w, h, truths, rendered, labels,
                                        taa_rgba, options.many_bounces);
  const std::string n = std::to_string(options.many_bounces);

  // The direct-light section, on its own frame with marbles.
  DirectOptions dopt;
  dopt.width = w;
  dopt.height = h;
  dopt.spp = options.spp * options.direct_spp_factor;
  dopt.seed = options.seed;
  dopt.jitter_frames = options.direct_jitter_frames;
  dopt.cache_dir = cache;
  dopt.out_dir = options.out_dir;
  const DirectResult direct = measure_direct(common, assets, tracer, dopt);
  j["direct"] = direct.json;

  // The marble section, on its own frame, only when asked (--marbles).
  MarbleResult marbles;
  if (options.marbles) {
    MarbleOptions mopt;
    mopt.width = w;
    mopt.height = h;
    mopt.spp = options.spp;
    mopt.bounces = options.many_bounces;
    mopt.converge_frames = options.converge_frames;
    mopt.reference_frames = options.reference_many_frames;
    mopt.seed = options.seed;
    mopt.cache_dir = cache;
    mopt.out_dir = options.out_dir;
    marbles = measure_marbles(common, assets, tracer, mopt);
    j["marbles"] = marbles.json;
  }

  // Thresholds, each on the fast mode (the default) against the truth at its bounce count.
  AccuracyResult result;
  std::ostringstream checks;
  auto check = [&](const char* name, double limit, double value, bool ok, const char* what,
                   nlohmann::json extra = nlohmann::json::object()) {
    extra["limit"] = limit;
    extra["value"] = value;  // NaN (no pixels to measure) is written as null and misses
    extra["passed"] = ok;
    extra["measures"] = what;
    j["thresholds"][name] = extra;
    result.passed = result.passed && ok;
    char b[256];
    std::snprintf(b, sizeof b, "threshold %-22s %s: %.4g, limit %.4g: %s\n", name, what, value,
                  limit, ok ? "met" : "MISSED");
    checks << b;
  };
  const nlohmann::json& cfg = j["configurations"];
  auto number = [](const nlohmann::json& v) { return v.is_number() ? v.get<double>() : NAN; };
  if (options.max_indirect_l1) {
    const double v = number(cfg["fast_many"]["indirect"]["image"]["rel_l1"]);
    check("max_indirect_l1", *options.max_indirect_l1, v, v <= *options.max_indirect_l1,
          "fast/N indirect relative L1 (image)");
  }
  if (options.max_indirect_bias) {
    const double v = std::abs(number(cfg["fast_many"]["indirect"]["image"]["bias"]));
    check("max_indirect_bias", *options.max_indirect_bias, v, v <= *options.max_indirect_bias,
          "fast/N |indirect bias| (image)");
  }
  if (options.max_region_bias) {
    // The worst named region; a region without pixels at this size has no figure and is skipped.
    double worst = NAN;
    std::string where;
    for (size_t r = 1; r < kDemoRegionCount; ++r) {
      const double v = std::abs(number(cfg["fast_many"]["indirect"][region_name(Region(r))]["bias"]));
      if (std::isfinite(v) && !(v <= worst)) {
        worst = v;
        where = region_name(Region(r));
      }
    }
    check("max_region_bias", *options.max_region_bias, worst, worst <= *options.max_region_bias,
          "fast/N |indirect bias| (worst named region)", {{"region", where}});
  }
  if (options.max_indirect_l1_single) {
    const double v = number(cfg["fast_one"]["indirect"]["image"]["rel_l1"]);
    check("max_indirect_l1_single", *options.max_indirect_l1_single, v,
          v <= *options.max_indirect_l1_single, "fast/1 indirect relative L1 (image)");
  }
  if (options.min_psnr_taa) {
    const double v = cfg[kTaaConfigKey]["final_psnr_db"].get<double>();
    check("min_psnr_taa", *options.min_psnr_taa, v, v >= *options.min_psnr_taa,
          "final PSNR with TAA, fast/N (dB)");
  }
  if (options.max_first_frame_gap) {
    const double v = cfg[kFirstFrameConfigKey]["gap_to_taa_db"].get<double>();
    check("max_first_frame_gap", *options.max_first_frame_gap, v,
          v <= *options.max_first_frame_gap,
          "final PSNR with TAA minus the first frame's, fast/N (dB)");
  }
  if (options.require_wall_hue) {
    nlohmann::json walls;
    int matched = 0;
    for (const char* wall : {"left_wall", "right_wall"})
      for (const char* key : {"fast_many", "fast_one"}) {
        const bool same = cfg[key]["incoming_indirect"][wall]["same_hue_sign_as_truth"].get<bool>();
        walls[wall][key] = same;
        matched += same ? 1 : 0;
      }
    check("require_wall_hue", 4, matched, matched == 4,
          "side-wall sign(R - B) as the truth's (of 4)", {{"walls", walls}});
  }
  {  // the direct section's, on the default shadow mode
    const nlohmann::json& dm = j["direct"]["modes"][j["direct"]["default_shadows"].get<std::string>()];
    const std::string mode = "fast, shadows " + j["direct"]["default_shadows"].get<std::string>();
    if (options.min_direct_psnr_floor) {
      const double v = number(dm["direct_psnr_db"]["floor"]);
      check("min_direct_psnr_floor", *options.min_direct_psnr_floor, v,
            v >= *options.min_direct_psnr_floor, "direct PSNR on the floor (dB)",
            {{"shadows", mode}});
    }
    if (options.max_penumbra_error) {
      const double a = number(dm["penumbra"]["tumbler"]["error"]);
      const double b = number(dm["penumbra"]["marble"]["error"]);
      const double v = std::isfinite(a) && std::isfinite(b) ? std::max(a, b) : NAN;
      check("max_penumbra_error", *options.max_penumbra_error, v,
            v <= *options.max_penumbra_error, "penumbra width |rt / truth - 1|, worst",
            {{"shadows", mode}, {"tumbler", a}, {"marble", b}});
    }
    if (options.min_albedo_psnr) {
      const double v = number(dm["albedo_psnr_db"]["image"]);
      check("min_albedo_psnr", *options.min_albedo_psnr, v, v >= *options.min_albedo_psnr,
            "albedo view PSNR (dB), image", {{"texture_filter", j["direct"]["texture_filter"]}});
    }
  }
  j["passed"] = result.passed;

  // The printed table.
  std::ostringstream t;
  char line[256];
  std::snprintf(line, sizeof line, "accuracy at %ux%u, demo frame at rest; truth %u spp, seed %llu\n",
                w, h, options.spp, static_cast<unsigned long long>(options.seed));
  t << line;
  t << truth_lines(j["truth"]);
  t << "  the 1-bounce truth's indirect light against " << n << " bounces: bias"
    << percent_cell(number(j["truth"]["one"]["indirect_vs_many"]["bias"]), true) << "\n";
  t << config_table_head(32, n);
  auto row = [&](const std::string& label, auto get) {
    std::snprintf(line, sizeof line, "%-32s", label.c_str());
    t << line;
    for (const AccuracyConfig& c : kAccuracyConfigs) t << ' ' << get(cfg[c.key]);
    t << '\n';
  };
  auto db = [](double v) {
    char b[16];
    std::snprintf(b, sizeof b, "%8.2f", v);
    return std::string(b);
  };
  row("final PSNR (dB)", [&](const nlohmann::json& m) { return db(number(m["final_psnr_db"])); });
  std::snprintf(line, sizeof line, "%-32s %s %8s %8s %8s\n", "final PSNR, TAA (dB)",
                db(cfg[kTaaConfigKey]["final_psnr_db"].get<double>()).c_str(), "-", "-", "-");
  t << line;
  std::snprintf(line, sizeof line, "%-32s %s %8s %8s %8s\n", "final PSNR, first frame (dB)",
                db(cfg[kFirstFrameConfigKey]["final_psnr_db"].get<double>()).c_str(), "-", "-",
                "-");
  t << line;
  row("direct bias", [&](const nlohmann::json& m) {
    return percent_cell(number(m["direct"]["bias"]), true);
  });
  for (const char* what : {"rel_l1", "bias"})
    for (size_t r = 0; r < kDemoRegionCount; ++r) {
      const std::string name = region_name(Region(r));
      row(std::string("indirect ") + (what[0] == 'r' ? "L1 " : "bias ") + name,
          [&](const nlohmann::json& m) {
            return percent_cell(number(m["indirect"][name][what]), what[0] == 'b');
          });
    }
  for (const char* what : {"rel_l1", "bias"})
    for (Region r : kCoatedRegions) {
      const std::string name = region_name(r);
      row(std::string("specular ") + (what[0] == 'r' ? "L1 " : "bias ") + name,
          [&](const nlohmann::json& m) {
            return percent_cell(number(m["specular"][name][what]), what[0] == 'b');
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
    put("fast N", cfg["fast_many"]["incoming_indirect"][wall]);
    put("fast 1", cfg["fast_one"]["incoming_indirect"][wall]);
    put("reference N", cfg["reference_many"]["incoming_indirect"][wall]);
    auto yes = [&](const char* key) {
      return cfg[key]["incoming_indirect"][wall]["same_hue_sign_as_truth"].get<bool>() ? "yes"
                                                                                       : "NO";
    };
    std::snprintf(line, sizeof line,
                  "  %-10s sign of R - B: fast N as truth N %s, fast 1 as truth 1 %s\n", wall,
                  yes("fast_many"), yes("fast_one"));
    t << line;
  }
  const nlohmann::json& images = j["images"];
  t << "wrote " << images["side_by_side"].get<std::string>() << ", "
    << images["heat_map"].get<std::string>() << " and " << images["final_taa"].get<std::string>()
    << "\n"
    << direct.table << marbles.table << checks.str();
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
  o.max_region_bias = options.max_region_bias;
  o.max_indirect_l1_single = options.max_indirect_l1_single;
  o.min_psnr_taa = options.min_psnr_taa;
  o.max_first_frame_gap = options.max_first_frame_gap;
  o.require_wall_hue = options.require_wall_hue;
  o.truth_noise = options.truth_noise;
  o.min_direct_psnr_floor = options.min_direct_psnr_floor;
  o.max_penumbra_error = options.max_penumbra_error;
  o.min_albedo_psnr = options.min_albedo_psnr;
  o.marbles = options.sim.marbles;
  o.command_line = options.command_line;
  AccuracyResult r;
  try {
    if (is_bench_scene_file(options.scene)) {
      // The scene file first: a malformed one fails before anything is traced.
      const FileScene file = open_scene_file(options.scene);
      r = measure_file_accuracy(common, file, scene_file_facts(file), o);
    } else if (common.open_demo && common.sky.given()) {
      // The half-open demo under a sky: its frame at rest, exported as glTF into the report's
      // folder, measured as a scene file (one region per material; the truth sees the sky).
      const FileScene file = open_scene_file(export_demo_at_rest(common, o.out_dir));
      r = measure_file_accuracy(common, file, scene_file_facts(file), o);
    } else {
      r = measure_accuracy(common, o);
    }
  } catch (const truth::PathTracer::Cancelled&) {
    std::fprintf(stderr,
                 "rolypoly: error: interrupted; no report was written (finished truths stay in "
                 "the cache)\n");
    return interrupted_exit_code();
  }
  std::fputs(r.table.c_str(), stdout);
  if (!options.json.empty()) std::printf("wrote %s\n", options.json.c_str());
  return r.passed ? 0 : 3;
}

}  // namespace rp::bench
