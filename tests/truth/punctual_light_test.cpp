// The path tracer's file-scene features against answers known in closed form: each punctual
// light type over a plane (direct = albedo * I * cos * attenuation), a blocker's shadow, an
// alpha-masked blocker that lets the light through its holes, a normal map that tilts the
// shading normal, and the light helper's spot cone and range window.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/punctual_light.h"
#include "truth/path_tracer.h"

namespace rp::truth {
namespace {

// A 4x4 floor quad at y = 0 (normal +y, uv 0..1), material 0; an optional 1x1 blocker quad at
// y = 0.5 over the centre (material 1).
scene::Mesh quad(float half, float y, uint32_t material) {
  scene::Mesh m;
  m.name = "quad";
  const glm::vec3 n(0, 1, 0);
  m.vertices = {{{-half, y, half}, n, {0, 0}},
                {{half, y, half}, n, {1, 0}},
                {{half, y, -half}, n, {1, 1}},
                {{-half, y, -half}, n, {0, 1}}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.materials = {material, material};
  return m;
}

scene::SceneAssets floor_assets(bool blocker) {
  scene::SceneAssets a;
  scene::Material floor;
  floor.name = "floor";
  floor.albedo = glm::vec3(0.5f);
  a.materials.push_back(floor);
  scene::Material block = floor;
  block.name = "blocker";
  a.materials.push_back(block);
  a.meshes.push_back(quad(2.0f, 0.0f, 0));
  if (blocker) a.meshes.push_back(quad(0.5f, 0.5f, 1));
  return a;
}

// Camera straight above the floor's centre looking down, a narrow view: every pixel sees the
// floor within 0.05 of the centre.
scene::FrameScene floor_frame(const scene::SceneAssets& a) {
  scene::FrameScene f;
  f.lamp = false;
  f.light.intensity = glm::vec3(0.0f);
  f.camera.position = {0.0f, 3.0f, 0.0f};
  f.camera.target = {0.0f, 0.0f, 0.0f};
  f.camera.up = {0.0f, 0.0f, -1.0f};
  f.camera.fov_y_deg = 1.0f;
  f.camera.near_plane = 0.01f;
  f.camera.far_plane = 10.0f;
  for (uint32_t i = 0; i < a.meshes.size(); ++i) {
    scene::MeshInstance inst;
    inst.mesh = i;
    f.instances.push_back(inst);
  }
  return f;
}

// Mean direct light of the image (red channel).
double mean_direct(const scene::SceneAssets& a, const scene::FrameScene& f) {
  PathTracer tracer(a);
  PathTraceSettings s;
  s.width = s.height = 8;
  s.spp = 4;
  s.bounces = 0;
  const PathTracedImage img = tracer.render(f, s);
  double sum = 0.0;
  for (size_t i = 0; i < img.direct.size(); i += 3) sum += img.direct[i];
  return sum / double(img.direct.size() / 3);
}

// The same view from between the blocker and the floor (the camera sees the floor only).
scene::FrameScene under_blocker(const scene::SceneAssets& a) {
  scene::FrameScene f = floor_frame(a);
  f.camera.position = {0.0f, 0.25f, 0.0f};
  return f;
}

// An instance that casts only the lights' shadows (MeshInstance::casts_light_shadow, the demo's
// box) blocks a punctual light and not the demo's lamp; without either flag it blocks neither.
TEST(PathTracerLights, ALightOnlyCasterShadesTheLightsNotTheLamp) {
  const scene::SceneAssets a = floor_assets(true);
  const auto direct = [&](bool sun, bool lamp, bool light_caster) {
    scene::FrameScene f = under_blocker(a);
    f.instances[1].casts_shadow = false;
    f.instances[1].casts_light_shadow = light_caster;
    if (sun) {
      scene::PunctualLight l;
      l.type = scene::LightType::kDirectional;
      l.direction = {0.0f, -1.0f, 0.0f};
      l.intensity = glm::vec3(2.0f);
      f.lights.push_back(l);
    }
    if (lamp) {
      f.lamp = true;
      f.light.position = {0.0f, 2.0f, 0.0f};
      f.light.intensity = glm::vec3(4.0f);
    }
    return mean_direct(a, f);
  };
  EXPECT_NEAR(direct(true, false, false), 0.5 * 2.0, 1e-3) << "no caster: the sun's full light";
  EXPECT_EQ(direct(true, false, true), 0.0) << "the light-only caster shades the sun";
  const double lamp_open = direct(false, true, false);
  EXPECT_GT(lamp_open, 0.0);
  EXPECT_EQ(direct(false, true, true), lamp_open) << "and not the lamp";
}

TEST(PathTracerLights, PointLightIsAlbedoTimesIntensityCosOverDistanceSquared) {
  const scene::SceneAssets a = floor_assets(false);
  scene::FrameScene f = floor_frame(a);
  scene::PunctualLight light;
  light.type = scene::LightType::kPoint;
  light.position = {0.0f, 2.0f, 0.0f};
  light.intensity = glm::vec3(4.0f);
  f.lights.push_back(light);
  EXPECT_NEAR(mean_direct(a, f), 0.5 * 4.0 / 4.0, 0.5 * 4.0 / 4.0 * 2e-3);
}

TEST(PathTracerLights, DirectionalLightIsAlbedoTimesIrradianceCos) {
  const scene::SceneAssets a = floor_assets(false);
  scene::FrameScene f = floor_frame(a);
  scene::PunctualLight sun;
  sun.type = scene::LightType::kDirectional;
  sun.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));  // 45 degrees
  sun.intensity = glm::vec3(2.0f);
  f.lights.push_back(sun);
  EXPECT_NEAR(mean_direct(a, f), 0.5 * 2.0 * std::sqrt(0.5), 1e-4);
}

TEST(PathTracerLights, SpotLightFollowsItsConeAndLightsAddUp) {
  const scene::SceneAssets a = floor_assets(false);
  scene::FrameScene f = floor_frame(a);
  scene::PunctualLight spot;
  spot.type = scene::LightType::kSpot;
  spot.position = {0.0f, 1.0f, 0.0f};
  spot.direction = {0.0f, -1.0f, 0.0f};
  spot.inner_cone = 0.1f;
  spot.outer_cone = 0.3f;
  spot.intensity = glm::vec3(1.0f);
  f.lights.push_back(spot);
  EXPECT_NEAR(mean_direct(a, f), 0.5, 0.5 * 2e-3);  // inside the inner cone
  f.lights[0].direction = glm::normalize(glm::vec3(std::sin(0.2f), -std::cos(0.2f), 0.0f));
  // The floor centre is 0.2 rad off the axis: halfway through the penumbra, t = 0.5 (the
  // narrow view spans +-0.026 rad around it, so allow a little).
  const float cos_o = std::cos(0.3f), cos_i = std::cos(0.1f);
  const float t = (std::cos(0.2f) - cos_o) / (cos_i - cos_o);
  EXPECT_NEAR(mean_direct(a, f), 0.5 * t * t, 0.5 * t * t * 0.05);
  f.lights[0].direction = {0.0f, -1.0f, 0.0f};
  f.lights.push_back(f.lights[0]);
  EXPECT_NEAR(mean_direct(a, f), 1.0, 2e-3);
}

TEST(PathTracerLights, ABlockerCastsAShadowAndAMaskedBlockerLetsLightThroughItsHoles) {
  scene::SceneAssets a = floor_assets(true);
  scene::FrameScene f = under_blocker(a);
  scene::PunctualLight light;
  light.position = {0.0f, 2.0f, 0.0f};
  light.intensity = glm::vec3(4.0f);
  f.lights.push_back(light);
  EXPECT_EQ(mean_direct(a, f), 0.0);
  // Fully transparent texture on a masked blocker: no shadow.
  scene::Texture clear;
  clear.name = "clear";
  clear.width = clear.height = 2;
  clear.rgba.assign(16, 255);
  for (int i = 0; i < 4; ++i) clear.rgba[size_t(4 * i + 3)] = 0;
  a.textures.push_back(clear);
  a.materials[1].texture = 0;
  a.materials[1].alpha_mode = scene::AlphaMode::kMask;
  EXPECT_NEAR(mean_direct(a, f), 0.5 * 4.0 / 4.0, 2e-3);
  // Opaque alpha: the shadow is back.
  for (int i = 0; i < 4; ++i) a.textures[0].rgba[size_t(4 * i + 3)] = 255;
  EXPECT_EQ(mean_direct(a, f), 0.0);
}

TEST(PathTracerLights, ANormalMapTiltsTheShadingNormal) {
  scene::SceneAssets a = floor_assets(false);
  // Tangent along +x (u); the floor's v runs towards -z, and so does the bitangent
  // w * cross(n, t) = cross(+y, +x) = -z with w = +1.
  a.meshes[0].tangents.assign(4, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  // A constant normal map tilting 45 degrees towards +u: (x, z) = (0.707, 0.707).
  scene::Texture map;
  map.name = "normal";
  map.srgb = false;
  map.width = map.height = 1;
  const uint8_t c = uint8_t(std::lround((std::sqrt(0.5) * 0.5 + 0.5) * 255.0));
  map.rgba = {c, 128, c, 255};
  a.textures.push_back(map);
  a.materials[0].normal_texture = 0;
  scene::FrameScene f = floor_frame(a);
  scene::PunctualLight sun;
  sun.type = scene::LightType::kDirectional;
  sun.direction = glm::normalize(glm::vec3(-1.0f, -1.0f, 0.0f));  // comes from +x, 45 degrees
  sun.intensity = glm::vec3(1.0f);
  f.lights.push_back(sun);
  // The tilted normal faces the sun: cos close to 1 (the texel's 8-bit rounding aside).
  const double x = (c / 255.0) * 2.0 - 1.0, y = (128 / 255.0) * 2.0 - 1.0;
  const glm::dvec3 n = glm::normalize(glm::dvec3(x, y, x));
  const double cos_theta = n.x * std::sqrt(0.5) + n.z * std::sqrt(0.5);
  EXPECT_NEAR(mean_direct(a, f), 0.5 * cos_theta, 2e-3);
  EXPECT_GT(cos_theta, 0.99);
}

TEST(PunctualLight, RangeWindowFadesToZeroAtTheRange) {
  scene::PunctualLight light;
  light.position = glm::vec3(0.0f);
  light.range = 2.0f;
  EXPECT_NEAR(scene::sample_light(light, {1.0f, 0.0f, 0.0f}).attenuation, 1.0f - 1.0f / 16.0f,
              1e-6f);
  EXPECT_EQ(scene::sample_light(light, {2.5f, 0.0f, 0.0f}).attenuation, 0.0f);
  EXPECT_EQ(scene::sample_light(light, {0.0f, 0.0f, 0.0f}).attenuation, 0.0f);
  light.type = scene::LightType::kSpot;
  light.direction = {1.0f, 0.0f, 0.0f};
  light.range = 0.0f;
  EXPECT_NEAR(scene::sample_light(light, {0.5f, 0.0f, 0.0f}).attenuation, 4.0f, 1e-5f);
  EXPECT_EQ(scene::sample_light(light, {-0.5f, 0.0f, 0.0f}).attenuation, 0.0f);
}

}  // namespace
}  // namespace rp::truth
