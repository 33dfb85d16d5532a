// The marble section of `bench --accuracy --marbles` (see accuracy_marbles.h).
#include "bench/src/accuracy_marbles.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "app/host_tone_map.h"
#include "app/png_output.h"
#include "bench/src/accuracy_metrics.h"
#include "bench/src/accuracy_render.h"
#include "scene/demo_scene.h"
#include "scene/world.h"

namespace rp::bench {

using app::CachedTruth;
using app::CommonOptions;
using app::encode_rgba8;
using app::write_png_atomic;

namespace {

// Floor positions (x, z) of the marbles' contact points. The open floor in front of the
// tumblers (which stand at z <= 0.35, their short shadows under the overhead lamp falling on
// z < 0.45) and behind the bottom image edge (the floor is seen up to z = 0.97 from the default
// camera): three loose rows, 0.14-0.24 apart, so each marble's floor_by_marbles disc (radius
// 0.1) is mostly its own; one touching pair (0.08 apart: marble against marble); one marble
// against each front tumbler's foot (0.19 from the bottom sphere's centre line, the contact
// distance sqrt(0.24^2 - 0.16^2) = 0.179 plus a little: the tumbler mesh's chords).
constexpr glm::vec2 kSpots[kMarbleFrameCount] = {
    {-0.30f, 0.60f}, {-0.14f, 0.62f}, {0.16f, 0.60f}, {0.31f, 0.63f},                   // row 1
    {-0.40f, 0.75f}, {-0.22f, 0.76f}, {0.02f, 0.72f}, {0.10f, 0.72f},                   // row 2,
    {0.26f, 0.77f},  {0.42f, 0.74f},                                                    // a pair
    {-0.30f, 0.84f}, {-0.08f, 0.85f}, {0.14f, 0.84f}, {0.34f, 0.85f},                   // row 3
    {-0.455f, 0.515f}, {0.455f, 0.515f}};  // at the feet of the front tumblers (+-0.55, 0.35)

struct Config {
  const char* key;
  const char* column;
  render::Quality quality;
};
constexpr Config kConfigs[] = {{"fast_many", "fast/N", render::Quality::kFast},
                               {"reference_many", "ref/N", render::Quality::kReference}};

// The regions the table prints (the JSON has every region).
constexpr Region kTableRegions[] = {Region::kImage, Region::kMarble, Region::kFloorByMarbles,
                                    Region::kFloorLit, Region::kFloorShadow};

std::vector<uint8_t> region_mask(const std::vector<uint16_t>& labels, Region r) {
  std::vector<uint8_t> m(labels.size());
  for (size_t i = 0; i < labels.size(); ++i) m[i] = (labels[i] >> unsigned(r)) & 1u;
  return m;
}

double number(const nlohmann::json& v) { return v.is_number() ? v.get<double>() : NAN; }

}  // namespace

scene::FrameScene marble_frame(const scene::SceneAssets& assets, uint32_t frame_index) {
  scene::FrameScene frame = scene::make_demo_frame(assets, frame_index);
  const float r = scene::world_constants::kMarbleRadius;
  for (uint32_t i = 0; i < kMarbleFrameCount; ++i) {
    // Hues spread by the golden ratio, so neighbours differ.
    const double hue = 0.1 + 0.6180339887 * i;
    frame.spheres.push_back(scene::resting_marble(
        kSpots[i], r, scene::glass_colour(float(hue - std::floor(hue)))));
  }
  return frame;
}

MarbleResult measure_marbles(const CommonOptions& common, const scene::SceneAssets& assets,
                             truth::PathTracer& tracer, const MarbleOptions& o) {
  const uint32_t w = o.width, h = o.height;
  const scene::FrameScene frame = marble_frame(assets, 0);
  const std::vector<uint16_t> labels =
      classify_regions(tracer.primary_hits(frame, w, h), w, h, frame.spheres);
  nlohmann::json j;
  j["scene"] = "demo frame at rest + " + std::to_string(kMarbleFrameCount) +
               " marbles (r 0.04) resting on the floor (bench/src/accuracy_marbles.h)";
  j["marble_contact_radii"] = kMarbleContactRadii;

  truth::PathTraceSettings s;
  s.width = w;
  s.height = h;
  s.spp = o.spp;
  s.bounces = o.bounces;
  s.seed = o.seed;
  const CachedTruth ct = cached_truth_with_progress(
      tracer, assets, frame, s, o.cache_dir,
      "path tracing (marbles, " + std::to_string(o.bounces) + " bounces)");
  const Images truth = from_truth("truth_marbles", ct.image);
  j["truth"] = {{"bounces", s.bounces},     {"spp", s.spp},
                {"seed", s.seed},           {"seconds", ct.image.seconds},
                {"from_cache", ct.from_cache}, {"file", ct.file.string()}};
  for (size_t r = 0; r < kRegionCount; ++r) {
    uint64_t n = 0;
    for (uint16_t l : labels) n += (l >> r) & 1u;
    j["region_pixels"][region_name(Region(r))] = n;
  }

  std::vector<Images> rendered;
  std::vector<uint8_t> rgba;
  for (const Config& c : kConfigs) {
    const uint32_t frames =
        c.quality == render::Quality::kFast ? o.converge_frames : o.reference_frames;
    rendered.push_back(render_mode(common, std::string("marbles ") + c.key, c.quality, o.bounces,
                                   false, w, h, frames, rgba, marble_frame));
    const Images& rp = rendered.back();
    nlohmann::json m;
    m["frames"] = frames;
    m["final_psnr_db"] = tone_mapped_psnr(rp.combined, truth.combined);
    for (size_t r = 0; r < kRegionCount; ++r) {
      const Region region = Region(r);
      const ErrorStats e = compare_region(rp.indirect, truth.indirect, labels, region);
      m["indirect"][region_name(region)] = {
          {"rel_l1", e.rel_l1}, {"bias", e.bias}, {"pixels", e.pixels}};
      m["region_psnr_db"][region_name(region)] =
          masked_tone_mapped_psnr(rp.combined, truth.combined, region_mask(labels, region));
    }
    for (size_t r = 0; r < kRegionCount; ++r) {
      const LeakStats leaks = leaks_and_misses(rp.indirect, truth.indirect, labels, Region(r));
      m["leaks"][region_name(Region(r))] = {{"leak_pixels", leaks.leak_pixels},
                                            {"missing_pixels", leaks.missing_pixels},
                                            {"epsilon", leaks.epsilon}};
    }
    j["configurations"][c.key] = m;
  }

  // Pictures: truth, fast, reference (rows: combined, indirect); heat maps fast, reference.
  std::vector<std::vector<uint8_t>> tiles;
  const Images* order[] = {&truth, &rendered[0], &rendered[1]};
  for (int row = 0; row < 2; ++row)
    for (const Images* img : order) {
      tiles.emplace_back();
      encode_rgba8(row == 0 ? img->combined : img->indirect, true, tiles.back());
    }
  const std::filesystem::path side = o.out_dir / "accuracy_marbles_side_by_side.png";
  write_png_atomic(side, int(w * 3), int(h * 2), tile_rgba8(tiles, w, h, 3));
  tiles.clear();
  const double eps = leaks_and_misses(rendered[0].indirect, truth.indirect, labels).epsilon;
  for (const Images& rp : rendered) {
    tiles.emplace_back();
    signed_heat_map(rp.indirect, truth.indirect, labels, eps, tiles.back());
  }
  const std::filesystem::path heat = o.out_dir / "accuracy_marbles_heat.png";
  write_png_atomic(heat, int(w * 2), int(h), tile_rgba8(tiles, w, h, 2));
  j["images"] = {{"side_by_side", side.string()},
                 {"side_by_side_layout",
                  "columns: truth, fast, reference (all at " + std::to_string(o.bounces) +
                      " bounces); rows: final (combined radiance), indirect component; tone "
                      "mapped x/(1+x), sRGB"},
                 {"heat_map", heat.string()},
                 {"heat_map_layout", "fast, reference: (rp - truth) / (truth + eps) of indirect "
                                     "luminance: blue -1 (too dark), white 0, red +1"}};

  // The printed lines.
  std::string t;
  char line[256];
  std::snprintf(line, sizeof line,
                "\nmarbles: demo + %u marbles at rest, %ux%u; truth %u bounces, %u spp, %.1f s%s\n",
                kMarbleFrameCount, w, h, s.bounces, s.spp, ct.image.seconds,
                ct.from_cache ? " (from the cache)" : "");
  t += line;
  std::snprintf(line, sizeof line, "%-36s %8s %8s %8s\n", "(rolypoly vs truth)", "pixels",
                kConfigs[0].column, kConfigs[1].column);
  t += line;
  const nlohmann::json& cfg = j["configurations"];
  auto pct = [](double v, bool sign) {
    char b[32];
    if (!std::isfinite(v)) return std::string("     n/a");
    std::snprintf(b, sizeof b, sign ? "%+7.1f%%" : "%7.1f%%", v * 100.0);
    return std::string(b);
  };
  auto put = [&](const std::string& label, uint64_t pixels, const std::string& a,
                 const std::string& b) {
    std::snprintf(line, sizeof line, "%-36s %8llu %s %s\n", label.c_str(),
                  static_cast<unsigned long long>(pixels), a.c_str(), b.c_str());
    t += line;
  };
  auto db = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%8.2f", v);
    return std::string(b);
  };
  for (Region r : kTableRegions) {
    const std::string name = region_name(r);
    const uint64_t n = j["region_pixels"][name].get<uint64_t>();
    put("final PSNR (dB) " + name, n, db(number(cfg["fast_many"]["region_psnr_db"][name])),
        db(number(cfg["reference_many"]["region_psnr_db"][name])));
  }
  for (const char* what : {"rel_l1", "bias"})
    for (Region r : kTableRegions) {
      const std::string name = region_name(r);
      const bool sign = what[0] == 'b';
      put(std::string("indirect ") + (sign ? "bias " : "L1 ") + name,
          j["region_pixels"][name].get<uint64_t>(),
          pct(number(cfg["fast_many"]["indirect"][name][what]), sign),
          pct(number(cfg["reference_many"]["indirect"][name][what]), sign));
    }
  for (const char* what : {"leak_pixels", "missing_pixels"})
    for (Region r : kTableRegions) {
      const std::string name = region_name(r);
      auto count = [&](const char* key) {
        char b[32];
        std::snprintf(b, sizeof b, "%8llu",
                      static_cast<unsigned long long>(cfg[key]["leaks"][name][what].get<uint64_t>()));
        return std::string(b);
      };
      put(std::string(what[0] == 'l' ? "leak" : "missing") + " pixels " + name,
          j["region_pixels"][name].get<uint64_t>(), count("fast_many"), count("reference_many"));
    }
  t += "wrote " + side.string() + " and " + heat.string() + "\n";
  return {j, t};
}

}  // namespace rp::bench
