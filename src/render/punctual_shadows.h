// The GPU form of a frame's punctual lights and their shadow views (kernels/shared/types.h
// PunctualLightGpu, ShadowViewGpu), in render space where the GI volume is [-1,1]^3
// (scene/file_scene.h). Directional: one square orthographic view over the frame's geometry;
// spot: one perspective view along the axis, as wide as the outer cone; point: six 90 degree
// cube faces at half the map size (they cover the whole sphere, so each texel of a face spans
// about the angle of a spot map texel). At most RP_MAX_PUNCTUAL_LIGHTS lights; views are laid
// out back to back after the lamp's planes of the shadow depth buffer.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "render/gpu_types.h"
#include "scene/frame_scene.h"

namespace rp::render {

// The region the frame's shadow casters and receivers occupy, in render space: the instances'
// and spheres' bounds, clipped to the volume. A directional light's view covers this region
// only, so its texels are as fine as the scene's extent allows (the atrium, 30 x 15 x 13 m:
// 1.6 x finer than over the whole volume's sphere). Empty (lo > hi): the whole volume.
struct ShadowBounds {
  glm::vec3 lo{1.0f}, hi{-1.0f};
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  // Grows the bounds to hold the box [a, b].
  void add(glm::vec3 a, glm::vec3 b) {
    if (empty()) {
      lo = a;
      hi = b;
    } else {
      lo = glm::min(lo, a);
      hi = glm::max(hi, b);
    }
  }
  // Widened to a grid of kStep render units (so that bounds which move a little keep the same
  // views, texels and cached voxel light) and clipped to the volume [-1,1]^3.
  ShadowBounds snapped() const;
  static constexpr float kStep = 1.0f / 16.0f;
};

struct PunctualSetup {
  std::vector<gpu::PunctualLightGpu> lights;
  std::vector<gpu::ShadowViewGpu> views;
  uint64_t floats = 0;  // of the shadow depth buffer the views use after `first_float`
};

// Lights beyond RP_MAX_PUNCTUAL_LIGHTS are left out (the app warns); shadow_size: the
// directional and spot maps' side (point faces get half). first_float: where the views start
// in the depth buffer (after the lamp's 2 size^2 floats).
// bounds: where the directional lights' views look (ShadowBounds; empty: the whole volume).
PunctualSetup setup_punctual_lights(const std::vector<scene::PunctualLight>& lights,
                                    uint32_t shadow_size, uint64_t first_float,
                                    const ShadowBounds& bounds = {});

// Floats the views of `lights` take (what setup_punctual_lights reports, without building it).
uint64_t punctual_shadow_floats(const std::vector<scene::PunctualLight>& lights,
                                uint32_t shadow_size);

}  // namespace rp::render
