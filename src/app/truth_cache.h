// The path-traced truth of `bench --accuracy`, cached on disk: a 360x360 truth at 1024 samples
// per pixel takes minutes, a re-run of the report should take seconds. An entry is keyed by a
// hash of everything the image depends on (assets: meshes, materials with their specular coats
// and the surface model's name, texels; the frame:
// camera, light, instances, spheres; the settings: size, spp, bounces, seed, lamp model (only
// kArea adds to the key, so point-lamp keys are unchanged); and the path
// tracer's version), so a change to any of them renders anew.
//
// Files in the cache folder: truth-<key>.exr (the components as layers, truth/exr_io.h) and
// truth-<key>.json (how it was made: size, spp, bounces, seed, seconds, rays). Both are written
// atomically, the EXR first; an entry counts only when both read back. The thread count is not
// part of the key: the image does not depend on it (truth/path_tracer.h).
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <string>

#include "scene/frame_scene.h"
#include "truth/path_tracer.h"

namespace rp::app {

// Bump when the path tracer's output changes for the same inputs (a fix, a new convention).
// 2: camera rays pass the back faces of single-sided materials.
inline constexpr const char* kPathTracerVersion = "rolypoly-pathtracer/2";
// The surface model of src/shading/brdf.h, part of the key of every frame with a coated
// surface (rename when its formulas or tables change).
inline constexpr const char* kSurfaceModel = "ggx-smith-hc-schlick-kulla-conty/1";

// 64-bit FNV-1a of the inputs above, as 16 hex digits.
std::string truth_key(const scene::SceneAssets& assets, const scene::FrameScene& frame,
                      const truth::PathTraceSettings& settings);

// $XDG_CACHE_HOME/rolypoly/truth, else $HOME/.cache/rolypoly/truth, else ./.rolypoly-cache/truth.
std::filesystem::path default_truth_cache_dir();

struct CachedTruth {
  truth::PathTracedImage image;  // seconds and rays: those of the original render
  bool from_cache = false;
  std::filesystem::path file;    // the EXR
};

// The cached entry when there is a complete one, else renders it with `tracer` and stores it
// (creating `dir`). A cache that cannot be written is reported on stderr and the render is still
// returned; a corrupt entry is rendered anew.
CachedTruth cached_path_trace(truth::PathTracer& tracer, const scene::SceneAssets& assets,
                              const scene::FrameScene& frame,
                              const truth::PathTraceSettings& settings,
                              const std::filesystem::path& dir,
                              const truth::ProgressFn& progress = {},
                              const std::atomic<bool>* cancel = nullptr);

}  // namespace rp::app
