// The direct-light section of `rolypoly bench --accuracy`: how close each shadow mode
// (RenderSettings::shadows) and the texture filter come to the area-lamp truth.
//
// Scene: the demo frame at rest plus two marbles at rest on the floor in front of the tumblers
// (direct_frame), so there is a penumbra under a tumbler and under a marble; the indirect
// section keeps the plain demo frame (so its figures stay comparable).
// Truth: the path tracer with LampModel::kArea at 0 bounces (direct light + seen emission), at
// the report's size, cached like the other truths; its own noise is stated (PSNR of two seeds).
// Real time: per shadow mode, the fast mode at 1 bounce (the direct term does not depend on the
// bounces), one unjittered frame (the albedo view), then `jitter_frames` frames with TAA's
// camera jitter on whose direct components (and albedo) are averaged on the host: what TAA
// converges to without its history clamp, so a per-frame rotated filter and texture aliasing
// resolve as on screen. Measures (bench/src/accuracy_metrics.h):
//   direct PSNR   masked_tone_mapped_psnr of the direct component (after the renderer's tone
//                 map and sRGB encode, peak 1, the scale of the report's final PSNR; also
//                 masked_psnr of it divided by the truth's mean lit-floor luminance, JSON
//                 direct_psnr_db_lit_floor_scale), on the floor, on the truth's penumbra
//                 pixels (lamp_fraction in (0.05, 0.95) at the pixel centre, dilated by one
//                 pixel) and over every covered pixel but the ceiling and the lamp cap (and
//                 the pixels beside them): the area lamp lights the ceiling, the point model
//                 cannot;
//   penumbra      10-90 % widths (world units along the floor) of the lamp's visible fraction
//                 along a line from a tumbler's and a marble's contact point directly away from
//                 the lamp's foot (0, -1, 0): direct / (albedo * I * unshadowed light of the
//                 image's own lamp model), bilinear in each image; error = |rt / truth - 1|;
//   albedo        srgb_psnr of the unjittered frame's albedo against the truth's pixel-averaged
//                 albedo (texture filtering), image and floor;
//   the penumbra taken apart (accuracy_penumbra.h): its PSNR on the open floor, on the floor
//                 beside objects' outlines and on the objects, and the open floor's error by the
//                 truth's lamp fraction (JSON penumbra_breakdown; the default mode's in the text).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/render_session.h"
#include "truth/path_tracer.h"

namespace rp::bench {

struct DirectOptions {
  uint32_t width = 360, height = 360;
  uint32_t spp = 4096;          // the area truth's samples per pixel
  uint64_t seed = 1;
  uint32_t jitter_frames = 16;  // one full cycle of TAA's 16-sample Halton jitter
  std::filesystem::path cache_dir;
  std::filesystem::path out_dir;  // accuracy_direct_{side_by_side,heat}.png
};

struct DirectResult {
  nlohmann::json json;  // the report's "direct" object (schema rolypoly-accuracy/3)
  std::string table;    // printed lines
};

// The demo frame `frame_index` at rest plus two marbles resting on the floor.
scene::FrameScene direct_frame(const scene::SceneAssets& assets, uint32_t frame_index);

// Renders the truth (or takes it from the cache) and every shadow mode, measures, writes the
// PNGs. Throws truth::PathTracer::Cancelled on Ctrl-C (as measure_accuracy).
DirectResult measure_direct(const app::CommonOptions& common, const scene::SceneAssets& assets,
                            truth::PathTracer& tracer, const DirectOptions& options);

}  // namespace rp::bench
