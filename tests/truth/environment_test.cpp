// The path tracer's environment light (truth/environment.h, scene/environment.h): the sampler's
// density integrates to one and matches its samples, map coordinates round-trip, a white
// sphere under a uniform sky is as bright as the sky (the furnace test), and a floor under an
// uneven sky (a small bright sun patch on a gradient) gets the irradiance integrated from the
// map texel by texel, through importance sampling combined with the BRDF's (MIS); a sun taken
// out of the map is direct light at the first vertex.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "scene/environment_suns.h"
#include "truth/environment.h"
#include "truth/path_tracer.h"

namespace rp::truth {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A w x w/2 map: a blue-white gradient from the zenith, a dim ground and a small bright patch
// (a "sun") at (u, v) = (0.3, 0.3).
std::shared_ptr<scene::EnvironmentMap> uneven_map(int w) {
  auto map = std::make_shared<scene::EnvironmentMap>();
  map->width = w;
  map->height = w / 2;
  for (int y = 0; y < map->height; ++y)
    for (int x = 0; x < w; ++x) {
      const float v = (float(y) + 0.5f) / float(map->height), u = (float(x) + 0.5f) / float(w);
      glm::vec3 c = v < 0.5f ? glm::vec3(0.4f, 0.6f, 1.0f) * (1.0f - v) : glm::vec3(0.05f);
      if (std::abs(u - 0.3f) < 0.03f && std::abs(v - 0.3f) < 0.06f) c = glm::vec3(200.0f);
      map->rgb.insert(map->rgb.end(), {c.x, c.y, c.z});
    }
  return map;
}

scene::Environment environment_of(std::shared_ptr<scene::EnvironmentMap> map,
                                  float rotate_deg = 0.0f) {
  scene::Environment e;
  e.map = std::move(map);
  e.rotate_deg = rotate_deg;
  return e;
}

TEST(Environment, MapCoordinatesRoundTrip) {
  for (float u : {0.01f, 0.25f, 0.5f, 0.77f, 0.99f})
    for (float v : {0.02f, 0.3f, 0.5f, 0.9f}) {
      const glm::vec2 uv = scene::environment_uv(scene::environment_direction(u, v));
      EXPECT_NEAR(uv.x, u, 1e-5f);
      EXPECT_NEAR(uv.y, v, 1e-5f);
    }
  // The convention: v = 0 is up (+y), the map's centre looks towards +z.
  EXPECT_NEAR(scene::environment_direction(0.5f, 0.0f).y, 1.0f, 1e-6f);
  EXPECT_NEAR(scene::environment_direction(0.5f, 0.5f).z, 1.0f, 1e-6f);
}

TEST(Environment, DensityIntegratesToOneAndMatchesTheSamples) {
  for (float turn : {0.0f, 70.0f}) {
    const EnvironmentSampler env(environment_of(uneven_map(64), turn));
    ASSERT_TRUE(env.enabled());
    // The integral of pdf over the sphere, by a fine midpoint rule in (u, v).
    double integral = 0.0;
    const int n = 512;
    for (int j = 0; j < n / 2; ++j)
      for (int i = 0; i < n; ++i) {
        const float u = (float(i) + 0.5f) / float(n), v = (float(j) + 0.5f) / float(n / 2);
        const glm::vec3 d = scene::environment_direction(u, v);
        integral += double(env.pdf(d)) * std::sin(kPi * v) * (2.0 * kPi / n) * (kPi / (n / 2));
      }
    EXPECT_NEAR(integral, 1.0, 2e-3) << "turn " << turn;
    // Each sample's pdf and radiance are those of its direction.
    for (int k = 0; k < 200; ++k) {
      const float u1 = (float(k) + 0.37f) / 200.0f, u2 = std::fmod(float(k) * 0.618034f, 1.0f);
      const EnvironmentSampler::Sample s = env.sample(u1, u2);
      ASSERT_GT(s.pdf, 0.0f);
      EXPECT_NEAR(s.pdf, env.pdf(s.dir), 1e-3f * s.pdf) << k;
      EXPECT_EQ(s.radiance, env.radiance(s.dir)) << k;
    }
  }
}

// A scene of one analytic sphere (no lamp, no meshes) seen by a camera on +z.
scene::FrameScene sphere_frame(glm::vec3 albedo, scene::Environment env) {
  scene::FrameScene frame;
  frame.lamp = false;
  frame.camera.position = {0.0f, 0.0f, 3.0f};
  frame.camera.target = {0.0f, 0.0f, 0.0f};
  frame.camera.fov_y_deg = 30.0f;
  scene::Sphere ball;
  ball.center = ball.prev_center = glm::vec3(0.0f);
  ball.radius = 0.7f;
  ball.albedo = albedo;
  frame.spheres.push_back(ball);
  frame.environment = std::move(env);
  return frame;
}

TEST(Environment, FurnaceWhiteSphereUnderUniformSkyIsAsBrightAsTheSky) {
  auto map = std::make_shared<scene::EnvironmentMap>();
  map->width = 16;
  map->height = 8;
  map->rgb.assign(16 * 8 * 3, 0.75f);
  PathTracer tracer(scene::SceneAssets{});
  PathTraceSettings s;
  s.width = s.height = 24;
  s.spp = 32;
  s.bounces = 8;
  const PathTracedImage img =
      tracer.render(sphere_frame(glm::vec3(1.0f), environment_of(map)), s);
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < img.combined.size(); ++i) {
    sum += img.combined[i];
    ++n;
    // a convex white sphere reflects exactly what arrives: 0.75 everywhere, sky or sphere
    ASSERT_NEAR(img.combined[i], 0.75f, 0.2f) << "sample " << i;
  }
  EXPECT_NEAR(sum / double(n), 0.75, 0.005);
}

// A large floor of albedo 0.6 facing +y, seen from 1 above by a narrow camera.
scene::SceneAssets floor_assets() {
  scene::SceneAssets assets;
  assets.materials.push_back({"floor", glm::vec3(0.6f), glm::vec3(0.0f), -1});
  scene::Mesh floor;
  floor.name = "floor";
  const glm::vec3 n(0.0f, 1.0f, 0.0f);
  floor.vertices = {{{-50, 0, -50}, n, {0, 0}}, {{50, 0, -50}, n, {1, 0}},
                    {{50, 0, 50}, n, {1, 1}}, {{-50, 0, 50}, n, {0, 1}}};
  floor.triangles = {{0, 2, 1}, {0, 3, 2}};
  floor.materials = {0, 0};
  assets.meshes.push_back(floor);
  return assets;
}

scene::FrameScene floor_frame(scene::Environment env) {
  scene::FrameScene frame;
  frame.lamp = false;
  frame.camera.position = {0.0f, 1.0f, 0.0f};
  frame.camera.target = {0.01f, 0.0f, 0.0f};
  frame.camera.fov_y_deg = 20.0f;
  frame.camera.far_plane = 10.0f;
  frame.instances.push_back(scene::MeshInstance{});
  frame.environment = std::move(env);
  return frame;
}

double mean_green(const std::vector<float>& rgb) {
  double sum = 0.0;
  for (size_t i = 1; i < rgb.size(); i += 3) sum += rgb[i];
  return sum / double(rgb.size() / 3);
}

TEST(Environment, FloorUnderUnevenSkyGetsTheIrradianceOfTheMap) {
  // A large white floor facing +y, seen from above: its radiance is albedo * E / pi, E the
  // map's irradiance on +y, integrated texel by texel (each texel's solid angle exactly).
  const auto map = uneven_map(128);
  for (float turn : {0.0f, 135.0f}) {
    double irradiance = 0.0;
    const int w = map->width, h = map->height;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double t0 = kPi * y / h, t1 = kPi * (y + 1) / h;
        const double omega = (2.0 * kPi / w) * (std::cos(t0) - std::cos(t1));
        const double ct = 0.5 * (std::cos(t0) + std::cos(t1));  // mean cos theta = n . dir
        if (ct > 0.0) irradiance += double(map->rgb[size_t(3 * (y * w + x) + 1)]) * omega * ct;
      }
    const scene::SceneAssets assets = floor_assets();
    scene::FrameScene frame = floor_frame(environment_of(map, turn));
    PathTracer tracer(assets);
    PathTraceSettings s;
    s.width = s.height = 16;
    s.spp = 256;
    s.bounces = 1;
    const PathTracedImage img = tracer.render(frame, s);
    const double mean = mean_green(img.indirect);
    const double want = 0.6 * irradiance / kPi;
    EXPECT_NEAR(mean, want, 0.02 * want) << "turn " << turn << ": map irradiance " << irradiance;
    // The sky's light is gathered light (the real-time passes bring it through their cones):
    // the indirect component holds all of it, the direct one (lamp and punctual lights) none.
    for (float v : img.direct) ASSERT_EQ(v, 0.0f);
  }
}

// With the map's sun taken out (scene/environment_suns.h), the path tracer still samples the
// whole map: the image's sum is the same, draw for draw, but the sun's part at the first
// vertex is direct light, as bright as its directional light makes the floor in the real-time
// modes (E cos / pi x albedo), and the directional light itself is not counted again.
TEST(Environment, TheMapsSunIsDirectLightAtTheFirstVertex) {
  // the uneven map with a sun 100 x its mean within 0.1 sr: 3 x 3 texels of 3000 (0.014 sr)
  // at (u, v) = (0.7, 0.25), away from its broad patch of 200 (0.12 sr: not a sun)
  const auto map = uneven_map(128);
  for (int y = 15; y <= 17; ++y)
    for (int x = 89; x <= 91; ++x)
      for (int c = 0; c < 3; ++c) map->rgb[size_t(3 * (y * 128 + x) + c)] = 3000.0f;
  const scene::EnvironmentSuns suns = scene::find_environment_suns(*map, 4);
  ASSERT_EQ(suns.suns.size(), 1u);
  const scene::SceneAssets assets = floor_assets();
  PathTraceSettings s;
  s.width = s.height = 16;
  s.spp = 256;
  s.bounces = 1;
  PathTracer tracer(assets);
  const PathTracedImage whole = tracer.render(floor_frame(environment_of(map, 30.0f)), s);
  scene::Environment split = environment_of(map, 30.0f);
  split.residual = suns.residual;
  scene::FrameScene frame = floor_frame(split);
  const scene::PunctualLight light = scene::environment_sun_light(suns.suns[0], 0, 30.0f, 1.0f);
  frame.lights.push_back(light);
  const PathTracedImage parts = tracer.render(frame, s);
  for (size_t i = 0; i < whole.combined.size(); ++i) {
    ASSERT_NEAR(parts.combined[i], whole.combined[i], 1e-5f * (1.0f + whole.combined[i])) << i;
    ASSERT_NEAR(parts.direct[i] + parts.indirect[i], whole.indirect[i],
                1e-5f * (1.0f + whole.indirect[i]))
        << i;
  }
  const float cos_sun = std::max(0.0f, -light.direction.y);
  const double want = 0.6 * light.intensity.y * cos_sun;  // albedo x (E / pi) x cos
  EXPECT_NEAR(mean_green(parts.direct), want, 0.03 * want);
  EXPECT_GT(mean_green(parts.indirect), 0.0);
}

TEST(Environment, LoadingRefusesWhatIsNotAnEquirectangularMap) {
  EXPECT_THROW(load_environment_map("/nonexistent/sky.exr"), std::runtime_error);
  EXPECT_THROW(load_environment_map("/nonexistent/sky.png"), std::runtime_error);
}

}  // namespace
}  // namespace rp::truth
