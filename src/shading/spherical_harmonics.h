// Real spherical harmonics up to band 4 (25 coefficients): the basis of precomputed radiance
// transfer and of a prefiltered sky (an environment light projected onto the first 9 or 25
// functions).
//
// Convention: the real, orthonormal basis (integral of Y_i Y_j over the sphere = delta_ij)
// without the Condon-Shortley phase, as graphics uses it: Y_1,-1 = c y, Y_1,0 = c z,
// Y_1,1 = c x with c = sqrt(3 / (4 pi)) for a unit direction (x, y, z). Coefficient (l, m),
// -l <= m <= l, is at index l (l + 1) + m; `bands` = l_max + 1 (3: 9 coefficients, 5: 25).
// Host code, double precision: the projections and rotations feed float tables.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/environment.h"
#include "scene/environment_glow.h"

namespace rp::shading {

inline constexpr int kShMaxBands = 5;
inline constexpr int kShMaxCount = kShMaxBands * kShMaxBands;

constexpr int sh_count(int bands) { return bands * bands; }
constexpr int sh_index(int l, int m) { return l * (l + 1) + m; }

// Y_i(dir) for i < bands^2 into out (unit `dir`; bands 1 .. kShMaxBands).
void sh_eval(glm::dvec3 dir, int bands, double* out);

// Coefficients of f over the sphere: the integral of f Y_i, by a product rule (Gauss-Legendre
// in cos(theta) x equally spaced phi) exact for polynomials of degree < 2 * rings in z and
// trigonometric polynomials of degree < segments in phi: with the defaults, exact (to
// rounding) for every product of two functions of the first 5 bands, and accurate for smooth f.
std::vector<double> sh_project(const std::function<double(glm::dvec3)>& f, int bands,
                               int rings = 24, int segments = 48);

// Coefficients of the clamped cosine lobe max(0, dot(n, dir)) for n = +z (zonal: only m = 0
// terms), A_l: sqrt(pi) / 2, sqrt(pi / 3), sqrt(5 pi) / 8, 0, -sqrt(pi) / 16 for l = 0 .. 4.
double sh_cosine_lobe_zonal(int l);

// The coefficients of a zonal function with zonal coefficients z_l (for axis +z), turned to
// axis `n` (unit): z_l sqrt(4 pi / (2 l + 1)) Y_lm(n).
std::vector<double> sh_rotate_zonal(const std::vector<double>& zonal, glm::dvec3 n, int bands);

// The rotation of coefficient vectors: for g(dir) = f(R^-1 dir) (f turned by R),
// g's coefficients = rotate(f's). Band by band, each band's (2l + 1)^2 matrix is solved from
// the basis at fixed directions (least squares over 2 (2l + 1) points of a Fibonacci sphere:
// exact to rounding, as band l of any rotation maps into band l).
// RGB coefficients of an environment map (scene/environment.h: its layout and direction
// convention; strength and turn applied): the integral over each texel's exact solid angle,
// (2 pi / width) (cos theta0 - cos theta1), of its radiance times Y_i at the texel's centre.
// A constant map of radiance L gives L sqrt(4 pi) in the first coefficient (to rounding).
std::vector<glm::dvec3> sh_project_environment(const scene::Environment& environment, int bands);

// The same for an environment's glow (scene/environment_glow.h) unturned at strength 1: the
// sum over its texels alone, equal to projecting a map that holds them and zero elsewhere (the
// same terms in the same order).
std::vector<glm::dvec3> sh_project_glow(const scene::EnvironmentGlow& glow, int bands);

// Irradiance on a surface of unit normal n from RGB coefficients (the integral of
// L max(0, n . dir) for the band-limited L): the coefficients dotted with the clamped cosine
// lobe's turned to n (sh_rotate_zonal).
glm::dvec3 sh_irradiance(const std::vector<glm::dvec3>& coefficients, glm::dvec3 n, int bands);

// The coefficients of an environment turned by rotate_deg about +y and scaled by strength (as
// sh_project_environment applies scene::Environment's), from those of the same map projected
// unturned at strength 1: one rotation per band (ShRotation), cheap enough for every frame.
// Equal to projecting the turned map where the turn maps texel centres onto texel centres
// (multiples of 360 / width degrees), to rounding; otherwise to the projection's quadrature.
std::vector<glm::dvec3> sh_turn_environment(const std::vector<glm::dvec3>& unturned,
                                            float rotate_deg, float strength);

// How far the irradiance from the environment's first bands^2 coefficients (sh_irradiance)
// is from the exact irradiance (the sum over every texel of L max(0, n . d) times its solid
// angle), over `normals` directions spread evenly over the sphere (a Fibonacci set):
// sum |E_sh - E| / sum E of the luminance (Rec. 709 weights). The floor unshadowed precomputed
// radiance transfer of that many bands cannot beat on a diffuse surface. 0 without a map.
double sh_irradiance_error(const scene::Environment& environment, int bands, int normals = 256);

class ShRotation {
 public:
  ShRotation(const glm::dmat3& rotation, int bands);
  // in and out: bands^2 coefficients each (may not alias).
  void apply(const double* in, double* out) const;
  int bands() const { return bands_; }

 private:
  int bands_;
  // Band l's matrix, row-major (2l + 1)^2, at offset sum_{k < l} (2k + 1)^2.
  std::vector<double> blocks_;
};

}  // namespace rp::shading
