// Writes a large glTF scene for load-time and frame-time benches of scene files (no third-party
// data): a 40 x 40 m floor, rows of tumblers of ten mesh variants (each variant one glTF mesh,
// instanced), one procedural 256x256 texture per material, a sun and three point lights.
// Usage: gen_load_scene OUT.glb [TRIANGLES] [TEXTURES]   (defaults: 250000, 50)
// Deterministic: integer hashing only, so the same arguments write the same bytes.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/gltf_export.h"
#include "scene/tumbler_shape.h"

namespace {

uint32_t hash(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// Checks and stripes in a hue of the texture's own (sRGB bytes), with some per-texel noise.
rp::scene::Texture make_texture(uint32_t index) {
  rp::scene::Texture t;
  t.name = "pattern_" + std::to_string(index);
  t.width = t.height = 256;
  t.rgba.resize(256 * 256 * 4);
  const uint32_t h = hash(index + 1);
  const int cell = 8 << (h % 3);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      const bool odd = ((x / cell) + (y / cell)) % 2 != 0;
      const uint32_t n = hash(uint32_t(y * 256 + x) ^ (h << 8)) & 31;
      uint8_t* p = &t.rgba[size_t(y * 256 + x) * 4];
      for (int c = 0; c < 3; ++c) {
        const int base = 60 + int((h >> (8 * c)) % 150);
        p[c] = uint8_t(std::min(255, (odd ? base : base / 2) + int(n)));
      }
      p[3] = 255;
    }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 4) {
    std::fprintf(stderr, "usage: gen_load_scene OUT.glb [TRIANGLES] [TEXTURES]\n");
    return 2;
  }
  const long triangles = argc > 2 ? std::strtol(argv[2], nullptr, 10) : 250000;
  const long textures = argc > 3 ? std::strtol(argv[3], nullptr, 10) : 50;
  if (triangles < 1000 || triangles > 50000000 || textures < 1 || textures > 4096) {
    std::fprintf(stderr, "gen_load_scene: TRIANGLES 1000..50000000, TEXTURES 1..4096\n");
    return 2;
  }
  using namespace rp::scene;
  SceneAssets a;
  for (long i = 0; i < textures; ++i) {
    a.textures.push_back(make_texture(uint32_t(i)));
    Material m;
    m.name = "material_" + std::to_string(i);
    m.albedo = glm::vec3(0.9f);
    m.texture = int(i);
    m.specular = {0.3f + 0.6f * float(hash(uint32_t(i) + 99) % 100) / 100.0f, 0.04f, false};
    a.materials.push_back(m);
  }
  // Floor: one quad, the first material.
  Mesh floor;
  floor.name = "floor";
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  floor.vertices = {{{-20, 0, 20}, up, {0, 0}}, {{20, 0, 20}, up, {8, 0}},
                    {{20, 0, -20}, up, {8, 8}}, {{-20, 0, -20}, up, {0, 8}}};
  floor.triangles = {{0, 1, 2}, {0, 2, 3}};
  floor.materials = {0, 0};
  a.meshes.push_back(floor);
  // Ten tumbler variants of growing detail.
  for (int v = 0; v < 10; ++v) {
    const TumblerMeshParams params{24 + 4 * v, 8 + v, 3, 6 + v / 2};
    Mesh mesh = make_tumbler_mesh(TumblerShape{}, params, uint32_t(v % textures));
    mesh.name = "tumbler_" + std::to_string(v);
    a.meshes.push_back(std::move(mesh));
  }
  FrameScene f;
  f.lamp = false;
  f.instances.push_back(MeshInstance{});
  long drawn = 2;
  for (uint32_t k = 0; drawn < triangles; ++k) {
    const uint32_t mesh = 1 + hash(k) % 10;
    const int side = 24;  // instances on a grid, 1.6 m apart, wrapping into more rows
    const float x = -19.0f + 1.6f * float(k % side), z = 19.0f - 1.6f * float((k / side) % side);
    const float y = 0.2f + 1.5f * float(k / (side * side));
    glm::mat4 model = glm::translate(glm::mat4(1.0f), glm::vec3(x, y, z));
    model = glm::rotate(model, float(hash(k + 7) % 628) * 0.01f, up);
    MeshInstance inst;
    inst.mesh = mesh;
    inst.model = inst.prev_model = model;
    f.instances.push_back(inst);
    drawn += long(a.meshes[mesh].triangles.size());
  }
  PunctualLight sun;
  sun.name = "sun";
  sun.type = LightType::kDirectional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -0.8f, -0.5f));
  sun.intensity = glm::vec3(1.0f, 0.95f, 0.85f);
  f.lights.push_back(sun);
  for (int i = 0; i < 3; ++i) {
    PunctualLight p;
    p.name = "lamp_" + std::to_string(i);
    p.position = glm::vec3(-12.0f + 12.0f * float(i), 4.0f, 0.0f);
    p.intensity = glm::vec3(8.0f);
    f.lights.push_back(p);
  }
  f.camera.position = {0.0f, 12.0f, 32.0f};
  f.camera.target = {0.0f, 0.0f, 0.0f};
  f.camera.near_plane = 0.1f;
  f.camera.far_plane = 120.0f;
  export_gltf(a, f, argv[1]);
  std::printf("wrote %s: %ld triangles drawn (%zu instances of 11 meshes), %ld textures, "
              "%zu lights\n", argv[1], drawn, f.instances.size(), textures, f.lights.size());
  return 0;
}
