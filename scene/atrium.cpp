// The atrium assembled (scene/atrium.h): the parts of atrium_parts.cpp and atrium_props.cpp
// placed as instances, the sun, three lanterns and two spot lights, and the camera.
#include "scene/atrium.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "scene/atrium_build.h"

namespace rp::scene {
namespace {

using namespace atrium;

// Translation to `p`, turned half round the vertical axis for the -z side (side < 0): an
// exact matrix, so both arcades are the same geometry.
glm::mat4 place(glm::vec3 p, float side = 1.0f) {
  glm::mat4 m(1.0f);
  m[0][0] = m[2][2] = side;
  m[3] = glm::vec4(p, 1.0f);
  return m;
}

struct Builder {
  Atrium out;
  uint32_t add_mesh(Mesh mesh) {
    out.assets.meshes.push_back(std::move(mesh));
    return uint32_t(out.assets.meshes.size() - 1);
  }
  void add(uint32_t mesh, const glm::mat4& model) {
    MeshInstance inst;
    inst.mesh = mesh;
    inst.model = inst.prev_model = model;
    out.frame.instances.push_back(inst);
  }
  // Intensities in the renderer's units (glTF candela or lux / pi).
  void light(const char* name, LightType type, glm::vec3 position, glm::vec3 direction,
             glm::vec3 intensity) {
    PunctualLight l;
    l.name = name;
    l.type = type;
    l.position = position;
    l.direction = glm::normalize(direction);
    l.intensity = intensity;
    if (type == LightType::kSpot) {
      l.inner_cone = 0.35f;
      l.outer_cone = 0.6f;
    }
    out.frame.lights.push_back(l);
  }
};

}  // namespace

Atrium make_atrium() {
  Builder b;
  add_materials(b.out.assets);
  b.add(b.add_mesh(make_shell()), glm::mat4(1.0f));
  // The end walls' relief, its local z turned to face the court: +-x (exact rotations).
  const uint32_t relief = b.add_mesh(make_end_relief());
  for (float s : {1.0f, -1.0f}) {
    glm::mat4 m(0.0f);
    m[0] = glm::vec4(0.0f, 0.0f, -s, 0.0f);  // local x
    m[1] = glm::vec4(0.0f, 1.0f, 0.0f, 0.0f);
    m[2] = glm::vec4(s, 0.0f, 0.0f, 0.0f);  // local z, towards the wall
    m[3] = glm::vec4(s * kHalfLength, 0.0f, 0.0f, 1.0f);
    b.add(relief, m);
  }

  // Two storeys of arcades: ten bays a side, columns between them (the end ones are the end
  // walls' half pilasters).
  const uint32_t ground = b.add_mesh(make_ground_bay()), upper = b.add_mesh(make_upper_bay());
  Mesh ground_column = make_column(kGroundSpring, 1.0f);
  Mesh upper_column = make_column(kUpperSpring - kGallery, 0.85f);
  upper_column.name = "column_upper";
  const uint32_t column = b.add_mesh(std::move(ground_column));
  const uint32_t column_up = b.add_mesh(std::move(upper_column));
  for (float side : {1.0f, -1.0f}) {
    for (int k = 0; k < kBays; ++k) {
      const float x = -kHalfLength + kBay * (float(k) + 0.5f);
      b.add(ground, place({x, 0.0f, 0.0f}, side));
      b.add(upper, place({x, 0.0f, 0.0f}, side));
    }
    for (int k = 1; k < kBays; ++k) {
      const float x = -kHalfLength + kBay * float(k);
      b.add(column, place({x, 0.0f, side * kColumnZ}));
      b.add(column_up, place({x, kGallery, side * kColumnZ}));
    }
  }

  // The court: a fountain in the middle, potted ferns and broad-leaved plants along both
  // arcades and in the aisles and gallery.
  b.add(b.add_mesh(make_fountain()), glm::mat4(1.0f));
  const uint32_t plants[2] = {b.add_mesh(make_plant(0, 1.3f)), b.add_mesh(make_plant(1, 1.5f))};
  int n = 0;
  const auto plant = [&](glm::vec3 p) {
    const float turn = 6.2831853f * unit(hash(uint32_t(n), 77u));
    b.add(plants[n % 2], glm::rotate(place(p), turn, glm::vec3(0.0f, 1.0f, 0.0f)));
    ++n;
  };
  for (float side : {1.0f, -1.0f})
    for (float x : {-9.0f, -3.0f, 3.0f, 9.0f}) plant({x, 0.0f, side * 5.7f});
  for (float x : {-10.5f, 7.5f}) plant({x, 0.0f, 9.4f});
  for (float x : {-4.5f, 10.5f}) plant({x, kGallery, -9.4f});
  for (float x : {-10.5f, 1.5f}) plant({x, kGallery, 9.4f});

  // Banners hung from the gallery rail in front of every other column (their front, +z in the
  // mesh, turned to the court), curtains in two arches of the shaded (-z) arcade, tapestries on
  // its back walls.
  const uint32_t banner_mats[3] = {kBannerRed, kBannerBlue, kBannerGreen};
  uint32_t banners[3];
  for (uint32_t k = 0; k < 3; ++k)
    banners[k] = b.add_mesh(make_banner(banner_mats[k], 1.3f, 4.6f, k));
  int nb = 0;
  for (float side : {1.0f, -1.0f})
    for (float x : {-9.0f, -3.0f, 3.0f, 9.0f})
      b.add(banners[nb++ % 3], place({x, kGallery + 1.1f, side * (kFacadeFront - 0.28f)}, -side));
  const uint32_t curtain = b.add_mesh(make_curtain(0.95f, 5.1f, 5u));
  for (float x : {-4.5f, 4.5f}) {
    const glm::mat4 rod = place({x, 5.15f, -(kFacadeBack + 0.15f)}, -1.0f);
    b.add(curtain, rod * place({-0.72f, 0.0f, 0.0f}));
    b.add(curtain, rod * place({0.72f, 0.0f, 0.0f}));
  }
  const uint32_t tapestry = b.add_mesh(make_tapestry(2.2f, 3.0f));
  b.add(tapestry, place({-1.5f, 3.9f, -(kBackWall - 0.06f)}));
  b.add(tapestry, place({4.5f, kGallery + 3.0f, -(kBackWall - 0.06f)}));

  // Lanterns under three vaults of the shaded arcade; benches beneath them and on the sunny side.
  const uint32_t lantern = b.add_mesh(make_lantern());
  const uint32_t bench = b.add_mesh(make_bench());
  const float aisle = 0.5f * (kFacadeBack + kBackWall);
  const float hook = kGroundSpring + kGroundVaultRise - 0.05f;
  const glm::vec3 warm(1.0f, 0.72f, 0.45f);
  int nl = 0;
  for (float x : {-7.5f, 1.5f, 10.5f}) {
    b.add(lantern, place({x, hook, -aisle}));
    b.add(bench, place({x, 0.0f, -(kBackWall - 0.45f)}));
    static const char* const names[3] = {"lantern_0", "lantern_1", "lantern_2"};
    // 10 W/sr: about 31 cd of warm light, 4.8 m above the floor.
    b.light(names[nl++], LightType::kPoint, {x, hook - 0.78f, -aisle}, {0, -1, 0}, warm * 10.0f);
  }
  for (float x : {-10.5f, -1.5f, 7.5f}) b.add(bench, place({x, 0.0f, kBackWall - 0.45f}));

  // The sun from high over the -z parapet: it lights the +z half of the floor and reaches into
  // the +z arcade. 3 W/m^2 in the renderer's units (about 9.4 lux in glTF's), so a sunlit
  // floor reads about 1 before tone mapping.
  b.light("sun", LightType::kDirectional, {}, {0.35f, -0.85f, 0.4f},
          glm::vec3(1.0f, 0.94f, 0.84f) * 3.0f);
  // Spot lights under the -z arcades' vaults on the two tapestries (about 90 and 60 cd).
  b.light("spot_tapestry_ground", LightType::kSpot, {-1.5f, 5.0f, -7.4f}, {0.0f, -2.6f, -2.6f},
          warm * 28.0f);
  b.light("spot_tapestry_gallery", LightType::kSpot, {4.5f, 11.4f, -7.4f}, {0.0f, -2.2f, -2.6f},
          warm * 20.0f);

  Camera& c = b.out.frame.camera;
  c.position = {-13.0f, 1.7f, -1.2f};
  c.target = {8.0f, 3.6f, 0.6f};
  c.fov_y_deg = 60.0f;
  c.near_plane = 0.05f;
  c.far_plane = 80.0f;
  b.out.frame.prev_camera = c;
  b.out.frame.lamp = false;
  return std::move(b.out);
}

}  // namespace rp::scene
