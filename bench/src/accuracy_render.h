// What the sections of `bench --accuracy` share (bench/src/accuracy_report.h, the marble section
// bench/src/accuracy_marbles.h): the linear images of one real-time mode or truth, the
// real-time renderer on a frame at rest, and a cached truth with a progress bar.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "app/render_session.h"
#include "app/truth_cache.h"
#include "scene/demo_scene.h"
#include "truth/path_tracer.h"

namespace rp::app {

// The linear images one mode or truth gives (3 floats per pixel).
struct Images {
  std::string name;
  std::vector<float> combined, direct, indirect, albedo;
  std::vector<float> specular;  // the coat's part of direct + indirect (issue 16)
};

Images from_truth(const std::string& name, const truth::PathTracedImage& t);

// The frame a section measures: frame `frame_index` of a scene at rest (scene::make_demo_frame,
// the marble section's marble_frame).
using FrameFn = scene::FrameScene (*)(const scene::SceneAssets&, uint32_t frame_index);

// The real-time renderer on `frame_fn`'s frames: `frames` frames (frame_index counting up, so
// the fast mode's interleaving, the shadow noise and TAA's jitter rotate as in the app), no
// bloom or motion blur, TAA only when asked. `final_rgba` gets the last finished frame.
Images render_mode(const CommonOptions& common, const std::string& name, render::Quality quality,
                   uint32_t bounces, bool taa, uint32_t w, uint32_t h, uint32_t frames,
                   std::vector<uint8_t>& final_rgba, FrameFn frame_fn = scene::make_demo_frame);

// cached_path_trace with a progress bar named `label`; Ctrl-C / SIGTERM (InterruptGuard) stops
// the render between rows (truth::PathTracer::Cancelled).
CachedTruth cached_truth_with_progress(truth::PathTracer& tracer,
                                       const scene::SceneAssets& assets,
                                       const scene::FrameScene& frame,
                                       const truth::PathTraceSettings& settings,
                                       const std::filesystem::path& cache,
                                       const std::string& label);

}  // namespace rp::app
