// Tumbler profile R(y) and analytic SDF (SPEC.md section 2) against hand-derived values, a
// brute-force distance to a fine mesh, and finite differences.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "scene/tumbler_shape.h"

namespace {

using rp::scene::TumblerShape;

constexpr double kPi = std::numbers::pi;

// Closest distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5), in
// double so the reference is far more precise than the float code under test.
double point_triangle_distance(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return glm::length(p - a);
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return glm::length(p - b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return glm::length(p - (a + ab * (d1 / (d1 - d3))));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return glm::length(p - c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  }
  const double denom = 1.0 / (va + vb + vc);
  return glm::length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

TEST(TumblerShape, ConstantsMatchSpec) {
  const TumblerShape s;
  EXPECT_FLOAT_EQ(s.b, 0.2f);
  EXPECT_FLOAT_EQ(s.t, 0.1f);
  EXPECT_FLOAT_EQ(s.alpha, static_cast<float>(kPi / 9.0));
  // y_t = (b - t) / sin(pi/9) = 0.1 / 0.3420201433 = 0.2923804400
  EXPECT_NEAR(s.y_t, 0.29238044, 1e-6);
  EXPECT_NEAR(s.y_top(), 0.39238044, 1e-6);
  EXPECT_NEAR(s.y_join_bottom(), 0.2 * 0.3420201433, 1e-7);
  EXPECT_NEAR(s.y_join_top(), 0.29238044 + 0.1 * 0.3420201433, 1e-6);
}

TEST(TumblerShape, OtherParametersDeriveTheTopCentre) {
  const TumblerShape d = TumblerShape::with(0.2f, 0.1f, static_cast<float>(kPi / 9.0));
  EXPECT_FLOAT_EQ(d.y_t, TumblerShape{}.y_t);
  const TumblerShape s = TumblerShape::with(0.3f, 0.1f, static_cast<float>(kPi / 6.0));
  EXPECT_NEAR(s.y_t, 0.2 / 0.5, 1e-6);  // (b - t) / sin(30 deg)
  // The profile stays C0 at the joins for other parameters too (slope tan 30 deg = 0.5774).
  EXPECT_NEAR(s.radius(s.y_join_bottom() - 1e-5f), s.radius(s.y_join_bottom() + 1e-5f), 2e-5 * 0.5774 + 1e-6);
  EXPECT_NEAR(s.radius(s.y_join_top() - 1e-5f), s.radius(s.y_join_top() + 1e-5f), 2e-5 * 0.5774 + 1e-6);
  EXPECT_NEAR(s.sdf({0.0f, s.y_top(), 0.0f}), 0.0f, 1e-6f);
}

TEST(TumblerShape, ProfileValuesAndJoins) {
  const TumblerShape s;
  EXPECT_NEAR(s.radius(-0.2f), 0.0f, 1e-6);
  EXPECT_NEAR(s.radius(0.0f), 0.2f, 1e-7);       // inside the bottom sphere piece
  EXPECT_NEAR(s.radius(s.y_top()), 0.0f, 1e-3);  // sqrt of a rounding error at the pole
  EXPECT_NEAR(s.radius(s.y_t + 0.05f), std::sqrt(0.01 - 0.0025), 1e-6);
  // Cone piece: -y tan(a) + b / cos(a) at y = 0.2: -0.2 * 0.3639702343 + 0.2 / 0.9396926208
  EXPECT_NEAR(s.radius(0.2f), -0.2 * 0.3639702343 + 0.2 / 0.9396926208, 1e-6);

  // At both joins the value and the slope must agree from either side (the profile is C1).
  // eps is small because the sphere side curves: |R''| is about 12 near the top join.
  const float eps = 1e-5f;
  for (const float y : {s.y_join_bottom(), s.y_join_top()}) {
    SCOPED_TRACE(y);
    EXPECT_NEAR(s.radius(y - eps), s.radius(y + eps), 2.0 * eps * std::tan(kPi / 9.0) + 1e-6);
    EXPECT_NEAR(s.radius_slope(y - eps), s.radius_slope(y + eps), 5e-4);
    EXPECT_NEAR(s.radius_slope(y - eps), -std::tan(kPi / 9.0), 5e-4);
  }
  // Join radii: b cos(a) and t cos(a).
  EXPECT_NEAR(s.radius(s.y_join_bottom()), 0.2 * std::cos(kPi / 9.0), 1e-6);
  EXPECT_NEAR(s.radius(s.y_join_top()), 0.1 * std::cos(kPi / 9.0), 1e-6);
}

TEST(TumblerShape, SdfZeroOnTheProfileAndSignedByIt) {
  const TumblerShape s;
  for (int i = 0; i <= 200; ++i) {
    const float y = s.y_bottom() + s.height() * static_cast<float>(i) / 200.0f;
    const float r = s.radius(y);
    for (const float angle : {0.0f, 1.0f, 2.5f, 4.0f}) {
      const glm::vec3 p(r * std::cos(angle), y, r * std::sin(angle));
      EXPECT_NEAR(s.sdf(p), 0.0f, 2e-6f) << "y=" << y;
      // Moving along the outward normal by d changes the distance by d.
      const glm::vec3 n = s.sdf_gradient(p);
      EXPECT_NEAR(s.sdf(p + 0.03f * n), 0.03f, 2e-6f) << "y=" << y;
    }
  }
}

TEST(TumblerShape, SdfMatchesBruteForceDistanceToFineMesh) {
  const TumblerShape s;
  // Sagitta of this mesh is below 3e-5, so the distances agree to about that.
  const rp::scene::Mesh mesh = rp::scene::make_tumbler_mesh(s, {256, 64, 16, 48}, 0);
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> xz(-0.35f, 0.35f), ys(-0.35f, 0.6f), unit(0.0f, 1.0f),
      offset(-0.08f, 0.08f);
  int inside = 0, outside = 0;
  for (int i = 0; i < 80; ++i) {
    // Half uniform in a box around the tumbler, half close to the surface on either side.
    glm::vec3 p(xz(rng), ys(rng), xz(rng));
    if (i % 2 == 1) {
      const float y = s.y_bottom() + s.height() * unit(rng);
      const float angle = 6.2831853f * unit(rng);
      const glm::vec3 on(s.radius(y) * std::cos(angle), y, s.radius(y) * std::sin(angle));
      p = on + offset(rng) * s.sdf_gradient(on);
    }
    double best = std::numeric_limits<double>::max();
    for (const glm::uvec3& tri : mesh.triangles) {
      best = std::min(best, point_triangle_distance(p, mesh.vertices[tri.x].position,
                                                    mesh.vertices[tri.y].position,
                                                    mesh.vertices[tri.z].position));
    }
    // Inside test from the profile alone (independent of the SDF code).
    const float r = std::sqrt(p.x * p.x + p.z * p.z);
    const bool is_inside = p.y > s.y_bottom() && p.y < s.y_top() && r < s.radius(p.y);
    (is_inside ? inside : outside)++;
    const float d = s.sdf(p);
    EXPECT_NEAR(std::fabs(d), best, 5e-5) << "p=" << p.x << "," << p.y << "," << p.z;
    EXPECT_EQ(d < 0.0f, is_inside) << "p=" << p.x << "," << p.y << "," << p.z;
  }
  EXPECT_GT(inside, 20);  // both sides were exercised
  EXPECT_GT(outside, 20);
}

TEST(TumblerShape, GradientIsUnitAndMatchesCentralDifferences) {
  const TumblerShape s;
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> xz(-0.4f, 0.4f), ys(-0.4f, 0.7f);
  int checked = 0;
  while (checked < 300) {
    const glm::vec3 p(xz(rng), ys(rng), xz(rng));
    // The SDF is not differentiable on the axis (a ridge inside) or at the sphere centres.
    if (std::sqrt(p.x * p.x + p.z * p.z) < 0.02f) continue;
    ++checked;
    const glm::vec3 g = s.sdf_gradient(p);
    EXPECT_NEAR(glm::length(g), 1.0f, 1e-5f);
    const float h = 1e-3f;
    const glm::vec3 fd((s.sdf(p + glm::vec3(h, 0, 0)) - s.sdf(p - glm::vec3(h, 0, 0))) / (2 * h),
                       (s.sdf(p + glm::vec3(0, h, 0)) - s.sdf(p - glm::vec3(0, h, 0))) / (2 * h),
                       (s.sdf(p + glm::vec3(0, 0, h)) - s.sdf(p - glm::vec3(0, 0, h))) / (2 * h));
    EXPECT_NEAR(glm::length(g - fd), 0.0f, 5e-3f)
        << "p=" << p.x << "," << p.y << "," << p.z;
  }
}

TEST(TumblerShape, GradientOnTheAxisIsAUnitVector) {
  const TumblerShape s;
  EXPECT_NEAR(glm::length(s.sdf_gradient({0.0f, 0.1f, 0.0f})), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::length(s.sdf_gradient({0.0f, 0.0f, 0.0f})), 1.0f, 1e-6f);  // a centre
  EXPECT_EQ(s.sdf_gradient({0.0f, -0.01f, 0.0f}), glm::vec3(0.0f, -1.0f, 0.0f));
  EXPECT_EQ(s.sdf_gradient({0.0f, s.y_top() + 0.1f, 0.0f}), glm::vec3(0.0f, 1.0f, 0.0f));
}

}  // namespace
