// The surface model (src/shading/brdf.h) against its defining properties: the white
// furnace (a rough white metal keeps its energy with Kulla-Conty, and how much it loses
// without), reciprocity, the sampler's densities, the E table against an independent Monte
// Carlo estimate, and the energy-conserving layered diffuse.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "shading/brdf.h"
#include "shading/brdf_tables.h"
#include "truth/sampling.h"

namespace rp::shading {
namespace {

const BrdfTables& tables() { return BrdfTables::get(); }

glm::vec3 dir_at(float mu, float phi) {
  const float s = std::sqrt(std::max(0.0f, 1.0f - mu * mu));
  return {s * std::cos(phi), s * std::sin(phi), mu};
}

// Directional albedo int f cos dw at wo by the BRDF's own sampler (stratified, fixed seed):
// unbiased for any roughness.
glm::dvec3 albedo_at(const SurfaceBsdf& s, float mu_o, bool compensate, int strata = 256) {
  const glm::vec3 n(0.0f, 0.0f, 1.0f), wo = dir_at(mu_o, 0.3f);
  truth::Pcg32 rng(7, uint64_t(mu_o * 1000.0f) + uint64_t(s.roughness * 1.0e6f));
  glm::dvec3 sum(0.0);
  for (int a = 0; a < strata; ++a)
    for (int b = 0; b < strata; ++b) {
      const float u1 = (float(a) + rng.uniform()) / float(strata);
      const float u2 = (float(b) + rng.uniform()) / float(strata);
      const BsdfSample bs = sample_brdf(s, n, wo, rng.uniform(), u1, u2, tables());
      if (!(bs.pdf > 0.0f)) continue;
      const BrdfValue f = eval_brdf(s, n, wo, bs.wi, tables(), compensate);
      sum += glm::dvec3(f.total() * (bs.wi.z / bs.pdf));
    }
  return sum / (double(strata) * strata);
}

TEST(Brdf, WhiteFurnaceKeepsTheEnergyWithKullaConty) {
  SurfaceBsdf metal;
  metal.metal = true;
  metal.albedo = glm::vec3(1.0f);  // F0 = 1: every microfacet reflects everything
  std::printf("white furnace, rough white metal (F0 = 1): albedo with / without Kulla-Conty\n");
  std::printf("roughness  mu_o:  1.0            0.5            0.2            0.05\n");
  for (float r : {0.05f, 0.1f, 0.25f, 0.4f, 0.55f, 0.7f, 0.85f, 1.0f}) {
    metal.roughness = r;
    std::printf("  %.2f       ", r);
    for (float mu : {1.0f, 0.5f, 0.2f, 0.05f}) {
      const double with = albedo_at(metal, mu, true).x;
      const double without = albedo_at(metal, mu, false).x;
      std::printf("%.3f / %.3f  ", with, without);
      EXPECT_GE(with, 0.99) << "roughness " << r << " mu_o " << mu;
      EXPECT_LE(with, 1.01) << "roughness " << r << " mu_o " << mu;
      // without compensation the rough metal loses what multiple scattering carries
      if (r >= 0.7f) {
        EXPECT_LT(without, 0.97) << "roughness " << r << " mu_o " << mu;
      }
    }
    std::printf("\n");
  }
}

TEST(Brdf, WhiteDiffuseUnderADielectricCoatKeepsTheEnergy) {
  // The layered diffuse weight (1 - E_spec(mu_o)) (1 - E_spec(mu_i)) / (1 - E_spec_avg) makes
  // a white base under any coat reflect everything.
  SurfaceBsdf s;
  s.albedo = glm::vec3(1.0f);
  for (float f0 : {0.02f, 0.04f, 0.1f})
    for (float r : {0.08f, 0.25f, 0.38f, 0.7f, 1.0f})
      for (float mu : {1.0f, 0.6f, 0.25f, 0.08f}) {
        s.f0 = f0;
        s.roughness = r;
        const double a = albedo_at(s, mu, true, 160).x;
        EXPECT_NEAR(a, 1.0, 0.01) << "f0 " << f0 << " roughness " << r << " mu_o " << mu;
      }
}

TEST(Brdf, IsReciprocal) {
  truth::Pcg32 rng(3, 1);
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  for (int k = 0; k < 2000; ++k) {
    SurfaceBsdf s;
    s.roughness = 0.05f + 0.95f * rng.uniform();
    s.metal = k % 3 == 0;
    s.f0 = s.metal ? 0.0f : 0.02f + 0.2f * rng.uniform();
    s.albedo = glm::vec3(rng.uniform(), rng.uniform(), rng.uniform());
    const glm::vec3 a = dir_at(0.02f + 0.98f * rng.uniform(), 6.2832f * rng.uniform());
    const glm::vec3 b = dir_at(0.02f + 0.98f * rng.uniform(), 6.2832f * rng.uniform());
    const glm::vec3 fab = eval_brdf(s, n, a, b, tables()).total();
    const glm::vec3 fba = eval_brdf(s, n, b, a, tables()).total();
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(fab[c], fba[c], 1.0e-4f * std::max(1.0f, fab[c])) << "pair " << k;
  }
}

TEST(Brdf, SamplingDensityIntegratesToOne) {
  // Quadrature in (mu, phi), fine enough for lobes of roughness >= 0.3. The visible-normal
  // lobe's density of reflected directions, G1(mu_o) D(h) / (4 mu_o), integrates to 1 over the
  // whole sphere (some reflections point below the surface: sample_brdf rejects those, an
  // unbiased zero); the mixture's density over the upper hemisphere then equals the share of
  // sample_brdf's draws it accepts.
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  const int nm = 2000, np = 1000;
  for (bool metal : {false, true})
    for (float r : {0.3f, 0.5f, 1.0f})
      for (float mu_o : {0.9f, 0.4f}) {
        SurfaceBsdf s;
        s.metal = metal;
        s.f0 = metal ? 0.0f : 0.04f;
        s.albedo = glm::vec3(0.6f);
        s.roughness = r;
        const float alpha = ggx_alpha(r);
        const glm::vec3 wo = dir_at(mu_o, 0.0f);
        double sphere = 0.0, mixture = 0.0;
        for (int i = 0; i < 2 * nm; ++i)
          for (int j = 0; j < np; ++j) {
            const float mu = -1.0f + (float(i) + 0.5f) / float(nm);
            const glm::vec3 wi = dir_at(mu, 2.0f * kPi * (float(j) + 0.5f) / float(np));
            const glm::vec3 h = glm::normalize(wo + wi);
            if (h.z > 0.0f) sphere += vndf_reflect_pdf(mu_o, h.z, alpha);
            if (mu > 0.0f) mixture += brdf_pdf(s, n, wo, wi, tables());
          }
        const double dw = (1.0 / nm) * (2.0 * kPi / np);
        EXPECT_NEAR(sphere * dw, 1.0, 0.005) << "roughness " << r << " mu_o " << mu_o;
        truth::Pcg32 rng(13, uint64_t(r * 100.0f));
        int accepted = 0;
        const int draws = 200000;
        for (int k = 0; k < draws; ++k)
          accepted += sample_brdf(s, n, wo, rng.uniform(), rng.uniform(), rng.uniform(),
                                  tables()).pdf > 0.0f;
        EXPECT_NEAR(mixture * dw, double(accepted) / draws, 0.01)
            << (metal ? "metal" : "dielectric") << " roughness " << r << " mu_o " << mu_o;
      }
}

TEST(Brdf, SamplerMatchesItsDensity) {
  // E[g / pdf] over the sampler's directions = int g dw: for g = 1 the hemisphere, 2 pi, and for
  // g = cos, pi (any mismatch between sample_brdf and brdf_pdf shows).
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  for (float r : {0.08f, 0.38f, 1.0f}) {
    SurfaceBsdf s;
    s.f0 = 0.04f;
    s.albedo = glm::vec3(0.5f);
    s.roughness = r;
    const glm::vec3 wo = dir_at(0.7f, 0.0f);
    truth::Pcg32 rng(11, uint64_t(r * 100.0f));
    double one = 0.0, cosine = 0.0;
    const int count = 400000;
    for (int k = 0; k < count; ++k) {
      const BsdfSample bs = sample_brdf(s, n, wo, rng.uniform(), rng.uniform(), rng.uniform(),
                                        tables());
      if (!(bs.pdf > 0.0f)) continue;
      one += 1.0 / bs.pdf;
      cosine += bs.wi.z / bs.pdf;
    }
    EXPECT_NEAR(one / count, 2.0 * kPi, 0.03 * 2.0 * kPi) << "roughness " << r;
    EXPECT_NEAR(cosine / count, kPi, 0.01 * kPi) << "roughness " << r;
  }
}

TEST(Brdf, LampShadingWithoutWideningIsPiTimesTheBrdf) {
  truth::Pcg32 rng(17, 2);
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  for (int k = 0; k < 500; ++k) {
    SurfaceBsdf s;
    s.roughness = 0.05f + 0.95f * rng.uniform();
    s.metal = k % 4 == 0;
    s.f0 = s.metal ? 0.0f : 0.02f + 0.1f * rng.uniform();
    s.albedo = glm::vec3(rng.uniform(), rng.uniform(), rng.uniform());
    const glm::vec3 wo = dir_at(0.05f + 0.95f * rng.uniform(), 6.2832f * rng.uniform());
    const glm::vec3 wi = dir_at(0.05f + 0.95f * rng.uniform(), 6.2832f * rng.uniform());
    const LampShading l = shade_lamp(s, n, wo, wi, 0.0f, tables());
    const glm::vec3 want = kPi * eval_brdf(s, n, wo, wi, tables()).total();
    const glm::vec3 got = s.albedo * l.diffuse_weight + l.specular;
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], want[c], 1.0e-4f * std::max(1.0f, want[c]));
    EXPECT_EQ(l.view_albedo, coat_albedo_at(s, wo.z, tables()));
  }
}

TEST(Brdf, LampWideningTracksTheAreaLamp) {
  // The light pass's specular from the lamp (shade_lamp: the lobe widened by the lamp disk,
  // times the disk model's cos * falloff / (d^2 + a^2)) against the lamp cap integrated as an
  // area light (truth::LampCap, L_e = I / a^2, the path tracer's --lamp area), on floor points
  // seen from the default camera: flat (the highlight's tail) and turned so the lamp's mirror
  // image lies on the normal (its peak). Within 0.85 .. 1.3 x everywhere.
  const truth::LampCap cap{{0.0f, 1.1f, 0.0f}, 0.35f, 1.0f};
  const float a2 = cap.projected_radius2();
  const glm::vec3 cam(0.0f, 0.0f, 2.7f), disk(0.0f, 1.0f, 0.0f);
  for (float rough : {0.08f, 0.25f, 0.38f})
    for (bool peak : {false, true})
      for (glm::vec3 p : {glm::vec3(0.0f, -1.0f, 0.5f), glm::vec3(0.5f, -1.0f, 0.0f),
                          glm::vec3(0.0f, -1.0f, -0.6f), glm::vec3(-0.6f, -1.0f, 0.8f)}) {
        SurfaceBsdf s;
        s.albedo = glm::vec3(0.0f);
        s.f0 = 0.04f;
        s.roughness = rough;
        const glm::vec3 wo = glm::normalize(cam - p);
        const glm::vec3 n = peak ? glm::normalize(wo + glm::normalize(disk - p)) : glm::vec3(0, 1, 0);
        const glm::vec3 to_centre = cap.centre - p;
        const float dist = glm::length(to_centre);
        const float omc = truth::sphere_cone_omc(cap.radius, dist);
        const int strata = 200;
        double sum = 0.0;
        for (int i = 0; i < strata; ++i)
          for (int j = 0; j < strata; ++j) {
            const glm::vec3 wi = truth::sample_cone(to_centre / dist, omc,
                                                    (float(i) + 0.5f) / strata,
                                                    (float(j) + 0.5f) / strata);
            const float c = glm::dot(n, wi);
            if (cap.hit(p, wi) < 0.0f || c <= 0.0f) continue;
            sum += double(eval_brdf(s, n, wo, wi, tables()).specular.x) * c;
          }
        const double truth_spec = sum * 2.0 * kPi * omc / (double(strata) * strata) / a2;
        const glm::vec3 l = glm::normalize(cap.centre - p);
        const float d2 = glm::dot(disk - p, disk - p);
        const float e = std::clamp(l.y, 0.0f, 1.0f);
        const float k = glm::dot(n, l) * (0.35f + e * (0.446f + 0.204f * e)) / (d2 + a2);
        const float widen = 0.5f * std::sqrt(a2 / d2);
        const double rt = double(shade_lamp(s, n, wo, l, widen, tables()).specular.x) * k;
        EXPECT_GT(rt / truth_spec, 0.85) << "roughness " << rough << (peak ? " peak " : " tail ")
                                         << p.x << "," << p.z;
        EXPECT_LT(rt / truth_spec, 1.3) << "roughness " << rough << (peak ? " peak " : " tail ")
                                        << p.x << "," << p.z;
      }
}

TEST(BrdfTables, EMatchesAnIndependentMonteCarloEstimate) {
  // E(mu) = int D Vis cos dw (F = 1) by GGX normal-distribution sampling (pdf of h:
  // D (n.h); not the visible-normal grid the table uses), random, 200k samples per point.
  for (float r : {0.1f, 0.3f, 0.5f, 0.75f, 0.95f})
    for (float mu : {0.05f, 0.2f, 0.5f, 0.8f, 0.98f}) {
      const float alpha = ggx_alpha(r);
      const glm::vec3 wo = dir_at(mu, 0.0f);
      truth::Pcg32 rng(5, uint64_t(r * 100.0f) * 100 + uint64_t(mu * 100.0f));
      double e = 0.0;
      const int count = 200000;
      for (int k = 0; k < count; ++k) {
        const float u1 = rng.uniform(), u2 = rng.uniform();
        const float cos_h = std::sqrt((1.0f - u1) / (1.0f + (alpha * alpha - 1.0f) * u1));
        const glm::vec3 h = dir_at(cos_h, 2.0f * kPi * u2);
        const float v_dot_h = glm::dot(wo, h);
        if (v_dot_h <= 0.0f) continue;
        const glm::vec3 wi = 2.0f * v_dot_h * h - wo;
        if (wi.z <= 0.0f) continue;
        // f cos / pdf, pdf(wi) = D cos_h / (4 v.h)
        e += smith_vis(mu, wi.z, alpha) * wi.z * 4.0f * v_dot_h / cos_h;
      }
      e /= count;
      const TableEntry t = tables().lookup(mu, r);
      EXPECT_NEAR(t.e, e, 0.01) << "roughness " << r << " mu " << mu;
      EXPECT_LE(t.s, t.e);
      EXPECT_GE(t.s, 0.0f);
    }
}

TEST(BrdfTables, AreDeterministicAndMonotone) {
  const BrdfTables& t = tables();
  // rougher surfaces lose more to masking: E_avg falls with roughness
  for (int j = 1; j < BrdfTables::kSize; ++j)
    EXPECT_LE(t.cells()[size_t(j) * BrdfTables::kSize].z,
              t.cells()[size_t(j - 1) * BrdfTables::kSize].z + 1.0e-6f);
  const glm::vec2 again = BrdfTables::integrate_es(0.5f, 0.25f, 32);
  const glm::vec2 once = BrdfTables::integrate_es(0.5f, 0.25f, 32);
  EXPECT_EQ(again, once);
}

TEST(GlossCode, RoundTripsTheQuantisedCoat) {
  EXPECT_EQ(gloss_code(scene::Specular{}), 0.0f);  // matte: no coat
  const scene::Specular floor{0.38f, 0.04f, false};
  const scene::Specular back = decode_gloss(gloss_code(floor));
  EXPECT_NEAR(back.roughness, 0.38f, 0.5f / 255.0f);
  EXPECT_NEAR(back.f0, 0.04f, 0.5f / RP_GLOSS_F0_SCALE);
  EXPECT_FALSE(back.metal);
  const scene::Specular gold = decode_gloss(gloss_code(scene::Specular{0.5f, 0.0f, true}));
  EXPECT_TRUE(gold.metal);
  EXPECT_NEAR(gold.roughness, 0.5f, 0.51f / 255.0f);
}

}  // namespace
}  // namespace rp::shading

namespace rp::shading {
namespace {

// The voxelizer's weight of a coated surface's base (voxel_base_weight, Material.albedo.w) is
// one minus the coat's cosine-weighted mean albedo: here that mean from the BRDF sampled
// directly (black base, 16 midpoint mu_o, 64^2 strata each), not from the tables' E_avg/S_avg.
// Matte and metal surfaces keep weight 1.
TEST(VoxelBaseWeight, IsOneMinusTheCoatsMeanAlbedo) {
  const scene::Specular coats[3] = {{0.38f, 0.04f, false}, {0.25f, 0.045f, false},
                                    {0.08f, 0.046f, false}};
  for (const scene::Specular& c : coats) {
    const float code = gloss_code(c);
    const scene::Specular q = decode_gloss(code);  // the quantised coat the device sees
    SurfaceBsdf s;
    s.albedo = glm::vec3(0.0f);
    s.roughness = q.roughness;
    s.f0 = q.f0;
    double mean = 0.0;
    const int n_mu = 16;
    for (int k = 0; k < n_mu; ++k) {
      const float mu = (float(k) + 0.5f) / float(n_mu);
      mean += 2.0 * double(mu) * albedo_at(s, mu, true, 64).x / n_mu;
    }
    const float w = voxel_base_weight(code, tables());
    std::printf("roughness %.2f f0 %.3f: weight %.4f, 1 - sampled mean %.4f\n", c.roughness, c.f0,
                w, 1.0 - mean);
    EXPECT_NEAR(w, 1.0 - mean, 0.004) << c.roughness;
    EXPECT_LT(w, 0.97f);
  }
  EXPECT_EQ(voxel_base_weight(0.0f, tables()), 1.0f);
  EXPECT_EQ(voxel_base_weight(gloss_code({0.3f, 0.0f, true}), tables()), 1.0f);
}

}  // namespace
}  // namespace rp::shading
