// The scene a glTF file places: node transforms down the hierarchy, instancing, lights, the
// camera, bounds, the volume extras, which scene is loaded, warnings, and the three ways of
// storing the same file (.gltf + .bin, data URIs, .glb).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "gltf/gltf_writer.h"
#include "scene/gltf_loader.h"

namespace rp::test {
namespace {

using scene::load_gltf;
using scene::LoadedScene;

void expect_vec(glm::vec3 got, glm::vec3 want, float tol = 1e-5f) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

glm::vec3 world(const LoadedScene& s, size_t instance, glm::vec3 local) {
  return glm::vec3(s.instances.at(instance).model * glm::vec4(local, 1.0f));
}

// One triangle with a vertex at (0, 1, 0), as mesh 0.
void triangle_mesh(GltfBuilder& b) {
  const int pos = b.vec3s({{0, 1, 0}, {-1, 0, 0}, {1, 0, 0}});
  const int nrm = b.vec3s(std::vector<glm::vec3>(3, {0, 0, 1}));
  b.mesh({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}}});
}

const float kS45 = std::sqrt(0.5f);

TEST(GltfScene, ComposesNodeTransformsDownTheHierarchy) {
  TempFolder dir;
  GltfBuilder b;
  triangle_mesh(b);
  // child: a matrix translating by (1, 0, 0); parent: T (1, 2, 3) R 90 deg about z, S 2.
  const int child =
      b.node({{"mesh", 0}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1}}});
  const int parent = b.node({{"children", {child}},
                             {"translation", {1, 2, 3}},
                             {"rotation", {0, 0, kS45, kS45}},
                             {"scale", {2, 2, 2}}});
  b.scene({parent});
  const LoadedScene s = load_gltf(b.write_gltf(dir, "scene"));
  ASSERT_EQ(s.instances.size(), 1u);
  // (0,1,0) -> child (1,1,0) -> scale (2,2,0) -> rotate (-2,2,0) -> translate (-1,4,3).
  expect_vec(world(s, 0, {0, 1, 0}), {-1, 4, 3});
  expect_vec(world(s, 0, {1, 0, 0}), {1, 6, 3});  // (2,0,0) -> (4,0,0) -> (0,4,0) -> (1,6,3)
  EXPECT_EQ(s.instances[0].model, s.instances[0].prev_model);
  EXPECT_TRUE(s.instances[0].casts_shadow);
}

TEST(GltfScene, DrawsAMeshUsedByTwoNodesAsOneMeshAndTwoInstances) {
  TempFolder dir;
  GltfBuilder b;
  triangle_mesh(b);
  b.scene({b.node({{"mesh", 0}}), b.node({{"mesh", 0}, {"translation", {10, 0, 0}}})});
  const LoadedScene s = load_gltf(b.write_gltf(dir, "scene"));
  ASSERT_EQ(s.assets.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), 2u);
  EXPECT_EQ(s.instances[0].mesh, 0u);
  EXPECT_EQ(s.instances[1].mesh, 0u);
  expect_vec(world(s, 1, {0, 1, 0}), {10, 1, 0});
  // Bounds: both instances' vertices in world space.
  expect_vec(s.bounds.lo, {-1, 0, 0});
  expect_vec(s.bounds.hi, {11, 1, 0});
}

TEST(GltfScene, GivesAMirroringInstanceACopyWithReversedWinding) {
  TempFolder dir;
  GltfBuilder b;
  triangle_mesh(b);
  b.scene({b.node({{"mesh", 0}}), b.node({{"mesh", 0}, {"scale", {-1, 1, 1}}})});
  const LoadedScene s = load_gltf(b.write_gltf(dir, "scene"));
  ASSERT_EQ(s.assets.meshes.size(), 2u);
  const scene::Mesh& plain = s.assets.meshes[s.instances[0].mesh];
  const scene::Mesh& flipped = s.assets.meshes[s.instances[1].mesh];
  EXPECT_EQ(plain.triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(flipped.triangles[0], glm::uvec3(0, 2, 1));
  // Seen in world space, both are counter-clockwise from +z.
  for (size_t i = 0; i < 2; ++i) {
    const scene::Mesh& m = s.assets.meshes[s.instances[i].mesh];
    const glm::vec3 a = world(s, i, m.vertices[m.triangles[0].x].position);
    const glm::vec3 c1 = world(s, i, m.vertices[m.triangles[0].y].position);
    const glm::vec3 c2 = world(s, i, m.vertices[m.triangles[0].z].position);
    EXPECT_GT(glm::cross(c1 - a, c2 - a).z, 0.0f) << i;
  }
}

TEST(GltfScene, ConvertsPointLightCandelaToTheRenderersIntensity) {
  TempFolder dir;
  GltfBuilder b;
  triangle_mesh(b);
  const int white = b.light({{"type", "point"}, {"intensity", 10}});
  const int orange =
      b.light({{"type", "point"}, {"intensity", 2}, {"color", {1, 0.5, 0}}, {"range", 7}});
  const int plain = b.light({{"type", "point"}});  // glTF defaults: intensity 1, white
  auto lit = [&](int light, glm::vec3 at) {
    return b.node({{"translation", {at.x, at.y, at.z}},
                   {"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}});
  };
  b.scene({b.node({{"mesh", 0}}), lit(white, {0, 3, 0}), lit(orange, {1, 2, 3}),
           lit(plain, {0, 0, 0})});
  const LoadedScene s = load_gltf(b.write_gltf(dir, "scene"));
  ASSERT_EQ(s.lights.size(), 3u);
  const float pi = glm::pi<float>();
  EXPECT_EQ(s.lights[0].type, scene::LightType::kPoint);
  expect_vec(s.lights[0].intensity, glm::vec3(10.0f / pi));
  expect_vec(s.lights[0].position, {0, 3, 0});
  EXPECT_EQ(s.lights[0].range, 0.0f);
  expect_vec(s.lights[1].intensity, {2.0f / pi, 1.0f / pi, 0.0f});
  EXPECT_EQ(s.lights[1].range, 7.0f);
  expect_vec(s.lights[2].intensity, glm::vec3(1.0f / pi));
}

TEST(GltfScene, PointsSpotAndDirectionalLightsAlongTheirNodesMinusZ) {
  TempFolder dir;
  GltfBuilder b;
  triangle_mesh(b);
  const int sun = b.light({{"type", "directional"}, {"intensity", 3}});
  const int spot =
      b.light({{"type", "spot"}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}});
  const int default_spot = b.light({{"type", "spot"}, {"spot", Json::object()}});
  auto ext = [](int light) { return Json{{"KHR_lights_punctual", {{"light", light}}}}; };
  // -90 degrees about x: -z turns to -y (straight down).
  const int down = b.node({{"rotation", {-kS45, 0, 0, kS45}}, {"extensions", ext(sun)}});
  // 90 degrees about y: -z turns to -x.
  const int west = b.node(
      {{"rotation", {0, kS45, 0, kS45}}, {"translation", {4, 5, 6}}, {"extensions", ext(spot)}});
  const int ahead = b.node({{"extensions", ext(default_spot)}});
  b.scene({b.node({{"mesh", 0}}), down, west, ahead});
  const LoadedScene s = load_gltf(b.write_gltf(dir, "scene"));
  ASSERT_EQ(s.lights.size(), 3u);
  EXPECT_EQ(s.lights[0].type, scene::LightType::kDirectional);
  expect_vec(s.lights[0].direction, {0, -1, 0});
  expect_vec(s.lights[0].intensity, glm::vec3(3.0f / glm::pi<float>()));  // lux as W/m^2, / pi
  EXPECT_EQ(s.lights[1].type, scene::LightType::kSpot);
  expect_vec(s.lights[1].direction, {-1, 0, 0});
  expect_vec(s.lights[1].position, {4, 5, 6});
  EXPECT_FLOAT_EQ(s.lights[1].inner_cone, 0.2f);
  EXPECT_FLOAT_EQ(s.lights[1].outer_cone, 0.6f);
  expect_vec(s.lights[2].direction, {0, 0, -1});
  EXPECT_FLOAT_EQ(s.lights[2].inner_cone, 0.0f);
  EXPECT_FLOAT_EQ(s.lights[2].outer_cone, glm::quarter_pi<float>());
}

// What `rolypoly export` writes for the demo's lamp and for instances that cast no shadow or
// stay out of the GI volume comes back as it was.
TEST(GltfScene, RestoresRolypolysLampAndInstanceFlagsFromExtras) {
  TempFolder dir;
  GltfBuilder b;
  triangle_mesh(b);
  const int lamp = b.light({{"type", "point"},
                            {"intensity", 8},
                            {"extras",
                             {{"rolypoly",
                               {{"lamp",
                                 {{"radius", 0.25},
                                  {"shadow_fov_y_deg", 100},
                                  {"shadow_near", 0.1},
                                  {"shadow_far", 3}}}}}}}});
  const int other = b.light({{"type", "point"}, {"intensity", 2}});
  auto ext = [](int light) { return Json{{"KHR_lights_punctual", {{"light", light}}}}; };
  b.scene({b.node({{"mesh", 0}, {"extras", {{"rolypoly", {{"casts_shadow", false}}}}}}),
           b.node({{"mesh", 0}, {"extras", {{"rolypoly", {{"voxelize", false}}}}}}),
           b.node({{"translation", {0, 1.1, 0}}, {"extensions", ext(lamp)}}),
           b.node({{"extensions", ext(other)}})});
  const LoadedScene s = load_gltf(b.write_gltf(dir, "scene"));
  ASSERT_TRUE(s.lamp.has_value());
  expect_vec(s.lamp->position, {0, 1.1f, 0});
  expect_vec(s.lamp->intensity, glm::vec3(8.0f / glm::pi<float>()));
  EXPECT_FLOAT_EQ(s.lamp->lamp_radius, 0.25f);
  EXPECT_FLOAT_EQ(s.lamp->shadow_fov_y_deg, 100.0f);
  EXPECT_FLOAT_EQ(s.lamp->shadow_near, 0.1f);
  EXPECT_FLOAT_EQ(s.lamp->shadow_far, 3.0f);
  ASSERT_EQ(s.lights.size(), 1u);  // the lamp is not an ordinary light
  expect_vec(s.lights[0].intensity, glm::vec3(2.0f / glm::pi<float>()));
  ASSERT_EQ(s.instances.size(), 2u);
  EXPECT_FALSE(s.instances[0].casts_shadow);
  EXPECT_TRUE(s.instances[0].voxelize);
  EXPECT_TRUE(s.instances[1].casts_shadow);
  EXPECT_FALSE(s.instances[1].voxelize);
}

TEST(GltfScene, TakesTheFirstPerspectiveCameraDepthFirstFromItsNode) {
  TempFolder dir;
  GltfBuilder b;
  triangle_mesh(b);
  b.doc["cameras"] = {
      {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.5}, {"zfar", 90}}}},
      {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.05}, {"zfar", 100}}}}};
  const int eye =
      b.node({{"camera", 1}, {"translation", {0, 1, 5}}, {"rotation", {0, kS45, 0, kS45}}});
  const int first_root = b.node({{"mesh", 0}, {"children", {eye}}});
  const int later_root = b.node({{"camera", 0}});
  b.scene({first_root, later_root});
  const LoadedScene s = load_gltf(b.write_gltf(dir, "scene"));
  ASSERT_TRUE(s.camera.has_value());
  expect_vec(s.camera->position, {0, 1, 5});
  expect_vec(s.camera->target, {-1, 1, 5});
  expect_vec(s.camera->up, {0, 1, 0});
  EXPECT_NEAR(s.camera->fov_y_deg, glm::degrees(0.8f), 1e-4f);
  EXPECT_FLOAT_EQ(s.camera->near_plane, 0.05f);
  EXPECT_FLOAT_EQ(s.camera->far_plane, 100.0f);
}

TEST(GltfScene, SetsTheFarPlaneFromTheBoundsWithoutZfarAndIgnoresOrthographicCameras) {
  TempFolder dir;
  GltfBuilder b;
  triangle_mesh(b);
  b.doc["cameras"] = {{{"type", "orthographic"},
                       {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 9}}}},
                      {{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}};
  b.scene({b.node({{"mesh", 0}, {"translation", {0, 0, -20}}}), b.node({{"camera", 0}}),
           b.node({{"camera", 1}, {"translation", {0, 0, 10}}})});
  const LoadedScene s = load_gltf(b.write_gltf(dir, "scene"));
  ASSERT_TRUE(s.camera.has_value());
  expect_vec(s.camera->position, {0, 0, 10});
  // The farthest scene point is ~30 away: the far plane must reach past it.
  EXPECT_GT(s.camera->far_plane, 31.0f);
  EXPECT_LT(s.camera->far_plane, 200.0f);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("orthographic"), std::string::npos);
}

TEST(GltfScene, ReadsTheVolumeFromTheScenesOrTheAssetsExtras) {
  for (const bool in_scene : {true, false}) {
    TempFolder dir;
    GltfBuilder b;
    triangle_mesh(b);
    b.scene({b.node({{"mesh", 0}})});
    const Json extras = {{"rolypoly", {{"volume", {-1, -2, -3, 4, 5, 6}}}}};
    if (in_scene)
      b.doc["scenes"][0]["extras"] = extras;
    else
      b.doc["asset"]["extras"] = extras;
    const LoadedScene s = load_gltf(b.write_gltf(dir, "scene"));
    ASSERT_TRUE(s.volume.has_value());
    expect_vec(s.volume->lo, {-1, -2, -3});
    expect_vec(s.volume->hi, {4, 5, 6});
  }
  TempFolder dir;
  GltfBuilder b;
  triangle_mesh(b);
  b.scene({b.node({{"mesh", 0}})});
  EXPECT_FALSE(load_gltf(b.write_gltf(dir, "scene")).volume.has_value());
}

TEST(GltfScene, LoadsTheDefaultSceneElseSceneZeroElseEveryRootNode) {
  TempFolder dir;
  GltfBuilder b;
  triangle_mesh(b);
  const int a = b.node({{"mesh", 0}});
  const int c = b.node({{"mesh", 0}, {"translation", {5, 0, 0}}});
  b.doc["scenes"] = {{{"nodes", {a}}}, {{"nodes", {c}}}};
  b.doc["scene"] = 1;
  const LoadedScene chosen = load_gltf(b.write_gltf(dir, "chosen"));
  ASSERT_EQ(chosen.instances.size(), 1u);
  expect_vec(world(chosen, 0, {0, 1, 0}), {5, 1, 0});
  ASSERT_EQ(chosen.warnings.size(), 1u);
  EXPECT_NE(chosen.warnings[0].find("only scene 1"), std::string::npos) << chosen.warnings[0];

  b.doc.erase("scene");
  const LoadedScene first = load_gltf(b.write_gltf(dir, "first"));
  ASSERT_EQ(first.instances.size(), 1u);
  expect_vec(world(first, 0, {0, 1, 0}), {0, 1, 0});

  b.doc.erase("scenes");
  EXPECT_EQ(load_gltf(b.write_gltf(dir, "all")).instances.size(), 2u);
}

TEST(GltfScene, NamesEachKindOfUnsupportedFeatureOnceWithItsPlaces) {
  TempFolder dir;
  GltfBuilder b;
  triangle_mesh(b);
  for (int i = 0; i < 6; ++i) b.material({{"alphaMode", "BLEND"}});
  Json primitives = Json::array();
  for (int i = 0; i < 6; ++i)
    primitives.push_back(
        {{"attributes", b.doc["meshes"][0]["primitives"][0]["attributes"]}, {"material", i}});
  b.mesh(primitives);
  b.use_extension("KHR_materials_clearcoat");
  b.use_extension("KHR_texture_transform");
  b.use_extension("KHR_lights_punctual");  // implemented: not named
  b.doc["animations"] = {{{"channels", Json::array()}, {"samplers", Json::array()}}};
  b.doc["skins"] = {{{"joints", {0}}}};
  b.scene({b.node({{"mesh", 1}}), b.node({{"mesh", 1}})});
  const LoadedScene s = load_gltf(b.write_gltf(dir, "scene"));
  ASSERT_EQ(s.warnings.size(), 4u);
  auto line = [&](const std::string& word) {
    const auto it = std::find_if(s.warnings.begin(), s.warnings.end(), [&](const std::string& w) {
      return w.find(word) != std::string::npos;
    });
    return it == s.warnings.end() ? std::string() : *it;
  };
  EXPECT_NE(line("extensions").find("KHR_materials_clearcoat, KHR_texture_transform"),
            std::string::npos);
  EXPECT_EQ(line("extensions").find("KHR_lights_punctual"), std::string::npos);
  EXPECT_FALSE(line("animations").empty());
  EXPECT_FALSE(line("skins").empty());
  // Six BLEND materials, met once each (the mesh is converted once for its two nodes).
  EXPECT_NE(line("BLEND").find("material 0, material 1, material 2, material 3 and 2 more"),
            std::string::npos)
      << line("BLEND");
}

TEST(GltfScene, ReadsTheSameSceneFromGltfBinDataUriAndGlb) {
  TempFolder dir;
  GltfBuilder b;
  const GltfBuilder::Quad q = b.quad();
  const int image = b.image_in_buffer(png(2, 1, {255, 0, 0, 255, 0, 255, 0, 255}));
  b.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", b.texture(image)}}}}}});
  b.mesh({{{"attributes", {{"POSITION", q.position}, {"TEXCOORD_0", q.uv}}},
           {"indices", q.indices},
           {"material", 0}}});
  b.scene({b.node({{"mesh", 0}})});
  const std::vector<std::string> paths = {
      b.write_gltf(dir, "split"), b.write_embedded(dir, "embedded"), b.write_glb(dir, "binary")};
  const LoadedScene reference = load_gltf(paths[0]);
  for (const std::string& path : paths) {
    SCOPED_TRACE(path);
    const LoadedScene s = load_gltf(path);
    ASSERT_EQ(s.assets.meshes.size(), 1u);
    ASSERT_EQ(s.assets.meshes[0].vertices.size(), reference.assets.meshes[0].vertices.size());
    for (size_t i = 0; i < s.assets.meshes[0].vertices.size(); ++i)
      EXPECT_EQ(s.assets.meshes[0].vertices[i].position,
                reference.assets.meshes[0].vertices[i].position);
    ASSERT_EQ(s.assets.textures.size(), 1u);
    EXPECT_EQ(s.assets.textures[0].width, 2);
    EXPECT_EQ(s.assets.textures[0].rgba, (std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 255}));
    EXPECT_TRUE(s.warnings.empty());
  }
}

}  // namespace
}  // namespace rp::test
