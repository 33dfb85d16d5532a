// What `render --quality pathtraced` and `bench --quality pathtraced` share: the path tracer's
// settings from the command line's and the words and figures they report.
#pragma once

#include <cstdint>
#include <string>

#include "app/render_session.h"
#include "scene/frame_scene.h"
#include "truth/path_tracer.h"

namespace rp::app {

// --spp, --bounces and --lamp at this size; every hardware thread; the same random streams every
// frame (a still scene gives the same image).
rp::truth::PathTraceSettings pathtrace_settings(const CommonOptions& common, uint32_t width,
                                                uint32_t height, uint64_t seed);

// What PathTraceSettings::threads = 0 means, for the report.
unsigned hardware_threads();

// The demo's assets from --assets (or the built-in folder), with the skylight of --open.
scene::SceneAssets load_demo_assets(const CommonOptions& common);

// "360x360, 1024 spp, 1 bounce" (+ ", area lamp")
std::string describe_settings(const rp::truth::PathTraceSettings& s);

// Millions of rays per second (0 for no time).
double mrays_per_second(uint64_t rays, double seconds);

}  // namespace rp::app
