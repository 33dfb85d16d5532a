// Writes generated glTF scenes (no third-party data):
//   gen_load_scene OUT.glb [TRIANGLES] [TEXTURES]   (defaults: 250000, 50)
//     for load-time and frame-time benches: a 40 x 40 m floor, rows of tumblers (one glTF mesh
//     per material, ten levels of detail, instanced), one procedural 256x256 texture per
//     material, a sun and three point lights;
//   gen_load_scene OUT.glb --room
//     a small room with every feature the renderers read from a file, for the tests: a sun, a
//     spot and a point light, a floor with normal and metallic-roughness maps, a red wall, two
//     boxes, a cube with an emission map, a trellis panel cut out by an alpha mask (mirrored
//     texture) (10 m across; tests/app/file_scene_truth_test.cpp, the oclgrind renders);
//   gen_load_scene OUT.glb --yard
//     the room's geometry in matte colours without lights, its faces split into 0.25 m cells:
//     only a sky (--env, --sky) lights it (the sky's accuracy tables in bench/results);
//   gen_load_scene OUT.glb --atrium
//     the atrium (scene/atrium.h): a courtyard with two storeys of arcades, about 250k
//     triangles and 43 textures, what `rolypoly --scene atrium` opens.
// Deterministic: integer hashing only, so the same arguments write the same bytes.
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/atrium.h"
#include "scene/box_mesh.h"
#include "scene/gltf_export.h"
#include "scene/integer_hash.h"
#include "scene/tumbler_shape.h"

namespace {

uint32_t hash(uint32_t x) { return rp::scene::integer_hash(x); }

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

// A 64x64 linear or sRGB texture from f(x, y) -> rgb bytes.
template <class F>
rp::scene::Texture pattern(const char* name, bool srgb, F f) {
  rp::scene::Texture t;
  t.name = name;
  t.srgb = srgb;
  t.width = t.height = 64;
  t.rgba.resize(64 * 64 * 4);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const glm::ivec3 c = f(x, y);
      uint8_t* p = &t.rgba[size_t(y * 64 + x) * 4];
      p[0] = uint8_t(c.x);
      p[1] = uint8_t(c.y);
      p[2] = uint8_t(c.z);
      p[3] = 255;
    }
  return t;
}

// The room's (and the yard's) frame: no lamp, one instance of mesh 0, the camera from the front.
void room_frame(rp::scene::FrameScene& f) {
  f.lamp = false;
  f.camera.position = {0.0f, 3.0f, 9.0f};
  f.camera.target = {0.0f, 0.9f, 2.0f};
  f.camera.fov_y_deg = 52.0f;
  f.camera.near_plane = 0.05f;
  f.camera.far_plane = 50.0f;
  f.instances.push_back(rp::scene::MeshInstance{});
}

int write_room(const char* path) {
  using namespace rp::scene;
  SceneAssets a;
  // Floor maps: ridges across u (the normal tilts +-30 degrees along the tangent), and
  // alternating rough dielectric / polished metal stripes (G roughness, B metallic).
  a.textures.push_back(pattern("floor_normal", false, [](int x, int) {
    const float tilt = 0.5f * std::sin(float(x) * 0.392699f);  // 16-texel period
    return glm::ivec3(int(std::lround((tilt * 0.5f + 0.5f) * 255.0f)), 128,
                      int(std::lround((std::sqrt(1.0f - tilt * tilt) * 0.5f + 0.5f) * 255.0f)));
  }));
  a.textures.push_back(pattern("floor_metallic_roughness", false, [](int, int y) {
    return (y / 16) % 2 ? glm::ivec3(0, 230, 0) : glm::ivec3(0, 80, 255);
  }));
  a.textures.push_back(pattern("glow_emission", true, [](int x, int y) {
    return ((x / 8) + (y / 8)) % 2 ? glm::ivec3(255, 220, 160) : glm::ivec3(60, 40, 20);
  }));
  const auto material = [&](const char* name, glm::vec3 albedo, float roughness) {
    Material m;
    m.name = name;
    m.albedo = albedo;
    m.specular = {roughness, 0.04f, false};
    a.materials.push_back(m);
    return &a.materials.back();
  };
  Material* floor = material("floor", glm::vec3(0.7f), 1.0f);
  floor->normal_texture = 0;
  floor->metallic_roughness_texture = 1;
  floor->metallic = 1.0f;
  material("wall", glm::vec3(0.8f, 0.8f, 0.75f), 1.0f);
  material("red", glm::vec3(0.8f, 0.1f, 0.1f), 1.0f);
  material("boxes", glm::vec3(0.3f, 0.5f, 0.8f), 0.4f);
  Material* glow = material("glow", glm::vec3(0.1f), 1.0f);
  glow->emission = glm::vec3(4.0f, 2.4f, 0.8f);
  glow->emission_texture = 2;
  // A trellis: 22-texel windows between 10-texel bars, cut out by alpha (MASK), mirrored so the
  // bars at the texture's edges meet; a thin double-sided panel.
  Texture trellis = pattern("trellis", true, [](int x, int y) {
    return glm::ivec3(150 + (x * 3) % 40, 110 + (y * 5) % 50, 60);
  });
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      trellis.rgba[size_t(y * 64 + x) * 4 + 3] = (x % 32 < 10 || y % 32 < 10) ? 255 : 0;
  trellis.wrap_u = trellis.wrap_v = TextureWrap::kMirroredRepeat;
  a.textures.push_back(trellis);
  Material* lattice = material("trellis", glm::vec3(0.9f), 0.8f);
  lattice->texture = 3;
  lattice->alpha_mode = AlphaMode::kMask;
  lattice->alpha_cutoff = 0.5f;
  lattice->double_sided = true;
  Mesh room;
  room.name = "room";
  append_box(room, {0, -0.05f, 0}, {5, 0.05f, 5}, 0);
  append_box(room, {0, 2.5f, -5}, {5, 2.5f, 0.05f}, 1);
  append_box(room, {-5, 2.5f, 0}, {0.05f, 2.5f, 5}, 2);
  append_box(room, {-1.5f, 0.75f, -1}, {0.75f, 0.75f, 0.75f}, 3);
  append_box(room, {1.5f, 1.25f, 0.5f}, {0.5f, 1.25f, 0.5f}, 3);
  append_box(room, {0, 0.4f, 2}, {0.4f, 0.4f, 0.4f}, 4);
  {  // the trellis panel, upright in z = 1, uv 0..2.5 (mirrored)
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    const uint32_t b = uint32_t(room.vertices.size());
    room.vertices.push_back({{-3.6f, 0.0f, 1.0f}, n, {0.0f, 0.0f}});
    room.vertices.push_back({{-0.9f, 0.0f, 1.0f}, n, {2.5f, 0.0f}});
    room.vertices.push_back({{-0.9f, 2.2f, 1.0f}, n, {2.5f, 2.0f}});
    room.vertices.push_back({{-3.6f, 2.2f, 1.0f}, n, {0.0f, 2.0f}});
    for (int k = 0; k < 4; ++k) room.tangents.push_back(glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
    room.triangles.push_back({b, b + 1, b + 2});
    room.triangles.push_back({b, b + 2, b + 3});
    room.materials.insert(room.materials.end(), {5, 5});
  }
  a.meshes.push_back(room);
  FrameScene f;
  room_frame(f);
  constexpr float kInvPi = 0.318309886f;  // glTF intensity / pi: the renderer's units
  PunctualLight sun;
  sun.name = "sun";
  sun.type = LightType::kDirectional;
  sun.direction = glm::normalize(glm::vec3(0.4f, -0.8f, -0.45f));
  sun.intensity = glm::vec3(1.0f, 0.95f, 0.85f) * (3.0f * kInvPi);
  f.lights.push_back(sun);
  PunctualLight spot;
  spot.name = "spot";
  spot.type = LightType::kSpot;
  spot.position = {3.0f, 4.0f, 3.0f};
  spot.direction = glm::normalize(glm::vec3(-0.6f, -0.8f, -0.6f));
  spot.inner_cone = 0.3f;
  spot.outer_cone = 0.5f;
  spot.intensity = glm::vec3(0.6f, 0.8f, 1.0f) * (60.0f * kInvPi);
  f.lights.push_back(spot);
  PunctualLight point;
  point.name = "point";
  point.position = {-2.5f, 3.0f, 1.5f};
  point.intensity = glm::vec3(1.0f, 0.8f, 0.6f) * (15.0f * kInvPi);
  f.lights.push_back(point);
  export_gltf(a, f, path);
  std::printf("wrote %s: the test room (%zu triangles, 3 lights)\n", path,
              room.triangles.size());
  return 0;
}

// The room's geometry without its lights, maps and coats: matte surfaces that only the sky
// lights, for measuring the sky's light (bench --accuracy --scene yard.glb --env FILE).
int write_yard(const char* path) {
  using namespace rp::scene;
  SceneAssets a;
  const auto material = [&](const char* name, glm::vec3 albedo) {
    Material m;
    m.name = name;
    m.albedo = albedo;
    a.materials.push_back(m);
  };
  material("ground", glm::vec3(0.6f));
  material("wall", glm::vec3(0.8f, 0.75f, 0.7f));
  material("red", glm::vec3(0.7f, 0.2f, 0.15f));
  material("blue", glm::vec3(0.25f, 0.45f, 0.75f));
  material("green", glm::vec3(0.2f, 0.6f, 0.25f));
  Mesh yard;
  yard.name = "yard";
  // Faces split into cells of at most 0.25 m: vertices for per-vertex PRT transfer to resolve
  // the boxes' contact shadows (the same surfaces as whole quads, for every other mode).
  constexpr float kCell = 0.25f;
  append_box(yard, {0, -0.05f, 0}, {5, 0.05f, 5}, 0, 1.0f, kCell);
  append_box(yard, {0, 2.5f, -5}, {5, 2.5f, 0.05f}, 1, 1.0f, kCell);
  append_box(yard, {-5, 2.5f, 0}, {0.05f, 2.5f, 5}, 2, 1.0f, kCell);
  append_box(yard, {-1.5f, 0.75f, -1}, {0.75f, 0.75f, 0.75f}, 3, 1.0f, kCell);
  append_box(yard, {1.5f, 1.25f, 0.5f}, {0.5f, 1.25f, 0.5f}, 1, 1.0f, kCell);
  append_box(yard, {0, 0.4f, 2}, {0.4f, 0.4f, 0.4f}, 4, 1.0f, kCell);
  a.meshes.push_back(yard);
  FrameScene f;
  room_frame(f);
  export_gltf(a, f, path);
  std::printf("wrote %s: the yard (%zu triangles, no lights)\n", path, yard.triangles.size());
  return 0;
}

int write_atrium(const char* path) {
  const rp::scene::Atrium atrium = rp::scene::make_atrium();
  size_t triangles = 0;
  for (const rp::scene::MeshInstance& inst : atrium.frame.instances)
    triangles += atrium.assets.meshes[inst.mesh].triangles.size();
  rp::scene::export_gltf(atrium.assets, atrium.frame, path);
  std::printf("wrote %s: the atrium (%zu triangles drawn, %zu instances of %zu meshes, %zu "
              "materials, %zu textures, %zu lights)\n",
              path, triangles, atrium.frame.instances.size(), atrium.assets.meshes.size(),
              atrium.assets.materials.size(), atrium.assets.textures.size(),
              atrium.frame.lights.size());
  return 0;
}

// A whole decimal number in [lo, hi], or -1.
long parse_count(const char* text, long lo, long hi) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text, &end, 10);
  if (errno != 0 || end == text || *end != '\0' || v < lo || v > hi) return -1;
  return v;
}

constexpr const char* kUsage =
    "usage: gen_load_scene OUT.glb [TRIANGLES] [TEXTURES]\n"
    "       gen_load_scene OUT.glb --room\n"
    "       gen_load_scene OUT.glb --atrium\n"
    "       gen_load_scene OUT.glb --yard\n";

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  // OUT never starts with '-': a mistyped option must not become a file of that name.
  if (argc < 2 || argc > 4 || argv[1][0] == '-') {
    std::fputs(kUsage, stderr);
    return 2;
  }
  if (argc == 3 && std::string(argv[2]) == "--room") return write_room(argv[1]);
  if (argc == 3 && std::string(argv[2]) == "--atrium") return write_atrium(argv[1]);
  if (argc == 3 && std::string(argv[2]) == "--yard") return write_yard(argv[1]);
  const long triangles = argc > 2 ? parse_count(argv[2], 1000, 50000000) : 250000;
  const long textures = argc > 3 ? parse_count(argv[3], 1, 4096) : 50;
  if (triangles < 0 || textures < 0) {
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
  // Tumblers of ten levels of detail, one mesh per material (so every texture is drawn).
  for (long v = 0; v < textures; ++v) {
    const int detail = int(v % 10);
    const TumblerMeshParams params{24 + 4 * detail, 8 + detail, 3, 6 + detail / 2};
    Mesh mesh = make_tumbler_mesh(TumblerShape{}, params, uint32_t(v));
    mesh.name = "tumbler_" + std::to_string(v);
    a.meshes.push_back(std::move(mesh));
  }
  const uint32_t variants = uint32_t(textures);
  FrameScene f;
  f.lamp = false;
  f.instances.push_back(MeshInstance{});
  long drawn = 2;
  for (uint32_t k = 0; drawn < triangles; ++k) {
    const uint32_t mesh = 1 + hash(k) % variants;
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
  std::printf("wrote %s: %ld triangles drawn (%zu instances of %zu meshes), %ld textures, "
              "%zu lights\n", argv[1], drawn, f.instances.size(), a.meshes.size(), textures,
              f.lights.size());
  return 0;
}
