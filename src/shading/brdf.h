// The surface model: a GGX microfacet specular coat with Kulla-Conty multiple
// scattering over a Lambertian base. C++ reference of kernels/common/brdf.h (same formulas, same
// table lookup), used by the path tracer (truth/), the renderer (the tables it uploads) and the
// tests. Physical units: f is in 1/sr; rolypoly's light units put a pi in front (DESIGN.md
// "Light units": the lamp's direct radiance is pi * f * I * cos / d^2 * falloff, so a Lambertian
// f = albedo / pi gives today's albedo * I * cos / d^2).
//
// Parameters (scene::Specular): roughness r in [0, 1] (perceptual), GGX alpha = r^2 (clamped to
// kMinAlpha); f0 = the dielectric coat's reflectance at normal incidence (((n - 1) / (n + 1))^2,
// 0.04 for n = 1.5), or for a metal (metal = true) F0 = the albedo colour and no diffuse base.
// f0 = 0 and not metal: no coat, plain Lambert (the walls), bit for bit as before coats.
//
// With mu_o = n.v, mu_i = n.l, h = normalize(v + l), alpha = r^2:
//   D(h)      = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2)                      (GGX)
//   Vis       = G2 / (4 mu_i mu_o) = 0.5 / (mu_i sqrt(mu_o^2 (1 - alpha^2) + alpha^2)
//                                        + mu_o sqrt(mu_i^2 (1 - alpha^2) + alpha^2))
//               (Smith, height-correlated; Heitz 2014)
//   F(v.h)    = F0 + (1 - F0) (1 - v.h)^5                                          (Schlick)
//   f_ss      = D Vis F                                   (single scattering)
//   E(mu), S(mu): directional albedo of D Vis with F = 1, and of D Vis (1 - v.h)^5, so
//     the single-scattering albedo is E_ss(mu) = F0 (E - S) + S; E_avg = 2 int E mu dmu
//     (likewise S_avg). Tabulated at start-up (brdf_tables.h).
//   f_ms      = (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg)) * f_add          (Kulla-Conty 2017)
//   f_add     = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)),  F_avg = F0 + (1 - F0) / 21
//               (the cosine-weighted mean of Schlick's F; per channel for a coloured metal)
//   E_spec(mu)= E_ss(mu) + (1 - E(mu)) f_add          (the coat's directional albedo)
//   f_d       = albedo / pi * (1 - E_spec(mu_o)) (1 - E_spec(mu_i)) / (1 - E_spec_avg)
//               (dielectric coat; 0 for a metal; albedo / pi without a coat)
//   f         = f_ss + f_ms + f_d
// The diffuse weight is reciprocal and, for a white base, conserves energy exactly: the albedo
// at mu_o is E_spec(mu_o) + (1 - E_spec(mu_o)) * 1 (int (1 - E_spec(mu_i)) 2 mu_i dmu_i =
// 1 - E_spec_avg). Under light that is uniform over the hemisphere the base reflects
// albedo * (1 - E_spec(mu_o)) and the coat E_spec(mu_o).
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "scene/frame_scene.h"

namespace rp::shading {

inline constexpr float kPi = 3.14159265358979323846f;
// Smallest GGX alpha (roughness ~0.03): below it D's peak (1 / (pi alpha^2)) outgrows float
// precision in the kernels' lamp term.
inline constexpr float kMinAlpha = 1.0e-3f;
// Cosines are clamped to this before the 1 / mu terms (grazing, interpolated normals).
inline constexpr float kMinCos = 1.0e-4f;

inline float ggx_alpha(float roughness) {
  return std::max(roughness * roughness, kMinAlpha);
}

inline float ggx_d(float n_dot_h, float alpha) {
  const float a2 = alpha * alpha;
  const float t = n_dot_h * n_dot_h * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * t * t);
}

// G2 / (4 mu_i mu_o), height-correlated Smith.
inline float smith_vis(float mu_o, float mu_i, float alpha) {
  const float a2 = alpha * alpha;
  const float go = mu_i * std::sqrt(mu_o * mu_o * (1.0f - a2) + a2);
  const float gi = mu_o * std::sqrt(mu_i * mu_i * (1.0f - a2) + a2);
  return 0.5f / (go + gi);
}

// Smith G1 of direction cosine mu (the VNDF's normalisation).
inline float smith_g1(float mu, float alpha) {
  const float a2 = alpha * alpha;
  return 2.0f * mu / (mu + std::sqrt(a2 + (1.0f - a2) * mu * mu));
}

inline float schlick_weight(float v_dot_h) {
  const float m = std::clamp(1.0f - v_dot_h, 0.0f, 1.0f);
  const float m2 = m * m;
  return m2 * m2 * m;
}

inline glm::vec3 fresnel_avg(glm::vec3 f0) { return f0 + (1.0f - f0) * (1.0f / 21.0f); }

// Tan of the half-angle of the reflection cone that stands for the GGX lobe at `roughness`
// (kernels/common/brdf.h, rp_brdf_spec_cone_tan, has the derivation): the
// reflected lobe's half width at half maximum, 2 atan(0.6436 alpha) (GGX D halves at
// tan(theta_h) = alpha sqrt(sqrt 2 - 1)), clamped to [0.1, 1].
inline constexpr float kSpecConeMinTan = 0.1f, kSpecConeMaxTan = 1.0f;
inline float spec_cone_tan(float roughness) {
  const double a = std::max(double(roughness) * roughness, double(kMinAlpha));
  const double th = std::atan(a * std::sqrt(std::sqrt(2.0) - 1.0));
  return std::clamp(float(std::tan(2.0 * th)), kSpecConeMinTan, kSpecConeMaxTan);
}

// One entry of the tables (brdf_tables.h): E(mu), S(mu), E_avg, S_avg at one roughness.
struct TableEntry {
  float e = 1.0f, s = 0.0f, e_avg = 1.0f, s_avg = 0.0f;
};

// Kulla-Conty's colour factor f_add (see the header).
inline glm::vec3 ms_factor(glm::vec3 f0, float e_avg) {
  const glm::vec3 fa = fresnel_avg(f0);
  return fa * fa * e_avg / (1.0f - fa * (1.0f - e_avg));
}

// The coat's directional albedo E_spec (see the header) at a table entry.
inline glm::vec3 coat_albedo(glm::vec3 f0, const TableEntry& t, glm::vec3 f_add) {
  return f0 * (t.e - t.s) + t.s + (1.0f - t.e) * f_add;
}
inline glm::vec3 coat_albedo_avg(glm::vec3 f0, const TableEntry& t, glm::vec3 f_add) {
  return f0 * (t.e_avg - t.s_avg) + t.s_avg + (1.0f - t.e_avg) * f_add;
}

// A surface ready to evaluate: the material's parameters resolved at a point.
struct SurfaceBsdf {
  glm::vec3 albedo{0.8f};   // diffuse base (texture included); the metal's colour if metal
  float roughness = 1.0f;
  float f0 = 0.0f;
  bool metal = false;
  bool coated() const { return metal || f0 > 0.0f; }
  glm::vec3 spec_f0() const { return metal ? albedo : glm::vec3(f0); }
};

// Lobes of f at (mu_o, mu_i, n.h, v.h) for a coated surface; `compensate` = false drops f_ms
// (the furnace test's "without Kulla-Conty").
struct BrdfValue {
  glm::vec3 specular{0.0f};  // f_ss + f_ms
  glm::vec3 diffuse{0.0f};   // f_d
  glm::vec3 total() const { return specular + diffuse; }
};

class BrdfTables;

// f for unit vectors in the frame of unit normal n (wo towards the viewer, wi towards the
// light); 0 below the surface. Uses `tables` for E, S and their averages.
BrdfValue eval_brdf(const SurfaceBsdf& s, glm::vec3 n, glm::vec3 wo, glm::vec3 wi,
                    const BrdfTables& tables, bool compensate = true);

// The coat's directional albedo E_spec(mu_o) (0 without a coat): what the base does not get
// from light uniform over the hemisphere; the indirect light's split (light pass).
glm::vec3 coat_albedo_at(const SurfaceBsdf& s, float mu_o, const BrdfTables& tables);

// Importance sampling for the path tracer: with probability spec_probability() a direction
// from GGX's distribution of visible normals (Heitz 2018) reflected about it, else cosine
// weighted. pdf() is the mixture's density per steradian of the returned direction.
struct BsdfSample {
  glm::vec3 wi{0.0f};
  float pdf = 0.0f;  // 0: no direction (below the surface)
};
float spec_probability(const SurfaceBsdf& s, float mu_o, const BrdfTables& tables);
BsdfSample sample_brdf(const SurfaceBsdf& s, glm::vec3 n, glm::vec3 wo, float u_lobe, float u1,
                       float u2, const BrdfTables& tables);
float brdf_pdf(const SurfaceBsdf& s, glm::vec3 n, glm::vec3 wo, glm::vec3 wi,
               const BrdfTables& tables);
// GGX VNDF in the local frame (z = normal, wo.z > 0): the sampled microfacet normal.
glm::vec3 sample_vndf(glm::vec3 wo_local, float alpha, float u1, float u2);
// Density per steradian of the reflected direction when h comes from sample_vndf:
// G1(mu_o) D(h) / (4 mu_o).
inline float vndf_reflect_pdf(float mu_o, float n_dot_h, float alpha) {
  return smith_g1(mu_o, alpha) * ggx_d(n_dot_h, alpha) / (4.0f * std::max(mu_o, kMinCos));
}

// The light pass's lamp shading (kernels/common/brdf.h rp_brdf_lamp8), rolypoly's units: the
// lamp's radiance toward wo is (albedo * diffuse_weight + specular) * I * cos / (d^2 + a^2) *
// falloff * shadow. `widen` (a / 2d of the lamp disk) widens the single-scattering lobe toward
// the lamp's image: alpha' = min(sqrt(alpha^2 + widen^2), 1), D = min(D_alpha, D_alpha') (the
// widened peak, the surface's own tails), Vis with alpha'. With widen = 0, albedo *
// diffuse_weight + specular = pi * eval_brdf(...).total().
struct LampShading {
  glm::vec3 diffuse_weight{1.0f};  // w_d (1 without a coat, 0 for a metal)
  glm::vec3 specular{0.0f};        // pi (f_ss + f_ms)
  glm::vec3 view_albedo{0.0f};     // E_spec(mu_o)
};
LampShading shade_lamp(const SurfaceBsdf& s, glm::vec3 n, glm::vec3 wo, glm::vec3 wi,
                       float widen, const BrdfTables& tables);

// scene::Specular -> SurfaceBsdf at a point with diffuse colour `albedo`.
inline SurfaceBsdf make_bsdf(const scene::Specular& spec, glm::vec3 albedo) {
  SurfaceBsdf s;
  s.albedo = albedo;
  s.roughness = spec.roughness;
  s.f0 = spec.f0;
  s.metal = spec.metal;
  return s;
}

}  // namespace rp::shading
