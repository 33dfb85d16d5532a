// The Kulla-Conty tables of the surface model (src/shading/brdf.h, layout in
// kernels/shared/brdf_layout.h): E(mu) and S(mu) per roughness and their cosine-weighted means,
// integrated numerically once per process (deterministic: a fixed 64 x 64 midpoint grid of the
// visible-normal sampler per entry, no random numbers), then read bilinearly like the kernels.
#pragma once

#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "kernels/shared/brdf_layout.h"
#include "shading/brdf.h"

namespace rp::shading {

class BrdfTables {
 public:
  static constexpr int kSize = RP_BRDF_TABLE_SIZE;

  // The tables of this process (integrated on first use, ~20 ms; thread safe).
  static const BrdfTables& get();

  // Bilinear (mu, roughness in [0, 1], clamped; brdf_layout.h): the device's lookup.
  TableEntry lookup(float mu, float roughness) const;
  // Raw cells, row j (roughness) major: the buffer the renderer uploads (float4 each).
  const std::array<glm::vec4, kSize * kSize>& cells() const { return cells_; }

  // Numerical integrals behind one cell (also the tests' reference): E and S at (mu, alpha)
  // from grid x grid midpoint samples of the visible-normal distribution.
  static glm::vec2 integrate_es(float mu, float alpha, int grid = 64);

 private:
  BrdfTables();
  std::array<glm::vec4, kSize * kSize> cells_{};
};

// The quantised gloss code of kernels/shared/brdf_layout.h for `spec`, and back.
float gloss_code(const scene::Specular& spec);
scene::Specular decode_gloss(float code);

// What the voxelizer multiplies a surface's albedo by (Material.albedo.w, Sphere.albedo.w;
// kernels/voxelize.cl): the cosine-weighted mean over outgoing directions of the layered base's
// weight, 1 - E_spec_avg, for a dielectric coat of gloss code `code` (the quantised coat, as
// the device sees it), so the voxels hold the base's diffuse outgoing radiance and the cones
// gather a Lambertian view of it; the coat's own reflection of the lamp is view dependent and
// stays out. 1 for matte surfaces and for metals (no diffuse base: their voxels keep the
// albedo, i.e. the F0 colour, times the lamp light, about the energy their lobe reflects).
float voxel_base_weight(float code, const BrdfTables& tables);

}  // namespace rp::shading
