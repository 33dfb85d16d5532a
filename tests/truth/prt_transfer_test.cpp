// PRT transfer vectors (src/truth/prt_transfer.h) against closed forms: an
// unoccluded plane's transfer is the clamped cosine lobe turned to its normal (E = pi L under a
// constant sky); a wall hiding half the sky leaves the lobe's half (against a fine quadrature);
// a roof hides it all; interreflection only adds light and converges with bounces; the white
// furnace (albedo 1 under a constant sky: radiance = sky) holds for a convex sphere and for an
// open box once the bounces converge; results are bit-identical for any thread count. A sun's
// traced bounce off a wide lit floor onto a wall is the floor's irradiance times albedo times the
// wall's view factor to the floor (1/2, less the sliver past the floor's far edge).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "prt_test_scenes.h"
#include "shading/spherical_harmonics.h"
#include "truth/prt_transfer.h"

namespace rp::truth {
namespace {

using namespace prt_test;
constexpr double kPi = 3.14159265358979323846;

std::vector<double> lobe(glm::dvec3 n, int bands) {
  std::vector<double> zonal;
  for (int l = 0; l < bands; ++l) zonal.push_back(shading::sh_cosine_lobe_zonal(l));
  return shading::sh_rotate_zonal(zonal, n, bands);
}

// SH coefficients of a constant sky of radiance `l`: only the DC term, l sqrt(4 pi) (what
// sh_project_environment gives a constant map, up to its texel-centre quadrature).
std::vector<glm::dvec3> constant_sky(glm::vec3 l, int bands) {
  std::vector<glm::dvec3> env(size_t(bands * bands), glm::dvec3(0.0));
  env[0] = glm::dvec3(l) * (2.0 * std::sqrt(kPi));
  return env;
}

PrtSettings settings(PrtKind kind, int bands = 3, uint32_t samples = 256, uint32_t bounces = 1) {
  PrtSettings s;
  s.kind = kind;
  s.bands = bands;
  s.samples = samples;
  s.bounces = bounces;
  return s;
}

TEST(PrtTransfer, UnoccludedPlaneIsTheCosineLobeTurnedToItsNormal) {
  // A tilted plane (turned 30 degrees about x then 50 about y): unshadowed in closed form,
  // shadowed by rays, none of which meets anything, so the control variate leaves the lobe.
  const auto assets = one_mesh_assets(glm::vec3(0.8f), [](scene::Mesh& m) { floor_grid(m); });
  scene::FrameScene frame = one_instance_frame();
  frame.instances[0].model = glm::rotate(glm::rotate(glm::mat4(1.0f), 0.87f, {0, 1, 0}), 0.52f,
                                         glm::vec3(1, 0, 0));
  const glm::dvec3 n = glm::normalize(glm::dvec3(glm::mat3(frame.instances[0].model) *
                                                 glm::vec3(0, 1, 0)));
  for (int bands : {3, 5})
    for (PrtKind kind : {PrtKind::kUnshadowed, PrtKind::kShadowed}) {
      const PrtTransfer t = compute_prt_transfer(assets, frame, settings(kind, bands));
      ASSERT_EQ(t.vertex_count(), 25u);
      ASSERT_EQ(t.channels, 1u);
      const std::vector<double> want = lobe(n, bands);
      for (uint32_t v = 0; v < t.vertex_count(); ++v)
        for (int i = 0; i < t.count(); ++i)
          ASSERT_NEAR(t.at(v, 0)[i], want[size_t(i)], 1e-6)
              << name_of(kind) << " bands " << bands << " vertex " << v << " coef " << i;
    }
}

TEST(PrtTransfer, ConstantSkyGivesPiLOnAnUnoccludedPlane) {
  const auto assets = one_mesh_assets(glm::vec3(0.8f), [](scene::Mesh& m) { floor_grid(m); });
  const glm::vec3 sky(0.7f, 1.1f, 2.3f);
  for (int bands : {3, 5}) {
    const std::vector<glm::dvec3> env = constant_sky(sky, bands);
    for (PrtKind kind : {PrtKind::kUnshadowed, PrtKind::kShadowed, PrtKind::kInterreflected}) {
      const PrtTransfer t =
          compute_prt_transfer(assets, one_instance_frame(), settings(kind, bands));
      for (uint32_t v = 0; v < t.vertex_count(); ++v) {
        const glm::dvec3 e = t.irradiance(v, env);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(e[c], kPi * sky[c], 1e-5 * kPi * sky[c]);
      }
    }
  }
}

TEST(PrtTransfer, WallHidingHalfTheSkyLeavesHalfTheLobe) {
  // A small floor patch at the origin facing +y and a huge wall x = 0.05 facing it: every
  // direction with x > 0 is blocked, so T = the projection of max(0, y) [x < 0] (reference: a
  // fine product quadrature). The shadow edge crosses the whole hemisphere, the worst case for
  // the Hammersley set: measured worst coefficient errors 0.016, 0.0053, 0.0016 at 256, 1024,
  // 4096 directions (about N^-0.85; the full lobe's DC term is 0.886).
  const auto assets = one_mesh_assets(glm::vec3(0.8f), [](scene::Mesh& m) {
    add_grid(m, {-0.01f, 0, 0.01f}, {0.02f, 0, 0}, {0, 0, -0.02f}, 1);
    add_grid(m, {0.05f, -1, 1000}, {0, 0, -2000}, {0, 2000, 0}, 1);  // faces -x
  });
  const std::vector<double> want = shading::sh_project(
      [](glm::dvec3 d) { return d.x < 0.0 ? std::max(0.0, d.y) : 0.0; }, 5, 256, 1024);
  EXPECT_NEAR(want[0], std::sqrt(kPi) / 4.0, 1e-4);  // half the lobe's DC: the reference holds
  for (auto [samples, tolerance, dc_tolerance] :
       {std::tuple{1024u, 8e-3, 1.5e-3}, std::tuple{4096u, 2.5e-3, 4e-4}}) {
    const PrtTransfer t = compute_prt_transfer(assets, one_instance_frame(),
                                               settings(PrtKind::kShadowed, 5, samples));
    for (uint32_t v = 0; v < 4; ++v) {  // the floor patch's vertices
      EXPECT_NEAR(t.at(v, 0)[0], want[0], dc_tolerance) << samples << " vertex " << v;
      for (int i = 1; i < t.count(); ++i)
        EXPECT_NEAR(t.at(v, 0)[i], want[size_t(i)], tolerance)
            << samples << " vertex " << v << " coef " << i;
    }
  }
}

TEST(PrtTransfer, OpaqueRoofHidesTheSky) {
  // Floor [-1, 1]^2, roof 200 x 200 at 0.05 above it: a floor vertex sees sky only below
  // 0.05 / 99 rad of the horizon, a cosine-weighted share under 1e-6.
  const auto assets = one_mesh_assets(glm::vec3(0.8f), [](scene::Mesh& m) {
    floor_grid(m);
    add_grid(m, {-100, 0.05f, -100}, {200, 0, 0}, {0, 0, 200}, 1);  // faces -y
  });
  const std::vector<glm::dvec3> env = constant_sky(glm::vec3(1.0f), 5);
  const PrtTransfer t =
      compute_prt_transfer(assets, one_instance_frame(), settings(PrtKind::kShadowed, 5, 512));
  for (uint32_t v = 0; v < 25; ++v) {
    EXPECT_NEAR(t.at(v, 0)[0], 0.0, 1e-6) << v;  // DC: exact per direction (header)
    // Higher terms: what the Hammersley set misses of the lobe itself (at most 0.0039 here).
    for (int i = 1; i < t.count(); ++i) EXPECT_NEAR(t.at(v, 0)[i], 0.0, 6e-3) << v << " " << i;
    EXPECT_LT(t.irradiance(v, env).x, 1e-5);
  }
}

TEST(PrtTransfer, InterreflectionAddsLightAndConvergesWithBounces) {
  // An open box of albedo (0.9, 0.6, 0.3): every bounce adds to every channel's DC term, and
  // each addition is at most 0.9 (the highest albedo) of the one before in the max norm (a
  // bounce row sums albedo x the share of rays that hit, at most 0.9); red gains the most.
  const auto assets =
      one_mesh_assets(glm::vec3(0.9f, 0.6f, 0.3f), [](scene::Mesh& m) { open_box(m, 4); });
  const auto frame = one_instance_frame();
  const PrtTransfer shadowed = compute_prt_transfer(assets, frame, settings(PrtKind::kShadowed));
  std::vector<PrtTransfer> runs;
  for (uint32_t b = 0; b <= 6; ++b)
    runs.push_back(
        compute_prt_transfer(assets, frame, settings(PrtKind::kInterreflected, 3, 256, b)));
  ASSERT_EQ(runs[0].channels, 3u);
  for (uint32_t v = 0; v < shadowed.vertex_count(); ++v)
    for (uint32_t c = 0; c < 3; ++c)
      EXPECT_EQ(runs[0].at(v, c)[0], shadowed.at(v, 0)[0]) << "0 bounces = shadowed";
  // What the bounces started from is kept beside them (a shader takes the bounces alone):
  // the shadowed kind's transfer; with no bounces it is the transfer itself, not kept again.
  EXPECT_TRUE(runs[0].shadowed.empty());
  for (size_t r = 1; r < runs.size(); ++r) {
    ASSERT_EQ(runs[r].shadowed.size(), shadowed.coefficients.size());
    for (size_t i = 0; i < shadowed.coefficients.size(); ++i)
      ASSERT_NEAR(runs[r].shadowed[i], shadowed.coefficients[i], 1e-6) << "coefficient " << i;
  }
  double prev_step = 0.0;
  for (size_t r = 1; r < runs.size(); ++r) {
    double step = 0.0;
    for (uint32_t v = 0; v < shadowed.vertex_count(); ++v) {
      for (uint32_t c = 0; c < 3; ++c) {
        ASSERT_GE(runs[r].at(v, c)[0], runs[r - 1].at(v, c)[0]) << "bounces " << r << " v " << v;
        step = std::max(step, double(runs[r].at(v, c)[0] - runs[r - 1].at(v, c)[0]));
      }
      EXPECT_GT(runs[r].at(v, 0)[0], runs[r].at(v, 2)[0]) << "red gains more than blue";
    }
    EXPECT_GT(step, 0.0) << "bounces " << r;
    if (r >= 2) {
      EXPECT_LE(step, 0.9 * prev_step * (1.0 + 1e-5)) << "bounces " << r;
    }
    prev_step = step;
  }
}

TEST(PrtTransfer, WhiteFurnaceConvexSphere) {
  // A white sphere under a constant sky: nothing in the way, radiance albedo / pi E = L.
  const auto assets = one_mesh_assets(glm::vec3(1.0f), [](scene::Mesh& m) { uv_sphere(m); });
  const glm::vec3 sky(0.5f, 1.0f, 2.0f);
  const std::vector<glm::dvec3> env = constant_sky(sky, 3);
  for (PrtKind kind : {PrtKind::kShadowed, PrtKind::kInterreflected}) {
    const PrtTransfer t =
        compute_prt_transfer(assets, one_instance_frame(), settings(kind, 3, 256, 4));
    for (uint32_t v = 0; v < t.vertex_count(); ++v) {
      const glm::dvec3 radiance = t.irradiance(v, env) / kPi;  // albedo 1
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(radiance[c], sky[c], 1e-5 * sky[c]) << v;
    }
  }
}

TEST(PrtTransfer, WhiteFurnaceOpenBoxConvergesToTheSky) {
  // Albedo 1 under a constant sky: with every bounce the radiance inside tends to the sky's
  // (light is neither lost nor made). Shadowed alone is far darker in the corners. Exact in the
  // limit, not only in expectation: a blocked direction takes pi / N of the DC term away and
  // its hit gives 1 / N of an irradiance pi L back (measured: within 1.6e-5 after 64 bounces).
  const auto assets = one_mesh_assets(glm::vec3(1.0f), [](scene::Mesh& m) { open_box(m, 4); });
  const glm::vec3 sky(1.0f, 0.5f, 0.25f);
  const std::vector<glm::dvec3> env = constant_sky(sky, 3);
  const auto frame = one_instance_frame();
  const PrtTransfer shadowed = compute_prt_transfer(assets, frame, settings(PrtKind::kShadowed));
  const PrtTransfer full =
      compute_prt_transfer(assets, frame, settings(PrtKind::kInterreflected, 3, 256, 64));
  double darkest = 1.0;
  for (uint32_t v = 0; v < full.vertex_count(); ++v) {
    darkest = std::min(darkest, shadowed.irradiance(v, env).x / (kPi * sky.x));
    const glm::dvec3 radiance = full.irradiance(v, env) / kPi;
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(radiance[c], sky[c], 1e-4 * sky[c]) << v << " " << c;
  }
  EXPECT_LT(darkest, 0.5);
}

TEST(PrtTransfer, SameResultForAnyThreadCount) {
  const auto assets =
      one_mesh_assets(glm::vec3(0.9f, 0.5f, 0.2f), [](scene::Mesh& m) { open_box(m, 5); });
  PrtSettings s = settings(PrtKind::kInterreflected, 5, 128, 3);
  s.threads = 1;
  const PrtTransfer one = compute_prt_transfer(assets, one_instance_frame(), s);
  s.threads = 3;
  const PrtTransfer three = compute_prt_transfer(assets, one_instance_frame(), s);
  ASSERT_EQ(one.coefficients.size(), three.coefficients.size());
  EXPECT_EQ(std::memcmp(one.coefficients.data(), three.coefficients.data(),
                        one.coefficients.size() * sizeof(float)),
            0);
}

TEST(PrtTransfer, RetracingBouncesEqualsKeepingTheMatrix) {
  // Without memory for the bounce matrix every bounce traces again: the same sums, same bits,
  // the suns' traced bounces included; tracing suns leaves the SH coefficients as they were.
  const auto assets =
      one_mesh_assets(glm::vec3(0.9f, 0.5f, 0.2f), [](scene::Mesh& m) { open_box(m, 4); });
  PrtSettings s = settings(PrtKind::kInterreflected, 3, 128, 3);
  const PrtTransfer no_suns = compute_prt_transfer(assets, one_instance_frame(), s);
  s.sun_directions = {{0.3f, 1.0f, 0.2f}, {-0.2f, 0.5f, 0.9f}};
  const PrtTransfer kept = compute_prt_transfer(assets, one_instance_frame(), s);
  s.bounce_matrix_mb = 0;
  const PrtTransfer retraced = compute_prt_transfer(assets, one_instance_frame(), s);
  EXPECT_EQ(kept.coefficients, retraced.coefficients);
  EXPECT_EQ(kept.sun_bounce, retraced.sun_bounce);
  EXPECT_EQ(kept.coefficients, no_suns.coefficients);
  EXPECT_EQ(kept.shadowed, no_suns.shadowed);
  ASSERT_EQ(kept.sun_bounce.size(), size_t(kept.vertex_count()) * 2 * 3);
  EXPECT_GT(*std::max_element(kept.sun_bounce.begin(), kept.sun_bounce.end()), 0.0f);
}

TEST(PrtTransfer, SunBounceOffAWideFloorIsItsViewFactor) {
  // A floor 200 m wide (grey albedo 0.8, vertices every 25 m) and a 2 m wall facing +z that
  // stands between floor vertices, so each floor vertex sees the sun at elevation 30: irradiance
  // sin 30 = 0.5 per unit sun. One bounce brings the wall 0.8 x 0.5 x F, F the share of its
  // cosine-weighted rays that meet the floor: 1/2 less those that pass above the far edge
  // 87.5 m away (at most 1.5 % of the hemisphere for h <= 2 m): 0.2, less at most 1.5 %
  // (measured 0.1996 at 1024 directions). The same sun behind the wall
  // leaves the wall unlit but the floor in front as lit: the same bounce, to the bit.
  const auto assets = one_mesh_assets(glm::vec3(0.8f), [](scene::Mesh& m) {
    add_grid(m, {-100, 0, 100}, {200, 0, 0}, {0, 0, -200}, 8);   // floor, +y
    add_grid(m, {-1, 0, 12.5f}, {2, 0, 0}, {0, 2, 0}, 4);       // wall, +z
  });
  const uint32_t floor_vertices = 81, wall_first = floor_vertices;
  PrtSettings s = settings(PrtKind::kInterreflected, 3, 1024, 1);
  const float c30 = std::sqrt(3.0f) / 2.0f;
  s.sun_directions = {{0.0f, 0.5f, c30}, {0.0f, 0.5f, -c30}};  // in front, behind
  const PrtTransfer t = compute_prt_transfer(assets, one_instance_frame(), s);
  ASSERT_EQ(t.sun_directions.size(), 2u);
  const auto bounce = [&](uint32_t v, uint32_t sun, uint32_t c) {
    return t.sun_bounce[(size_t(v) * 2 + sun) * 3 + c];
  };
  for (uint32_t v = wall_first; v < t.vertex_count(); ++v) {
    const float h = t.positions[v].y;
    if (h <= 0.0f || h >= 2.0f || std::abs(t.positions[v].x) >= 1.0f) continue;  // inner ones
    for (uint32_t c = 0; c < 3; ++c) {
      EXPECT_GT(bounce(v, 0, c), 0.2f * 0.975f) << "wall vertex at height " << h;
      EXPECT_LT(bounce(v, 0, c), 0.2f * 1.005f) << "wall vertex at height " << h;
      EXPECT_EQ(bounce(v, 1, c), bounce(v, 0, c)) << "sun behind the wall, height " << h;
    }
  }
  // The floor at one bounce: only the wall's light, which is far from every floor vertex
  // (12.5 m or more from a 2 x 2 m wall: under 1e-3), and none from the unlit back.
  for (uint32_t v = 0; v < floor_vertices; ++v)
    for (uint32_t c = 0; c < 3; ++c) {
      EXPECT_LT(bounce(v, 0, c), 1e-3f) << v;
      EXPECT_GE(bounce(v, 0, c), 0.0f) << v;
    }
}

TEST(PrtTransfer, GlowCellsAreLitLikeSunsWithTheirFirstVertex) {
  // One glow cell of irradiance (1, 0.5, 0.25) from a sun's direction: each vertex's glow is the
  // cell's light on it (cosine and shadow ray: a sun's direct light) plus that sun's traced
  // bounce, per channel in the cell's colour; two cells add up; a shadowed transfer has the
  // direct light alone; the SH coefficients do not change.
  const auto assets =
      one_mesh_assets(glm::vec3(0.9f, 0.5f, 0.2f), [](scene::Mesh& m) { open_box(m, 4); });
  const glm::vec3 d = glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f));
  const glm::vec3 e(1.0f, 0.5f, 0.25f);
  PrtSettings s = settings(PrtKind::kInterreflected, 3, 128, 3);
  s.sun_directions = {d};
  const PrtTransfer suns = compute_prt_transfer(assets, one_instance_frame(), s);
  s.glow_cells = {{d, e}};
  const PrtTransfer glow = compute_prt_transfer(assets, one_instance_frame(), s);
  EXPECT_EQ(glow.coefficients, suns.coefficients);
  EXPECT_EQ(glow.sun_bounce, suns.sun_bounce);
  ASSERT_EQ(glow.glow_cells.size(), 1u);
  ASSERT_EQ(glow.glow.size(), size_t(glow.vertex_count()) * 3);
  s.kind = PrtKind::kShadowed;
  const PrtTransfer direct = compute_prt_transfer(assets, one_instance_frame(), s);
  ASSERT_EQ(direct.glow.size(), glow.glow.size());
  s.kind = PrtKind::kInterreflected;
  s.glow_cells = {{d, e * 0.75f}, {d, e * 0.25f}};
  const PrtTransfer halves = compute_prt_transfer(assets, one_instance_frame(), s);
  size_t lit = 0, bounced = 0;
  for (uint32_t v = 0; v < glow.vertex_count(); ++v) {
    const float cosine = glm::dot(glm::normalize(glow.normals[v]), d);
    const float light = direct.glow[size_t(v) * 3] / e[0];  // 0 (hidden) or the cosine
    if (light > 0.0f) {
      EXPECT_NEAR(light, cosine, 1e-5f) << v;
      ++lit;
    }
    for (int c = 0; c < 3; ++c) {
      const size_t i = size_t(v) * 3 + size_t(c);
      EXPECT_NEAR(direct.glow[i], e[c] * light, 1e-6f) << v;
      const float want = e[c] * (light + suns.sun_bounce[i]);
      EXPECT_NEAR(glow.glow[i], want, 1e-5f * want + 1e-7f) << v << " channel " << c;
      EXPECT_NEAR(halves.glow[i], glow.glow[i], 1e-5f * glow.glow[i] + 1e-7f) << v;
    }
    if (suns.sun_bounce[size_t(v) * 3] > 0.0f) ++bounced;
  }
  EXPECT_GT(lit, 0u);
  EXPECT_LT(lit, glow.vertex_count());  // the box hides the cell from some vertices
  EXPECT_GT(bounced, 0u);
  // An unshadowed transfer traces nothing: no glow.
  s.kind = PrtKind::kUnshadowed;
  EXPECT_TRUE(compute_prt_transfer(assets, one_instance_frame(), s).glow.empty());
}

TEST(PrtTransfer, InstancesLayVerticesOutInFrameOrderAndSkipSpheres) {
  const auto assets = one_mesh_assets(glm::vec3(0.8f), [](scene::Mesh& m) { floor_grid(m, 2); });
  scene::FrameScene frame = one_instance_frame();
  scene::MeshInstance above;
  above.model = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.2f, 0));
  frame.instances.push_back(above);
  const PrtTransfer t = compute_prt_transfer(assets, frame, settings(PrtKind::kShadowed));
  ASSERT_EQ(t.instances.size(), 2u);
  EXPECT_EQ(t.instances[1].first, 9u);
  EXPECT_EQ(t.instances[1].count, 9u);
  EXPECT_FLOAT_EQ(t.positions[9 + 4].y, 0.2f);
  // The upper floor (0.2 above, facing up) hides most of the lower floor's sky, not its own.
  const std::vector<double> up = lobe({0, 1, 0}, 3);
  EXPECT_LT(t.at(4, 0)[0], 0.2 * up[0]);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(t.at(9 + 4, 0)[i], up[size_t(i)], 1e-6);
  // A sphere between them changes nothing: spheres move, PRT skips them.
  frame.spheres.push_back(scene::Sphere{});
  frame.spheres.back().center = glm::vec3(0, 0.1f, 0);
  frame.spheres.back().radius = 0.05f;
  const PrtTransfer with_sphere = compute_prt_transfer(assets, frame, settings(PrtKind::kShadowed));
  EXPECT_EQ(with_sphere.coefficients, t.coefficients);
}

TEST(PrtTransfer, ReportsProgressUpToOne) {
  const auto assets = one_mesh_assets(glm::vec3(0.8f), [](scene::Mesh& m) { open_box(m, 3); });
  std::vector<double> seen;
  compute_prt_transfer(assets, one_instance_frame(), settings(PrtKind::kInterreflected, 3, 64, 2),
                       [&](double f) { seen.push_back(f); });
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_EQ(seen.back(), 1.0);
}

TEST(PrtTransfer, StopsWhenCancelled) {
  const auto assets = one_mesh_assets(glm::vec3(0.8f), [](scene::Mesh& m) { open_box(m, 3); });
  const std::atomic<bool> cancel{true};
  EXPECT_THROW(compute_prt_transfer(assets, one_instance_frame(), settings(PrtKind::kShadowed),
                                    {}, &cancel),
               PrtCancelled);
}

TEST(PrtTransfer, RefusesBadSettings) {
  const auto assets = one_mesh_assets(glm::vec3(0.8f), [](scene::Mesh& m) { floor_grid(m); });
  EXPECT_THROW(compute_prt_transfer(assets, one_instance_frame(), settings(PrtKind::kShadowed, 4)),
               std::invalid_argument);
  EXPECT_THROW(
      compute_prt_transfer(assets, one_instance_frame(), settings(PrtKind::kShadowed, 3, 0)),
      std::invalid_argument);
  PrtSettings suns = settings(PrtKind::kInterreflected, 3, 16, 1);
  suns.sun_directions.assign(kPrtMaxSuns + 1, glm::vec3(0.0f, 1.0f, 0.0f));
  EXPECT_THROW(compute_prt_transfer(assets, one_instance_frame(), suns), std::invalid_argument);
  suns.sun_directions = {glm::vec3(0.0f)};
  EXPECT_THROW(compute_prt_transfer(assets, one_instance_frame(), suns), std::invalid_argument);
  PrtSettings glow = settings(PrtKind::kShadowed, 3, 16);
  glow.glow_cells.assign(scene::kMaxGlowCells + 1, {glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(1.0f)});
  EXPECT_THROW(compute_prt_transfer(assets, one_instance_frame(), glow), std::invalid_argument);
  glow.glow_cells = {{glm::vec3(0.0f), glm::vec3(1.0f)}};
  EXPECT_THROW(compute_prt_transfer(assets, one_instance_frame(), glow), std::invalid_argument);
}

}  // namespace
}  // namespace rp::truth
