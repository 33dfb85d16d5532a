#include "scene/clear_sky.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rp::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Perez {
  double a, b, c, d, e;
  double f(double theta, double gamma) const {
    const double cos_t = std::max(std::cos(theta), 0.01);  // at the horizon: finite
    const double cos_g = std::cos(gamma);
    return (1.0 + a * std::exp(b / cos_t)) * (1.0 + c * std::exp(d * gamma) + e * cos_g * cos_g);
  }
};

// The paper's appendix: distribution coefficients for Y, x, y, linear in turbidity.
Perez perez_y(double t) {
  return {0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251,
          0.1206 * t - 2.5771, -0.0670 * t + 0.3703};
}
Perez perez_x(double t) {
  return {-0.0193 * t - 0.2592, -0.0665 * t + 0.0008, -0.0004 * t + 0.2125,
          -0.0641 * t - 0.8989, -0.0033 * t + 0.0452};
}
Perez perez_yc(double t) {
  return {-0.0167 * t - 0.2608, -0.0950 * t + 0.0092, -0.0079 * t + 0.2102,
          -0.0441 * t - 1.6537, -0.0109 * t + 0.0529};
}

// Zenith chromaticity: [T^2 T 1] M [theta_s^3 theta_s^2 theta_s 1]^T.
double zenith_chroma(const double m[3][4], double t, double ts) {
  const double tv[3] = {t * t, t, 1.0}, sv[4] = {ts * ts * ts, ts * ts, ts, 1.0};
  double r = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) r += tv[i] * m[i][j] * sv[j];
  return r;
}

constexpr double kZenithX[3][4] = {{0.00166, -0.00375, 0.00209, 0.0},
                                   {-0.02903, 0.06377, -0.03202, 0.00394},
                                   {0.11693, -0.21196, 0.06052, 0.25886}};
constexpr double kZenithY[3][4] = {{0.00275, -0.00610, 0.00317, 0.0},
                                   {-0.04214, 0.08970, -0.04153, 0.00516},
                                   {0.15346, -0.26756, 0.06670, 0.26688}};

// CIE xyY -> linear sRGB (D65 primaries).
glm::dvec3 xyy_to_rgb(double x, double y, double lum) {
  if (!(y > 0.0)) return glm::dvec3(0.0);
  const double X = x / y * lum, Z = (1.0 - x - y) / y * lum;
  return {3.2406 * X - 1.5372 * lum - 0.4986 * Z, -0.9689 * X + 1.8758 * lum + 0.0415 * Z,
          0.0557 * X - 0.2040 * lum + 1.0570 * Z};
}

}  // namespace

ClearSky make_clear_sky(const ClearSkySettings& s) {
  if (!(s.turbidity >= 1.7f && s.turbidity <= 10.0f))
    throw std::invalid_argument("clear sky: turbidity " + std::to_string(s.turbidity) +
                                " outside 1.7 .. 10");
  if (!(s.sun_elevation_deg >= 1.0f && s.sun_elevation_deg <= 90.0f))
    throw std::invalid_argument("clear sky: sun elevation " + std::to_string(s.sun_elevation_deg) +
                                " outside 1 .. 90 degrees");
  if (s.width < 8 || s.width % 2 != 0 || !(s.scale > 0.0f))
    throw std::invalid_argument("clear sky: the map needs an even width >= 8 and a scale > 0");
  const double t = s.turbidity;
  const double theta_s = (90.0 - s.sun_elevation_deg) * kPi / 180.0;
  const double az = s.sun_azimuth_deg * kPi / 180.0;
  // The sun's direction in the map's convention (u = azimuth / 360, v = theta_s / pi).
  const glm::dvec3 sun_dir(environment_direction(float(az / (2.0 * kPi)), float(theta_s / kPi)));

  const double chi = (4.0 / 9.0 - t / 120.0) * (kPi - 2.0 * theta_s);
  const double zenith_y = std::max(0.0, (4.0453 * t - 4.9710) * std::tan(chi) - 0.2155 * t + 2.4192);
  const double zenith_x = zenith_chroma(kZenithX, t, theta_s);
  const double zenith_yc = zenith_chroma(kZenithY, t, theta_s);
  const Perez py = perez_y(t), px = perez_x(t), pyc = perez_yc(t);
  const double fy0 = py.f(0.0, theta_s), fx0 = px.f(0.0, theta_s), fyc0 = pyc.f(0.0, theta_s);

  ClearSky out;
  out.map = std::make_shared<EnvironmentMap>();
  EnvironmentMap& map = *out.map;
  map.width = s.width;
  map.height = s.width / 2;
  map.rgb.resize(size_t(map.width) * size_t(map.height) * 3);
  auto sky = [&](glm::dvec3 d) {
    const double theta = std::acos(std::clamp(d.y, -1.0, 1.0));
    const double gamma = std::acos(std::clamp(glm::dot(d, sun_dir), -1.0, 1.0));
    const double lum = zenith_y * py.f(theta, gamma) / fy0;
    const double x = zenith_x * px.f(theta, gamma) / fx0;
    const double y = zenith_yc * pyc.f(theta, gamma) / fyc0;
    return glm::max(xyy_to_rgb(x, y, lum), glm::dvec3(0.0));
  };
  // The ground: the mean sky colour along the horizon times the ground's albedo.
  glm::dvec3 horizon(0.0);
  for (int i = 0; i < 64; ++i)
    horizon += sky(glm::dvec3(environment_direction((float(i) + 0.5f) / 64.0f, 0.499f)));
  const glm::dvec3 ground = horizon / 64.0 * double(s.ground_albedo);
  for (int row = 0; row < map.height; ++row)
    for (int col = 0; col < map.width; ++col) {
      const glm::dvec3 d(environment_direction((float(col) + 0.5f) / float(map.width),
                                               (float(row) + 0.5f) / float(map.height)));
      const glm::dvec3 c = (d.y >= 0.0 ? sky(d) : ground) * double(s.scale);
      float* p = &map.rgb[3 * (size_t(row) * size_t(map.width) + size_t(col))];
      p[0] = float(c.x);
      p[1] = float(c.y);
      p[2] = float(c.z);
    }

  // The sun: 128 klux at the top of the atmosphere, exp(-0.1 T m) through it, redder with m.
  const double elevation = double(s.sun_elevation_deg);
  const double air_mass =
      1.0 / (std::sin(elevation * kPi / 180.0) + 0.50572 * std::pow(elevation + 6.07995, -1.6364));
  const double e_sun = 128.0 * std::exp(-0.1 * t * air_mass);
  const glm::dvec3 tint = glm::exp(-0.04 * t * air_mass * glm::dvec3(0.35, 0.6, 1.2));
  out.sun.name = "sun";
  out.sun.type = LightType::kDirectional;
  out.sun.direction = glm::vec3(-sun_dir);
  const double tint_luminance = 0.2126 * tint.x + 0.7152 * tint.y + 0.0722 * tint.z;
  out.sun.intensity = glm::vec3(tint / tint_luminance * (e_sun * double(s.scale) / kPi));
  return out;
}

}  // namespace rp::scene
