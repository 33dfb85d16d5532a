// Precomputed radiance transfer (Sloan, Kautz, Snyder 2002): per-vertex diffuse
// transfer vectors of a frame's meshes for an environment light given as spherical harmonics
// (src/shading/spherical_harmonics.h: its basis, index order and direction convention; the
// environment's own coefficients come from sh_project_environment, in the same world frame).
//
// Convention. For RGB environment coefficients L_i (radiance, i < bands^2) a vertex's transfer
// T gives its irradiance, per colour channel c,
//     E_c(x) = sum_i T_{c,i}(x) L_{c,i}            (W/m^2 for L in W/(m^2 sr))
// and the exitant radiance of its Lambertian base is albedo(x) / pi * E(x): the receiver's own
// albedo is NOT in T (the shader multiplies by it, texture included), the albedo of the surfaces
// light bounces off on its way is. The three kinds:
//   kUnshadowed      T_i = integral over the sphere of max(0, n . w) Y_i(w) dw: the clamped
//                    cosine lobe turned to n, in closed form (sh_rotate_zonal of
//                    sh_cosine_lobe_zonal); no rays. A constant environment L gives E = pi L.
//   kShadowed        T_i = integral of V(x, w) max(0, n . w) Y_i(w) dw, V = 0 where a ray from x
//                    meets any instance of the frame (either face), 1 where it leaves.
//   kInterreflected  the shadowed T plus `bounces` diffuse bounces: a ray that meets a front face
//                    (the side its vertex normals face) at point h gathers albedo(h) / pi times
//                    the previous bounce's irradiance transfer there (interpolated from h's
//                    triangle's vertices by barycentrics), times the cosine at x. Albedo is
//                    coloured, so T is RGB: one vector per channel (channels = 3); the other
//                    kinds are grey (channels = 1, the same T for every channel).
//
// Sampling. `samples` directions per vertex: a Hammersley set (k + 1/2) / N x radical inverse of
// k, mapped to the cosine-weighted hemisphere about the vertex normal; the same local set for
// every vertex, so neighbours' errors are alike (smooth shading, no per-vertex noise). The
// shadowed part is a control variate about the exact unshadowed lobe:
//     T = T_unshadowed - (pi / N) sum over blocked directions w_k of Y(w_k),
// unbiased, exact (to float rounding) for a vertex that sees the whole sky, and with exact DC
// term pi / N * Y_0 per direction (so DC >= 0 always). Bounce k: T_k(x) = (1 / N) sum over rays
// meeting a front face of albedo(h) * T_{k-1}(h) (the cosine-weighted density cancels cos / pi).
// The bounces iterate a sparse matrix of those hits (or trace the rays again per bounce where
// that matrix would not fit: PrtSettings::bounce_matrix_mb). Under a constant sky with albedo 1
// light is kept exactly (a blocked ray takes pi / N of E's DC away, its hit gives 1 / N of pi L
// back), so the white furnace converges to E = pi L with the bounces. Accuracy, worst case (a
// shadow edge across the whole hemisphere, tests/truth/prt_transfer_test.cpp): coefficient
// errors 0.016, 0.0053, 0.0016 at 256, 1024, 4096 directions (the full lobe's DC is 0.886).
//
// Geometry. Receivers and occluders are every mesh instance of the frame (the model matrix of
// this frame; prev_model and casts_shadow are ignored: a box that casts no shadow map still hides
// the sky). Spheres (marbles, fireballs, particles) are skipped: they move, so a static transfer
// cannot hold them. Things that move are the caller's to leave out: pass a frame holding only
// the static instances. Alpha-masked holes let rays through (truth/trace_scene.h). The albedo of
// a hit is the material's albedo times its base-colour texture at the hit; specular coats are
// ignored (a metal bounces as a Lambertian surface of its albedo: energy kept, lobe not).
// Emission is not light here (PRT carries the sky only). Back faces have no transfer of their
// own, so they reflect nothing.
//
// Ray origins: the vertex moved 1 % of the way to the centroid of its triangles (off edges and
// corners, where a wall meets a floor at the vertex itself) and then along the normal by 1e-4 of
// the frame's size (off its own triangles).
//
// Deterministic: each vertex depends only on the scene and the settings, never on the thread
// count or the order the threads run in.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "scene/environment_glow.h"
#include "scene/frame_scene.h"
#include "util/named_enum.h"

namespace rp::truth {

enum class PrtKind : uint32_t { kUnshadowed = 0, kShadowed = 1, kInterreflected = 2 };

constexpr NamedValue<PrtKind> kPrtKindNames[] = {{PrtKind::kUnshadowed, "unshadowed"},
                                                 {PrtKind::kShadowed, "shadowed"},
                                                 {PrtKind::kInterreflected, "interreflected"}};
constexpr std::span<const NamedValue<PrtKind>> names(PrtKind) { return kPrtKindNames; }

struct PrtSettings {
  int bands = 3;                      // 3 (9 coefficients) or 5 (25)
  PrtKind kind = PrtKind::kShadowed;
  uint32_t bounces = 1;               // kInterreflected only (0: as kShadowed, but RGB)
  uint32_t samples = 512;             // directions per vertex (>= 1; kUnshadowed: ignored)
  unsigned threads = 0;               // 0 = every hardware thread; does not change the result
  // kInterreflected: the rays' hits are kept as a sparse matrix (bounces then cost a product)
  // when its worst case, vertices x samples x 3 entries of 16 bytes, fits this many MiB; else
  // every bounce traces the same rays again (slower, little memory). Same result either way,
  // bit for bit (the same sums in the same order), so it is no part of the cache key.
  uint32_t bounce_matrix_mb = 1024;
  // kInterreflected with bounces: directional lights (unit, world space, from the surface
  // towards the light) whose bounced light is traced exactly per vertex (PrtTransfer::
  // sun_bounce) instead of through the band-limited transfer: a sun near the horizon, where the
  // transfer as a function of the light's direction jumps (the ground hides what lies below),
  // is smeared by 9 or 25 coefficients. At most kPrtMaxSuns.
  std::vector<glm::vec3> sun_directions;
  // Traced kinds: the glow around an environment's suns (scene/environment_glow.h) as cells in
  // world space (direction: unit, towards the cell; irradiance on a plane facing it), lit by a
  // shadow ray per cell from every vertex and, with bounces, bounced like the sky
  // (PrtTransfer::glow), so that the band-limited transfer need not carry that sharp light.
  // At most scene::kMaxGlowCells.
  std::vector<scene::GlowCell> glow_cells;
};

inline constexpr size_t kPrtMaxSuns = 8;

// Where one frame instance's vertices lie in PrtTransfer's arrays: vertex v of the instance's
// mesh (scene::Mesh::vertices order) is PRT vertex first + v.
struct PrtInstanceRange {
  uint32_t first = 0, count = 0;
};

struct PrtTransfer {
  int bands = 3;
  PrtKind kind = PrtKind::kShadowed;
  uint32_t bounces = 0;
  uint32_t samples = 0;
  uint32_t channels = 1;                    // 1 (grey) or 3 (RGB: kInterreflected)
  std::vector<PrtInstanceRange> instances;  // one per frame instance, in frame order
  std::vector<glm::vec3> positions;         // world space, per vertex
  std::vector<glm::vec3> normals;           // world space, unit (zero: degenerate vertex)
  // Vertex-major: vertex v, channel c, coefficient i at (v * channels + c) * bands^2 + i.
  std::vector<float> coefficients;
  // kInterreflected with bounces: the shadowed transfer the bounces start from (grey, vertex
  // v's coefficient i at v * bands^2 + i), so a shader can take the bounces alone (coefficients
  // minus this) for light whose first vertex it computes itself: an environment's suns. Empty
  // otherwise.
  std::vector<float> shadowed;
  // The settings' sun_directions (empty without the shadowed transfer) and each one's bounced
  // light: vertex v, sun j, channel c at (v * suns + j) * 3 + c, the irradiance that reaches v
  // after 1 to `bounces` diffuse bounces when the sun gives a surface facing it irradiance 1
  // (its first vertex, lit with shadow rays from every vertex, not included). A sun of
  // irradiance E_sun (per channel) adds E_sun * sun_bounce to the vertex.
  std::vector<glm::vec3> sun_directions;
  std::vector<float> sun_bounce;
  // The settings' glow_cells (empty for kUnshadowed) and the irradiance they give each vertex,
  // rgb at v * 3: their light reaching v directly (shadow rays; the first vertex included, unlike
  // the suns') plus, with bounces, after 1 to `bounces` diffuse bounces. Empty without cells.
  std::vector<scene::GlowCell> glow_cells;
  std::vector<float> glow;

  uint32_t vertex_count() const { return uint32_t(positions.size()); }
  int count() const { return bands * bands; }
  const float* at(uint32_t vertex, uint32_t channel) const {
    return coefficients.data() + (size_t(vertex) * channels + channel) * size_t(count());
  }
  // E(x) = T . L per channel (grey transfer: the same T for r, g, b); `env` holds at least
  // bands^2 RGB coefficients (sh_project_environment).
  glm::dvec3 irradiance(uint32_t vertex, const std::vector<glm::dvec3>& env) const;
};

// Fraction of the work done, in [0, 1], called from the thread that called
// compute_prt_transfer about ten times a second and once with 1 at the end.
using PrtProgressFn = std::function<void(double fraction)>;

// Thrown when `cancel` became true before the transfer was done.
struct PrtCancelled {};

// The transfer of every vertex of every instance of `frame` (see the header). Builds its own
// Embree BVHs of `assets` (truth/trace_scene.h). Throws std::invalid_argument for bands other than
// 3 or 5 or zero samples of a traced kind, std::runtime_error for broken assets (missing
// vertices, materials). Cost (demo room, 6833 vertices, 2 busy cores): shadowed 512 directions
// 0.7 s; interreflected 512 directions, 3 bounces 2.1 s (tests/truth/prt_timing_test.cpp).
PrtTransfer compute_prt_transfer(const scene::SceneAssets& assets, const scene::FrameScene& frame,
                                 const PrtSettings& settings, const PrtProgressFn& progress = {},
                                 const std::atomic<bool>* cancel = nullptr);

}  // namespace rp::truth
