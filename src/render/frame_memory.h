// The device memory of the buffers that follow a frame's size (the image, the render scale,
// the lamp's shadow map), part by part: each part named by the pass that allocates or writes
// its buffers (passes/pass_names.h; kPostBuffers for the renderer's post-processing
// ping-pong). frame_memory() states it from the settings, summing the passes' frame_bytes
// (passes/frame_memory.h); Renderer::frame_device_memory() reports what a renderer holds.
// What follows the scene (meshes, textures, the raster's triangle lists, the punctual lights'
// shadow maps) and the GI volume are counted elsewhere (app/scene_memory.h,
// app/render_session.h).
#pragma once

#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "render/render_settings.h"

namespace rp::render {

inline constexpr const char* kPostBuffers = "post";  // two float4 images at the output size

struct FrameMemory {
  std::vector<std::pair<std::string_view, uint64_t>> parts;  // one per name, in adding order

  void add(std::string_view name, uint64_t bytes);  // to the part of that name
  uint64_t of(std::string_view name) const;          // 0 for a part not listed
  uint64_t total() const;
  // Each part the larger of this one's and other's: what a renderer holds after frames of
  // both configurations, as its buffers of a part grow and are not given back.
  void take_max(const FrameMemory& other);
};

// What frames need beyond the settings.
struct FrameMemoryOptions {
  bool light_components = false;  // the light pass's direct / indirect / specular images
  bool prt = false;               // --sky-light prt: the PRT pass's sky light per pixel
};

// The buffers a renderer with `settings` holds once it has rendered the final view, with the
// effects settings.effects turns on and the shadows of settings.shadows: exact (bytes), as
// tests/render/frame_memory_test.cpp checks against Renderer::frame_device_memory. The render
// size is the output size scaled by settings.render_scale, or the output size when the scale
// follows the frame time (it may reach 1).
FrameMemory frame_memory(const RenderSettings& settings, const FrameMemoryOptions& options);

}  // namespace rp::render
