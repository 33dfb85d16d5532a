// The glow around an environment's suns (scene/environment_glow.h): the residual's bright texels
// joined to a sun's patch are the glow and nothing else is (a bright area apart from every sun
// stays out) with the residual's radiance there, the cells carry the glow
// texels' light exactly for a plane that sees them all, a wide glow is gathered in at most
// kMaxGlowCells coarser cells, and a map without suns has no glow.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "scene/environment_glow.h"
#include "scene/environment_suns.h"
#include "support/square_maps.h"

namespace rp::scene {
namespace {

using Square = test::MapSquare;
using test::texel_solid_angle;

// A grey map of radiance 0.1 with `squares` painted on it.
EnvironmentMap squares_map(const std::vector<Square>& squares) {
  return test::square_map([](int, int) { return glm::vec3(0.1f); }, squares);
}

glm::dvec3 texel_direction(const EnvironmentMap& map, int x, int y) {
  return glm::dvec3(environment_direction((float(x) + 0.5f) / float(map.width),
                                          (float(y) + 0.5f) / float(map.height)));
}

// Irradiance on a plane of normal n from the glow's texels alone (no occluders), per texel.
glm::dvec3 texel_irradiance(const EnvironmentMap& map, const EnvironmentGlow& glow, glm::dvec3 n) {
  glm::dvec3 e(0.0);
  for (size_t k = 0; k < glow.texels.size(); ++k) {
    const int x = int(glow.texels[k]) % map.width, y = int(glow.texels[k]) / map.width;
    e += glm::dvec3(glow.radiance[k]) * texel_solid_angle(map, y) *
         std::max(0.0, glm::dot(n, texel_direction(map, x, y)));
  }
  return e;
}

glm::dvec3 cell_irradiance(const EnvironmentGlow& glow, glm::dvec3 n) {
  glm::dvec3 e(0.0);
  for (const GlowCell& c : glow.cells)
    e += glm::dvec3(c.irradiance) * std::max(0.0, glm::dot(n, glm::dvec3(c.direction)));
  return e;
}

// A sun (500) inside a halo (15: above the glow's edge, below the sun's), and a bright square
// (15) apart from both.
const std::vector<Square> kHaloScene = {{38, 19, 5, 15.0f}, {38, 19, 2, 500.0f},
                                        {100, 20, 3, 15.0f}};

TEST(EnvironmentGlow, IsTheResidualJoinedToASunAndNothingElse) {
  const EnvironmentMap map = squares_map(kHaloScene);
  const EnvironmentSuns suns = find_environment_suns(map, kMaxEnvironmentSuns);
  ASSERT_EQ(suns.suns.size(), 1u);  // the halo and the apart square are no suns
  const auto glow = find_environment_glow(map, *suns.residual);
  ASSERT_NE(glow, nullptr);
  EXPECT_EQ(glow->width, map.width);
  EXPECT_EQ(glow->height, map.height);
  std::vector<uint32_t> halo;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x)
      if (std::abs(x - 38) <= 5 && std::abs(y - 19) <= 5)
        halo.push_back(uint32_t(y * map.width + x));
  EXPECT_EQ(glow->texels, halo);
  ASSERT_EQ(glow->radiance.size(), glow->texels.size());
  for (size_t k = 0; k < glow->texels.size(); ++k)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(glow->radiance[k][c], suns.residual->rgb[size_t(glow->texels[k]) * 3 + size_t(c)]);
}

TEST(EnvironmentGlow, CellsCarryTheGlowTexelsLight) {
  const EnvironmentMap map = squares_map(kHaloScene);
  const EnvironmentSuns suns = find_environment_suns(map, kMaxEnvironmentSuns);
  const auto glow = find_environment_glow(map, *suns.residual);
  ASSERT_NE(glow, nullptr);
  // the halo spans 11 x 11 texels = 4 x 4 or so cells of the 128 x 64 grid (1 texel a cell
  // here: the grid is the map's size), each with a unit direction
  EXPECT_EQ(glow->cells.size(), 121u);
  for (const GlowCell& c : glow->cells) EXPECT_NEAR(glm::length(c.direction), 1.0f, 1e-6f);
  // normals that see the whole halo (it lies within 27 degrees of the sun's direction)
  const glm::dvec3 sun = glm::dvec3(suns.suns[0].direction);
  const glm::dvec3 side = glm::normalize(glm::cross(sun, glm::dvec3(0.0, 1.0, 0.0)));
  for (const glm::dvec3 n : {sun, glm::normalize(sun + 0.5 * side),
                             glm::normalize(sun - 0.8 * side + glm::dvec3(0.0, 0.3, 0.0))}) {
    const glm::dvec3 want = texel_irradiance(map, *glow, n), got = cell_irradiance(*glow, n);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-5 * want[c]);
  }
}

TEST(EnvironmentGlow, AWideGlowIsGatheredInAtMostTheLimitsCells) {
  // a sun in a bright band of 6 x 64 texels above the horizon: 384 glow texels, one a cell of
  // the finest grid
  EnvironmentMap map = squares_map({{32, 16, 2, 1000.0f}});
  for (int y = 14; y < 20; ++y)
    for (int x = 0; x < 64; ++x)
      if (std::abs(x - 32) > 2 || std::abs(y - 16) > 2)
        for (int c = 0; c < 3; ++c) map.rgb[size_t(3 * (y * map.width + x) + c)] = 30.0f;
  const EnvironmentSuns suns = find_environment_suns(map, kMaxEnvironmentSuns);
  ASSERT_EQ(suns.suns.size(), 1u);
  const auto glow = find_environment_glow(map, *suns.residual);
  ASSERT_NE(glow, nullptr);
  EXPECT_LE(glow->cells.size(), kMaxGlowCells);
  EXPECT_EQ(glow->cells.size(), 96u);  // coarsened once: 3 x 32 of the 64 x 32 cells
  // the band lies above the horizon: the zenith-facing plane sees all of it
  const glm::dvec3 up(0.0, 1.0, 0.0);
  const glm::dvec3 want = texel_irradiance(map, *glow, up), got = cell_irradiance(*glow, up);
  EXPECT_GT(want.x, 0.0);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-5 * want[c]);
}

TEST(EnvironmentGlow, AMapWithoutSunsHasNone) {
  const EnvironmentMap map = squares_map({{40, 20, 4, 15.0f}});
  EXPECT_EQ(find_environment_glow(map, map), nullptr);
  EnvironmentMap other = map;
  other.width = 64;
  EXPECT_THROW((void)find_environment_glow(map, other), std::invalid_argument);
}

}  // namespace
}  // namespace rp::scene
