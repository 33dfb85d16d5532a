// The atrium's furnishings (scene/atrium_build.h): cloth (banners, curtains, a tapestry),
// potted plants with alpha-masked leaf cards, lanterns, the fountain and benches.
#include <cmath>

#include "scene/atrium_build.h"

namespace rp::scene::atrium {
namespace {

constexpr float kPi = 3.14159265f;

// Cloth hanging from y = 0 in the x-y plane (x in [-width/2, width/2]), folds across x as
// z = depth * sin(2 pi x / wavelength + phase), growing from 40 % at the rod to 100 % at the
// hem; u across (0..1, or metres / tile when tile > 0), v up (1 at the rod).
Mesh cloth(const char* name, uint32_t material, float width, float length, float depth,
           float wavelength, uint32_t seed, int nu, int nv, float tile) {
  Mesh m;
  m.name = name;
  const float phase = 6.2831853f * unit(hash(seed));
  const float k = 6.2831853f / wavelength;
  append_grid(m, nu, nv, material, [&](int i, int j) {
    const float x = width * (float(i) / float(nu) - 0.5f), f = float(j) / float(nv);
    const float y = -length * f, grow = 0.4f + 0.6f * f;
    const float z = depth * grow * std::sin(k * x + phase);
    const float zx = depth * grow * k * std::cos(k * x + phase);
    const float zy = -depth * 0.6f / length * std::sin(k * x + phase);  // d/dy of grow
    const glm::vec3 n = glm::normalize(glm::vec3(-zx, -zy, 1.0f));
    const glm::vec2 uv =
        tile > 0.0f ? glm::vec2(x, y) / tile : glm::vec2(float(i) / float(nu), 1.0f - f);
    return GridVertex{{x, y, z}, n, uv};
  });
  return m;
}

}  // namespace

Mesh make_banner(uint32_t material, float width, float length, uint32_t seed) {
  static const char* const names[3] = {"banner_red", "banner_blue", "banner_green"};
  Mesh m = cloth(names[(material - kBannerRed) % 3], material, width, length, 0.03f, width / 2.5f,
                 seed, 24, 40, 0.0f);
  append_tube(m, {-0.5f * width - 0.1f, 0.02f, 0.0f}, {0.5f * width + 0.1f, 0.02f, 0.0f}, 0.02f, 12,
              kIron);
  for (float s : {-1.0f, 1.0f}) {
    std::vector<glm::vec2> knob;
    for (int k = 0; k <= 6; ++k) {
      const double a = -0.5 * kPi + kPi * double(k) / 6.0;
      knob.push_back({0.045f * float(std::cos(a)), 0.045f * float(std::sin(a))});
    }
    append_lathe(m, {s * (0.5f * width + 0.14f), 0.02f, 0.0f}, knob, 12, kBrass);
  }
  compute_tangents(m);
  return m;
}

Mesh make_curtain(float width, float height, uint32_t seed) {
  Mesh m = cloth("curtain", kCurtain, width, height, 0.07f, 0.28f, seed, 40, 30, 1.0f);
  compute_tangents(m);
  return m;
}

Mesh make_tapestry(float width, float height) {
  Mesh m = cloth("tapestry", kTapestry, width, height, 0.015f, 0.8f, 3u, 16, 20, 0.0f);
  append_tube(m, {-0.5f * width - 0.1f, 0.03f, 0.0f}, {0.5f * width + 0.1f, 0.03f, 0.0f}, 0.025f,
              12, kBrass);
  compute_tangents(m);
  return m;
}

Mesh make_plant(uint32_t seed, float height) {
  Mesh m;
  m.name = seed % 2 == 0 ? "plant_fern" : "plant_broad_leaf";
  // Terracotta pot 0.55 m tall: a tapered wall, a rolled lip, the inner wall, the soil.
  append_lathe(m, {}, {{0.0f, 0.0f}, {0.17f, 0.0f}}, 24, kTerracotta);
  append_lathe(m, {}, {{0.17f, 0.0f}, {0.2f, 0.15f}, {0.23f, 0.3f}, {0.26f, 0.45f}}, 24,
               kTerracotta, 2.0f);
  std::vector<glm::vec2> lip;
  for (int k = 0; k <= 8; ++k) {
    const double a = -0.5 * kPi + kPi * double(k) / 8.0;
    lip.push_back({0.26f + 0.04f * float(std::cos(a)), 0.5f + 0.05f * float(std::sin(a))});
  }
  append_lathe(m, {}, lip, 24, kTerracotta, 2.0f);
  append_lathe(m, {}, {{0.26f, 0.55f}, {0.24f, 0.47f}}, 24, kTerracotta, 2.0f);
  append_lathe(m, {}, {{0.24f, 0.47f}, {0.0f, 0.47f}}, 24, kSoil, 1.0f, 0.5f);
  // Leaf cards (double-sided, alpha-masked): fern fronds or broad leaves arching out of the
  // soil, each bent along its length by a droop that grows towards the tip.
  const bool fern = seed % 2 == 0;
  const int cards = fern ? 26 : 34;
  const uint32_t material = fern ? kFern : kBroadLeaf;
  for (int c = 0; c < cards; ++c) {
    const uint32_t h = hash(seed, uint32_t(c));
    const float az = 6.2831853f * (float(c) + 0.6f * unit(h)) / float(cards);
    const float rise = (fern ? 0.55f : 0.35f) + 0.5f * unit(hash(h)) + (c % 3 == 0 ? 0.35f : 0.0f);
    const float len = height * (fern ? 0.9f : 0.5f) * (0.7f + 0.3f * unit(hash(h, 1u)));
    const float w = fern ? 0.34f * len : 0.42f * len, droop = fern ? 0.55f : 0.3f;
    const glm::vec3 out(std::cos(az), 0.0f, std::sin(az)), up(0.0f, 1.0f, 0.0f);
    const glm::vec3 across = glm::vec3(-out.z, 0.0f, out.x);
    const float lift = fern ? 0.0f : 0.25f * height * unit(hash(h, 2u));  // broad leaves on stalks
    const glm::vec3 base = out * (0.06f * unit(hash(h, 3u))) + up * (0.47f + lift);
    if (!fern) append_tube(m, base - up * lift, base, 0.008f, 5, kBroadLeaf);
    const auto centre = [&](float t) {
      return base + len * (t * std::cos(rise) * out + (t * std::sin(rise) - droop * t * t) * up);
    };
    append_grid(m, 2, 8, material, [&](int i, int j) {
      const float t = float(j) / 8.0f, a = float(i) / 2.0f - 0.5f;
      const glm::vec3 tangent = centre(t + 0.01f) - centre(t);
      // The leaf folds slightly along its midrib (a shallow V), so it is not one flat plane.
      const glm::vec3 p = centre(t) + across * (a * w) + up * (std::abs(a) * 0.15f * w);
      const glm::vec3 n = glm::normalize(glm::cross(across, tangent));
      return GridVertex{p, n, glm::vec2(float(i) / 2.0f, t)};
    });
  }
  compute_tangents(m);
  return m;
}

Mesh make_lantern() {
  Mesh m;
  m.name = "lantern";
  append_tube(m, {0.0f, 0.0f, 0.0f}, {0.0f, -0.5f, 0.0f}, 0.012f, 8, kIron);  // the chain
  // A brass cap over the light (its reflector), an open iron cage, a small finial.
  // (A lathe's normals face left of the profile's direction in the radius-height plane:
  // the top runs from the rim in, the underside from the axis out.)
  append_lathe(m, {}, {{0.23f, -0.62f}, {0.16f, -0.58f}, {0.05f, -0.5f}, {0.0f, -0.48f}}, 24,
               kBrass);
  append_lathe(m, {}, {{0.0f, -0.6f}, {0.2f, -0.63f}, {0.23f, -0.62f}}, 24, kBrass);
  for (int k = 0; k < 6; ++k) {
    const double a = 6.2831853 * double(k) / 6.0;
    const glm::vec3 d(0.18f * float(std::cos(a)), 0.0f, 0.18f * float(std::sin(a)));
    append_tube(m, d + glm::vec3(0.0f, -0.62f, 0.0f), d + glm::vec3(0.0f, -1.0f, 0.0f), 0.01f, 6,
                kIron);
  }
  std::vector<glm::vec2> ring;
  for (int k = 0; k <= 8; ++k) {
    const double a = 6.2831853 * double(k) / 8.0;
    ring.push_back({0.18f + 0.015f * float(std::cos(a)), -1.0f + 0.015f * float(std::sin(a))});
  }
  append_lathe(m, {}, ring, 24, kIron);
  append_lathe(m, {}, {{0.0f, -1.12f}, {0.03f, -1.06f}, {0.0f, -1.0f}}, 12, kBrass);
  compute_tangents(m);
  return m;
}

Mesh make_fountain() {
  Mesh m;
  m.name = "fountain";
  // A round marble basin 3.4 m across (outer wall, rolled rim, inner wall), water 0.1 m under
  // the rim, a baluster-shaped pedestal with an upper bowl and a brass spout.
  append_lathe(m, {}, {{1.62f, 0.0f}, {1.66f, 0.2f}, {1.7f, 0.42f}}, 48, kMarble, 4.0f);
  std::vector<glm::vec2> rim;
  for (int k = 0; k <= 10; ++k) {
    const double a = -0.5 * kPi + kPi * double(k) / 10.0;
    rim.push_back({1.62f + 0.1f * float(std::cos(a)), 0.52f + 0.1f * float(std::sin(a))});
  }
  append_lathe(m, {}, rim, 48, kMarble, 4.0f);
  append_lathe(m, {}, {{1.62f, 0.62f}, {1.52f, 0.55f}, {1.5f, 0.2f}}, 48, kMarble, 4.0f);
  append_lathe(m, {}, {{1.5f, 0.42f}, {0.0f, 0.42f}}, 48, kWater, 1.0f, 0.5f);
  std::vector<glm::vec2> pedestal;
  for (int k = 0; k <= 16; ++k) {
    const float f = float(k) / 16.0f;
    pedestal.push_back(
        {0.22f + 0.12f * std::sin(kPi * f) * (1.0f - f) + 0.05f * f, 0.42f + 0.9f * f});
  }
  append_lathe(m, {}, pedestal, 32, kMarble);
  std::vector<glm::vec2> bowl;  // outside of the upper bowl, then its inside back to the spout
  for (int k = 0; k <= 10; ++k) {
    const float f = float(k) / 10.0f;
    bowl.push_back({0.27f + 0.45f * std::sin(0.5f * kPi * f), 1.32f + 0.25f * f * f});
  }
  append_lathe(m, {}, bowl, 48, kMarble, 2.0f);
  append_lathe(m, {}, {{0.72f, 1.57f}, {0.68f, 1.6f}, {0.5f, 1.52f}, {0.0f, 1.5f}}, 48, kMarble,
               2.0f);
  append_lathe(m, {}, {{0.06f, 1.5f}, {0.08f, 1.62f}, {0.04f, 1.75f}, {0.05f, 1.85f}, {0.0f, 1.9f}},
               16, kBrass);
  compute_tangents(m);
  return m;
}

Mesh make_bench() {
  Mesh m;
  m.name = "bench";
  append_block(m, {-0.9f, 0.42f, -0.22f}, {0.9f, 0.5f, 0.22f}, kWood, 1.0f);
  for (float x : {-0.7f, 0.7f})
    append_block(m, {x - 0.08f, 0.0f, -0.18f}, {x + 0.08f, 0.42f, 0.18f}, kStone, 1.0f);
  compute_tangents(m);
  return m;
}

}  // namespace rp::scene::atrium
