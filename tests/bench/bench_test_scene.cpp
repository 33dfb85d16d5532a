#include "bench_test_scene.h"

#include <glm/gtc/matrix_transform.hpp>

#include "scene/box_mesh.h"
#include "scene/frame_scene.h"
#include "scene/gltf_export.h"

namespace rp::test {
BenchTestScene write_bench_test_scene(const std::filesystem::path& file, float spot_scale) {
  scene::SceneAssets a;
  const auto material = [&](const char* name, glm::vec3 albedo, glm::vec3 emission, float f0,
                            float roughness) {
    scene::Material m;
    m.name = name;
    m.albedo = albedo;
    m.emission = emission;
    m.specular = {roughness, f0, false};
    a.materials.push_back(m);
  };
  material("floor", glm::vec3(0.75f), glm::vec3(0.0f), 0.04f, 0.5f);  // coated
  material("wall", glm::vec3(0.8f, 0.75f, 0.7f), glm::vec3(0.0f), 0.0f, 1.0f);
  material("red box", glm::vec3(0.8f, 0.15f, 0.1f), glm::vec3(0.0f), 0.0f, 1.0f);
  material("blue box", glm::vec3(0.15f, 0.3f, 0.8f), glm::vec3(0.0f), 0.0f, 1.0f);
  material("glow", glm::vec3(0.1f), glm::vec3(3.0f, 2.4f, 1.2f), 0.0f, 1.0f);
  a.materials[0].texture = 0;

  scene::Texture checker;  // 8x8 texels, two greys (sRGB)
  checker.name = "checker";
  checker.width = checker.height = 8;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const uint8_t v = ((x / 2 + y / 2) % 2) ? 255 : 190;
      checker.rgba.insert(checker.rgba.end(), {v, v, v, 255});
    }
  a.textures.push_back(checker);

  scene::Mesh room;  // floor 8 m x 8 m, back wall 3 m high, a glowing patch on the wall
  room.name = "room";
  scene::append_box(room, {0.0f, -0.05f, 0.0f}, {4.0f, 0.05f, 4.0f}, 0, 4.0f);
  scene::append_box(room, {0.0f, 1.5f, -3.0f}, {4.0f, 1.5f, 0.05f}, 1);
  scene::append_box(room, {0.0f, 1.9f, -2.93f}, {0.9f, 0.45f, 0.02f}, 4);
  scene::Mesh red, blue;  // unit cubes, placed and scaled by their instances
  red.name = "red box";
  blue.name = "blue box";
  scene::append_box(red, glm::vec3(0.0f), glm::vec3(0.5f), 2);
  scene::append_box(blue, glm::vec3(0.0f), glm::vec3(0.5f), 3);
  a.meshes = {room, red, blue};

  scene::FrameScene f;
  f.lamp = false;
  f.camera.position = {0.0f, 2.4f, 5.0f};
  f.camera.target = {0.0f, 0.7f, -1.0f};
  f.camera.fov_y_deg = 55.0f;
  f.camera.near_plane = 0.05f;
  f.camera.far_plane = 30.0f;
  f.prev_camera = f.camera;
  scene::MeshInstance inst;
  f.instances.push_back(inst);
  inst.mesh = 1;
  inst.model = glm::translate(glm::mat4(1.0f), glm::vec3(-1.2f, 0.6f, -1.0f)) *
               glm::scale(glm::mat4(1.0f), glm::vec3(1.2f));
  inst.prev_model = inst.model;
  f.instances.push_back(inst);
  inst.mesh = 2;
  inst.model = glm::translate(glm::mat4(1.0f), glm::vec3(1.2f, 0.8f, 0.2f)) *
               glm::scale(glm::mat4(1.0f), glm::vec3(0.7f, 1.6f, 0.7f));
  inst.prev_model = inst.model;
  f.instances.push_back(inst);

  scene::PunctualLight sun;
  sun.name = "sun";
  sun.type = scene::LightType::kDirectional;
  sun.direction = glm::normalize(glm::vec3(-0.5f, -0.8f, -0.35f));
  sun.intensity = glm::vec3(1.0f, 0.95f, 0.85f) * (2.5f / 3.14159265f);
  f.lights.push_back(sun);
  scene::PunctualLight spot;
  spot.name = "spot";
  spot.type = scene::LightType::kSpot;
  spot.position = {-2.0f, 3.5f, 1.5f};
  spot.direction = glm::normalize(glm::vec3(0.8f, -3.0f, -2.5f));
  spot.inner_cone = 0.35f;
  spot.outer_cone = 0.6f;
  spot.intensity = glm::vec3(0.7f, 0.85f, 1.0f) * (40.0f / 3.14159265f) * spot_scale;
  f.lights.push_back(spot);
  scene::export_gltf(a, f, file);

  BenchTestScene s;
  for (const scene::MeshInstance& i : f.instances)
    s.triangles += uint32_t(a.meshes[i.mesh].triangles.size());
  s.meshes = uint32_t(a.meshes.size());
  s.instances = uint32_t(f.instances.size());
  s.textures = uint32_t(a.textures.size());
  s.lights = uint32_t(f.lights.size());
  for (const scene::Material& m : a.materials) s.materials.push_back(m.name);
  return s;
}

}  // namespace rp::test
