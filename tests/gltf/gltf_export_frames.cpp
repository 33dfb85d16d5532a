// The frames the exporter's tests write (declared in gltf_export_checks.h).
#include <stdlib.h>

#include <filesystem>
#include <stdexcept>

#include <gtest/gtest.h>

#include "gltf/gltf_export_checks.h"
#include "scene/demo_scene.h"

namespace rp::test::gltf_export_checks {

ExportFolder::ExportFolder() {
  std::string pattern = ::testing::TempDir() + "gltf_export_XXXXXX";
  if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed: " + pattern);
  path_ = pattern;
}

ExportFolder::~ExportFolder() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

const scene::SceneAssets& demo_assets() {
  static const scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  return assets;
}

scene::ExportOptions demo_options() {
  scene::ExportOptions options;
  options.volume = scene::Bounds{glm::vec3(-1.0f), glm::vec3(1.0f)};
  return options;
}

scene::FrameScene demo_frame_with_marbles() {
  scene::FrameScene frame = scene::make_demo_frame(demo_assets());
  frame.spheres.push_back(scene::resting_marble({-0.3f, 0.6f}, 0.06f, {0.85f, 0.2f, 0.1f}));
  frame.spheres.push_back(scene::resting_marble({0.25f, 0.65f}, 0.05f, {0.1f, 0.3f, 0.9f}));
  return frame;
}

namespace {

scene::Texture pattern_texture(const std::string& name, int w, int h, bool srgb, uint8_t seed) {
  scene::Texture t;
  t.name = name;
  t.width = w;
  t.height = h;
  t.srgb = srgb;
  for (int i = 0; i < w * h * 4; ++i) t.rgba.push_back(static_cast<uint8_t>(seed + 37 * i));
  return t;
}

}  // namespace

SyntheticScene synthetic_scene() {
  using namespace scene;
  SyntheticScene s;
  Texture base = pattern_texture("base", 4, 2, true, 10);
  base.wrap_u = TextureWrap::kClampToEdge;
  base.wrap_v = TextureWrap::kMirroredRepeat;
  s.assets.textures = {base, pattern_texture("normal", 2, 2, false, 90),
                       pattern_texture("metal_rough", 2, 3, false, 150),
                       pattern_texture("glow", 3, 1, true, 200)};
  Material all;
  all.name = "everything";
  all.albedo = {0.5f, 0.25f, 0.8f};
  all.opacity = 0.75f;
  all.texture = 0;
  all.specular = {0.3f, 0.02f, false};
  all.metallic = 0.25f;
  all.metallic_roughness_texture = 2;
  all.normal_texture = 1;
  all.normal_scale = 0.5f;
  all.emission = {3.0f, 1.5f, 0.0f};
  all.emission_texture = 3;
  all.alpha_mode = AlphaMode::kMask;
  all.alpha_cutoff = 0.3f;
  all.double_sided = true;
  Material gold;
  gold.name = "gold";
  gold.albedo = {1.0f, 0.78f, 0.34f};
  gold.specular = {0.2f, 0.0f, true};
  s.assets.materials = {all, gold};
  Mesh m;
  m.name = "card";
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  m.vertices = {{{-1, -1, 0}, n, {0, 0}}, {{1, -1, 0}, n, {1, 0}}, {{1, 1, 0}, n, {1, 1}},
                {{-1, 1, 0}, n, {0, 1}},  {{2, -1, 0}, n, {0, 0}}, {{3, -1, 0}, n, {1, 0}},
                {{2, 1, 0}, n, {0.5f, 1}}};
  m.triangles = {{0, 1, 2}, {4, 5, 6}, {0, 2, 3}};
  m.materials = {0, 1, 0};
  m.tangents.assign(m.vertices.size(), glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  m.tangents[6].w = -1.0f;
  s.assets.meshes = {m};
  MeshInstance inst;
  inst.model = glm::mat4(glm::vec4(0.0f, 0.5f, 0.0f, 0.0f), glm::vec4(-0.5f, 0.0f, 0.0f, 0.0f),
                         glm::vec4(0.0f, 0.0f, 0.5f, 0.0f), glm::vec4(0.1f, 0.2f, 0.3f, 1.0f));
  inst.prev_model = inst.model;
  s.frame.instances = {inst};
  s.frame.lamp = false;
  PunctualLight sun;
  sun.name = "sun";
  sun.type = LightType::kDirectional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.2f));
  sun.intensity = {2.0f, 1.9f, 1.7f};
  PunctualLight bulb;
  bulb.name = "bulb";
  bulb.type = LightType::kPoint;
  bulb.position = {0.5f, 0.9f, -0.25f};
  bulb.intensity = glm::vec3(0.6f);
  bulb.range = 4.0f;
  PunctualLight spot;
  spot.name = "spot";
  spot.type = LightType::kSpot;
  spot.position = {-0.5f, 0.8f, 0.5f};
  spot.direction = glm::normalize(glm::vec3(0.0f, -1.0f, 0.1f));
  spot.intensity = {5.0f, 3.0f, 1.0f};
  spot.inner_cone = 0.2f;
  spot.outer_cone = 0.6f;
  PunctualLight hard = spot;
  hard.name = "hard spot";
  hard.direction = glm::vec3(0.0f, 0.0f, 1.0f);  // +z: the half-turn case
  hard.inner_cone = hard.outer_cone = 0.5f;
  s.frame.lights = {sun, bulb, spot, hard};
  return s;
}

std::vector<glm::vec3> corners_by_material(const scene::Mesh& mesh) {
  std::map<uint32_t, std::vector<glm::vec3>> groups;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      groups[mesh.materials[t]].push_back(mesh.vertices[mesh.triangles[t][k]].position);
  std::vector<glm::vec3> out;
  for (const auto& [material, corners] : groups)
    out.insert(out.end(), corners.begin(), corners.end());
  return out;
}

std::map<uint32_t, size_t> triangles_per_material(const scene::Mesh& mesh) {
  std::map<uint32_t, size_t> out;
  for (const uint32_t m : mesh.materials) ++out[m];
  return out;
}

double f0_of_ior(double ior) {
  const double r = (ior - 1.0) / (ior + 1.0);
  return r * r;
}

}  // namespace rp::test::gltf_export_checks
