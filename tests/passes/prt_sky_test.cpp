// The PRT sky pass (passes/prt_sky.h, kernels/prt.cl) against a plain C++ reference: the
// transfer of the visibility buffer's triangle interpolated by its barycentrics, dotted with
// the environment's coefficients. The reference projects the turned map itself
// (sh_project_environment at the frame's turn and strength), so the pass's per-frame rotation
// (sh_turn_environment) is checked too: the turns are whole numbers of texel columns, where
// rotating and re-projecting agree to rounding; the second frame turns the sky again.
//
// With a shadowed transfer beside the interreflected one and an environment whose suns were
// taken out, the pass gathers the whole map and takes the suns' shadowed light away:
// E = T . L(map) - T_shadowed . L(suns); the reference projects the suns' own map (the test
// map's bright texel alone), not the difference of two projections the pass computes. A
// directional light's bounce is gathered the same way, its radiance pi I delta(w + direction)
// with coefficients pi I Y(-direction) (a point light's is not: it has no distant radiance).
//
// Where the transfer traced the directional lights' bounces (PrtShading::sun_bounce) and every
// directional light of the frame shines from a traced direction, the pass gathers the residual
// map alone and adds each sun's traced bounce times its intensity: E / pi = T . L(residual) / pi
// + sum_j I_j B_j. A light that moved off its traced direction sends the pass back to the SH
// formula above (the third frame).
//
// With a traced glow (PrtShading::glow, for the environment's glow turned as the first frame
// turns the map) the glow's texels leave the gathered map and the glow's traced light is added:
// E / pi += strength / pi * G. The second frame turns the map away from the glow's turn (the glow
// goes back into the SH sky), the third turns it back while the moved light sends the suns to
// the SH formula (the glow is traced again beside it).
//
// Tolerance: 1e-4 of the largest value plus 1e-4 relative (float sums of 9 or 25 products of
// numbers near 1, and the two coefficient paths' rounding).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "cl/error.h"
#include "passes/prt_sky.h"
#include "passes/reference_raster.h"
#include "passes/visibility.h"
#include "render/gpu_scene.h"
#include "shading/spherical_harmonics.h"
#include "support/cl_fixture.h"

namespace rp::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A smooth, coloured 16 x 8 map (no texel is negative).
std::shared_ptr<scene::EnvironmentMap> test_map() {
  auto map = std::make_shared<scene::EnvironmentMap>();
  map->width = 16;
  map->height = 8;
  for (int y = 0; y < map->height; ++y)
    for (int x = 0; x < map->width; ++x) {
      const double u = (x + 0.5) / map->width, v = (y + 0.5) / map->height;
      map->rgb.push_back(float(1.0 + 0.8 * std::cos(2 * kPi * u) * std::sin(kPi * v)));
      map->rgb.push_back(float(0.6 + 0.5 * std::cos(kPi * v)));
      map->rgb.push_back(float(0.4 + 0.3 * std::sin(4 * kPi * u) + (y == 1 && x == 3 ? 4.0 : 0.0)));
    }
  return map;
}

struct Readback {
  std::vector<glm::uvec2> ids;
  std::vector<glm::vec2> bary;
  std::vector<glm::vec4> out;
};

// The test map without its bright texel (the residual), and that texel alone (the suns).
std::shared_ptr<scene::EnvironmentMap> without_spike(const scene::EnvironmentMap& map,
                                                     bool spike_only) {
  auto out = std::make_shared<scene::EnvironmentMap>(map);
  for (size_t i = 0; i < out->rgb.size(); ++i) {
    const bool spike = i == (size_t(1) * size_t(map.width) + 3) * 3 + 2;
    const float excess = spike ? 4.0f : 0.0f;
    out->rgb[i] = spike_only ? excess : out->rgb[i] - excess;
  }
  return out;
}

// Three texels of the residual around the sun's texel: a glow.
std::shared_ptr<scene::EnvironmentGlow> glow_of(const scene::EnvironmentMap& residual) {
  auto glow = std::make_shared<scene::EnvironmentGlow>();
  glow->width = residual.width;
  glow->height = residual.height;
  for (const uint32_t texel : {uint32_t(1 * residual.width + 3), uint32_t(1 * residual.width + 4),
                               uint32_t(2 * residual.width + 3)}) {
    glow->texels.push_back(texel);
    const float* t = &residual.rgb[size_t(texel) * 3];
    glow->radiance.emplace_back(t[0], t[1], t[2]);
  }
  glow->cells = {{glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(1.0f)}};  // the pass reads none
  return glow;
}

// The glow's texels as a map, zero elsewhere.
std::shared_ptr<scene::EnvironmentMap> glow_map(const scene::EnvironmentGlow& glow) {
  auto map = std::make_shared<scene::EnvironmentMap>();
  map->width = glow.width;
  map->height = glow.height;
  map->rgb.assign(size_t(glow.width) * size_t(glow.height) * 3, 0.0f);
  for (size_t k = 0; k < glow.texels.size(); ++k)
    for (int c = 0; c < 3; ++c)
      map->rgb[size_t(glow.texels[k]) * 3 + size_t(c)] = glow.radiance[k][c];
  return map;
}

enum class Suns { kNone, kShadowedNoSuns, kShadowedWithSuns, kTraced, kTracedGlow };

void check_pass(int bands, uint32_t channels, Suns suns = Suns::kNone) {
  // Mesh 0: a quad of two triangles; mesh 1: one triangle. Instances: the quad, the triangle in
  // front of it, a second quad to the right, and a third quad without transfer.
  const std::vector<glm::vec3> quad = {{-0.5f, -0.5f, 0.0f}, {0.5f, -0.5f, 0.0f},
                                       {0.5f, 0.5f, 0.0f}, {-0.5f, 0.5f, 0.0f}};
  const std::vector<glm::vec3> tri = {{-0.3f, -0.2f, 0.2f}, {0.3f, -0.3f, 0.2f},
                                      {0.0f, 0.35f, 0.2f}};
  scene::SceneAssets assets = make_test_assets(
      {make_test_mesh(quad, {{0, 1, 2}, {0, 2, 3}}), make_test_mesh(tri, {{0, 1, 2}})});
  scene::FrameScene frame = make_test_frame();
  scene::MeshInstance a, b, right, d;
  a.model = glm::translate(glm::mat4(1.0f), glm::vec3(-0.4f, 0.0f, 0.0f));
  b.mesh = 1;
  right.model = glm::translate(glm::mat4(1.0f), glm::vec3(0.6f, 0.1f, -0.1f));
  d.model = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -0.75f, 0.05f));
  frame.instances = {a, b, right, d};
  for (scene::MeshInstance& i : frame.instances) i.prev_model = i.model;
  frame.environment.map = test_map();
  frame.environment.strength = 1.5f;
  const bool traced_suns = suns == Suns::kTraced || suns == Suns::kTracedGlow;
  if (suns == Suns::kShadowedWithSuns || traced_suns)
    frame.environment.residual = without_spike(*frame.environment.map, false);
  if (suns == Suns::kTracedGlow) frame.environment.glow = glow_of(*frame.environment.residual);
  // a directional light (its bounce gathered with a shadowed transfer) and a point light (never);
  // traced: the map's sun as a directional light too (its direction the pass only compares)
  std::vector<scene::PunctualLight> lights(traced_suns ? 3 : 2);
  lights[0].type = scene::LightType::kDirectional;
  lights[0].direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
  lights[0].intensity = {2.0f, 1.5f, 0.5f};
  lights[1].position = {0.0f, 1.0f, 0.0f};
  lights[1].intensity = glm::vec3(50.0f);
  if (traced_suns) {
    lights[2].type = scene::LightType::kDirectional;
    lights[2].direction = glm::normalize(glm::vec3(-0.5f, -0.6f, 0.2f));
    lights[2].intensity = {0.7f, 0.9f, 3.0f};
    lights[2].in_environment = true;
  }

  // Transfer: random numbers per PRT vertex (instance a: 0..3, b: 4..6, c: 7..10).
  passes::PrtShading prt;
  prt.bands = bands;
  prt.channels = channels;
  const int count = bands * bands;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> t(-0.3f, 1.0f);
  prt.coefficients.resize(size_t(11) * channels * size_t(count));
  for (float& v : prt.coefficients) v = t(rng);
  if (suns != Suns::kNone) {
    prt.shadowed.resize(size_t(11) * size_t(count));
    for (float& v : prt.shadowed) v = t(rng);
  }
  prt.instances = {{0, 0}, {1, 4}, {0, 7}, {0, passes::PrtShading::kNoTransfer}};
  if (traced_suns) {  // traced in the opposite order to the lights'
    prt.sun_directions = {-lights[2].direction, -lights[0].direction};
    prt.sun_bounce.resize(size_t(11) * 2 * 3);
    for (float& v : prt.sun_bounce) v = std::abs(t(rng));
  }
  std::vector<float> turns = {3 * 360.0f / 16.0f, -5 * 360.0f / 16.0f};
  if (traced_suns) turns.push_back(suns == Suns::kTracedGlow ? turns[0] : 2 * 360.0f / 16.0f);
  if (suns == Suns::kTracedGlow) {
    prt.glow.resize(size_t(11) * 3);
    for (float& v : prt.glow) v = std::abs(t(rng));
    prt.glow_source = frame.environment.glow;
    prt.glow_turn_deg = turns[0];
  }

  const uint32_t w = 96, h = 80;
  render::GpuScene gpu(context().context, context().queue, assets);
  gpu.update(frame, w, h, 64);
  render::VisibilityBuffer vis;
  vis.resize(context().context, w, h);
  rp::cl::Profiler profiler(context().queue);
  passes::VisibilityPass visibility(context(), programs());
  visibility.render(profiler, gpu, vis);
  passes::PrtSkyPass pass(context(), programs(), gpu, prt);
  EXPECT_EQ(pass.carries_suns_bounce(), suns != Suns::kNone);
  // Two frames of one pass: the second turns the sky further (a whole number of columns
  // again), so the vertices' sky light must be recomputed, not reused.
  for (size_t frame_number = 0; frame_number < turns.size(); ++frame_number) {
    const float turn = turns[frame_number];
    // Traced: the third frame moves the directional light off its traced direction.
    const bool moved = frame_number == 2;
    if (moved) lights[0].direction = glm::normalize(glm::vec3(0.35f, -1.0f, -0.4f));
    const bool traced = traced_suns && !moved;
    const bool glow = suns == Suns::kTracedGlow && turn == prt.glow_turn_deg;
    frame.environment.rotate_deg = turn;
    pass.run(profiler, gpu, vis, frame.environment, lights);
    EXPECT_EQ(pass.suns_traced(), traced) << "frame " << frame_number;
    EXPECT_EQ(pass.glow_traced(), glow) << "frame " << frame_number;
    profiler.collect();

    Readback r;
    const size_t n = size_t(w) * h;
    r.ids.resize(n);
    r.bary.resize(n);
    r.out.resize(n);
    ::cl::CommandQueue& q = context().queue;
    q.enqueueReadBuffer(vis.ids, CL_TRUE, 0, n * 8, r.ids.data());
    q.enqueueReadBuffer(vis.bary, CL_TRUE, 0, n * 8, r.bary.data());
    q.enqueueReadBuffer(pass.output(), CL_TRUE, 0, n * 16, r.out.data());

    const std::vector<glm::dvec3> env = shading::sh_project_environment(frame.environment, bands);
    std::vector<glm::dvec3> sun_env(env.size(), glm::dvec3(0.0));
    if (suns == Suns::kShadowedWithSuns || traced_suns) {
      scene::Environment alone = frame.environment;
      alone.map = without_spike(*frame.environment.map, true);
      alone.residual = nullptr;
      sun_env = shading::sh_project_environment(alone, bands);
    }
    std::vector<glm::dvec3> light_env = env;  // the directional light's added where gathered
    if (traced) {  // the residual alone; the suns' traced bounces are added per vertex below
      scene::Environment residual = frame.environment;
      residual.map = frame.environment.residual;
      residual.residual = nullptr;
      light_env = shading::sh_project_environment(residual, bands);
    } else if (suns != Suns::kNone) {
      double y[shading::kShMaxCount];
      shading::sh_eval(-glm::dvec3(lights[0].direction), bands, y);
      for (size_t i = 0; i < env.size(); ++i) {
        light_env[i] += kPi * glm::dvec3(lights[0].intensity) * y[i];
        sun_env[i] += kPi * glm::dvec3(lights[0].intensity) * y[i];
      }
    }
    if (glow) {  // the glow's texels leave the gathered sky (either formula)
      scene::Environment alone = frame.environment;
      alone.map = glow_map(*frame.environment.glow);
      alone.residual = nullptr;
      const std::vector<glm::dvec3> glow_env = shading::sh_project_environment(alone, bands);
      for (size_t i = 0; i < env.size(); ++i) light_env[i] -= glow_env[i];
    }
    // Vertex indices of each instance's triangles, local to its mesh.
    const auto local = [&](uint32_t instance, uint32_t primitive) {
      return assets.meshes[frame.instances[instance].mesh].triangles.at(primitive);
    };
    size_t shaded[4] = {0, 0, 0, 0}, bad = 0;
    for (size_t p = 0; p < n; ++p) {
      const glm::uvec2 id = r.ids[p];
      if (id.x == 0xFFFFFFFFu || id.x == 3u) {
        EXPECT_EQ(r.out[p], glm::vec4(0.0f)) << "pixel " << p << " without transfer";
        if (id.x == 3u) ++shaded[3];
        continue;
      }
      ASSERT_LT(id.x, 3u);
      ++shaded[id.x];
      const glm::uvec3 v = local(id.x, id.y);
      const uint32_t first = prt.instances[id.x].first;
      const double b1 = r.bary[p].x, b2 = r.bary[p].y, b0 = 1.0 - b1 - b2;
      glm::dvec3 e(0.0);
      for (int c = 0; c < 3; ++c) {
        const uint32_t ch = channels == 1 ? 0u : uint32_t(c);
        for (int i = 0; i < count; ++i) {
          const auto at = [&](uint32_t vertex) {
            return double(prt.coefficients[(size_t(first + vertex) * channels + ch) * count + i]);
          };
          e[c] += (b0 * at(v.x) + b1 * at(v.y) + b2 * at(v.z)) * light_env[size_t(i)][c];
          if (prt.shadowed.empty() || traced) continue;
          const auto at0 = [&](uint32_t vertex) {
            return double(prt.shadowed[size_t(first + vertex) * count + i]);
          };
          e[c] -= (b0 * at0(v.x) + b1 * at0(v.y) + b2 * at0(v.z)) * sun_env[size_t(i)][c];
        }
      }
      e /= kPi;
      if (traced) {
        const glm::vec3 intensity[2] = {lights[2].intensity, lights[0].intensity};
        for (uint32_t j = 0; j < 2; ++j)
          for (int c = 0; c < 3; ++c) {
            const auto at = [&](uint32_t vertex) {
              return double(prt.sun_bounce[(size_t(first + vertex) * 2 + j) * 3 + size_t(c)]);
            };
            e[c] += (b0 * at(v.x) + b1 * at(v.y) + b2 * at(v.z)) * double(intensity[j][c]);
          }
      }
      if (glow)
        for (int c = 0; c < 3; ++c) {
          const auto at = [&](uint32_t vertex) {
            return double(prt.glow[size_t(first + vertex) * 3 + size_t(c)]);
          };
          e[c] += (b0 * at(v.x) + b1 * at(v.y) + b2 * at(v.z)) *
                  double(frame.environment.strength) / kPi;
        }
      e = glm::max(e, glm::dvec3(0.0));
      for (int c = 0; c < 3; ++c)
        if (!(std::abs(r.out[p][c] - e[c]) <= 1e-4 + 1e-4 * std::abs(e[c])) && bad++ < 5)
          ADD_FAILURE() << "pixel " << p << " channel " << c << ": " << r.out[p][c] << " vs "
                        << e[c];
      EXPECT_EQ(r.out[p].w, 1.0f);
    }
    EXPECT_EQ(bad, 0u) << "turn " << turn;
    for (int i = 0; i < 4; ++i) EXPECT_GT(shaded[i], 100u) << "instance " << i << " barely seen";
  }
}

TEST(PrtSkyPass, NineGreyCoefficientsMatchTheReference) { check_pass(3, 1); }
TEST(PrtSkyPass, TwentyFiveRgbCoefficientsMatchTheReference) { check_pass(5, 3); }
TEST(PrtSkyPass, ShadowedTransferGathersADirectionalLightsBounce) {
  check_pass(5, 3, Suns::kShadowedNoSuns);
}
TEST(PrtSkyPass, TracedSunsAddTheirBouncesPerVertexUntilALightMoves) {
  check_pass(5, 3, Suns::kTraced);
}
TEST(PrtSkyPass, TracedGlowLeavesTheShSkyWhileTheMapKeepsItsTurn) {
  check_pass(5, 3, Suns::kTracedGlow);
}
TEST(PrtSkyPass, TheSunsBouncesAreGatheredTheirFirstVertexIsNot) {
  check_pass(3, 3, Suns::kShadowedWithSuns);
  check_pass(5, 3, Suns::kShadowedWithSuns);
}

// Where the transfer gathers the suns' bounces the GI volume must not carry their light as
// well: the scene marks the environment's suns and the directional lights
// RP_LIGHT_NOT_IN_VOXELS (kernels/voxelize.cl skips them), not point or spot lights, and only
// when told.
TEST(PrtSkyPass, TheGiVolumeLeavesTheSunsOutOnlyWhenThePassGathersThem) {
  scene::SceneAssets assets =
      make_test_assets({make_test_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}})});
  scene::FrameScene frame = make_test_frame();
  frame.instances = {scene::MeshInstance{}};
  scene::PunctualLight lamp, spot, directional, sun;
  lamp.position = {0.0f, 1.0f, 0.0f};
  spot.type = scene::LightType::kSpot;
  spot.position = {0.0f, 1.0f, 0.0f};
  directional.type = sun.type = scene::LightType::kDirectional;
  directional.direction = sun.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
  sun.in_environment = true;
  frame.lights = {lamp, directional, spot, sun};
  render::GpuScene gpu(context().context, context().queue, assets);
  const auto flags = [&](size_t light) { return gpu.constants.punctual[light].flags; };
  gpu.update(frame, 8, 8, 64);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(flags(i), 0u) << i;
  gpu.set_suns_in_voxels(false);
  gpu.update(frame, 8, 8, 64);
  EXPECT_EQ(flags(0), 0u);
  EXPECT_EQ(flags(1), uint32_t(RP_LIGHT_NOT_IN_VOXELS));
  EXPECT_EQ(flags(2), 0u);
  EXPECT_EQ(flags(3), uint32_t(RP_LIGHT_NOT_IN_VOXELS));
  gpu.set_suns_in_voxels(true);
  gpu.update(frame, 8, 8, 64);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(flags(i), 0u) << i;
}

TEST(PrtSkyPass, RejectsTransferThatDoesNotFitTheScene) {
  scene::SceneAssets assets =
      make_test_assets({make_test_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}})});
  render::GpuScene gpu(context().context, context().queue, assets);
  passes::PrtShading prt;
  prt.coefficients.resize(2 * 9);  // two vertices: the mesh has three
  prt.instances = {{0, 0}};
  EXPECT_THROW(passes::PrtSkyPass(context(), programs(), gpu, prt), rp::cl::Error);
  prt.coefficients.resize(3 * 9);
  prt.instances = {{1, 0}};  // no mesh 1
  EXPECT_THROW(passes::PrtSkyPass(context(), programs(), gpu, prt), rp::cl::Error);
  prt.instances = {{0, 0}};
  prt.bands = 4;
  EXPECT_THROW(passes::PrtSkyPass(context(), programs(), gpu, prt), rp::cl::Error);
  prt.bands = 3;
  prt.channels = 3;
  prt.coefficients.resize(3 * 3 * 9);
  prt.shadowed.resize(2 * 9);  // a shadowed transfer of two vertices beside three
  EXPECT_THROW(passes::PrtSkyPass(context(), programs(), gpu, prt), rp::cl::Error);
  prt.shadowed.resize(3 * 9);
  EXPECT_NO_THROW(passes::PrtSkyPass(context(), programs(), gpu, prt));
  prt.sun_directions = {{0.0f, 1.0f, 0.0f}};
  prt.sun_bounce.resize(2 * 3);  // one sun's bounces for two vertices of three
  EXPECT_THROW(passes::PrtSkyPass(context(), programs(), gpu, prt), rp::cl::Error);
  prt.sun_bounce.resize(3 * 3);
  EXPECT_NO_THROW(passes::PrtSkyPass(context(), programs(), gpu, prt));
  prt.shadowed.clear();  // traced suns need the shadowed transfer beside them
  EXPECT_THROW(passes::PrtSkyPass(context(), programs(), gpu, prt), rp::cl::Error);
}

}  // namespace
}  // namespace rp::test
