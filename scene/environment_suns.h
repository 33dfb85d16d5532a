// The suns of an environment map: compact patches that hold a large share of its light (an
// outdoor map's sun, a studio's softboxes, a lamp in a night scene), taken out of the map so the
// real-time modes light by them as directional lights with shadow maps. Read through the voxel
// cones' wide footprints, such a patch leaks past the walls that hide it from a point (the
// studio map lit the test yard's floor +76 % through the cones, bench/results sky table); as a
// directional light it casts its shadows like the clear sky's sun. The path tracer keeps the
// whole map (scene::Environment::map) and counts the patches' light at the first vertex as
// direct light, as the real-time modes do.
//
// A patch: the 8-connected texels (wrapping in u) around a texel at least kSunPeak times the
// map's mean luminance, down to kSunEdge times it. It is taken out when its excess over the
// edge holds at least kSunMinShare of the map's power and it covers at most kSunMaxSolidAngle;
// its texels keep their colour at the edge's luminance (the map stays continuous: PRT traces
// those flattened patches and their bright rim apart, scene/environment_glow.h) and the
// excess becomes the light: irradiance E = sum (texel - its residual) x texel solid angle on a
// plane facing the patch, from the excess-weighted mean direction. Luminance: Rec. 709
// (0.2126, 0.7152, 0.0722); a texel's solid angle (2 pi / w)(pi / h) sin theta at its centre.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "scene/environment.h"
#include "scene/frame_scene.h"

namespace rp::scene {

inline constexpr float kSunPeak = 100.0f;         // x the mean luminance, the brightest texel
inline constexpr float kSunEdge = 10.0f;          // x the mean luminance, the patch's edge
inline constexpr float kSunMinShare = 0.05f;      // of the map's power, the excess
inline constexpr float kSunMaxSolidAngle = 0.1f;  // sr (a cone of 10.3 degrees half-angle)
inline constexpr int kMaxEnvironmentSuns = 4;

struct EnvironmentSun {
  glm::vec3 direction{0.0f, 1.0f, 0.0f};  // map frame, unit, from a point towards the patch
  glm::vec3 irradiance{0.0f};             // rgb, on a plane facing the patch (strength 1)
  float solid_angle = 0.0f;               // sr, the patch's texels
  float share = 0.0f;                     // of the map's power (sum of luminance x solid angle)
};

struct EnvironmentSuns {
  std::vector<EnvironmentSun> suns;  // brightest first; empty: the map has none
  // The map with the suns' excess taken out (nullptr when there are no suns): per texel,
  // map = residual + the suns' part, exactly in float.
  std::shared_ptr<const EnvironmentMap> residual;
};

// Finds up to `max_suns` suns of `map` (0: none), brightest excess first.
EnvironmentSuns find_environment_suns(const EnvironmentMap& map, int max_suns);

// The directional light of `sun` in world space for an environment turned by `rotate_deg` and
// scaled by `strength` (scene/environment.h; intensity = irradiance / pi, the renderer's
// directional unit), named "environment sun N" (N from 1) and marked in_environment.
PunctualLight environment_sun_light(const EnvironmentSun& sun, int index, float rotate_deg,
                                    float strength);

}  // namespace rp::scene
