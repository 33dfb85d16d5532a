// The GPU form of a frame's punctual lights and their shadow views (kernels/shared/types.h
// PunctualLightGpu, ShadowViewGpu), in render space where the GI volume is [-1,1]^3
// (scene/file_scene.h). Directional: one orthographic view over the volume's bounding sphere;
// spot: one perspective view along the axis, as wide as the outer cone; point: six 90 degree
// cube faces at half the map size (they cover the whole sphere, so each texel of a face spans
// about the angle of a spot map texel). At most RP_MAX_PUNCTUAL_LIGHTS lights; views are laid
// out back to back after the lamp's planes of the shadow depth buffer.
#pragma once

#include <cstdint>
#include <vector>

#include "render/gpu_types.h"
#include "scene/frame_scene.h"

namespace rp::render {

struct PunctualSetup {
  std::vector<gpu::PunctualLightGpu> lights;
  std::vector<gpu::ShadowViewGpu> views;
  uint64_t floats = 0;  // of the shadow depth buffer the views use after `first_float`
};

// Lights beyond RP_MAX_PUNCTUAL_LIGHTS are left out (the app warns); shadow_size: the
// directional and spot maps' side (point faces get half). first_float: where the views start
// in the depth buffer (after the lamp's 2 size^2 floats).
PunctualSetup setup_punctual_lights(const std::vector<scene::PunctualLight>& lights,
                                    uint32_t shadow_size, uint64_t first_float);

// Floats the views of `lights` take (what setup_punctual_lights reports, without building it).
uint64_t punctual_shadow_floats(const std::vector<scene::PunctualLight>& lights,
                                uint32_t shadow_size);

}  // namespace rp::render
