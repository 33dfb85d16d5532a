// The atrium's architecture (scene/atrium_build.h): columns, the arcade bays of both storeys
// and the shell (floors, slabs, walls). A bay is built once for the +z side around x = 0 and
// drawn as instances along the court, turned half round for the -z side.
#include <cmath>

#include "scene/atrium_build.h"

namespace rp::scene::atrium {
namespace {

constexpr float kPi = 3.14159265f;

// Points on a quarter-or-more circle in the (radius, height) plane: centre c, radius r, from
// angle a0 to a1 (radians, 0 = outward), n segments.
void arc(std::vector<glm::vec2>& out, glm::vec2 c, float r, float a0, float a1, int n) {
  for (int k = 0; k <= n; ++k) {
    const double a = double(a0) + (double(a1) - double(a0)) * double(k) / double(n);
    out.push_back(c + r * glm::vec2(float(std::cos(a)), float(std::sin(a))));
  }
}

// A wall from z0 (court side) to z1 pierced by a round arch of radius r springing at `spring`
// over x in [-r, r], filling x in [-half, half]; the front face rises to front_top, the back
// face to back_top. The soffit (the arch's underside) is `trim`; an archivolt band 0.25 m wide
// stands 0.06 m proud of the front face, with a keystone.
void append_arch_wall(Mesh& m, float half, float r, float spring, float z0, float z1,
                      float front_top, float back_top, uint32_t wall, uint32_t trim) {
  constexpr int kArc = 24;
  // x samples: the wall beside the arch, then the arch from left (angle pi) to right (0).
  const auto sample = [&](int i, float& x, float& y) {
    if (i == 0) {
      x = -half;
      y = spring;
      return;
    }
    if (i == kArc + 2) {
      x = half;
      y = spring;
      return;
    }
    const double a = kPi * (1.0 - double(i - 1) / kArc);
    x = r * float(std::cos(a));
    y = spring + r * float(std::sin(a));
  };
  for (int face = 0; face < 2; ++face) {
    const float z = face ? z1 : z0, top = face ? back_top : front_top;
    const glm::vec3 n(0.0f, 0.0f, face ? 1.0f : -1.0f);
    append_grid(m, kArc + 2, 1, wall, [&](int i, int j) {
      float x, y;
      sample(i, x, y);
      if (j) y = top;
      return GridVertex{{x, y, z}, n, glm::vec2(x + half, y) / (2.0f * half)};
    });
  }
  const float zf = z0 - 0.06f;                       // the archivolt's face
  append_grid(m, kArc, 1, trim, [&](int i, int j) {  // soffit, through the archivolt
    const double a = kPi * double(i) / kArc;
    const glm::vec3 d(float(std::cos(a)), float(std::sin(a)), 0.0f);
    const float z = j ? z1 : zf;
    return GridVertex{glm::vec3(0.0f, spring, z) + r * d, -d, glm::vec2(float(a) * r, z)};
  });
  const float ro = r + 0.25f;
  append_grid(m, kArc, 1, trim, [&](int i, int j) {  // archivolt face
    const double a = kPi * double(i) / kArc;
    const glm::vec3 d(float(std::cos(a)), float(std::sin(a)), 0.0f);
    const glm::vec3 p = glm::vec3(0.0f, spring, zf) + (j ? ro : r) * d;
    return GridVertex{p, {0.0f, 0.0f, -1.0f}, glm::vec2(p.x, p.y) * 0.5f};
  });
  append_grid(m, kArc, 1, trim, [&](int i, int j) {  // archivolt rim
    const double a = kPi * double(i) / kArc;
    const glm::vec3 d(float(std::cos(a)), float(std::sin(a)), 0.0f);
    const float z = j ? z0 : zf;
    return GridVertex{glm::vec3(0.0f, spring, z) + ro * d, d, glm::vec2(float(a) * ro, z)};
  });
  append_block(m, {-0.16f, spring + r - 0.05f, zf - 0.04f}, {0.16f, spring + ro + 0.1f, z0}, trim,
               1.0f);
}

// A groin vault over x in [-a, a], z in [zc - b, zc + b]: two semi-elliptic barrels (along x
// and along z) of rise h meeting in the diagonals; intrados height
// spring + h * sqrt(1 - min(s^2, t^2)) with s = x / a, t = (z - zc) / b. Built as four
// triangular sectors so each keeps its barrel's normals and the groins stay sharp.
void append_groin_vault(Mesh& m, float a, float b, float zc, float spring, float h, int n,
                        uint32_t material) {
  for (int sector = 0; sector < 4; ++sector) {
    const bool along_t = sector < 2;  // the sector where |t| >= |s|: height from s
    const float sign = sector % 2 ? -1.0f : 1.0f;
    append_tri_grid(m, n, material, [&](int i, int j) {
      const float outer = sign * float(j) / float(n);
      const float cross = j ? std::abs(outer) * (2.0f * float(i) / float(j) - 1.0f) : 0.0f;
      const float s = along_t ? cross : outer, t = along_t ? outer : cross;
      const float q = along_t ? s : t;  // the coordinate the visible barrel depends on
      const float root = std::sqrt(std::max(1.0f - q * q, 1e-4f));
      const glm::vec3 p(s * a, spring + h * root, zc + t * b);
      // d height / d x (or z) = -h q / (a root); the normal faces down into the aisle.
      const float slope = -h * q / ((along_t ? a : b) * root);
      const glm::vec3 nrm =
          glm::normalize(along_t ? glm::vec3(slope, -1.0f, 0.0f) : glm::vec3(0.0f, -1.0f, slope));
      return GridVertex{p, nrm, glm::vec2(p.x, p.z) * 0.5f};
    });
  }
}

}  // namespace

Mesh make_column(float height, float scale) {
  Mesh m;
  m.name = "column";
  const float s = scale;
  const float plinth = 0.3f * s, abacus = 0.25f * s, half = 0.375f * s;
  append_block(m, {-half, 0.0f, -half}, {half, plinth, half}, kStone, 1.0f);
  // Attic base: a torus, a groove, a smaller torus; then the shaft with entasis (a slight
  // swelling a third of the way up, tapering to 85 % at the top), an astragal ring, the
  // echinus flaring out to the abacus.
  std::vector<glm::vec2> base;
  arc(base, {0.29f * s, plinth + 0.07f * s}, 0.07f * s, -0.5f * kPi, 0.5f * kPi, 8);
  append_lathe(m, {}, base, 32, kStone);
  base.clear();
  base.push_back({0.25f * s, plinth + 0.14f * s});
  arc(base, {0.265f * s, plinth + 0.19f * s}, 0.045f * s, -0.5f * kPi, 0.5f * kPi, 6);
  append_lathe(m, {}, base, 32, kStone);
  const float y0 = plinth + 0.235f * s, y1 = height - abacus - 0.32f * s;
  std::vector<glm::vec2> shaft;
  for (int k = 0; k <= 14; ++k) {
    const float f = float(k) / 14.0f;
    const float swell = 0.04f * std::sin(kPi * std::min(1.0f, f * 1.5f));
    shaft.push_back({0.25f * s * (1.0f - 0.15f * f + swell), y0 + (y1 - y0) * f});
  }
  append_lathe(m, {}, shaft, 32, kStone, 2.0f, 1.5f);
  std::vector<glm::vec2> ring;
  arc(ring, {0.215f * s, y1 + 0.04f * s}, 0.04f * s, -0.5f * kPi, 0.5f * kPi, 6);
  append_lathe(m, {}, ring, 32, kStone);
  std::vector<glm::vec2> echinus;
  for (int k = 0; k <= 8; ++k) {
    const float f = float(k) / 8.0f;
    echinus.push_back({(0.22f + 0.13f * f * (2.0f - f)) * s, y1 + 0.08f * s + 0.24f * s * f});
  }
  append_lathe(m, {}, echinus, 32, kStone);
  append_block(m, {-half, height - abacus, -half}, {half, height, half}, kStone, 1.0f);
  compute_tangents(m);
  return m;
}

Mesh make_ground_bay() {
  Mesh m;
  m.name = "arcade_ground";
  const float half = 0.5f * kBay;
  append_arch_wall(m, half, kArchRadius, kGroundSpring, kFacadeFront, kFacadeBack, kGallery,
                   kSlabBottom, kAshlar, kStone);
  const float zc = 0.5f * (kFacadeBack + kBackWall), b = 0.5f * (kBackWall - kFacadeBack);
  append_groin_vault(m, half, b, zc, kGroundSpring, kGroundVaultRise, 24, kPlaster);
  // A pilaster on the back wall under the vault's springing, and a transverse rib's corbel.
  append_block(m, {-half - 0.25f, 0.0f, kBackWall - 0.2f},
               {-half + 0.25f, kGroundSpring, kBackWall}, kStone, 1.0f);
  append_block(m, {-half - 0.32f, kGroundSpring - 0.25f, kBackWall - 0.3f},
               {-half + 0.32f, kGroundSpring, kBackWall}, kStone, 1.0f);
  compute_tangents(m);
  return m;
}

Mesh make_upper_bay() {
  Mesh m;
  m.name = "arcade_upper";
  const float half = 0.5f * kBay, z0 = kFacadeFront + 0.05f, z1 = kFacadeBack - 0.05f;
  append_arch_wall(m, half, kArchRadius, kUpperSpring, z0, z1, kCornice, kCornice, kAshlar, kStone);
  // Balustrade between the columns' plinths: a plinth, vase-shaped balusters, a marble rail
  // and an iron handrail on posts above it.
  const float zb = kColumnZ, y0 = kGallery;
  append_block(m, {-1.2f, y0, zb - 0.2f}, {1.2f, y0 + 0.2f, zb + 0.2f}, kMarble, 1.0f);
  std::vector<glm::vec2> vase;
  for (int k = 0; k <= 14; ++k) {
    const float f = float(k) / 14.0f;
    // A bulb low down and a neck near the top: r = 0.05..0.1 m over 0.62 m.
    const float r = 0.055f + 0.05f * std::sin(kPi * std::min(1.0f, f * 1.6f)) * (1.0f - f) +
                    (f > 0.85f ? 0.06f * (f - 0.85f) / 0.15f : 0.0f);
    vase.push_back({r, y0 + 0.2f + 0.62f * f});
  }
  for (int k = 0; k < 7; ++k)
    append_lathe(m, {-0.9f + 0.3f * float(k), 0.0f, zb}, vase, 12, kMarble);
  append_block(m, {-1.2f, y0 + 0.82f, zb - 0.25f}, {1.2f, y0 + 0.97f, zb + 0.25f}, kMarble, 1.0f);
  for (int k = 0; k < 3; ++k) {
    const float x = -1.0f + 1.0f * float(k);
    append_tube(m, {x, y0 + 0.97f, zb}, {x, y0 + 1.12f, zb}, 0.015f, 8, kIron);
  }
  append_tube(m, {-1.2f, y0 + 1.12f, zb}, {1.2f, y0 + 1.12f, zb}, 0.025f, 12, kIron);
  // The gallery's wooden ceiling: boards under the roof slab on three beams across the aisle.
  append_block(m, {-half, kRoofBottom - 0.1f, z1}, {half, kRoofBottom, kBackWall}, kWood, 2.0f);
  for (int k = 0; k < 3; ++k) {
    const float x = -1.0f + 1.0f * float(k);
    append_block(m, {x - 0.1f, kRoofBottom - 0.38f, z1}, {x + 0.1f, kRoofBottom - 0.1f, kBackWall},
                 kWood, 2.0f);
  }
  compute_tangents(m);
  return m;
}

Mesh make_end_relief() {
  Mesh m;
  m.name = "end_wall_relief";
  // Local frame: the wall's face is z = 0, the court at z < 0, x across the court.
  const float court = kFacadeFront;
  // A tall blind arch framing the door, on pilasters.
  append_arch_wall(m, 2.5f, 2.0f, 3.0f, -0.2f, 0.0f, kGallery - 0.2f, kGallery - 0.2f, kAshlar,
                   kStone);
  for (float s : {-1.0f, 1.0f})
    append_block(m, {s > 0 ? 2.0f : -2.5f, 0.0f, -0.2f}, {s > 0 ? 2.5f : -2.0f, 3.0f, 0.0f}, kStone,
                 1.0f);
  // Bands continuing the facades' string course and cornice.
  append_block(m, {-court, kGallery - 0.2f, -0.14f}, {court, kGallery + 0.05f, 0.0f}, kStone, 1.0f);
  append_block(m, {-court, kCornice - 0.15f, -0.25f}, {court, kCornice + 0.15f, 0.0f}, kStone,
               1.0f);
  // Three blind arches across the upper storey, each on two pilasters.
  const float half = court / 3.0f, r = 1.5f, spring = 9.8f;
  Mesh arch;
  append_arch_wall(arch, half, r, spring, -0.15f, 0.0f, kCornice - 0.15f, kCornice - 0.15f, kAshlar,
                   kStone);
  for (float s : {-1.0f, 1.0f})
    append_block(arch, {s > 0 ? r : -half, kGallery + 0.05f, -0.15f},
                 {s > 0 ? half : -r, spring, 0.0f}, kStone, 1.0f);
  for (int k = -1; k <= 1; ++k) {
    glm::mat4 shift(1.0f);
    shift[3] = glm::vec4(2.0f * half * float(k), 0.0f, 0.0f, 1.0f);
    append_mesh(m, arch, shift);
  }
  compute_tangents(m);
  return m;
}

Mesh make_shell() {
  Mesh m;
  m.name = "shell";
  const float L = kHalfLength, E = L + kEndWall;
  append_block(m, {-L, -0.5f, -kFacadeFront}, {L, 0.0f, kFacadeFront}, kFloorTiles, 4.0f);
  for (float s : {-1.0f, 1.0f}) {
    const auto zs = [s](float a, float b) { return s > 0 ? glm::vec2(a, b) : glm::vec2(-b, -a); };
    glm::vec2 z = zs(kFacadeFront, kBackWallOut);
    append_block(m, {-L, -0.5f, z.x}, {L, 0.0f, z.y}, kFlagstone, 4.0f);  // aisle floor
    z = zs(kFacadeFront, kBackWall);
    append_block(m, {-L, kSlabBottom, z.x}, {L, kGallery, z.y}, kFlagstone, 4.0f);  // gallery
    z = zs(kFacadeFront, kBackWallOut);
    append_block(m, {-L, kRoofBottom, z.x}, {L, kRoofTop, z.y}, kPlaster, 4.0f);  // roof
    z = zs(kBackWall, kBackWallOut);
    append_block(m, {-L, 0.0f, z.x}, {L, kGallery, z.y}, kPlaster, 4.0f);  // aisle wall
    append_block(m, {-L, kGallery, z.x}, {L, kTop, z.y}, kBrick, 1.0f);    // gallery wall
    z = zs(kFacadeFront - 0.12f, kFacadeFront + 0.02f);
    append_block(m, {-L, kGallery - 0.2f, z.x}, {L, kGallery + 0.05f, z.y}, kStone, 1.0f);
    z = zs(kFacadeFront - 0.2f, kFacadeFront + 0.1f);
    append_block(m, {-L, kCornice - 0.15f, z.x}, {L, kCornice + 0.15f, z.y}, kStone, 1.0f);
    z = zs(kFacadeFront + 0.05f, kFacadeBack - 0.05f);
    append_block(m, {-L, kCornice + 0.15f, z.x}, {L, kTop, z.y}, kAshlar, 3.0f);  // parapet
    z = zs(kFacadeFront - 0.25f, kFacadeFront + 0.05f);
    append_block(m, {-L, kTop - 0.15f, z.x}, {L, kTop + 0.05f, z.y}, kStone, 1.0f);  // coping
    // End walls, full height, and half pilasters where the arcades meet them.
    append_block(m, {s > 0 ? L : -E, -0.5f, -kBackWallOut}, {s > 0 ? E : -L, kTop, kBackWallOut},
                 kAshlar, 3.0f);
    for (float zs2 : {-1.0f, 1.0f}) {
      const float x0 = s > 0 ? L - 0.3f : -L, x1 = s > 0 ? L : -L + 0.3f;
      append_block(m, {x0, 0.0f, zs2 * kColumnZ - 0.38f},
                   {x1, kGroundSpring, zs2 * kColumnZ + 0.38f}, kStone, 1.0f);
      append_block(m, {x0, kGallery, zs2 * kColumnZ - 0.32f},
                   {x1, kUpperSpring, zs2 * kColumnZ + 0.32f}, kStone, 1.0f);
    }
  }
  // A wooden double door in a stone frame in the middle of each end wall.
  for (float s : {-1.0f, 1.0f}) {
    const float face = s * L, inward = -s;
    const float xf = face + inward * 0.12f;
    append_block(m, {std::min(face, xf), 0.0f, -1.6f}, {std::max(face, xf), 4.6f, -1.2f}, kStone,
                 1.0f);
    append_block(m, {std::min(face, xf), 0.0f, 1.2f}, {std::max(face, xf), 4.6f, 1.6f}, kStone,
                 1.0f);
    append_block(m, {std::min(face, xf), 4.2f, -1.6f}, {std::max(face, xf), 4.6f, 1.6f}, kStone,
                 1.0f);
    const float xd = face + inward * 0.06f;
    append_block(m, {std::min(face, xd), 0.0f, -1.2f}, {std::max(face, xd), 4.2f, 1.2f}, kWood,
                 2.0f);
  }
  compute_tangents(m);
  return m;
}

}  // namespace rp::scene::atrium
