// Real spherical harmonics (src/shading/spherical_harmonics.h) against closed forms: the basis
// is orthonormal, a constant and the clamped cosine lobe project onto their known
// coefficients, a zonal lobe turned to any axis matches its projection, and rotating
// coefficients equals projecting the rotated function.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "shading/spherical_harmonics.h"

namespace rp::shading {
namespace {

constexpr double kPi = 3.14159265358979323846;

glm::dmat3 rotation(double angle, glm::dvec3 axis) {
  return glm::dmat3(glm::rotate(glm::dmat4(1.0), angle, glm::normalize(axis)));
}

TEST(SphericalHarmonics, BasisIsOrthonormalUpToBandFour) {
  // Products of two band-4 functions are polynomials of degree 8: the product rule with 24
  // rings and 48 segments integrates them exactly (to rounding).
  double y[kShMaxCount];
  for (int j = 0; j < kShMaxCount; ++j) {
    const std::vector<double> c = sh_project(
        [&](glm::dvec3 d) {
          sh_eval(d, kShMaxBands, y);
          return y[j];
        },
        kShMaxBands);
    for (int i = 0; i < kShMaxCount; ++i)
      EXPECT_NEAR(c[size_t(i)], i == j ? 1.0 : 0.0, 1e-12) << "<Y_" << i << ", Y_" << j << ">";
  }
}

TEST(SphericalHarmonics, BandOneIsTheDirectionScaled) {
  // The convention: Y_1,-1 = c y, Y_1,0 = c z, Y_1,1 = c x, c = sqrt(3 / (4 pi)).
  double y[4];
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  sh_eval(d, 2, y);
  const double c = std::sqrt(3.0 / (4.0 * kPi));
  EXPECT_NEAR(y[0], 0.5 / std::sqrt(kPi), 1e-15);
  EXPECT_NEAR(y[1], c * d.y, 1e-15);
  EXPECT_NEAR(y[2], c * d.z, 1e-15);
  EXPECT_NEAR(y[3], c * d.x, 1e-15);
}

TEST(SphericalHarmonics, ConstantProjectsOntoTheFirstCoefficientOnly) {
  const std::vector<double> c = sh_project([](glm::dvec3) { return 2.5; }, 5);
  EXPECT_NEAR(c[0], 2.5 * 2.0 * std::sqrt(kPi), 1e-12);  // 2.5 * integral of Y_0 = 2.5 sqrt(4 pi)
  for (size_t i = 1; i < c.size(); ++i) EXPECT_NEAR(c[i], 0.0, 1e-12) << i;
}

TEST(SphericalHarmonics, CosineLobeMatchesItsClosedForm) {
  // max(0, z) has a kink at the equator: many rings, a looser tolerance.
  const std::vector<double> c = sh_project([](glm::dvec3 d) { return std::max(0.0, d.z); }, 5,
                                           400, 16);
  for (int l = 0; l < 5; ++l)
    for (int m = -l; m <= l; ++m)
      EXPECT_NEAR(c[size_t(sh_index(l, m))], m == 0 ? sh_cosine_lobe_zonal(l) : 0.0, 2e-5)
          << "l " << l << " m " << m;
  // The irradiance of a unit-radiance sky through the lobe is pi: sqrt(4 pi) * A_0.
  EXPECT_NEAR(2.0 * std::sqrt(kPi) * sh_cosine_lobe_zonal(0), kPi, 1e-12);
}

TEST(SphericalHarmonics, ZonalLobeTurnedToAnAxisMatchesItsProjection) {
  const glm::dvec3 n = glm::normalize(glm::dvec3(-0.4, 0.7, 0.2));
  std::vector<double> zonal;
  for (int l = 0; l < 5; ++l) zonal.push_back(sh_cosine_lobe_zonal(l));
  const std::vector<double> turned = sh_rotate_zonal(zonal, n, 5);
  const std::vector<double> projected = sh_project(
      [&](glm::dvec3 d) { return std::max(0.0, glm::dot(n, d)); }, 5, 400, 400);
  for (size_t i = 0; i < turned.size(); ++i) EXPECT_NEAR(turned[i], projected[i], 2e-4) << i;
}

TEST(SphericalHarmonics, RotatingCoefficientsEqualsProjectingTheRotatedFunction) {
  // A smooth, not band-limited function: projection commutes with rotation, so both sides
  // agree to the quadrature's accuracy.
  const glm::dvec3 a(0.8, -0.3, 0.5);
  const auto f = [&](glm::dvec3 d) { return std::exp(glm::dot(a, d)) + 0.3 * d.x * d.y * d.z; };
  for (const glm::dmat3& r :
       {rotation(0.7, {1.0, 2.0, 0.5}), rotation(2.9, {0.0, 0.0, 1.0}),
        rotation(-1.3, {-0.2, 1.0, -0.7}), glm::dmat3(1.0)}) {
    for (int bands : {3, 5}) {
      const std::vector<double> c = sh_project(f, bands);
      std::vector<double> turned(c.size());
      ShRotation(r, bands).apply(c.data(), turned.data());
      const glm::dmat3 inverse = glm::transpose(r);
      const std::vector<double> want =
          sh_project([&](glm::dvec3 d) { return f(inverse * d); }, bands);
      for (size_t i = 0; i < c.size(); ++i) EXPECT_NEAR(turned[i], want[i], 1e-10) << i;
    }
  }
}

TEST(SphericalHarmonics, RotationsComposeAndKeepTheEnergy) {
  const glm::dmat3 r1 = rotation(0.9, {0.3, -1.0, 0.4}), r2 = rotation(-2.1, {1.0, 0.2, 0.1});
  std::vector<double> c(kShMaxCount);
  for (int i = 0; i < kShMaxCount; ++i) c[size_t(i)] = std::sin(1.7 * i + 0.3);
  std::vector<double> once(c.size()), twice(c.size()), direct(c.size());
  ShRotation(r1, 5).apply(c.data(), once.data());
  ShRotation(r2, 5).apply(once.data(), twice.data());
  ShRotation(r2 * r1, 5).apply(c.data(), direct.data());
  double e0 = 0.0, e1 = 0.0;
  for (size_t i = 0; i < c.size(); ++i) {
    EXPECT_NEAR(twice[i], direct[i], 1e-12) << i;
    e0 += c[i] * c[i];
    e1 += direct[i] * direct[i];
  }
  EXPECT_NEAR(e1, e0, 1e-11);  // rotations are orthogonal on each band
}

TEST(SphericalHarmonics, RefusesBandsOutsideOneToFive) {
  double y[kShMaxCount];
  EXPECT_THROW(sh_eval(glm::dvec3(0, 0, 1), 0, y), std::invalid_argument);
  EXPECT_THROW(sh_eval(glm::dvec3(0, 0, 1), 6, y), std::invalid_argument);
  EXPECT_THROW(ShRotation(glm::dmat3(1.0), 6), std::invalid_argument);
  EXPECT_THROW(sh_cosine_lobe_zonal(5), std::invalid_argument);
}

TEST(SphericalHarmonics, EnvironmentProjectionIntegratesTheMap) {
  // A constant map: the texels' solid angles sum to 4 pi exactly, so c_0 = L sqrt(4 pi) and
  // the irradiance is pi L on every normal; the other coefficients vanish up to the texel
  // rule's error (each texel's Y taken at its centre: O(1 / height^2), 1e-2 at 32x16).
  auto flat = std::make_shared<scene::EnvironmentMap>();
  flat->width = 256;
  flat->height = 128;
  flat->rgb.assign(256 * 128 * 3, 0.5f);
  scene::Environment env;
  env.map = flat;
  env.strength = 2.0f;
  const std::vector<glm::dvec3> c = sh_project_environment(env, 5);
  EXPECT_NEAR(c[0].x, 1.0 * 2.0 * std::sqrt(kPi), 1e-6);
  for (size_t i = 1; i < c.size(); ++i) EXPECT_NEAR(c[i].y, 0.0, 3e-4) << i;
  EXPECT_NEAR(sh_irradiance(c, glm::normalize(glm::dvec3(0.3, 0.4, -0.2)), 5).z, kPi, 1e-3);

  // A sky brighter towards +y (L = 1 + y): band-limited (bands 0 and 1), so 9 coefficients
  // give its irradiance exactly up to the texel quadrature: pi + (2 pi / 3) n.y.
  auto sky = std::make_shared<scene::EnvironmentMap>();
  sky->width = 256;
  sky->height = 128;
  for (int row = 0; row < 128; ++row)
    for (int col = 0; col < 256; ++col) {
      const float y = scene::environment_direction((float(col) + 0.5f) / 256.0f,
                                                   (float(row) + 0.5f) / 128.0f)
                          .y;
      sky->rgb.insert(sky->rgb.end(), {1.0f + y, 1.0f + y, 1.0f + y});
    }
  env.map = sky;
  env.strength = 1.0f;
  env.rotate_deg = 40.0f;  // a turn about +y changes nothing here
  const std::vector<glm::dvec3> s = sh_project_environment(env, 3);
  for (const glm::dvec3 n : {glm::dvec3(0, 1, 0), glm::dvec3(0, -1, 0),
                             glm::normalize(glm::dvec3(1, 1, 0.5))})
    EXPECT_NEAR(sh_irradiance(s, n, 3).x, kPi + 2.0 * kPi / 3.0 * n.y, 2e-3) << n.y;
}

// Turning the environment in real time (PRT's key and option): rotating the unturned map's
// coefficients equals projecting the turned map, to rounding where the turn moves texel centres
// onto texel centres (whole columns), and to the projection's quadrature otherwise; the
// strength scales them.
TEST(SphericalHarmonics, TurningTheEnvironmentEqualsProjectingItTurned) {
  auto map = std::make_shared<scene::EnvironmentMap>();
  map->width = 64;
  map->height = 32;
  for (int row = 0; row < 32; ++row)
    for (int col = 0; col < 64; ++col) {
      const glm::vec3 d = scene::environment_direction((float(col) + 0.5f) / 64.0f,
                                                       (float(row) + 0.5f) / 32.0f);
      const float sun = std::pow(std::max(0.0f, glm::dot(d, glm::normalize(glm::vec3(1, 1, -2)))), 8.0f);
      map->rgb.insert(map->rgb.end(), {0.3f + 5.0f * sun, 0.5f + 0.4f * d.y, 0.2f + d.x * d.x});
    }
  scene::Environment unturned;
  unturned.map = map;
  for (const int bands : {3, 5}) {
    const std::vector<glm::dvec3> base = sh_project_environment(unturned, bands);
    for (const float deg : {5.625f * 7.0f, -5.625f * 13.0f, 23.0f}) {
      scene::Environment turned = unturned;
      turned.rotate_deg = deg;
      turned.strength = 2.5f;
      const std::vector<glm::dvec3> want = sh_project_environment(turned, bands);
      const std::vector<glm::dvec3> got = sh_turn_environment(base, deg, 2.5f);
      const bool whole_columns = std::fmod(std::fabs(deg), 5.625f) == 0.0f;
      // whole columns: rounding; 23 degrees: the texel rule's error at 64 x 32 (measured 2e-3
      // of the first coefficient)
      const double tol = (whole_columns ? 1e-9 : 1e-2) * std::abs(want[0].x);
      ASSERT_EQ(got.size(), want.size());
      for (size_t i = 0; i < got.size(); ++i)
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(got[i][c], want[i][c], tol) << bands << " bands, " << deg << " deg, " << i;
    }
  }
  EXPECT_THROW(sh_turn_environment(std::vector<glm::dvec3>(7), 10.0f, 1.0f), std::invalid_argument);
}

// The SH irradiance's own error: none to speak of for a map of the first two bands (1 + y),
// clearly some for a small bright sun, less with 25 coefficients than with 9.
TEST(SphericalHarmonics, IrradianceErrorIsTheBandLimitsFloor) {
  const auto make = [](auto f) {
    auto map = std::make_shared<scene::EnvironmentMap>();
    map->width = 128;
    map->height = 64;
    for (int row = 0; row < 64; ++row)
      for (int col = 0; col < 128; ++col) {
        const glm::vec3 d = scene::environment_direction((float(col) + 0.5f) / 128.0f,
                                                         (float(row) + 0.5f) / 64.0f);
        const float v = f(d);
        map->rgb.insert(map->rgb.end(), {v, v, v});
      }
    scene::Environment env;
    env.map = map;
    return env;
  };
  const scene::Environment smooth = make([](glm::vec3 d) { return 1.0f + d.y; });
  EXPECT_LT(sh_irradiance_error(smooth, 3), 2e-3);
  const scene::Environment sun = make([](glm::vec3 d) {
    return 0.2f + (glm::dot(d, glm::normalize(glm::vec3(0.3f, 0.8f, 0.2f))) > 0.98f ? 50.0f : 0.0f);
  });
  const double e9 = sh_irradiance_error(sun, 3), e25 = sh_irradiance_error(sun, 5);
  EXPECT_GT(e9, 0.02);
  EXPECT_LT(e25, e9);
  EXPECT_EQ(sh_irradiance_error(scene::Environment{}, 3), 0.0);
}

TEST(SphericalHarmonics, GlowProjectsAsTheMapOfItsTexels) {
  // A few scattered texels of a 32 x 16 map, coloured; the glow's sparse projection against the
  // projection of a map that holds them and zero elsewhere: the same sums, to the bit.
  scene::EnvironmentGlow glow;
  glow.width = 32;
  glow.height = 16;
  auto map = std::make_shared<scene::EnvironmentMap>();
  map->width = glow.width;
  map->height = glow.height;
  map->rgb.assign(size_t(32 * 16 * 3), 0.0f);
  for (const uint32_t texel : {3u, 40u, 41u, 200u, 201u, 233u, 500u}) {
    const glm::vec3 radiance(0.5f + 0.01f * float(texel), 2.0f, 0.25f * float(texel % 7));
    glow.texels.push_back(texel);
    glow.radiance.push_back(radiance);
    for (int c = 0; c < 3; ++c) map->rgb[size_t(texel) * 3 + size_t(c)] = radiance[c];
  }
  for (const int bands : {3, 5}) {
    const auto sparse = sh_project_glow(glow, bands);
    const auto dense = sh_project_environment(scene::Environment{map, 1.0f, 0.0f, nullptr, nullptr},
                                              bands);
    ASSERT_EQ(sparse.size(), dense.size());
    for (size_t i = 0; i < sparse.size(); ++i) EXPECT_EQ(sparse[i], dense[i]) << i;
    EXPECT_GT(sparse[0].x, 0.0);
  }
}

}  // namespace
}  // namespace rp::shading
