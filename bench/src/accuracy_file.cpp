// `bench --accuracy --scene FILE` (see accuracy_file.h).
#include "bench/src/accuracy_file.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <utility>
#include <vector>

#include "app/host_tone_map.h"
#include "app/png_output.h"
#include "app/sky_input.h"
#include "app/truth_cache.h"
#include "bench/src/accuracy_materials.h"
#include "bench/src/accuracy_metrics.h"
#include "bench/src/accuracy_render.h"
#include "bench/src/scene_file_facts.h"
#include "render/renderer.h"
#include "shading/spherical_harmonics.h"

namespace rp::bench {

using app::CommonOptions;
using app::FileFrameSource;
using app::FileScene;
using app::SkyLight;
using app::add_sky;
using app::default_truth_cache_dir;
using app::describe_sky;
using app::ensure_directory;
using app::load_sky;
using app::encode_rgba8;
using app::write_png_atomic;
using app::write_text_atomic;

namespace {

// The regions' labels, built once: the whole image, then each material the camera sees.
struct Regions {
  MaterialPixels pixels;
  std::vector<std::string> names;     // per material (material_region_names)
  std::vector<uint16_t> image;        // material_labels(kNoMaterial)
  std::vector<uint32_t> seen;         // materials with pixels, ascending
  std::vector<std::vector<uint16_t>> labels;  // per entry of `seen`
};

Regions make_regions(truth::PathTracer& tracer, const scene::FrameScene& frame,
                     const scene::SceneAssets& assets, uint32_t w, uint32_t h) {
  Regions r;
  r.pixels = classify_materials(tracer.primary_hits(frame, w, h), w, h, assets.materials.size());
  r.names = material_region_names(assets.materials);
  r.image = material_labels(r.pixels, kNoMaterial);
  for (uint32_t m = 0; m < r.pixels.counts.size(); ++m)
    if (r.pixels.counts[m] > 0) {
      r.seen.push_back(m);
      r.labels.push_back(material_labels(r.pixels, m));
    }
  return r;
}

bool coated(const scene::Material& m) { return m.specular.metal || m.specular.f0 > 0.0f; }

nlohmann::json no_pixels() { return {{"rel_l1", nullptr}, {"bias", nullptr}, {"pixels", 0}}; }

// One mode against one truth, over the image and every material (null figures for a material
// the camera does not see).
nlohmann::json compare(const Images& rp, const Images& truth, const Regions& regions,
                       const scene::SceneAssets& assets) {
  nlohmann::json j;
  const std::string image = region_name(Region::kImage);
  j["final_psnr_db"] = tone_mapped_psnr(rp.combined, truth.combined);
  j["albedo_psnr_db"] = srgb_psnr(rp.albedo, truth.albedo, regions.pixels.covered);
  j["direct"] = stats_json(compare_region(rp.direct, truth.direct, regions.image, Region::kImage));
  j["direct_psnr_db"][image] =
      masked_tone_mapped_psnr(rp.direct, truth.direct, regions.pixels.covered);
  j["direct_by_region"][image] = j["direct"];
  j["indirect"][image] =
      stats_json(compare_region(rp.indirect, truth.indirect, regions.image, Region::kImage));
  j["specular"][image] =
      stats_json(compare_region(rp.specular, truth.specular, regions.image, Region::kImage));
  const LeakStats leaks = leaks_and_misses(rp.indirect, truth.indirect, regions.image);
  j["leaks"] = {{"leak_pixels", leaks.leak_pixels},
                {"missing_pixels", leaks.missing_pixels},
                {"covered_pixels", leaks.covered_pixels},
                {"epsilon", leaks.epsilon}};
  for (size_t m = 0; m < assets.materials.size(); ++m) {
    const std::string& name = regions.names[m];
    j["indirect"][name] = no_pixels();
    j["direct_psnr_db"][name] = nullptr;
    j["direct_by_region"][name] = no_pixels();
    if (coated(assets.materials[m])) j["specular"][name] = no_pixels();
  }
  for (size_t k = 0; k < regions.seen.size(); ++k) {
    const uint32_t m = regions.seen[k];
    const std::string& name = regions.names[m];
    const std::vector<uint16_t>& labels = regions.labels[k];
    j["indirect"][name] =
        stats_json(compare_region(rp.indirect, truth.indirect, labels, kMaterialRegion));
    j["direct_psnr_db"][name] = masked_tone_mapped_psnr(rp.direct, truth.direct,
                                                        material_mask(regions.pixels, m));
    j["direct_by_region"][name] =
        stats_json(compare_region(rp.direct, truth.direct, labels, kMaterialRegion));
    if (coated(assets.materials[m]))
      j["specular"][name] =
          stats_json(compare_region(rp.specular, truth.specular, labels, kMaterialRegion));
    const LeakStats l = leaks_and_misses(rp.indirect, truth.indirect, labels, kMaterialRegion);
    j["leaks"]["regions"][name] = {{"leak_pixels", l.leak_pixels},
                                   {"missing_pixels", l.missing_pixels},
                                   {"covered_pixels", l.covered_pixels}};
  }
  return j;
}

}  // namespace

AccuracyResult measure_file_accuracy(const CommonOptions& common, const FileScene& file,
                                     const SceneFileFacts& facts, const AccuracyOptions& options) {
  if (options.require_wall_hue || options.min_direct_psnr_floor || options.max_penumbra_error ||
      options.marbles)
    throw std::invalid_argument(
        "the side-wall hue, the direct-light section's thresholds and the marble section "
        "measure the demo's box, not a scene file");
  const uint32_t w = options.width, h = options.height;
  const scene::SceneAssets& assets = file.loaded.assets;
  // The still frame, numbered as the renders count (TAA's jitter and the fast mode's
  // interleaving rotate with frame_index); the camera never moves, so no velocity.
  const FrameFn frame_fn = [&file](const scene::SceneAssets&, uint32_t index) {
    FileFrameSource source(file);
    scene::FrameScene frame = source.next();
    frame.frame_index = index;
    return frame;
  };
  // The truth's frame carries the options' sky; the real-time renders get it from their
  // RenderSession (app/render_session.h), so frame_fn stays without it.
  scene::FrameScene frame = frame_fn(assets, 0);
  SkyLight sky = load_sky(common.sky);  // add_sky may put suns back into the map
  add_sky(sky, frame);
  const std::filesystem::path cache =
      (options.cache_dir.empty() ? default_truth_cache_dir() : options.cache_dir) /
      ("scene-" + facts.content_hash);
  ensure_directory(options.out_dir);  // before the long renders

  truth::PathTracer tracer(assets);
  const Regions regions = make_regions(tracer, frame, assets, w, h);
  nlohmann::json j;
  j["schema"] = "rolypoly-accuracy-file/1";
  j["command"] = options.command_line;
  j["gi_volume"] = name_of(common.render.gi_volume);
  j["scene"] = scene_file_json<nlohmann::json>(facts);
  if (const std::string line = describe_sky(common.sky, sky); !line.empty()) j["sky"] = line;
  if (sky.environment.enabled()) {
    // how the real-time modes take the sky's diffuse light, and the floor of PRT on the map
    const truth::PrtSettings& prt = common.sky.prt_settings;
    j["sky_light"] =
        common.sky.prt
            ? "prt, " + std::to_string(prt.bands * prt.bands) + " coefficients, " +
                  std::string(name_of(prt.kind)) +
                  (prt.kind == truth::PrtKind::kInterreflected
                       ? " (" + std::to_string(prt.bounces) + " bounces)"
                       : std::string()) +
                  ", " + std::to_string(prt.samples) + " directions"
            : "cones";
    // the map the real-time modes gather: without its suns, which are directional lights
    scene::Environment gathered = sky.environment;
    gathered.map = sky.environment.gathered_map();
    gathered.residual = nullptr;
    for (const int bands : {3, 5})
      j["sky_sh_irradiance_error"][std::to_string(bands * bands)] =
          shading::sh_irradiance_error(gathered, bands);
    j["sky_suns"] = nlohmann::json::array();
    for (const scene::EnvironmentSun& sun : sky.map_suns)
      j["sky_suns"].push_back({{"share", sun.share},
                               {"solid_angle_sr", sun.solid_angle},
                               {"irradiance", {sun.irradiance.x, sun.irradiance.y,
                                               sun.irradiance.z}}});
  }
  j["width"] = w;
  j["height"] = h;
  j["many_bounces"] = options.many_bounces;
  j["truth_spp"] = options.spp;
  j["truth_seed"] = options.seed;
  uint64_t covered = 0;
  for (uint8_t c : regions.pixels.covered) covered += c;
  j["region_pixels"][region_name(Region::kImage)] = covered;
  j["materials"] = nlohmann::json::array();
  for (size_t m = 0; m < assets.materials.size(); ++m) {
    const scene::Material& mat = assets.materials[m];
    j["region_pixels"][regions.names[m]] = regions.pixels.counts[m];
    j["materials"].push_back({{"index", m},
                              {"name", mat.name},
                              {"region", regions.names[m]},
                              {"pixels", regions.pixels.counts[m]},
                              {"emissive", mat.emission != glm::vec3(0.0f)},
                              {"coated", coated(mat)}});
  }

  // Truths at one gather and at many: truths[0] "one", truths[1] "many".
  const std::vector<Images> truths =
      truths_one_and_many(tracer, assets, frame, w, h, options.spp, options.many_bounces,
                          options.seed, cache, j["truth"]);
  j["truth"]["one"]["indirect_vs_many"] = stats_json(
      compare_region(truths[0].indirect, truths[1].indirect, regions.image, Region::kImage));
  if (options.truth_noise) {
    // The many-bounce truth again with the next seed: the indirect light's L1 between the two
    // is the yardstick's own noise (twice its variance), in every L1 below.
    const std::vector<Images> second =
        truths_one_and_many(tracer, assets, frame, w, h, options.spp, options.many_bounces,
                            options.seed + 1, cache, j["truth"]["noise"]["truths"], false);
    nlohmann::json& noise = j["truth"]["noise"];
    noise["seeds"] = {options.seed, options.seed + 1};
    noise["indirect"][region_name(Region::kImage)] = stats_json(
        compare_region(second[0].indirect, truths[1].indirect, regions.image, Region::kImage));
    for (size_t k = 0; k < regions.seen.size(); ++k)
      noise["indirect"][regions.names[regions.seen[k]]] = stats_json(compare_region(
          second[0].indirect, truths[1].indirect, regions.labels[k], kMaterialRegion));
  }

  std::vector<Images> rendered;
  std::vector<uint8_t> rgba;
  for (const AccuracyConfig& c : kAccuracyConfigs) {
    const uint32_t bounces = c.many ? options.many_bounces : 1u;
    const uint32_t frames = c.quality == render::Quality::kFast ? options.converge_frames
                            : c.many                            ? options.reference_many_frames
                                                                : 1u;
    rendered.push_back(render_mode(common, c.key, c.quality, bounces, false, w, h, frames, rgba,
                                   frame_fn, &assets));
    nlohmann::json m = compare(rendered.back(), truths[c.many ? 1 : 0], regions, assets);
    m["quality"] = name_of(c.quality);
    m["bounces"] = bounces;
    m["frames"] = frames;
    m["taa"] = false;
    m["truth"] = c.many ? "many" : "one";
    j["configurations"][c.key] = m;
  }
  std::filesystem::path direct_png;
  // The fast mode's light averaged over one cycle of TAA's jitter: the error of the light
  // itself, without the single unjittered frame's aliasing (which dominates the direct PSNR of
  // a detailed scene at a small size) or TAA's clamp.
  {
    const Images avg = render_jittered_average(common, kJitteredConfigKey, options.many_bounces,
                                               w, h, std::max(options.converge_frames, 16u), 16,
                                               frame_fn, &assets);
    nlohmann::json m = compare(avg, truths[1], regions, assets);
    m["quality"] = "fast";
    m["bounces"] = options.many_bounces;
    m["frames"] = std::max(options.converge_frames, 16u);
    m["averaged_frames"] = 16;
    m["taa"] = false;
    m["jitter"] = true;
    m["truth"] = "many";
    j["configurations"][kJitteredConfigKey] = m;
    // truth's direct light, the averaged one, and their signed difference
    std::vector<std::vector<uint8_t>> tiles(3);
    encode_rgba8(truths[1].direct, true, tiles[0]);
    encode_rgba8(avg.direct, true, tiles[1]);
    const double eps = leaks_and_misses(avg.direct, truths[1].direct, regions.image).epsilon;
    signed_heat_map(avg.direct, truths[1].direct, regions.image, eps, tiles[2]);
    direct_png = options.out_dir / "accuracy_direct_jittered.png";
    write_png_atomic(direct_png, int(w * 3), int(h), tile_rgba8(tiles, w, h, 3));
  }
  const std::vector<uint8_t> taa_rgba =
      render_finished_frames(common, options.many_bounces, w, h, options.converge_frames,
                             truths[1].combined, j["configurations"], frame_fn, &assets);
  j["images"] = write_accuracy_pictures(options.out_dir, w, h, truths, rendered, regions.image, taa_rgba,
                               options.many_bounces);
  j["images"]["direct_jittered"] = direct_png.string();
  j["images"]["direct_jittered_layout"] =
      "the truth's direct light, the fast mode's averaged over TAA's jitter, (rp - truth) / "
      "(truth + eps) of their luminance: blue -1 (too dark), white 0, red +1 (too bright)";

  AccuracyResult result;
  const std::string checks = check_file_thresholds(options, j, result.passed);
  result.table = file_accuracy_table(j) + checks;
  result.json = j;
  if (!options.json_path.empty()) write_text_atomic(options.json_path, j.dump(2) + "\n");
  return result;
}

}  // namespace rp::bench
