// The path tracer (src/truth) against answers known in closed form: the direct-only
// image against the analytic lamp light on the walls, a closed emitting box with one and with
// unlimited gathers, a sphere light over a plane (next-event estimation + MIS), error falling as
// 1 / sqrt(spp), and bit-identical images for any thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "scene/cornell_box.h"
#include "scene/demo_scene.h"
#include "truth/path_tracer.h"

namespace rp::truth {
namespace {

scene::SceneAssets demo_assets() { return scene::make_demo_assets(scene::default_asset_dir()); }

// Mean and standard error of one channel over all pixels (each pixel an independent estimate).
struct MeanSe {
  double mean = 0.0, se = 0.0;
};
MeanSe mean_se(const std::vector<float>& rgb, int channel) {
  const size_t n = rgb.size() / 3;
  double sum = 0.0, sum2 = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double v = rgb[3 * i + size_t(channel)];
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / double(n);
  const double var = std::max(0.0, sum2 / double(n) - mean * mean) * double(n) / double(n - 1);
  return {mean, std::sqrt(var / double(n))};
}

// A closed box [-1,1]^3 (six walls, normals inwards), one material.
scene::SceneAssets closed_box_assets(glm::vec3 albedo, glm::vec3 emission) {
  scene::SceneAssets assets;
  assets.materials.push_back({"box", albedo, emission, -1});
  scene::Mesh m;
  m.name = "closed_box";
  auto quad = [&](glm::vec3 o, glm::vec3 u, glm::vec3 v) {
    const glm::vec3 n = glm::normalize(glm::cross(u, v));
    const uint32_t b = uint32_t(m.vertices.size());
    for (glm::vec3 p : {o, o + u, o + u + v, o + v}) m.vertices.push_back({p, n, glm::vec2(0)});
    m.triangles.push_back({b, b + 1, b + 2});
    m.triangles.push_back({b, b + 2, b + 3});
    m.materials.insert(m.materials.end(), {0u, 0u});
  };
  quad({-1, -1, 1}, {2, 0, 0}, {0, 0, -2});   // floor, normal +y
  quad({-1, 1, -1}, {2, 0, 0}, {0, 0, 2});    // ceiling, -y
  quad({-1, -1, -1}, {2, 0, 0}, {0, 2, 0});   // back, +z
  quad({1, -1, 1}, {-2, 0, 0}, {0, 2, 0});    // front, -z
  quad({-1, -1, 1}, {0, 0, -2}, {0, 2, 0});   // left, +x
  quad({1, -1, -1}, {0, 0, 2}, {0, 2, 0});    // right, -x
  assets.meshes.push_back(std::move(m));
  return assets;
}

scene::FrameScene closed_box_frame() {
  scene::FrameScene frame;
  frame.camera.position = {0.0f, 0.0f, 0.5f};
  frame.camera.target = {0.0f, 0.0f, -1.0f};
  frame.light.intensity = glm::vec3(0.0f);  // only the walls' emission
  scene::MeshInstance box;
  box.mesh = 0;
  frame.instances.push_back(box);
  return frame;
}

TEST(PathTracer, ClosedBoxOneGatherIsEmissionTimesOnePlusAlbedo) {
  const glm::vec3 albedo(0.5f, 0.3f, 0.7f), emission(1.0f, 0.5f, 0.25f);
  PathTracer tracer(closed_box_assets(albedo, emission));
  PathTraceSettings s;
  s.width = s.height = 24;
  s.spp = 16;
  s.bounces = 1;
  const PathTracedImage img = tracer.render(closed_box_frame(), s);
  for (int c = 0; c < 3; ++c) {
    const MeanSe m = mean_se(img.combined, c);
    const double expected = emission[c] * (1.0 + albedo[c]);
    EXPECT_NEAR(m.mean, expected, std::max(3.0 * m.se, 1e-5 * expected)) << "channel " << c;
    // The components: the camera sees the emission; one gather brings a E.
    EXPECT_NEAR(mean_se(img.emission, c).mean, emission[c], 1e-6);
    EXPECT_NEAR(mean_se(img.direct, c).mean, 0.0, 1e-12);
  }
}

TEST(PathTracer, ClosedBoxUnlimitedGathersIsEmissionOverOneMinusAlbedo) {
  const glm::vec3 albedo(0.5f, 0.3f, 0.7f), emission(1.0f, 0.5f, 0.25f);
  PathTracer tracer(closed_box_assets(albedo, emission));
  PathTraceSettings s;
  s.width = s.height = 32;
  s.spp = 64;
  s.bounces = 1000;  // Russian roulette ends the paths long before (unbiased)
  const PathTracedImage img = tracer.render(closed_box_frame(), s);
  for (int c = 0; c < 3; ++c) {
    const MeanSe m = mean_se(img.combined, c);
    const double expected = emission[c] / (1.0 - albedo[c]);
    EXPECT_GT(m.se, 0.0);  // roulette makes it random: the 3-sigma test means something
    EXPECT_NEAR(m.mean, expected, 3.0 * m.se) << "channel " << c << " se " << m.se;
  }
  // Truncated at 2 gathers it must be E (1 + a + a^2): the bounce count is what it says.
  s.bounces = 2;
  const PathTracedImage two = tracer.render(closed_box_frame(), s);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(mean_se(two.combined, c).mean,
                emission[c] * (1.0 + albedo[c] + albedo[c] * albedo[c]), 1e-4 * emission[c]);
}

// Analytic direct light of the demo room (box + lamp cap, no tumblers) on the back, left and
// right walls, averaged over an 8x8 grid inside each pixel; pixels that see more than one wall
// or the lamp cap within a quarter pixel of their edges are left out.
std::optional<double> analytic_wall_pixel(const scene::FrameScene& frame,
                                          const scene::SceneAssets& assets, uint32_t w,
                                          uint32_t h, uint32_t x, uint32_t y, int channel) {
  const glm::mat4 inv = glm::inverse(frame.camera.projection(float(w) / float(h)) *
                                     frame.camera.view());
  const glm::vec3 o = frame.camera.position;
  const scene::PointLight& light = frame.light;
  double sum = 0.0;
  int wall = -1;
  for (int j = -2; j < 10; ++j)
    for (int i = -2; i < 10; ++i) {
      const bool inside_pixel = i >= 0 && i < 8 && j >= 0 && j < 8;
      const float px = float(x) + (float(i) + 0.5f) / 8.0f, py = float(y) + (float(j) + 0.5f) / 8.0f;
      glm::vec4 far = inv * glm::vec4(2.0f * px / float(w) - 1.0f, 1.0f - 2.0f * py / float(h), 1, 1);
      const glm::vec3 d = glm::normalize(glm::vec3(far) / far.w - o);
      // Nearest of the planes x = -1 (left), x = 1 (right), z = -1 (back), y = +-1.
      float best = std::numeric_limits<float>::infinity();
      int which = -1;
      auto plane = [&](int axis, float value, int id) {
        if (d[axis] == 0.0f) return;
        const float t = (value - o[axis]) / d[axis];
        if (t > 0.0f && t < best) {
          const glm::vec3 p = o + t * d;
          bool inside = true;
          for (int a = 0; a < 3; ++a) inside = inside && (a == axis || std::abs(p[a]) <= 1.0f);
          if (inside) best = t, which = id;
        }
      };
      plane(0, -1.0f, 0);
      plane(0, 1.0f, 1);
      plane(2, -1.0f, 2);
      plane(1, -1.0f, 3);
      plane(1, 1.0f, 4);
      if (which > 2 || (wall >= 0 && which != wall)) return std::nullopt;  // floor/ceiling/edge
      wall = which;
      const glm::vec3 p = o + best * d;
      // The lamp cap: the sphere around the lamp centre, below the ceiling.
      const glm::vec3 oc = o - light.position;
      const float b = glm::dot(oc, d), c = glm::dot(oc, oc) - light.lamp_radius * light.lamp_radius;
      if (b * b - c > 0.0f && -b - std::sqrt(b * b - c) < best) return std::nullopt;
      const glm::vec3 n = which == 0 ? glm::vec3(1, 0, 0)
                          : which == 1 ? glm::vec3(-1, 0, 0) : glm::vec3(0, 0, 1);
      const uint32_t mat = which == 0   ? scene::demo::kLeftMaterial
                           : which == 1 ? scene::demo::kRightMaterial
                                        : scene::demo::kBackMaterial;
      if (!inside_pixel) continue;
      const glm::vec3 to_l = light.position - p;
      const double d2 = glm::dot(to_l, to_l);
      const glm::vec3 l = to_l / float(std::sqrt(d2));
      const double cos_t = std::max(0.0f, glm::dot(n, l));
      const double s = std::clamp(double(l.y), 0.0, 1.0);
      const double falloff = 0.35 + s * (0.446 + 0.204 * s);
      sum += double(assets.materials[mat].albedo[channel]) * light.intensity[channel] * cos_t / d2 *
             falloff;
    }
  return sum / 64.0;
}

TEST(PathTracer, DirectOnlyEqualsAnalyticLampLightOnWallInteriors) {
  const scene::SceneAssets assets = demo_assets();
  scene::FrameScene frame;
  scene::add_room_instances(frame);
  PathTracer tracer(assets);
  PathTraceSettings s;
  s.width = s.height = 40;
  s.spp = 2048;  // the pixel mean's standard error stays below 0.3 % where the light varies most
  s.bounces = 0;
  const PathTracedImage img = tracer.render(frame, s);
  int checked = 0;
  double worst = 0.0;
  for (uint32_t y = 0; y < s.height; ++y)
    for (uint32_t x = 0; x < s.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const std::optional<double> truth = analytic_wall_pixel(frame, assets, s.width, s.height, x, y, c);
        if (!truth) continue;
        const double got = img.direct[3 * (size_t(y) * s.width + x) + size_t(c)];
        EXPECT_NEAR(got, *truth, 0.01 * *truth + 1e-6) << "pixel " << x << "," << y << " ch " << c;
        worst = std::max(worst, std::abs(got - *truth) / (*truth + 1e-9));
        ++checked;
        // Zero gathers: nothing but the lamp and the camera's own emission.
        EXPECT_EQ(img.indirect[3 * (size_t(y) * s.width + x) + size_t(c)], 0.0f);
      }
  EXPECT_GT(checked, 3 * 400) << "too few wall pixels compared";
  RecordProperty("worst_relative_error", std::to_string(worst));
}

// A Lambertian plane lit by one emissive sphere straight above the point the camera looks at:
// outgoing radiance albedo * Le * (r / d)^2 (irradiance pi Le sin^2 of the cone's half angle).
TEST(PathTracer, SphereLightOverPlaneMatchesClosedForm) {
  scene::SceneAssets assets;
  assets.materials.push_back({"plane", glm::vec3(0.6f), glm::vec3(0.0f), -1});
  scene::Mesh m;
  m.name = "plane";
  const glm::vec3 n(0, 1, 0);
  m.vertices = {{{-50, 0, 50}, n, {}}, {{50, 0, 50}, n, {}}, {{50, 0, -50}, n, {}}, {{-50, 0, -50}, n, {}}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.materials = {0, 0};
  assets.meshes.push_back(m);
  scene::FrameScene frame;
  frame.light.intensity = glm::vec3(0.0f);
  frame.instances.push_back({});
  frame.camera.position = {0.0f, 3.0f, 0.001f};  // looking straight down at the origin
  frame.camera.target = {0.0f, 0.0f, 0.0f};
  frame.camera.fov_y_deg = 0.5f;                  // a tiny footprint around the origin
  frame.camera.far_plane = 10.0f;
  scene::Sphere light;
  light.center = {0.0f, 1.0f, 0.0f};
  light.radius = 0.2f;
  light.albedo = glm::vec3(0.0f);
  light.emission = glm::vec3(5.0f, 4.0f, 3.0f);
  light.casts_shadow = false;
  frame.spheres.push_back(light);
  frame.camera.position.y = 0.5f;  // below the sphere: sees the plane, not the light
  frame.camera.target = {0.0f, 0.0f, 0.0f};
  PathTracer tracer(assets);
  PathTraceSettings s;
  s.width = s.height = 8;
  s.spp = 1024;
  s.bounces = 1;
  const PathTracedImage img = tracer.render(frame, s);
  const double sin2 = 0.2 * 0.2 / (1.0 * 1.0);
  for (int c = 0; c < 3; ++c) {
    const MeanSe got = mean_se(img.indirect, c);
    const double expected = 0.6 * light.emission[c] * sin2;
    EXPECT_NEAR(got.mean, expected, std::max(3.0 * got.se, 0.003 * expected)) << "channel " << c;
  }
}

TEST(PathTracer, ErrorFallsAsOneOverSqrtSpp) {
  const scene::SceneAssets assets = demo_assets();
  const scene::FrameScene frame = scene::make_demo_frame(assets);
  PathTracer tracer(assets);
  PathTraceSettings s;
  s.width = s.height = 16;
  s.bounces = 1;
  s.seed = 99;
  s.spp = 4096;
  const std::vector<float> reference = tracer.render(frame, s).indirect;
  s.seed = 1;
  auto rmse = [&](uint32_t spp) {
    s.spp = spp;
    const std::vector<float> v = tracer.render(frame, s).indirect;
    double sum = 0.0;
    for (size_t i = 0; i < v.size(); ++i) sum += double(v[i] - reference[i]) * (v[i] - reference[i]);
    return std::sqrt(sum / double(v.size()));
  };
  const double e8 = rmse(8), e32 = rmse(32), e128 = rmse(128);
  // Expected ratios with the reference's own noise: sqrt((1/8 + 1/4096) / (1/32 + 1/4096)) = 1.99
  // and from 8 to 128 spp 3.94.
  EXPECT_GT(e8 / e32, 1.6);
  EXPECT_LT(e8 / e32, 2.5);
  EXPECT_GT(e8 / e128, 3.2);
  EXPECT_LT(e8 / e128, 4.8);
}

TEST(PathTracer, BitIdenticalForAnyThreadCount) {
  const scene::SceneAssets assets = demo_assets();
  scene::FrameScene frame = scene::make_demo_frame(assets);
  // A marble (shadow caster) and a fire sphere (next-event estimation) on top of the demo.
  scene::Sphere marble;
  marble.center = {0.3f, -0.9f, 0.6f};
  marble.radius = 0.08f;
  frame.spheres.push_back(marble);
  scene::Sphere fire;
  fire.center = {-0.2f, 0.2f, 0.0f};
  fire.radius = 0.1f;
  fire.emission = glm::vec3(8.0f, 3.0f, 0.5f);
  fire.casts_shadow = false;
  frame.spheres.push_back(fire);
  PathTracer tracer(assets);
  PathTraceSettings s;
  s.width = 24;
  s.height = 20;
  s.spp = 8;
  s.bounces = 5;
  s.threads = 1;
  const PathTracedImage one = tracer.render(frame, s);
  s.threads = 2;
  const PathTracedImage two = tracer.render(frame, s);
  s.threads = 3;
  const PathTracedImage three = tracer.render(frame, s);
  for (const PathTracedImage* other : {&two, &three}) {
    EXPECT_EQ(0, std::memcmp(one.combined.data(), other->combined.data(), one.combined.size() * 4));
    EXPECT_EQ(0, std::memcmp(one.indirect.data(), other->indirect.data(), one.indirect.size() * 4));
    EXPECT_EQ(one.rays, other->rays);
  }
  s.seed = 2;
  EXPECT_NE(0, std::memcmp(one.combined.data(), tracer.render(frame, s).combined.data(),
                           one.combined.size() * 4));
  // The area lamp draws from the same per-pixel streams.
  s.seed = 1;
  s.lamp = LampModel::kArea;
  s.threads = 1;
  const PathTracedImage area_one = tracer.render(frame, s);
  s.threads = 3;
  const PathTracedImage area_three = tracer.render(frame, s);
  EXPECT_EQ(0, std::memcmp(area_one.combined.data(), area_three.combined.data(),
                           area_one.combined.size() * 4));
  EXPECT_NE(0, std::memcmp(one.direct.data(), area_one.direct.data(), one.direct.size() * 4));
}

}  // namespace
}  // namespace rp::truth
