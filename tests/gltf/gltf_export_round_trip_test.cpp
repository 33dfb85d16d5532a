// The exporter (scene/gltf_export.h) and the loader (scene/gltf_loader.h) agree: a frame
// written and read back has the same instances (matrices, triangles per material, world
// positions within 1e-6), materials (albedo, coat, emission within 1e-6; f0 through
// KHR_materials_ior), texture bytes, lights, the demo's lamp, the camera and the GI volume.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "gltf/gltf_export_checks.h"
#include "scene/demo_scene.h"
#include "scene/gltf_export.h"
#include "scene/gltf_loader.h"

namespace rp::test::gltf_export_checks {
namespace {

constexpr float kTolerance = 1e-6f;

scene::LoadedScene export_and_load(const std::filesystem::path& file,
                                   const scene::FrameScene& frame,
                                   const scene::ExportOptions& options = demo_options(),
                                   const scene::SceneAssets& assets = demo_assets()) {
  scene::export_gltf(assets, frame, file, options);
  return scene::load_gltf(file.string());
}

// Within kTolerance of the larger of 1 and |want| (emission and intensities reach 10 and more).
void expect_near(glm::vec3 got, glm::vec3 want, const std::string& what) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(got[c], want[c], kTolerance * std::max(1.0f, std::abs(want[c])))
        << what << "[" << c << "]";
}

glm::vec3 apply(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

void expect_same_texture(const scene::SceneAssets& got_assets, int got,
                         const scene::SceneAssets& want_assets, int want, const std::string& what) {
  ASSERT_EQ(got < 0, want < 0) << what;
  if (want < 0) return;
  const scene::Texture& g = got_assets.textures.at(static_cast<size_t>(got));
  const scene::Texture& w = want_assets.textures.at(static_cast<size_t>(want));
  EXPECT_EQ(g.width, w.width) << what;
  EXPECT_EQ(g.height, w.height) << what;
  EXPECT_TRUE(g.rgba == w.rgba) << what << ": texel bytes differ";
  EXPECT_EQ(g.srgb, w.srgb) << what;
  EXPECT_EQ(g.wrap_u, w.wrap_u) << what;
  EXPECT_EQ(g.wrap_v, w.wrap_v) << what;
}

void expect_same_material(const scene::SceneAssets& got_assets, const scene::Material& got,
                          const scene::SceneAssets& want_assets, const scene::Material& want) {
  SCOPED_TRACE(want.name);
  EXPECT_EQ(got.name, want.name);
  expect_near(got.albedo, want.albedo, "albedo");
  expect_near(got.emission, want.emission, "emission");
  EXPECT_NEAR(got.opacity, want.opacity, kTolerance);
  EXPECT_NEAR(got.specular.roughness, want.specular.roughness, kTolerance);
  EXPECT_EQ(got.specular.metal, want.specular.metal);
  if (!want.specular.metal) {
    EXPECT_NEAR(got.specular.f0, want.specular.f0, kTolerance) << "f0 (ior)";
  }
  EXPECT_EQ(got.alpha_mode, want.alpha_mode);
  if (want.alpha_mode == scene::AlphaMode::kMask) {
    EXPECT_NEAR(got.alpha_cutoff, want.alpha_cutoff, kTolerance);
  }
  EXPECT_EQ(got.double_sided, want.double_sided);
  expect_same_texture(got_assets, got.texture, want_assets, want.texture, "base colour");
  expect_same_texture(got_assets, got.emission_texture, want_assets, want.emission_texture,
                      "emission");
  expect_same_texture(got_assets, got.normal_texture, want_assets, want.normal_texture,
                      "normal map");
  if (want.normal_texture >= 0) {
    EXPECT_NEAR(got.normal_scale, want.normal_scale, kTolerance);
  }
  expect_same_texture(got_assets, got.metallic_roughness_texture, want_assets,
                      want.metallic_roughness_texture, "metallic-roughness");
  if (want.metallic_roughness_texture >= 0) {
    EXPECT_NEAR(got.metallic, want.metallic, kTolerance);
  }
}

// The loaded instances 0..n-1 against the frame's: same matrices, the same triangles (world
// corners within 1e-6, in the exporter's order: by material, then the mesh's order), the same
// triangle count per material (by name), and the same materials.
void expect_instances(const scene::LoadedScene& loaded, const scene::FrameScene& frame,
                      const scene::SceneAssets& assets) {
  ASSERT_GE(loaded.instances.size(), frame.instances.size());
  std::map<std::string, size_t> want_counts, got_counts;
  for (size_t i = 0; i < frame.instances.size(); ++i) {
    SCOPED_TRACE("instance " + std::to_string(i));
    const scene::MeshInstance& want = frame.instances[i];
    const scene::MeshInstance& got = loaded.instances[i];
    EXPECT_EQ(got.model, want.model);
    const scene::Mesh& wm = assets.meshes[want.mesh];
    const scene::Mesh& gm = loaded.assets.meshes.at(got.mesh);
    ASSERT_EQ(gm.triangles.size(), wm.triangles.size());
    const std::vector<glm::vec3> corners = corners_by_material(wm);
    float worst = 0.0f;
    for (size_t t = 0; t < gm.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const glm::vec3 g = apply(got.model, gm.vertices.at(gm.triangles[t][k]).position);
        worst = std::max(
            worst, glm::length(g - apply(want.model, corners[3 * t + static_cast<size_t>(k)])));
      }
      ++want_counts[assets.materials[wm.materials[t]].name];
      ++got_counts[loaded.assets.materials.at(gm.materials[t]).name];
    }
    EXPECT_LE(worst, kTolerance);
  }
  EXPECT_EQ(got_counts, want_counts);
  for (const scene::Material& got : loaded.assets.materials) {
    const auto want = std::find_if(assets.materials.begin(), assets.materials.end(),
                                   [&](const scene::Material& m) { return m.name == got.name; });
    if (want != assets.materials.end()) expect_same_material(loaded.assets, got, assets, *want);
  }
}

void expect_lamp_camera_volume(const scene::LoadedScene& loaded, const scene::FrameScene& frame) {
  ASSERT_TRUE(loaded.lamp.has_value());
  expect_near(loaded.lamp->position, frame.light.position, "lamp position");
  expect_near(loaded.lamp->intensity, frame.light.intensity, "lamp intensity");
  EXPECT_FLOAT_EQ(loaded.lamp->lamp_radius, frame.light.lamp_radius);
  EXPECT_FLOAT_EQ(loaded.lamp->shadow_fov_y_deg, frame.light.shadow_fov_y_deg);
  EXPECT_FLOAT_EQ(loaded.lamp->shadow_near, frame.light.shadow_near);
  EXPECT_FLOAT_EQ(loaded.lamp->shadow_far, frame.light.shadow_far);
  EXPECT_TRUE(loaded.lights.empty()) << "the lamp is not an ordinary light";
  ASSERT_TRUE(loaded.volume.has_value());
  EXPECT_EQ(loaded.volume->lo, glm::vec3(-1.0f));
  EXPECT_EQ(loaded.volume->hi, glm::vec3(1.0f));
  ASSERT_TRUE(loaded.camera.has_value());
  const scene::Camera& c = *loaded.camera;
  expect_near(c.position, frame.camera.position, "camera position");
  expect_near(glm::normalize(c.target - c.position),
              glm::normalize(frame.camera.target - frame.camera.position), "camera direction");
  expect_near(glm::normalize(c.up), glm::normalize(frame.camera.up), "camera up");
  EXPECT_NEAR(c.fov_y_deg, frame.camera.fov_y_deg, 1e-4f);
  EXPECT_FLOAT_EQ(c.near_plane, frame.camera.near_plane);
  EXPECT_FLOAT_EQ(c.far_plane, frame.camera.far_plane);
}

std::string lines(const std::vector<std::string>& v) {
  std::string out;
  for (const std::string& s : v) out += s + "\n";
  return out;
}

TEST(GltfExport, DemoFrameRoundTripsThroughTheLoader) {
  ExportFolder dir;
  const scene::FrameScene frame = scene::make_demo_frame(demo_assets());
  const scene::LoadedScene loaded = export_and_load(dir.file("demo.glb"), frame);
  EXPECT_TRUE(loaded.warnings.empty()) << lines(loaded.warnings);
  EXPECT_EQ(loaded.instances.size(), frame.instances.size());
  EXPECT_EQ(loaded.assets.materials.size(), demo_assets().materials.size());
  EXPECT_EQ(loaded.assets.textures.size(), demo_assets().textures.size());
  expect_instances(loaded, frame, demo_assets());
  expect_lamp_camera_volume(loaded, frame);
}

TEST(GltfExport, DemoFrameWithMarblesRoundTripsThroughTheLoader) {
  ExportFolder dir;
  const scene::FrameScene frame = demo_frame_with_marbles();
  const scene::LoadedScene loaded = export_and_load(dir.file("marbles.glb"), frame);
  EXPECT_TRUE(loaded.warnings.empty()) << lines(loaded.warnings);
  ASSERT_EQ(loaded.instances.size(), frame.instances.size() + frame.spheres.size());
  expect_instances(loaded, frame, demo_assets());
  expect_lamp_camera_volume(loaded, frame);
  for (size_t s = 0; s < frame.spheres.size(); ++s) {
    SCOPED_TRACE("marble " + std::to_string(s));
    const scene::Sphere& want = frame.spheres[s];
    const scene::MeshInstance& got = loaded.instances[frame.instances.size() + s];
    const scene::Mesh& mesh = loaded.assets.meshes.at(got.mesh);
    // Every vertex on the sphere; the material is the marble's.
    float worst = 0.0f;
    for (const scene::Vertex& v : mesh.vertices)
      worst = std::max(
          worst, std::abs(glm::distance(apply(got.model, v.position), want.center) - want.radius));
    EXPECT_LE(worst, kTolerance);
    const std::map<uint32_t, size_t> per_material = triangles_per_material(mesh);
    ASSERT_EQ(per_material.size(), 1u);
    scene::Material marble;
    marble.name = loaded.assets.materials.at(per_material.begin()->first).name;
    marble.albedo = want.albedo;
    marble.emission = want.emission;
    marble.specular = want.specular;
    expect_same_material(loaded.assets, loaded.assets.materials.at(per_material.begin()->first),
                         demo_assets(), marble);
  }
}

TEST(GltfExport, InstanceFlagsRoundTripThroughTheLoader) {
  ExportFolder dir;
  scene::FrameScene frame = demo_frame_with_marbles();
  frame.spheres[1].casts_shadow = false;  // as a fireball
  const scene::LoadedScene loaded = export_and_load(dir.file("flags.glb"), frame);
  ASSERT_EQ(loaded.instances.size(), frame.instances.size() + frame.spheres.size());
  for (size_t i = 0; i < loaded.instances.size(); ++i) {
    const bool sphere = i >= frame.instances.size();
    const size_t s = i - frame.instances.size();
    EXPECT_EQ(loaded.instances[i].casts_shadow,
              sphere ? frame.spheres[s].casts_shadow : frame.instances[i].casts_shadow)
        << "instance " << i;
    EXPECT_EQ(loaded.instances[i].voxelize, sphere || frame.instances[i].voxelize)
        << "instance " << i;
  }
}

TEST(GltfExport, GltfTextLoadsLikeTheGlb) {
  ExportFolder dir;
  const scene::FrameScene frame = scene::make_demo_frame(demo_assets());
  const scene::LoadedScene glb = export_and_load(dir.file("demo.glb"), frame);
  const scene::LoadedScene text = export_and_load(dir.file("demo.gltf"), frame);
  expect_instances(text, frame, demo_assets());
  expect_lamp_camera_volume(text, frame);
  ASSERT_EQ(text.assets.meshes.size(), glb.assets.meshes.size());
  for (size_t m = 0; m < glb.assets.meshes.size(); ++m)
    EXPECT_EQ(text.assets.meshes[m].triangles, glb.assets.meshes[m].triangles);
  ASSERT_EQ(text.assets.textures.size(), glb.assets.textures.size());
  for (size_t t = 0; t < glb.assets.textures.size(); ++t)
    EXPECT_TRUE(text.assets.textures[t].rgba == glb.assets.textures[t].rgba);
}

TEST(GltfExport, EveryMaterialFeatureAndLightRoundTripsThroughTheLoader) {
  ExportFolder dir;
  const SyntheticScene s = synthetic_scene();
  const scene::LoadedScene loaded =
      export_and_load(dir.file("synthetic.glb"), s.frame, {}, s.assets);
  EXPECT_TRUE(loaded.warnings.empty()) << lines(loaded.warnings);
  expect_instances(loaded, s.frame, s.assets);
  EXPECT_EQ(loaded.assets.materials.size(), 2u);
  // Tangents in the exporter's vertex order: the quad's 4 vertices, then the triangle's 3.
  const scene::Mesh& mesh = loaded.assets.meshes.at(loaded.instances.at(0).mesh);
  ASSERT_EQ(mesh.tangents.size(), 7u);
  for (size_t v = 0; v < 7; ++v)
    EXPECT_EQ(mesh.tangents[v], glm::vec4(1.0f, 0.0f, 0.0f, v == 6 ? -1.0f : 1.0f))
        << "vertex " << v;
  EXPECT_FALSE(loaded.lamp.has_value());
  EXPECT_FALSE(loaded.volume.has_value());
  ASSERT_EQ(loaded.lights.size(), s.frame.lights.size());
  for (size_t i = 0; i < loaded.lights.size(); ++i) {
    const scene::PunctualLight& got = loaded.lights[i];
    const scene::PunctualLight& want = s.frame.lights[i];
    SCOPED_TRACE(want.name);
    EXPECT_EQ(got.name, want.name);
    EXPECT_EQ(got.type, want.type);
    expect_near(got.intensity, want.intensity, "intensity");
    if (want.type != scene::LightType::kDirectional) {
      expect_near(got.position, want.position, "position");
    }
    if (want.type != scene::LightType::kPoint) {
      expect_near(got.direction, want.direction, "direction");
    }
    EXPECT_FLOAT_EQ(got.range, want.range);
    if (want.type == scene::LightType::kSpot) {
      EXPECT_FLOAT_EQ(got.outer_cone, want.outer_cone);
      EXPECT_FLOAT_EQ(got.inner_cone, want.inner_cone);  // the hard edge: inner == outer again
    }
  }
}

}  // namespace
}  // namespace rp::test::gltf_export_checks
