// `rolypoly bench --accuracy --scene FILE`: the accuracy report (accuracy_report.h) on a scene
// file's still frame, seen from the file's camera in render space (scene/file_scene.h), as
// `render --scene FILE` draws it. The same renders as the demo's report: the truth at one
// gather and at many (AccuracyOptions::many_bounces), the fast and reference modes at each
// count (fast/N, ref/N, fast/1, ref/1; no TAA, bloom or motion blur) and fast/N with TAA.
// The regions are the scene's materials (bench/src/accuracy_materials.h) and the whole image.
// Per configuration and region: direct PSNR after the tone map and relative L1 / bias of the
// direct, indirect and (coated materials) specular components; over the image: the final PSNR,
// the albedo PSNR and the leak / missing pixel counts (also per region in the JSON). The
// demo's sections that need its box (the side walls' hue, the direct-light section with the
// area lamp and penumbrae, the marbles) have no counterpart: parse_cli refuses their
// thresholds and --marbles for a file.
//
// The truths are cached as the demo's are (app/truth_cache.h), in a subfolder of the cache per
// content hash of the file (bench/src/scene_file_facts.h): the truth cache's key hashes the
// frame and the assets, but not what only a file has (its punctual lights, normal and
// metallic-roughness maps, alpha masks), and the same path may hold other content tomorrow.
//
// JSON: schema rolypoly-accuracy-file/1 (README "Accuracy against the ground truth"): "scene"
// (bench/src/scene_file_facts.h), "materials" [{index, name, region, pixels, emissive,
// coated}], "region_pixels", "truth", "configurations" (as rolypoly-accuracy/4 without
// incoming_indirect, plus direct_psnr_db, albedo_psnr_db and leaks.regions), "images",
// "thresholds", "passed". PNGs: the demo's three (accuracy_side_by_side.png,
// accuracy_indirect_heat.png, accuracy_final_taa.png) in the same layout.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "app/scene_input.h"
#include "bench/src/accuracy_report.h"
#include "bench/src/bench_matrix.h"

namespace rp::bench {

// Renders everything, measures, writes the PNGs (and the JSON when asked). Throws
// std::invalid_argument for an option that needs the demo (require_wall_hue,
// min_direct_psnr_floor, max_penumbra_error, marbles), what RenderSession and the path tracer
// throw, and truth::PathTracer::Cancelled after Ctrl-C / SIGTERM.
AccuracyResult measure_file_accuracy(const app::CommonOptions& common, const app::FileScene& scene,
                                     const SceneFileFacts& facts, const AccuracyOptions& options);

// ---- The report's text and thresholds (accuracy_file_table.cpp), from its JSON ----

// Adds j["thresholds"] for every threshold `options` gives and j["passed"]; returns the
// printed lines ("threshold NAME ...: met / MISSED") and sets `passed`.
std::string check_file_thresholds(const AccuracyOptions& options, nlohmann::json& j,
                                  bool& passed);

// The printed table of a file's report.
std::string file_accuracy_table(const nlohmann::json& j);

}  // namespace rp::bench
