// The demo scene: assets load from the committed folder, five tumblers stand on the floor inside
// the box without touching, and the default camera sees the whole box.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>

#include "scene/demo_scene.h"

namespace {

using namespace rp::scene;

const SceneAssets& assets() {
  static const SceneAssets a = make_demo_assets(default_asset_dir());
  return a;
}

glm::vec3 transform(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

TEST(DemoScene, AssetsLoadWithTheExpectedLayout) {
  const SceneAssets& a = assets();
  ASSERT_EQ(a.meshes.size(), 4u);
  EXPECT_EQ(a.meshes[demo::kBoxMesh].name, "cornell_box");
  EXPECT_EQ(a.meshes[demo::kLampMesh].name, "lamp_cap");
  EXPECT_EQ(a.meshes[demo::kTumblerMesh].name, "tumbler");
  EXPECT_EQ(a.meshes[demo::kTumblerProxyMesh].name, "tumbler_proxy");
  // Only the tumbler has a proxy, for volumes up to 64^3 and shadow maps up to 512^2
  // (scene::voxel_mesh and scene::shadow_mesh pick it).
  for (uint32_t m = 0; m < a.meshes.size(); ++m) {
    const int want = m == demo::kTumblerMesh ? int(demo::kTumblerProxyMesh) : -1;
    EXPECT_EQ(a.meshes[m].proxy, want) << a.meshes[m].name;
  }
  EXPECT_EQ(voxel_mesh(a.meshes, demo::kTumblerMesh, 32), demo::kTumblerProxyMesh);
  EXPECT_EQ(voxel_mesh(a.meshes, demo::kTumblerMesh, 64), demo::kTumblerProxyMesh);
  EXPECT_EQ(voxel_mesh(a.meshes, demo::kTumblerMesh, 128), demo::kTumblerMesh);
  EXPECT_EQ(voxel_mesh(a.meshes, demo::kBoxMesh, 64), demo::kBoxMesh);
  EXPECT_EQ(shadow_mesh(a.meshes, demo::kTumblerMesh, 256), demo::kTumblerProxyMesh);
  EXPECT_EQ(shadow_mesh(a.meshes, demo::kTumblerMesh, 512), demo::kTumblerProxyMesh);
  EXPECT_EQ(shadow_mesh(a.meshes, demo::kTumblerMesh, 1024), demo::kTumblerMesh);
  EXPECT_EQ(shadow_mesh(a.meshes, demo::kLampMesh, 1024), demo::kLampMesh);
  ASSERT_EQ(a.textures.size(), 2u);
  EXPECT_EQ(a.textures[demo::kWoodTexture].width, 512);
  EXPECT_EQ(a.textures[demo::kWoodTexture].height, 512);
  EXPECT_EQ(a.textures[demo::kTumblerTexture].width, 512);
  EXPECT_EQ(a.textures[demo::kTumblerTexture].height, 256);
  ASSERT_EQ(a.materials.size(), 7u);
  EXPECT_EQ(a.materials[demo::kFloorMaterial].texture, static_cast<int>(demo::kWoodTexture));
  EXPECT_EQ(a.materials[demo::kTumblerMaterial].texture, static_cast<int>(demo::kTumblerTexture));
  EXPECT_GT(a.materials[demo::kLampMaterial].emission.x, 1.0f);
  EXPECT_EQ(a.materials[demo::kLampMaterial].albedo, glm::vec3(0.0f));
  // Every triangle's material exists; every textured material's texture exists.
  for (const Mesh& mesh : a.meshes) {
    ASSERT_EQ(mesh.materials.size(), mesh.triangles.size());
    for (const uint32_t m : mesh.materials) EXPECT_LT(m, a.materials.size());
    for (const glm::uvec3& t : mesh.triangles) {
      EXPECT_LT(std::max({t.x, t.y, t.z}), mesh.vertices.size());
    }
  }
  for (const Material& m : a.materials) EXPECT_LT(m.texture, static_cast<int>(a.textures.size()));
}

TEST(DemoScene, AssetDirFromEnvironment) {
  ASSERT_EQ(::setenv("ROLYPOLY_ASSET_DIR", "/some/where", 1), 0);
  EXPECT_EQ(default_asset_dir(), "/some/where");
  ASSERT_EQ(::unsetenv("ROLYPOLY_ASSET_DIR"), 0);
  EXPECT_EQ(default_asset_dir(), std::string(ROLYPOLY_ASSET_DIR));
}

TEST(DemoScene, InstancesAndFlags) {
  const FrameScene frame = make_demo_frame(assets(), 7);
  EXPECT_EQ(frame.frame_index, 7u);
  ASSERT_EQ(frame.instances.size(), 7u);
  int tumblers = 0;
  for (const MeshInstance& inst : frame.instances) {
    EXPECT_EQ(inst.model, inst.prev_model);
    if (inst.mesh == demo::kTumblerMesh) {
      ++tumblers;
      EXPECT_TRUE(inst.casts_shadow);
    } else {
      EXPECT_FALSE(inst.casts_shadow);
      EXPECT_EQ(inst.model, glm::mat4(1.0f));
    }
    // the box keeps a sky's sun out, not the lamp's light
    EXPECT_EQ(inst.casts_light_shadow, inst.mesh == demo::kBoxMesh);
  }
  EXPECT_EQ(tumblers, 5);
  EXPECT_EQ(frame.camera.position, frame.prev_camera.position);
  EXPECT_EQ(frame.camera.view(), frame.prev_camera.view());
  EXPECT_TRUE(frame.spheres.empty());
}

TEST(DemoScene, TumblersStandOnTheFloorInsideTheBoxWithoutTouching) {
  const SceneAssets& a = assets();
  const FrameScene frame = make_demo_frame(a, 0);
  const Mesh& mesh = a.meshes[demo::kTumblerMesh];
  const TumblerShape shape;
  std::vector<glm::mat4> models;
  for (const MeshInstance& inst : frame.instances) {
    if (inst.mesh == demo::kTumblerMesh) models.push_back(inst.model);
  }
  ASSERT_EQ(models.size(), 5u);
  for (const glm::mat4& m : models) {
    float min_y = 10.0f;
    for (const Vertex& v : mesh.vertices) {
      const glm::vec3 p = transform(m, v.position);
      min_y = std::min(min_y, p.y);
      // Inside the box with room to rock: at least 0.25 from the side and back walls.
      EXPECT_LT(std::fabs(p.x), 0.75f);
      EXPECT_LT(std::fabs(p.z), 0.75f);
      EXPECT_LT(p.y, 1.0f);
    }
    EXPECT_NEAR(min_y, -1.0f, 1e-6f);  // touching the floor at the bottom pole
    // Upright: the local axis is world +y.
    const glm::vec3 axis = glm::vec3(m * glm::vec4(0, 1, 0, 0));
    EXPECT_NEAR(axis.y, 1.0f, 1e-6f);
    // The painted face (local +z) turns towards the camera, within 25 degrees.
    const glm::vec3 face = glm::vec3(m * glm::vec4(0, 0, 1, 0));
    const glm::vec3 base = transform(m, glm::vec3(0.0f));
    glm::vec3 to_camera = frame.camera.position - base;
    to_camera.y = 0.0f;
    EXPECT_GT(glm::dot(face, glm::normalize(to_camera)), std::cos(glm::radians(25.0f)));
  }
  // No two tumblers touch: every vertex of one is outside the other (SDF > 0), with margin.
  for (size_t i = 0; i < models.size(); ++i) {
    for (size_t j = 0; j < models.size(); ++j) {
      if (i == j) continue;
      const glm::mat4 to_local_j = glm::inverse(models[j]);
      float closest = 10.0f;
      for (const Vertex& v : mesh.vertices) {
        const glm::vec3 p = transform(to_local_j, transform(models[i], v.position));
        closest = std::min(closest, shape.sdf(p));
      }
      EXPECT_GT(closest, 0.1f) << "tumblers " << i << " and " << j;
    }
  }
}

TEST(DemoScene, CameraLooksIntoTheBoxAndTheWallsFillTheFrame) {
  const FrameScene frame = make_demo_frame(assets(), 0);
  const glm::mat4 vp = frame.camera.projection(1.0f) * frame.camera.view();
  for (const float x : {-1.0f, 1.0f}) {
    for (const float y : {-1.0f, 1.0f}) {
      for (const float z : {-1.0f, 1.0f}) {
        const glm::vec4 c = vp * glm::vec4(x, y, z, 1.0f);
        ASSERT_GT(c.w, 0.0f);
        const glm::vec3 ndc = glm::vec3(c) / c.w;
        EXPECT_LT(std::fabs(ndc.z), 1.0f) << x << "," << y << "," << z;  // within near..far
        if (z < 0.0f) {
          // The back wall's corners are in view...
          EXPECT_LE(std::fabs(ndc.x), 1.0f) << x << "," << y << "," << z;
          EXPECT_LE(std::fabs(ndc.y), 1.0f) << x << "," << y << "," << z;
        } else {
          // ...and the open side's edges lie just outside it, so no background shows at the
          // frame's border, yet the walls are cut by less than 3 % of the view.
          EXPECT_GT(std::fabs(ndc.x), 1.0f) << x << "," << y << "," << z;
          EXPECT_LT(std::fabs(ndc.x), 1.03f) << x << "," << y << "," << z;
          EXPECT_GT(std::fabs(ndc.y), 1.0f) << x << "," << y << "," << z;
        }
      }
    }
  }
}

// --open: the skylight leaves out ceiling quads behind the lamp only (the cap's rim, 0.335 from
// the ceiling's centre, stays on whole ceiling), and nothing else changes.
TEST(DemoScene, OpenVariantCutsTheSkylightBehindTheLamp) {
  const SceneAssets open = make_demo_assets(default_asset_dir(), true);
  const SceneAssets& closed = assets();
  ASSERT_EQ(open.meshes.size(), closed.meshes.size());
  const Mesh& box = open.meshes[demo::kBoxMesh];
  EXPECT_EQ(box.triangles.size(), closed.meshes[demo::kBoxMesh].triangles.size() - 16u);
  for (size_t m = 1; m < open.meshes.size(); ++m)
    EXPECT_EQ(open.meshes[m].triangles.size(), closed.meshes[m].triangles.size()) << m;
  const FrameScene frame = make_demo_frame(open, 0);
  const float rim = std::sqrt(frame.light.lamp_radius * frame.light.lamp_radius -
                              (frame.light.position.y - 1.0f) * (frame.light.position.y - 1.0f));
  // the skylight's nearest edge to the lamp's axis (z = -0.5) lies beyond the cap's rim
  EXPECT_LT(rim, -demo::kSkylightMax.y);
  EXPECT_GT(demo::kSkylightMax.x - demo::kSkylightMin.x, 0.0f);
}

TEST(DemoScene, LampCentreIsOutsideTheBox) {
  const FrameScene frame = make_demo_frame(assets(), 0);
  EXPECT_GT(frame.light.position.y, 1.0f);
  EXPECT_LT(frame.light.position.y - frame.light.lamp_radius, 1.0f);  // part of it is inside
}

}  // namespace
