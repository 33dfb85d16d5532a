// The thresholds and the printed table of a scene file's accuracy report (accuracy_file.h),
// read from its JSON so that what is printed is what is written.
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "bench/src/accuracy_file.h"
#include "bench/src/accuracy_metrics.h"
#include "bench/src/accuracy_render.h"

namespace rp::bench {
namespace {

// Material names can be long: the table's label column keeps their first characters.
std::string short_name(const std::string& name) {
  constexpr size_t kMax = 18;
  return name.size() <= kMax ? name : name.substr(0, kMax - 2) + "..";
}

// The fast mode's light averaged over TAA's jitter cycle (kJitteredConfigKey): one line for
// the image, one per seen material.
std::string jittered_lines(const nlohmann::json& j, const nlohmann::json& m) {
  std::ostringstream t;
  char line[200];
  std::snprintf(line, sizeof line,
                "\nfast/N, its light averaged over TAA's %u jitter positions (no history clamp: "
                "the light's\nerror without a single frame's aliasing), against the %u-bounce "
                "truth:\n",
                m["averaged_frames"].get<uint32_t>(), j["many_bounces"].get<uint32_t>());
  t << line;
  std::snprintf(line, sizeof line, "  final PSNR %.2f dB, albedo PSNR %.2f dB\n",
                json_number(m["final_psnr_db"]), json_number(m["albedo_psnr_db"]));
  t << line;
  std::snprintf(line, sizeof line, "  %-20s %10s %11s %11s %13s\n", "region",
                "direct dB", "direct bias", "indirect L1", "indirect bias");
  t << line;
  auto region_line = [&](const std::string& r) {
    std::snprintf(line, sizeof line, "  %-20s   %s    %s    %s      %s\n",
                  short_name(r).c_str(), db_cell(json_number(m["direct_psnr_db"][r])).c_str(),
                  percent_cell(json_number(m["direct_by_region"][r]["bias"]), true).c_str(),
                  percent_cell(json_number(m["indirect"][r]["rel_l1"]), false).c_str(),
                  percent_cell(json_number(m["indirect"][r]["bias"]), true).c_str());
    t << line;
  };
  region_line("image");
  for (const nlohmann::json& mat : j["materials"])
    if (mat["pixels"].get<uint64_t>() > 0) region_line(mat["region"].get<std::string>());
  return t.str();
}

}  // namespace

std::string check_file_thresholds(const AccuracyOptions& options, nlohmann::json& j,
                                  bool& passed) {
  passed = true;
  std::ostringstream lines;
  auto check = [&](const char* name, double limit, double value, bool ok, const char* what,
                   nlohmann::json extra = nlohmann::json::object()) {
    extra["limit"] = limit;
    extra["value"] = value;  // NaN (no pixels to measure) is written as null and misses
    extra["passed"] = ok;
    extra["measures"] = what;
    j["thresholds"][name] = extra;
    passed = passed && ok;
    char b[256];
    std::snprintf(b, sizeof b, "threshold %-22s %s: %.4g, limit %.4g: %s\n", name, what, value,
                  limit, ok ? "met" : "MISSED");
    lines << b;
  };
  const nlohmann::json& cfg = j["configurations"];
  const nlohmann::json& fast = cfg["fast_many"];
  if (options.max_indirect_l1) {
    const double v = json_number(fast["indirect"]["image"]["rel_l1"]);
    check("max_indirect_l1", *options.max_indirect_l1, v, v <= *options.max_indirect_l1,
          "fast/N indirect relative L1 (image)");
  }
  if (options.max_indirect_bias) {
    const double v = std::abs(json_number(fast["indirect"]["image"]["bias"]));
    check("max_indirect_bias", *options.max_indirect_bias, v, v <= *options.max_indirect_bias,
          "fast/N |indirect bias| (image)");
  }
  if (options.max_region_bias) {
    // The worst material; one without pixels (or light) at this size has no figure.
    double worst = NAN;
    std::string where;
    for (const nlohmann::json& m : j["materials"]) {
      const std::string region = m["region"].get<std::string>();
      const double v = std::abs(json_number(fast["indirect"][region]["bias"]));
      if (std::isfinite(v) && !(v <= worst)) {
        worst = v;
        where = region;
      }
    }
    check("max_region_bias", *options.max_region_bias, worst, worst <= *options.max_region_bias,
          "fast/N |indirect bias| (worst material)", {{"region", where}});
  }
  if (options.max_indirect_l1_single) {
    const double v = json_number(cfg["fast_one"]["indirect"]["image"]["rel_l1"]);
    check("max_indirect_l1_single", *options.max_indirect_l1_single, v,
          v <= *options.max_indirect_l1_single, "fast/1 indirect relative L1 (image)");
  }
  if (options.min_psnr_taa) {
    const double v = json_number(cfg[kTaaConfigKey]["final_psnr_db"]);
    check("min_psnr_taa", *options.min_psnr_taa, v, v >= *options.min_psnr_taa,
          "final PSNR with TAA, fast/N (dB)");
  }
  if (options.max_first_frame_gap) {
    const double v = json_number(cfg[kFirstFrameConfigKey]["gap_to_taa_db"]);
    check("max_first_frame_gap", *options.max_first_frame_gap, v,
          v <= *options.max_first_frame_gap,
          "final PSNR with TAA minus the first frame's, fast/N (dB)");
  }
  if (options.min_albedo_psnr) {
    // The fast mode without TAA draws unjittered: its albedo is the albedo view's.
    const double v = json_number(fast["albedo_psnr_db"]);
    check("min_albedo_psnr", *options.min_albedo_psnr, v, v >= *options.min_albedo_psnr,
          "albedo PSNR, fast/N (dB), image");
  }
  j["passed"] = passed;
  return lines.str();
}

std::string file_accuracy_table(const nlohmann::json& j) {
  std::ostringstream t;
  char line[512];
  const nlohmann::json& scene = j["scene"];
  std::snprintf(line, sizeof line,
                "accuracy at %ux%u, scene %s (%u triangles, %u materials, %u texture%s, %u "
                "light%s); truth %u spp, seed %llu\n",
                j["width"].get<uint32_t>(), j["height"].get<uint32_t>(),
                scene["path"].get<std::string>().c_str(), scene["triangles"].get<uint32_t>(),
                scene["materials"].get<uint32_t>(), scene["textures"].get<uint32_t>(),
                scene["textures"] == 1 ? "" : "s", scene["lights"].get<uint32_t>(),
                scene["lights"] == 1 ? "" : "s", j["truth_spp"].get<uint32_t>(),
                static_cast<unsigned long long>(j["truth_seed"].get<uint64_t>()));
  t << line;
  if (j.contains("sky_light")) {
    t << "  sky light: " << j["sky_light"].get<std::string>();
    if (j.contains("sky_sh_irradiance_error")) {
      char e[160];
      std::snprintf(e, sizeof e,
                    "; the map's SH irradiance error (PRT's floor): %.1f %% with 9 "
                    "coefficients, %.1f %% with 25",
                    100.0 * json_number(j["sky_sh_irradiance_error"]["9"]),
                    100.0 * json_number(j["sky_sh_irradiance_error"]["25"]));
      t << e;
    }
    t << "\n";
  }
  t << truth_lines(j["truth"]);
  const std::string n = std::to_string(j["many_bounces"].get<uint32_t>());
  t << "  the 1-bounce truth's indirect light against " << n << " bounces: bias"
    << percent_cell(json_number(j["truth"]["one"]["indirect_vs_many"]["bias"]), true) << "\n";
  if (j["truth"].contains("noise")) {
    const nlohmann::json& noise = j["truth"]["noise"];
    const nlohmann::json& second = noise["truths"]["many"];
    std::snprintf(line, sizeof line,
                  "  the truth's own noise: indirect L1 against the %u-bounce truth of seed %llu "
                  "(%.1f s%s):",
                  second["bounces"].get<uint32_t>(),
                  static_cast<unsigned long long>(second["seed"].get<uint64_t>()),
                  second["seconds"].get<double>(),
                  second["from_cache"].get<bool>() ? ", cached" : "");
    t << line;
    // the image first, then the regions (the JSON object's order: by name)
    const std::string image = region_name(Region::kImage);
    std::vector<std::string> names{image};
    for (const auto& [region, stats] : noise["indirect"].items())
      if (region != image && stats["pixels"].get<uint64_t>() > 0) names.push_back(region);
    for (size_t i = 0; i < names.size(); ++i) {
      std::snprintf(line, sizeof line, "%s %s %.1f %%", i == 0 ? "" : ",", names[i].c_str(),
                    100.0 * json_number(noise["indirect"][names[i]]["rel_l1"]));
      t << line;
    }
    t << "\n    (in every indirect L1 below; an exact image would read about 0.71 x it)\n";
  }
  t << "  regions: image (" << j["region_pixels"]["image"].get<uint64_t>() << " pixels)";
  std::string unseen;
  for (const nlohmann::json& m : j["materials"]) {
    const std::string region = m["region"].get<std::string>();
    if (m["pixels"].get<uint64_t>() == 0)
      unseen += (unseen.empty() ? "" : ", ") + region;
    else
      t << ", " << region << " (" << m["pixels"].get<uint64_t>() << ")";
  }
  t << "\n";
  if (!unseen.empty())
    t << "  materials not seen at this size (no figures): " << unseen << "\n";

  const nlohmann::json& cfg = j["configurations"];
  t << config_table_head(34, n);
  auto row = [&](const std::string& label, auto get) {
    std::snprintf(line, sizeof line, "%-34s", label.c_str());
    t << line;
    for (const AccuracyConfig& c : kAccuracyConfigs) t << ' ' << get(cfg[c.key]);
    t << '\n';
  };
  // The regions of a figure: the image first, then the seen materials (coated ones only for
  // the specular component).
  auto regions = [&](const char* component) {
    std::vector<std::string> out = {"image"};
    for (const nlohmann::json& m : j["materials"])
      if (m["pixels"].get<uint64_t>() > 0 &&
          cfg["fast_many"][component].contains(m["region"].get<std::string>()))
        out.push_back(m["region"].get<std::string>());
    return out;
  };
  row("final PSNR (dB)",
      [](const nlohmann::json& m) { return db_cell(json_number(m["final_psnr_db"])); });
  std::snprintf(line, sizeof line, "%-34s %s %8s %8s %8s\n", "final PSNR, TAA (dB)",
                db_cell(json_number(cfg[kTaaConfigKey]["final_psnr_db"])).c_str(), "-", "-",
                "-");
  t << line;
  std::snprintf(line, sizeof line, "%-34s %s %8s %8s %8s\n", "final PSNR, first frame (dB)",
                db_cell(json_number(cfg[kFirstFrameConfigKey]["final_psnr_db"])).c_str(), "-",
                "-", "-");
  t << line;
  row("albedo PSNR (dB)",
      [](const nlohmann::json& m) { return db_cell(json_number(m["albedo_psnr_db"])); });
  for (const std::string& r : regions("direct_psnr_db"))
    row("direct PSNR (dB) " + short_name(r), [&](const nlohmann::json& m) {
      return db_cell(json_number(m["direct_psnr_db"][r]));
    });
  row("direct bias image",
      [](const nlohmann::json& m) { return percent_cell(json_number(m["direct"]["bias"]), true); });
  for (const char* component : {"indirect", "specular"})
    for (const char* what : {"rel_l1", "bias"})
      for (const std::string& r : regions(component)) {
        const bool bias = what[0] == 'b';
        row(std::string(component) + (bias ? " bias " : " L1 ") + short_name(r),
            [&](const nlohmann::json& m) {
              return percent_cell(json_number(m[component][r][what]), bias);
            });
      }
  for (const char* what : {"leak_pixels", "missing_pixels"})
    row(std::string(what[0] == 'l' ? "leak" : "missing") + " pixels (indirect)",
        [&](const nlohmann::json& m) {
          char b[32];
          std::snprintf(b, sizeof b, "%8llu",
                        static_cast<unsigned long long>(m["leaks"][what].get<uint64_t>()));
          return std::string(b);
        });
  if (cfg.contains(kJitteredConfigKey)) t << jittered_lines(j, cfg[kJitteredConfigKey]);
  const nlohmann::json& images = j["images"];
  t << "wrote " << images["side_by_side"].get<std::string>() << ", "
    << images["heat_map"].get<std::string>() << ", " << images["final_taa"].get<std::string>();
  if (images.contains("direct_jittered"))
    t << " and " << images["direct_jittered"].get<std::string>();
  t << "\n";
  return t.str();
}

}  // namespace rp::bench
