// The suns of an environment map (scene/environment_suns.h): a compact bright patch is taken
// out whole (its light, direction and the map it leaves agree with the map texel by texel), the
// light the map loses is the light's, faint or broad patches stay in the map, several patches
// come brightest first up to the limit, and the directional light points where the turned map
// shows the patch.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "scene/environment_suns.h"
#include "support/square_maps.h"
#include "truth/environment.h"

namespace rp::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A blue-white gradient from the zenith, a dim ground; `patches` painted on it.
using Square = test::MapSquare;
EnvironmentMap gradient_map(const std::vector<Square>& patches) {
  return test::square_map(
      [](int, int y) {
        const float v = (float(y) + 0.5f) / 64.0f;
        return v < 0.5f ? glm::vec3(0.4f, 0.6f, 1.0f) * (1.0f - v) : glm::vec3(0.05f);
      },
      patches);
}
using test::texel_solid_angle;

double luminance(const float* t) { return 0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2]; }

// Luminance x solid angle over the map.
double power(const EnvironmentMap& map) {
  double sum = 0.0;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x)
      sum += luminance(&map.rgb[size_t(3 * (y * map.width + x))]) * texel_solid_angle(map, y);
  return sum;
}

TEST(EnvironmentSuns, ASunIsTakenOutWholeAndTheMapKeepsTheRest) {
  const EnvironmentMap map = gradient_map({{38, 19, 2, 200.0f}});
  const EnvironmentSuns found = find_environment_suns(map, kMaxEnvironmentSuns);
  ASSERT_EQ(found.suns.size(), 1u);
  ASSERT_NE(found.residual, nullptr);
  const EnvironmentSun& sun = found.suns[0];

  // The patch's texels drop to the edge level (10 x the mean), colour kept; the rest stays.
  const double edge = 10.0 * power(map) / (4.0 * kPi);
  double excess = 0.0, solid_angle = 0.0;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      const size_t i = size_t(3 * (y * map.width + x));
      const bool in_patch = std::abs(x - 38) <= 2 && std::abs(y - 19) <= 2;
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(found.residual->rgb[i + size_t(c)], in_patch ? edge : map.rgb[i + size_t(c)],
                    in_patch ? 1e-4 * edge : 0.0)
            << x << "," << y;
      if (in_patch) {
        excess += (200.0 - edge) * texel_solid_angle(map, y);
        solid_angle += texel_solid_angle(map, y);
      }
    }
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sun.irradiance[c], excess, 1e-4 * excess) << c;
  EXPECT_NEAR(sun.solid_angle, solid_angle, 1e-4 * solid_angle);
  EXPECT_NEAR(sun.share, excess / power(map), 1e-4);
  // The light the map loses is the sun's: power(map) = power(residual) + its irradiance.
  EXPECT_NEAR(power(*found.residual) + excess, power(map), 1e-5 * power(map));
  // Its direction is the square's centre texel's (symmetric square, rows weighted by sin).
  const glm::vec3 centre = environment_direction(38.5f / 128.0f, 19.5f / 64.0f);
  EXPECT_GT(glm::dot(sun.direction, centre), std::cos(0.25 * kPi / 64.0));
}

TEST(EnvironmentSuns, SmoothFaintOrBroadLightStaysInTheMap) {
  EXPECT_TRUE(find_environment_suns(gradient_map({}), 4).suns.empty());
  // one texel 150 x the mean: bright enough, but under 5 % of the map's light
  const EnvironmentMap faint = gradient_map({{64, 32, 0, 60.0f}});
  const double mean = power(faint) / (4.0 * kPi);
  ASSERT_GT(60.0, 100.0 * mean);
  ASSERT_LT((60.0 - 10.0 * mean) * texel_solid_angle(faint, 32), 0.05 * power(faint));
  const EnvironmentSuns none = find_environment_suns(faint, 4);
  EXPECT_TRUE(none.suns.empty());
  EXPECT_EQ(none.residual, nullptr);
  // a large bright region is never 100 x the mean of the map it dominates
  EXPECT_TRUE(find_environment_suns(gradient_map({{64, 16, 12, 50.0f}}), 4).suns.empty());
  // and --env-suns 0 takes nothing
  EXPECT_TRUE(find_environment_suns(gradient_map({{38, 19, 2, 200.0f}}), 0).suns.empty());
}

TEST(EnvironmentSuns, SeveralSunsComeBrightestFirstUpToTheLimit) {
  // excess: the 5 x 5 square about 3 x either 3 x 3 one, the brighter 3 x 3 next
  const EnvironmentMap map =
      gradient_map({{20, 20, 1, 300.0f}, {80, 24, 2, 300.0f}, {110, 12, 1, 600.0f}});
  const EnvironmentSuns all = find_environment_suns(map, 4);
  ASSERT_EQ(all.suns.size(), 3u);
  EXPECT_GT(all.suns[0].share, all.suns[1].share);
  EXPECT_GT(all.suns[1].share, all.suns[2].share);
  // the biggest square (5 x 5 texels at x = 80) first
  const glm::vec2 uv = environment_uv(all.suns[0].direction);
  EXPECT_NEAR(uv.x * 128.0f, 80.5f, 0.5f);
  const EnvironmentSuns two = find_environment_suns(map, 2);
  ASSERT_EQ(two.suns.size(), 2u);
  EXPECT_EQ(two.suns[1].share, all.suns[1].share);
  EXPECT_NEAR(environment_uv(two.suns[1].direction).x * 128.0f, 110.5f, 0.5f);
  // the third stays in the map
  const size_t third = size_t(3 * (20 * 128 + 20));
  EXPECT_EQ(two.residual->rgb[third], 300.0f);
  EXPECT_LT(all.residual->rgb[third], 300.0f);
}

TEST(EnvironmentSuns, TheLightComesFromWhereTheTurnedMapShowsTheSun) {
  auto map = std::make_shared<EnvironmentMap>(gradient_map({{38, 19, 2, 200.0f}}));
  const EnvironmentSuns found = find_environment_suns(*map, 4);
  ASSERT_EQ(found.suns.size(), 1u);
  for (float turn : {0.0f, 90.0f, -135.0f}) {
    const PunctualLight light = environment_sun_light(found.suns[0], 0, turn, 2.0f);
    EXPECT_EQ(light.type, LightType::kDirectional);
    EXPECT_TRUE(light.in_environment);
    EXPECT_EQ(light.name, "environment sun 1");
    // the renderer's directional unit: irradiance / pi, times the strength
    EXPECT_NEAR(light.intensity.y, found.suns[0].irradiance.y * 2.0f / kPi, 1e-5);
    Environment env;
    env.map = map;
    env.rotate_deg = turn;
    const truth::EnvironmentSampler sampler(env);
    EXPECT_EQ(sampler.radiance(-light.direction), glm::vec3(200.0f)) << "turn " << turn;
  }
}

}  // namespace
}  // namespace rp::scene
