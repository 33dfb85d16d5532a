// The marble section of `rolypoly bench --accuracy --marbles`: how the GI volume
// treats marbles, which the plain demo frame of the main section has none of. At 64^3 a marble
// (r 0.04) is under three voxels across, the cause of its contact leaks and over-darkening that
// the octree (256^3, 512^3) is meant to cure.
//
// Scene: marble_frame, the demo frame at rest plus kMarbleFrameCount marbles resting on the
// open floor in front of the tumblers (single ones, a touching pair, one against each front
// tumbler's foot). Separate from the main section's frame so that its figures (the CI gate of
// tests/app/accuracy.cmake) stay as they are; the marble section runs only when asked.
// Truth: the path tracer at the main section's many bounces and spp (point lamp, as there),
// cached like the others (the spheres are part of the cache key).
// Real time: the fast mode at those bounces after its accumulation converged ("fast/N") and the
// reference mode after its bounce feedback converged ("ref/N"), as the main section's.
// Measures (bench/src/accuracy_metrics.h), per region of classify_regions with the frame's
// spheres (every region, the marble ones included: marbles, floor_by_marbles):
//   final PSNR      masked_tone_mapped_psnr of the combined image over the region (dB);
//   indirect        relative L1 and bias of the indirect component over the region;
//   leaks           leak / missing pixel counts of the indirect component (whole image).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "app/render_session.h"
#include "truth/path_tracer.h"

namespace rp::bench {

inline constexpr uint32_t kMarbleFrameCount = 16;

// The demo frame `frame_index` at rest plus kMarbleFrameCount marbles (r = the simulated
// marbles' 0.04, albedos their glass colours, the marbles' coat) resting on the floor.
scene::FrameScene marble_frame(const scene::SceneAssets& assets, uint32_t frame_index);

struct MarbleOptions {
  uint32_t width = 360, height = 360;
  uint32_t spp = 1024;
  uint32_t bounces = 64;                 // the truth's and the real-time modes'
  uint32_t converge_frames = 128;        // fast-mode frames
  uint32_t reference_frames = 32;        // reference-mode frames
  uint64_t seed = 1;
  std::filesystem::path cache_dir;
  std::filesystem::path out_dir;         // accuracy_marbles_{side_by_side,heat}.png
};

struct MarbleResult {
  nlohmann::json json;  // the report's "marbles" object
  std::string table;    // printed lines
};

// Renders the truth (or takes it from the cache) and both modes, measures, writes the PNGs.
// Throws truth::PathTracer::Cancelled on Ctrl-C (as measure_accuracy).
MarbleResult measure_marbles(const app::CommonOptions& common, const scene::SceneAssets& assets,
                             truth::PathTracer& tracer, const MarbleOptions& options);

}  // namespace rp::bench
