#include "scene/demo_scene.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/cornell_box.h"
#include "scene/textures.h"

namespace rp::scene {

std::array<TumblerPlacement, demo::kTumblerCount> demo_tumbler_placements() {
  // Floor positions (x, z) and a yaw offset in degrees from "facing the camera". A "W": the back
  // pair stands between the others as seen from the default camera, so no face is hidden.
  struct Spot {
    float x, z, yaw_offset_deg;
  };
  constexpr std::array<Spot, demo::kTumblerCount> kSpots = {{
      {0.00f, 0.20f, 0.0f},     // centre, a little forward
      {-0.42f, -0.45f, 12.0f},  // back left
      {0.42f, -0.45f, -10.0f},  // back right
      {-0.55f, 0.35f, -15.0f},  // front left
      {0.55f, 0.35f, 18.0f},    // front right
  }};
  const glm::vec3 camera = Camera{}.position;
  std::array<TumblerPlacement, demo::kTumblerCount> placements{};
  for (size_t i = 0; i < kSpots.size(); ++i) {
    const Spot& s = kSpots[i];
    // Yaw that turns local +z (the painted face) towards the camera: R_y(yaw) * +z =
    // (sin yaw, 0, cos yaw) must point along (camera - position) projected on the floor.
    const float facing = std::atan2(camera.x - s.x, camera.z - s.z);
    placements[i] = {glm::vec2(s.x, s.z), facing + glm::radians(s.yaw_offset_deg)};
  }
  return placements;
}

glm::mat4 upright_tumbler_model(const TumblerShape& shape, const TumblerPlacement& placement) {
  const glm::vec3 centre(placement.xz.x, -1.0f + shape.b, placement.xz.y);
  return glm::rotate(glm::translate(glm::mat4(1.0f), centre), placement.yaw,
                     glm::vec3(0.0f, 1.0f, 0.0f));
}

std::string default_asset_dir() {
  if (const char* env = std::getenv("ROLYPOLY_ASSET_DIR"); env != nullptr && env[0] != '\0') {
    return env;
  }
  return ROLYPOLY_ASSET_DIR;
}

SceneAssets make_demo_assets(const std::string& asset_dir, bool open) {
  SceneAssets assets;
  // Order must match the demo:: indices.
  assets.textures.push_back(load_texture(asset_dir + "/wood.png", "wood"));
  assets.textures.push_back(load_texture(asset_dir + "/tumbler_face.png", "tumbler_face"));

  assets.materials = {
      {"floor_wood", box_colors::kFloorTint, glm::vec3(0.0f), static_cast<int>(demo::kWoodTexture),
       demo::kFloorSpecular},
      {"ceiling", box_colors::kWhite, glm::vec3(0.0f), -1},
      {"back_wall", box_colors::kWhite, glm::vec3(0.0f), -1},
      {"left_wall_orange", box_colors::kOrange, glm::vec3(0.0f), -1},
      {"right_wall_sky_blue", box_colors::kSkyBlue, glm::vec3(0.0f), -1},
      {"lamp", glm::vec3(0.0f), box_colors::kLampEmission, -1},
      // The painted texture carries the colour; albedo 1 keeps it as painted.
      {"tumbler", glm::vec3(1.0f), glm::vec3(0.0f), static_cast<int>(demo::kTumblerTexture),
       demo::kTumblerSpecular},
  };

  BoxMaterialIds box_ids;
  box_ids.floor = demo::kFloorMaterial;
  box_ids.ceiling = demo::kCeilingMaterial;
  box_ids.back = demo::kBackMaterial;
  box_ids.left = demo::kLeftMaterial;
  box_ids.right = demo::kRightMaterial;
  CeilingOpening skylight;
  if (open) skylight = {demo::kSkylightMin, demo::kSkylightMax};
  assets.meshes.push_back(make_cornell_box(box_ids, 8, skylight));
  assets.meshes.push_back(make_lamp_cap(PointLight{}, demo::kLampMaterial));
  assets.meshes.push_back(
      make_tumbler_mesh(TumblerShape{}, TumblerMeshParams{}, demo::kTumblerMaterial));
  Mesh proxy =
      make_tumbler_mesh(TumblerShape{}, demo::kTumblerProxyParams, demo::kTumblerMaterial);
  proxy.name = "tumbler_proxy";
  assets.meshes.push_back(std::move(proxy));
  Mesh& tumbler = assets.meshes[demo::kTumblerMesh];
  tumbler.proxy = static_cast<int>(demo::kTumblerProxyMesh);
  tumbler.proxy_max_voxels = demo::kTumblerProxyMaxVoxels;
  tumbler.proxy_max_shadow_texels = demo::kTumblerProxyMaxShadowTexels;
  return assets;
}

void add_room_instances(FrameScene& frame) {
  MeshInstance box;
  box.mesh = demo::kBoxMesh;
  box.casts_shadow = false;
  box.casts_light_shadow = true;  // keeps a sky's sun out; the lamp's map does without it
  frame.instances.push_back(box);
  MeshInstance lamp;
  lamp.mesh = demo::kLampMesh;
  lamp.casts_shadow = false;
  lamp.voxelize = false;  // lit by the analytic point light; voxelized it would count twice
  frame.instances.push_back(lamp);
}

FrameScene make_demo_frame(const SceneAssets& assets, uint32_t frame_index) {
  if (assets.meshes.size() <= demo::kTumblerMesh ||
      assets.meshes[demo::kTumblerMesh].name != "tumbler") {
    throw std::invalid_argument("make_demo_frame: assets do not come from make_demo_assets");
  }
  FrameScene frame;
  frame.frame_index = frame_index;
  frame.prev_camera = frame.camera;

  add_room_instances(frame);

  const TumblerShape shape;
  for (const TumblerPlacement& placement : demo_tumbler_placements()) {
    MeshInstance tumbler;
    tumbler.mesh = demo::kTumblerMesh;
    tumbler.model = upright_tumbler_model(shape, placement);
    tumbler.prev_model = tumbler.model;
    tumbler.casts_shadow = true;
    frame.instances.push_back(tumbler);
  }
  return frame;
}

Sphere resting_marble(glm::vec2 xz, float radius, glm::vec3 albedo) {
  Sphere s;
  s.center = s.prev_center = glm::vec3(xz.x, -1.0f + radius, xz.y);
  s.radius = radius;
  s.albedo = albedo;
  s.specular = demo::kMarbleSpecular;  // as the simulated world's marbles
  s.casts_shadow = true;
  return s;
}

}  // namespace rp::scene
