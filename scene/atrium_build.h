// The atrium's building blocks (scene/atrium.h), shared by its source files: mesh builders,
// procedural textures and materials, and the parts the courtyard is assembled from.
// Lengths in metres; texture coordinates are world-planar where a surface tiles (one texture
// repeat per `tile` metres) so every wall has the same texel density.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "scene/frame_scene.h"
#include "scene/integer_hash.h"

namespace rp::scene::atrium {

// Integer hashing: the only source of variation (same bytes on every run).
inline uint32_t hash(uint32_t x) { return integer_hash(x); }
inline uint32_t hash(uint32_t a, uint32_t b) { return hash(a ^ hash(b + 0x9e3779b9u)); }
inline uint32_t hash(uint32_t a, uint32_t b, uint32_t c) { return hash(a, hash(b, c)); }
// A hash mapped to [0, 1).
inline float unit(uint32_t h) { return float(h >> 8) * (1.0f / 16777216.0f); }

// ---- layout (metres) -------------------------------------------------------------------------
inline constexpr float kHalfLength = 15.0f;  // court x in [-15, 15]; end walls beyond
inline constexpr float kEndWall = 0.8f;      // end wall thickness
inline constexpr float kFacadeFront = 6.5f;  // court-side face of the arcades (|z|)
inline constexpr float kFacadeBack = 7.1f;   // aisle-side face of the ground storey's facade
inline constexpr float kColumnZ = 6.8f;      // column axes (|z|)
inline constexpr float kBackWall = 10.0f;    // aisle-side face of the back walls (|z|)
inline constexpr float kBackWallOut = 10.6f;
inline constexpr float kBay = 3.0f;  // column spacing along x
inline constexpr int kBays = 10;
inline constexpr float kArchRadius = 1.15f;   // (bay - abacus width) / 2
inline constexpr float kGroundSpring = 4.2f;  // top of the ground columns' capitals
inline constexpr float kGroundVaultRise = 1.45f;
inline constexpr float kSlabBottom = 6.2f;  // gallery slab, 0.7 m thick
inline constexpr float kGallery = 6.9f;     // gallery floor
inline constexpr float kUpperSpring = 10.3f;
inline constexpr float kRoofBottom = 12.2f;  // roof slab over the aisles, 0.6 m thick
inline constexpr float kRoofTop = 12.8f;
inline constexpr float kCornice = 13.6f;
inline constexpr float kTop = 15.0f;  // parapet top

// ---- mesh builders (atrium_shapes.cpp) -------------------------------------------------------
struct GridVertex {
  glm::vec3 p;
  glm::vec3 n;  // unit; triangles are wound counter-clockwise seen from the side it points to
  glm::vec2 uv;
};
using GridFn = std::function<GridVertex(int i, int j)>;

// A (nu+1) x (nv+1) vertex grid, two triangles per cell, wound to face the vertex normals.
void append_grid(Mesh& m, int nu, int nv, uint32_t material, const GridFn& f);
// A triangular grid of rows j = 0..n with j + 1 vertices each (i = 0..j): n^2 triangles.
void append_tri_grid(Mesh& m, int n, uint32_t material, const GridFn& f);
// A box from `lo` to `hi`, texture coordinates world-planar (one repeat per `tile` metres).
void append_block(Mesh& m, glm::vec3 lo, glm::vec3 hi, uint32_t material, float tile = 2.0f);
// A solid of revolution about the vertical axis through `base`: profile points (radius,
// height) bottom to top, one smooth run (normals from the neighbouring points; call again for
// a crease). u goes around (u_repeat times), v along the profile (one repeat per `tile` m).
void append_lathe(Mesh& m, glm::vec3 base, const std::vector<glm::vec2>& profile, int segments,
                  uint32_t material, float u_repeat = 1.0f, float tile = 1.0f);
// A closed-sided cylinder of `radius` from a to b (no caps), `segments` around.
void append_tube(Mesh& m, glm::vec3 a, glm::vec3 b, float radius, int segments, uint32_t material);
// Recomputes every tangent of `m` from its texture coordinates (per-triangle derivatives
// summed per vertex, made orthogonal to the normal; w = +-1 so w * cross(n, t) follows +v).
void compute_tangents(Mesh& m);
// Appends `part` moved by `model` (rotation and translation only) to `m`.
void append_mesh(Mesh& m, const Mesh& part, const glm::mat4& model);

// ---- textures and materials (atrium_textures.cpp) --------------------------------------------
enum Mat : uint32_t {
  kFloorTiles,
  kFlagstone,
  kStone,
  kAshlar,
  kPlaster,
  kBrick,
  kWood,
  kMarble,
  kTerracotta,
  kBannerRed,
  kBannerBlue,
  kBannerGreen,
  kCurtain,
  kTapestry,
  kFern,
  kBroadLeaf,
  kIron,
  kBrass,
  kSoil,
  kWater,
  kMaterialCount
};
// Appends the textures and the materials, in the order of Mat.
void add_materials(SceneAssets& assets);

// ---- parts (atrium_parts.cpp, atrium_props.cpp) -----------------------------------------------
Mesh make_column(float height, float scale);  // standing on y = 0, axis x = z = 0
Mesh make_ground_bay();  // one +z bay, x in [-1.5, 1.5]: facade, arch, groin vault
Mesh make_upper_bay();   // one +z bay of the gallery: facade, arch, balustrade, ceiling
Mesh make_shell();       // floors, slabs, roofs, back and end walls, cornices, parapet
Mesh make_end_relief();  // blind arches and bands on an end wall: its face z = 0, court z < 0
Mesh make_plant(uint32_t seed, float height);  // pot on y = 0 with leaf cards
Mesh make_lantern();   // hangs from y = 0 down; its light goes 0.78 m below the hook
Mesh make_fountain();  // on y = 0 at the origin
Mesh make_bench();
Mesh make_banner(uint32_t material, float width, float length, uint32_t seed);  // from y = 0 down
Mesh make_curtain(float width, float height, uint32_t seed);  // in the x-y plane, from y = 0 down
Mesh make_tapestry(float width, float height);  // on a rod, in the x-y plane, facing +z

}  // namespace rp::scene::atrium
