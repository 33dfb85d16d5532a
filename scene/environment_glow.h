// The glow around an environment's suns: the texels of the map's residual (scene/
// environment_suns.h) that join a sun's patch and stay bright, down to kGlowEdge times the map's
// mean luminance. Taking a sun out flattens its patch to the patch's edge luminance (10 x the
// mean), so a studio's softbox still leaves a sharp bright rectangle in the residual, about a
// third of the residual's light in the studio map. A band-limited sky (the 9 or 25 spherical
// harmonics of precomputed radiance transfer) smears such a patch over the horizon; the glow is
// lit instead like a cluster of small suns, each cell a shadow ray from every vertex
// (truth/prt_transfer.h: PrtSettings::glow_cells). It stays part of the residual everywhere else
// (the cones, the background, the path tracer): the glow is a split of the residual's light for
// PRT, not a light of its own.
//
// The glow's texels are the 8-connected texels (wrapping in u) reached from a sun's patch
// (map != residual) through residual texels of at least kGlowEdge x the mean luminance
// (Rec. 709). They are gathered in cells of a kGlowCells x kGlowCells / 2 grid over the map's
// (u, v), coarsened by halves while more than kMaxGlowCells cells hold glow. A cell's light is
// the sum of its texels' radiance x solid angle, given as the irradiance it puts on a plane
// facing its direction: the luminance-weighted sum of the texels' directions, so that a plane
// that sees all of a cell gets exactly its texels' luminance-weighted cosine integral.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "scene/environment.h"

namespace rp::scene {

inline constexpr float kGlowEdge = 4.0f;      // x the map's mean luminance
inline constexpr int kGlowCells = 128;        // cells around the equator, finest grid
inline constexpr size_t kMaxGlowCells = 256;  // shadow rays per vertex, at most

struct GlowCell {
  glm::vec3 direction{0.0f, 1.0f, 0.0f};  // map frame, unit, towards the cell
  glm::vec3 irradiance{0.0f};             // rgb, on a plane facing `direction` (strength 1)
  bool operator==(const GlowCell&) const = default;
};

struct EnvironmentGlow {
  // The residual's glow texels, sparse (a glow is a few thousand texels of a map that may hold
  // tens of millions): their indices in the map (row-major, ascending) and their radiance (the
  // residual's). The residual less them is the part that stays band-limited.
  int width = 0, height = 0;  // the map's
  std::vector<uint32_t> texels;
  std::vector<glm::vec3> radiance;
  std::vector<GlowCell> cells;  // in row-major grid order
};

// The glow of `residual` around the suns taken out of `map` (find_environment_suns), or nullptr
// when the maps differ nowhere (no suns) or no texel glows. The maps must be the same size.
std::shared_ptr<const EnvironmentGlow> find_environment_glow(const EnvironmentMap& map,
                                                             const EnvironmentMap& residual);

}  // namespace rp::scene
