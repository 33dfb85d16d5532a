// The built-in clear sky (scene/clear_sky.h): the Preetham model's zenith luminance at the
// zenith, symmetry about the sun's meridian, a brighter sky around the sun, and a sun whose
// direct light outweighs the sky's on the ground (64 against 26 klux at 45 degrees, T = 2.5).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "scene/clear_sky.h"

namespace rp::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

double luminance(const EnvironmentMap& m, int col, int row) {
  const float* p = &m.rgb[3 * (size_t(row) * size_t(m.width) + size_t(col))];
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

// The texel of the map in direction (azimuth, elevation) in degrees.
double luminance_at(const EnvironmentMap& m, double az_deg, double el_deg) {
  const double u = std::fmod(az_deg / 360.0 + 1.0, 1.0), v = (90.0 - el_deg) / 180.0;
  return luminance(m, std::min(m.width - 1, int(u * m.width)),
                   std::min(m.height - 1, int(v * m.height)));
}

TEST(ClearSky, ZenithHasThePreethamZenithLuminance) {
  ClearSkySettings s;
  s.turbidity = 2.5f;
  s.sun_elevation_deg = 45.0f;
  s.scale = 1.0f;  // kcd/m^2
  s.width = 1024;
  const ClearSky sky = make_clear_sky(s);
  // Y_z = (4.0453 T - 4.9710) tan chi - 0.2155 T + 2.4192, chi = (4/9 - T/120)(pi - 2 theta_s)
  const double theta_s = kPi / 4.0, t = 2.5;
  const double chi = (4.0 / 9.0 - t / 120.0) * (kPi - 2.0 * theta_s);
  const double want = (4.0453 * t - 4.9710) * std::tan(chi) - 0.2155 * t + 2.4192;
  double top = 0.0;
  for (int col = 0; col < sky.map->width; ++col) top += luminance(*sky.map, col, 0);
  top /= sky.map->width;
  EXPECT_NEAR(top, want, 0.03 * want);  // the top row is 0.09 degrees below the zenith
  EXPECT_GT(want, 3.0);                 // a clear sky's zenith: a few kcd/m^2
  EXPECT_LT(want, 9.0);
}

TEST(ClearSky, SymmetricAboutTheSunAndBrightestAroundIt) {
  ClearSkySettings s;
  s.sun_azimuth_deg = 100.0f;
  s.sun_elevation_deg = 30.0f;
  const ClearSky sky = make_clear_sky(s);
  for (double d : {20.0, 60.0, 120.0})
    for (double el : {10.0, 40.0, 70.0})
      EXPECT_NEAR(luminance_at(*sky.map, 100.0 + d, el), luminance_at(*sky.map, 100.0 - d, el),
                  0.02 * luminance_at(*sky.map, 100.0 + d, el))
          << d << " " << el;
  EXPECT_GT(luminance_at(*sky.map, 100.0, 35.0), 3.0 * luminance_at(*sky.map, 190.0, 35.0));
  // Blue overhead away from the sun.
  const float* z = &sky.map->rgb[3 * size_t(sky.map->width / 2)];
  EXPECT_GT(z[2], z[0]);
}

TEST(ClearSky, SunOutshinesTheSkyAsOnAClearDay) {
  ClearSkySettings s;  // T 2.5, 45 degrees
  s.width = 256;
  const ClearSky sky = make_clear_sky(s);
  EXPECT_EQ(sky.sun.type, LightType::kDirectional);
  EXPECT_LT(sky.sun.direction.y, -0.6f);  // travels downwards at 45 degrees
  // Horizontal illuminance: the sun's pi I cos(45), the sky's integral of L cos over the upper
  // hemisphere (texel solid angles).
  const glm::vec3 i = sky.sun.intensity;
  const double sun_h =
      kPi * (0.2126 * i.x + 0.7152 * i.y + 0.0722 * i.z) * std::sin(kPi / 4.0) / s.scale;
  double sky_h = 0.0;
  const EnvironmentMap& m = *sky.map;
  for (int row = 0; row < m.height / 2; ++row) {
    const double t0 = kPi * row / m.height, t1 = kPi * (row + 1) / m.height;
    const double omega = (2.0 * kPi / m.width) * (std::cos(t0) - std::cos(t1));
    for (int col = 0; col < m.width; ++col)
      sky_h += luminance(m, col, row) / s.scale * omega * 0.5 * (std::cos(t0) + std::cos(t1));
  }
  EXPECT_GT(sky_h, 15.0);  // klux
  EXPECT_LT(sky_h, 35.0);
  std::printf("sun %.1f klux, sky %.1f klux on the ground\n", sun_h, sky_h);
  EXPECT_NEAR(sun_h, 128.0 * std::exp(-0.25 * 1.4128) * std::sin(kPi / 4.0), 1.0);
  EXPECT_GT(sun_h / sky_h, 1.8);
  EXPECT_LT(sun_h / sky_h, 6.0);
}

TEST(ClearSky, RefusesSettingsOutsideTheModel) {
  ClearSkySettings s;
  s.turbidity = 0.5f;
  EXPECT_THROW(make_clear_sky(s), std::invalid_argument);
  s = {};
  s.sun_elevation_deg = -5.0f;
  EXPECT_THROW(make_clear_sky(s), std::invalid_argument);
  s = {};
  s.width = 7;
  EXPECT_THROW(make_clear_sky(s), std::invalid_argument);
}

}  // namespace
}  // namespace rp::scene
