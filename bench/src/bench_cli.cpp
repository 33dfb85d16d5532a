#include "bench/src/bench_cli.h"

#include <cstdlib>
#include <optional>
#include <string>

#include "app/scene_input.h"
#include "render/renderer.h"

namespace rp::bench {

using app::add_bounces;
using app::add_common;
using app::add_simulation;
using app::add_size;
using app::add_sky_options;
using app::add_spp;
using app::decimal_in;
using app::pixel_count;
using app::whole_number;

BenchCli::BenchCli(CLI::App& app, app::CommonOptions& common, BenchOptions& options)
    : common_(common), options_(options) {
  CLI::App* bench = command_ = app.add_subcommand(
      "bench", "time every pass over many frames, on one or many devices, sizes and voxel "
               "resolutions");
  add_common(bench, common_, false, true);
  add_sky_options(bench, common_);
  add_spp(bench, common_);
  add_bounces(bench, common_);
  add_size(bench, size_);
  bench->add_option("--frames", options_.frames, "measured frames")
      ->capture_default_str()
      ->transform(whole_number(1, 1000000));
  bench->add_option("--warmup", options_.warmup, "frames rendered first, not measured")
      ->capture_default_str()
      ->transform(whole_number(0, 1000000));
  bench->add_option("--json", options_.json, "also write the results as JSON to this file");
  bench->add_flag("--compare-visibility", options_.compare_visibility,
                  "render the same frames with the compute rasterizer and with Embree and "
                  "compare the visibility cost side by side");
  bench->add_flag("--quality-report", options_.quality_report,
                  "measure how close the fast quality mode comes to the reference mode at the "
                  "bench size: PSNR on the static demo after TAA converged, per frame on the "
                  "busy animation, and the flicker of both");
  bench->add_flag("--accuracy", options_.accuracy,
                  "hold the fast and reference modes against the path-traced truth of the demo "
                  "frame or the --scene file's (cached on disk): each at 64 bounces against the "
                  "64-bounce truth and at --bounces 1 against the 1-bounce truth, plus the fast "
                  "mode's final image with TAA; PSNR, indirect L1 and bias per region (a file's: "
                  "per material), side-wall hue, leaks; default size 360, --spp 1024");
  bench->add_option("--out", options_.out_dir,
                    "--accuracy: folder for the side-by-side PNGs and the heat maps")
      ->capture_default_str();
  bench->add_option("--truth-cache", options_.truth_cache,
                    "--accuracy: folder of cached path-traced truths (default "
                    "$XDG_CACHE_HOME/rolypoly/truth or ~/.cache/rolypoly/truth)");
  // --accuracy's thresholds: exit 3 when one is missed. Fractions (0.15 = 15 %), PSNR in dB.
  auto threshold = [&](const char* name, std::optional<double>& value, const std::string& what) {
    bench->add_option_function<std::string>(
             name, [&value](const std::string& v) { value = std::strtod(v.c_str(), nullptr); },
             "--accuracy: exit 3 when " + what)
        ->check(decimal_in(0.0, 1000.0));
  };
  threshold("--max-indirect-l1", options_.max_indirect_l1,
            "the fast mode's indirect relative L1 over the image (64 bounces against the "
            "64-bounce truth) exceeds this fraction (e.g. 0.15)");
  threshold("--max-indirect-bias", options_.max_indirect_bias,
            "the fast mode's |indirect bias| over the image (64 bounces against the 64-bounce "
            "truth) exceeds this fraction (e.g. 0.10)");
  threshold("--max-region-bias", options_.max_region_bias,
            "the fast mode's |indirect bias| (64 bounces against the 64-bounce truth) in any "
            "named region exceeds this fraction (e.g. 0.15)");
  threshold("--max-indirect-l1-single", options_.max_indirect_l1_single,
            "the fast mode's indirect relative L1 over the image at --bounces 1 against the "
            "1-bounce truth exceeds this fraction (e.g. 0.12)");
  threshold("--min-psnr-taa", options_.min_psnr_taa,
            "the PSNR (dB) of the fast mode's final image with TAA (no bloom or motion blur, "
            "64 bounces) against the 64-bounce truth is below this (e.g. 30)");
  threshold("--max-first-frame-gap", options_.max_first_frame_gap,
            "the fast mode's first frame (no history: `render --frames 1`, a cut) is more than "
            "this many dB below its converged frame with TAA, both against the 64-bounce truth "
            "(e.g. 1.5)");
  threshold("--min-direct-psnr-floor", options_.min_direct_psnr_floor,
            "the default shadow mode's direct PSNR (dB) on the floor against the area-lamp truth "
            "is below this (e.g. 35)");
  threshold("--max-penumbra-error", options_.max_penumbra_error,
            "the default shadow mode's penumbra width under the tumbler or the marble differs "
            "from the area-lamp truth's by more than this fraction (e.g. 0.25)");
  threshold("--min-albedo-psnr", options_.min_albedo_psnr,
            "the albedo view's PSNR (dB) against the truth's pixel-averaged albedo is below this");
  bench->add_flag("--require-wall-hue", options_.require_wall_hue,
                  "--accuracy: exit 3 unless on each side wall the incoming indirect light's "
                  "sign of R - B is the truth's: fast at 64 bounces as the 64-bounce truth, fast "
                  "at 1 bounce as the 1-bounce truth");
  bench->add_flag("--truth-noise", options_.truth_noise,
                  "--accuracy on a scene file (or --open with a sky): also path-trace the "
                  "many-bounce truth with the next seed and report the indirect light's L1 "
                  "between the two truths per region: the truth's own noise, which every L1 of "
                  "the report includes (a noiseless image reads about 0.71 x it)");
  add_simulation(bench, options_.sim);
  bench->get_option("--marbles")
      ->description("start with the 30 marbles (key S toggles them); with --accuracy: also "
                    "measure the marble frame (16 marbles at rest: fast and reference mode "
                    "against its truth, the marbles and the floor beside them as regions)");
  devices_ = bench->add_option(
      "--devices", options_.devices,
      "devices to bench one after the other: all, or a comma-separated list of indices from "
      "`rolypoly devices` and/or parts of device names (instead of --device)");
  sizes_ =
      bench->add_option("--sizes", options_.sizes,
                        "comma-separated square image sizes, e.g. 256,512,720 (instead of --size)")
          ->delimiter(',')
          ->transform(pixel_count());
  bench->add_option("--voxels", options_.voxels,
                    "comma-separated GI voxel resolutions per side, each 32, 64 or 128 (default " +
                        std::to_string(render::RenderSettings{}.voxel_resolution) +
                        "), or 256 or 512 with --gi-volume svo (default " +
                        std::to_string(render::RenderSettings::kDefaultSvoResolution) + ")")
      ->delimiter(',')
      ->check(CLI::IsMember({32u, 64u, 128u, 256u, 512u}));
  bench->add_option("--scene", options_.scene,
                    "default or demo (the simulated demo, the simulation options as given), busy "
                    "(30 marbles, a fireball and the particle budget kept full), atrium (a "
                    "generated courtyard, opened as a file), or a glTF 2.0 "
                    "file (.gltf or .glb: its still frame from the file's camera; with "
                    "--accuracy its materials are the regions)")
      ->capture_default_str();
  bench->add_option("--chart", options_.chart,
                    "also write an SVG chart: per-pass time per device, frame time against "
                    "resolution and voxel count");
  bench->add_option("--markdown", options_.markdown,
                    "also write the summary table as Markdown to this file");
}

std::string BenchCli::finish(int argc, const char* const* argv) {
  app::CommonOptions& common = common_;
  BenchOptions& bench_opts = options_;
  const CLI::App* bench = command_;
  if (bench_opts.scene == app::kDemoScene) bench_opts.scene = "default";
  // Neither demo name: a scene file (bench/src/bench_scene.h), static and with its own
  // materials, so the simulation's options and the demo-only reports cannot apply.
  if (bench_opts.scene != "default" && bench_opts.scene != "busy") {
    std::string why;
    for (const char* name :
         {"--seed", "--marbles", "--fireball", "--replay", "--assets", "--open"})
      if (why.empty() && bench->count(name))
        why = std::string(name) + " applies to the simulated demo, not to a scene file";
    if (why.empty() && bench_opts.quality_report)
      why = "--quality-report measures the demo (at rest and the busy animation), not a "
            "scene file";
    for (const char* name :
         {"--require-wall-hue", "--min-direct-psnr-floor", "--max-penumbra-error"})
      if (why.empty() && bench->count(name))
        why = std::string(name) + " measures the demo's box (its side walls, the floor's "
              "shadows under its lamp); a scene file's report has its materials as regions";
    if (!why.empty()) return why + " (--scene " + bench_opts.scene + ")";
  }
  const char* why = nullptr;
  if (devices_->count() && bench->count("--device"))
    why = "--devices and --device both choose devices; use one";
  else if (sizes_->count() && (bench->count("--size") || bench->count("--width") ||
                                  bench->count("--height")))
    why = "--sizes and --size/--width/--height both choose sizes; use one";
  else if (bench_opts.compare_visibility &&
           (devices_->count() || sizes_->count() || bench_opts.voxels.size() > 1))
    why = "--compare-visibility runs one device, size and voxel resolution";
  else if (bench_opts.quality_report &&
           (devices_->count() || sizes_->count() || bench_opts.voxels.size() > 1 ||
            bench_opts.compare_visibility))
    why = "--quality-report runs one device, size and voxel resolution";
  else if (common.pathtraced &&
           (devices_->count() || sizes_->count() || bench->count("--voxels") ||
            bench_opts.compare_visibility || bench_opts.quality_report ||
            bench->count("--chart") || bench->count("--markdown") ||
            bench_opts.scene == "busy"))
    why = "--quality pathtraced benches the path tracer on the host at one size on the "
          "demo or a scene file (no --devices, --sizes, --voxels, --compare-visibility, "
          "--quality-report, --chart, --markdown or --scene busy)";
  else if (bench_opts.accuracy &&
           (devices_->count() || sizes_->count() || bench_opts.voxels.size() > 1 ||
            bench_opts.compare_visibility || bench_opts.quality_report || common.pathtraced ||
            bench->count("--bounces") || bench->count("--chart") ||
            bench->count("--markdown") || bench_opts.scene == "busy"))
    why = "--accuracy runs one device and voxel resolution on the demo frame or a scene "
          "file, at 1 and 64 bounces (no --devices, --sizes, --compare-visibility, "
          "--quality-report, --quality pathtraced, --bounces, --chart, --markdown or --scene "
          "busy)";
  else if (!bench_opts.accuracy &&
           (bench->count("--out") || bench->count("--truth-cache") ||
            bench->count("--max-indirect-l1") || bench->count("--max-indirect-bias") ||
            bench->count("--max-region-bias") || bench->count("--max-indirect-l1-single") ||
            bench->count("--min-psnr-taa") || bench->count("--max-first-frame-gap") ||
            bench_opts.require_wall_hue || bench_opts.truth_noise ||
            bench->count("--min-direct-psnr-floor") || bench->count("--max-penumbra-error") ||
            bench->count("--min-albedo-psnr")))
    why = "--out, --truth-cache and the thresholds (--max-indirect-l1, --max-indirect-bias, "
          "--max-region-bias, --max-indirect-l1-single, --min-psnr-taa, --max-first-frame-gap, "
          "--require-wall-hue, --min-direct-psnr-floor, --max-penumbra-error, "
          "--min-albedo-psnr, --truth-noise) belong to --accuracy";
  if (why) return why;
  const bool demo_scene = bench_opts.scene == "default" || bench_opts.scene == "busy" ||
                          app::is_demo_scene(bench_opts.scene);
  if (std::string sky =
          app::check_sky(bench, common, bench_opts.accuracy && demo_scene && !common.open_demo,
                         demo_scene);
      !sky.empty())
    return sky;
  // --accuracy with --render-scale: the finished frame with TAA at that scale (its final PSNR
  // against the truth), every light term at the output size; a held rate is no fixed picture.
  if (bench_opts.accuracy && common.target_ms > 0.0)
    return "--target-ms holds a frame time, so its pictures depend on the machine's speed; "
           "--accuracy measures a fixed --render-scale";
  if (std::string scale = app::check_render_scale(common, nullptr); !scale.empty())
    return scale;
  if (std::string gi = app::check_gi_volume(common, bench_opts.voxels); !gi.empty())
    return gi;
  if (common.render.gi_volume == render::GiVolume::kSvo && bench_opts.voxels.empty())
    bench_opts.voxels = {render::RenderSettings::kDefaultSvoResolution};
  if (bench_opts.accuracy) {
    if (bench_opts.truth_noise && demo_scene && !(common.open_demo && common.sky.given()))
      return "--truth-noise measures a scene file's truth (or the half-open demo's under a "
             "sky); the demo's report states its truth's noise in its direct section";
    if (bench->count("--lamp"))
      return "--lamp applies to --quality pathtraced (--accuracy uses both lamp models)";
    if (bench->count("--spp")) bench_opts.accuracy_spp = common.spp;
  } else if (std::string pt = app::check_pathtrace(bench, common); !pt.empty()) {
    return pt;
  }
  bench_opts.size = size_.resolve();
  bench_opts.size_given =
      bench->count("--size") || bench->count("--width") || bench->count("--height");
  bench_opts.command_line = "rolypoly";
  for (int i = 1; i < argc; ++i) {
    bench_opts.command_line += ' ';
    bench_opts.command_line += argv[i];
  }
  return "";
}

}  // namespace rp::bench
