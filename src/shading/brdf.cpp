// The surface model's evaluation, sampling and tables (src/shading/brdf.h, brdf_tables.h).
#include "shading/brdf.h"

#include "shading/basis.h"

#include <cmath>

#include "shading/brdf_tables.h"

namespace rp::shading {
namespace {

float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// Smith's Lambda of a direction with cosine mu.
float smith_lambda(float mu, float alpha) {
  const float m2 = std::max(mu * mu, kMinCos * kMinCos);
  return 0.5f * (-1.0f + std::sqrt(1.0f + alpha * alpha * (1.0f - m2) / m2));
}


// Linear interpolation coordinate on an N-entry axis (kernels/shared/brdf_layout.h): entry i0
// and the weight of i0 + 1. mu: cell centres (i + 0.5) / N, clamped; roughness: nodes
// j / (N - 1), so the table holds roughness 0 and 1 exactly.
void table_coord(float u, int& i0, float& t) {
  const int n = BrdfTables::kSize;
  u = std::clamp(u, 0.0f, float(n - 1));
  i0 = std::min(int(u), n - 2);
  t = u - float(i0);
}

}  // namespace

glm::vec3 sample_vndf(glm::vec3 wo, float alpha, float u1, float u2) {
  // Heitz 2018, "Sampling the GGX Distribution of Visible Normals".
  const glm::vec3 vh = glm::normalize(glm::vec3(alpha * wo.x, alpha * wo.y, wo.z));
  const float lensq = vh.x * vh.x + vh.y * vh.y;
  const glm::vec3 t1 = lensq > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lensq)
                                    : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 t2 = glm::cross(vh, t1);
  const float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
  const float p1 = r * std::cos(phi);
  const float s = 0.5f * (1.0f + vh.z);
  const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
  const glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(0.0f, nh.z)));
}

glm::vec2 BrdfTables::integrate_es(float mu, float alpha, int grid) {
  const glm::vec3 wo(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
  const float lambda_o = smith_lambda(mu, alpha);
  const float g1 = 1.0f / (1.0f + lambda_o);
  double e = 0.0, s = 0.0;
  for (int a = 0; a < grid; ++a)
    for (int b = 0; b < grid; ++b) {
      const glm::vec3 h =
          sample_vndf(wo, alpha, (float(a) + 0.5f) / float(grid), (float(b) + 0.5f) / float(grid));
      const float v_dot_h = glm::dot(wo, h);
      const glm::vec3 wi = 2.0f * v_dot_h * h - wo;
      if (wi.z <= 0.0f) continue;
      // f cos / pdf = G2 / G1(v) for VNDF-sampled reflections
      const float w = (1.0f / (1.0f + lambda_o + smith_lambda(wi.z, alpha))) / g1;
      e += w;
      s += w * schlick_weight(v_dot_h);
    }
  const double inv = 1.0 / (double(grid) * grid);
  return {float(e * inv), float(s * inv)};
}

BrdfTables::BrdfTables() {
  for (int j = 0; j < kSize; ++j) {
    const float alpha = ggx_alpha(float(j) / float(kSize - 1));
    double e_avg = 0.0, s_avg = 0.0;
    for (int i = 0; i < kSize; ++i) {
      const float mu = (float(i) + 0.5f) / float(kSize);
      const glm::vec2 es = integrate_es(mu, alpha, 32);
      cells_[size_t(j) * kSize + size_t(i)] = glm::vec4(es, 0.0f, 0.0f);
      // E_avg = 2 int E mu dmu, midpoint rule over the cell centres
      e_avg += 2.0 * double(es.x) * mu / kSize;
      s_avg += 2.0 * double(es.y) * mu / kSize;
    }
    for (int i = 0; i < kSize; ++i) {
      cells_[size_t(j) * kSize + size_t(i)].z = float(e_avg);
      cells_[size_t(j) * kSize + size_t(i)].w = float(s_avg);
    }
  }
}

const BrdfTables& BrdfTables::get() {
  static const BrdfTables tables;
  return tables;
}

TableEntry BrdfTables::lookup(float mu, float roughness) const {
  int i0, j0;
  float ti, tj;
  table_coord(mu * float(kSize) - 0.5f, i0, ti);
  table_coord(roughness * float(kSize - 1), j0, tj);
  auto at = [&](int j, int i) { return cells_[size_t(j) * kSize + size_t(i)]; };
  const glm::vec4 v = (at(j0, i0) * (1.0f - ti) + at(j0, i0 + 1) * ti) * (1.0f - tj) +
                      (at(j0 + 1, i0) * (1.0f - ti) + at(j0 + 1, i0 + 1) * ti) * tj;
  return {v.x, v.y, v.z, v.w};
}

BrdfValue eval_brdf(const SurfaceBsdf& s, glm::vec3 n, glm::vec3 wo, glm::vec3 wi,
                    const BrdfTables& tables, bool compensate) {
  BrdfValue out;
  const float mu_i = glm::dot(n, wi);
  if (mu_i <= 0.0f) return out;
  if (!s.coated()) {
    out.diffuse = s.albedo / kPi;
    return out;
  }
  const float mo = std::max(glm::dot(n, wo), kMinCos), mi = std::max(mu_i, kMinCos);
  const glm::vec3 h = glm::normalize(wo + wi);
  const float alpha = ggx_alpha(s.roughness);
  const glm::vec3 f0 = s.spec_f0();
  const glm::vec3 fresnel = f0 + (1.0f - f0) * schlick_weight(glm::dot(wo, h));
  out.specular = ggx_d(std::max(glm::dot(n, h), 0.0f), alpha) * smith_vis(mo, mi, alpha) * fresnel;
  const TableEntry to = tables.lookup(mo, s.roughness), ti = tables.lookup(mi, s.roughness);
  const glm::vec3 f_add = compensate ? ms_factor(f0, to.e_avg) : glm::vec3(0.0f);
  out.specular += (1.0f - to.e) * (1.0f - ti.e) / (kPi * std::max(1.0f - to.e_avg, 1.0e-4f)) * f_add;
  if (!s.metal) {
    const glm::vec3 eo = coat_albedo(f0, to, f_add), ei = coat_albedo(f0, ti, f_add);
    const glm::vec3 ea = coat_albedo_avg(f0, to, f_add);
    out.diffuse = s.albedo / kPi * (1.0f - eo) * (1.0f - ei) / (1.0f - ea);
  }
  return out;
}

LampShading shade_lamp(const SurfaceBsdf& s, glm::vec3 n, glm::vec3 wo, glm::vec3 wi,
                       float widen, const BrdfTables& tables) {
  LampShading out;
  if (!s.coated()) return out;
  const float mo = std::max(glm::dot(n, wo), kMinCos), mi = std::max(glm::dot(n, wi), kMinCos);
  const glm::vec3 f0 = s.spec_f0();
  const TableEntry to = tables.lookup(mo, s.roughness), ti = tables.lookup(mi, s.roughness);
  const glm::vec3 f_add = ms_factor(f0, to.e_avg);
  const float alpha = ggx_alpha(s.roughness);
  const float aw = std::min(std::sqrt(alpha * alpha + widen * widen), 1.0f);
  const glm::vec3 h = glm::normalize(wo + wi);
  const float v_dot_h = std::clamp(glm::dot(wo, h), 0.0f, 1.0f);
  const glm::vec3 fresnel = f0 + (1.0f - f0) * schlick_weight(v_dot_h);
  const float n_dot_h = std::max(glm::dot(n, h), 0.0f);
  const float d = std::min(ggx_d(n_dot_h, alpha), ggx_d(n_dot_h, aw));
  out.specular = kPi * d * smith_vis(mo, mi, aw) * fresnel +
                 (1.0f - to.e) * (1.0f - ti.e) / std::max(1.0f - to.e_avg, 1.0e-4f) * f_add;
  const glm::vec3 eo = coat_albedo(f0, to, f_add), ei = coat_albedo(f0, ti, f_add);
  out.diffuse_weight =
      s.metal ? glm::vec3(0.0f) : (1.0f - eo) * (1.0f - ei) / (1.0f - coat_albedo_avg(f0, to, f_add));
  out.view_albedo = eo;
  return out;
}

glm::vec3 coat_albedo_at(const SurfaceBsdf& s, float mu_o, const BrdfTables& tables) {
  if (!s.coated()) return glm::vec3(0.0f);
  const glm::vec3 f0 = s.spec_f0();
  const TableEntry t = tables.lookup(std::max(mu_o, kMinCos), s.roughness);
  return coat_albedo(f0, t, ms_factor(f0, t.e_avg));
}

float spec_probability(const SurfaceBsdf& s, float mu_o, const BrdfTables& tables) {
  if (!s.coated()) return 0.0f;
  if (s.metal) return 0.75f;  // the cosine lobe covers Kulla-Conty's broad f_ms
  // the coat's share of the reflected energy, kept in [0.1, 0.9] so neither lobe starves
  const float e = luminance(coat_albedo_at(s, mu_o, tables));
  const float d = (1.0f - e) * luminance(s.albedo);
  return std::clamp(e / std::max(e + d, 1.0e-6f), 0.1f, 0.9f);
}

float brdf_pdf(const SurfaceBsdf& s, glm::vec3 n, glm::vec3 wo, glm::vec3 wi,
               const BrdfTables& tables) {
  const float mu_i = glm::dot(n, wi);
  if (mu_i <= 0.0f) return 0.0f;
  const float mu_o = std::max(glm::dot(n, wo), kMinCos);
  const float ps = spec_probability(s, mu_o, tables);
  float pdf = (1.0f - ps) * mu_i / kPi;
  if (ps > 0.0f) {
    const glm::vec3 h = glm::normalize(wo + wi);
    pdf += ps * vndf_reflect_pdf(mu_o, std::max(glm::dot(n, h), 0.0f), ggx_alpha(s.roughness));
  }
  return pdf;
}

BsdfSample sample_brdf(const SurfaceBsdf& s, glm::vec3 n, glm::vec3 wo, float u_lobe, float u1,
                       float u2, const BrdfTables& tables) {
  BsdfSample out;
  const Basis basis(n);
  const float mu_o = std::max(glm::dot(n, wo), kMinCos);
  const float ps = spec_probability(s, mu_o, tables);
  glm::vec3 wi;
  if (u_lobe < ps) {
    glm::vec3 wo_local = basis.to_local(wo);
    wo_local.z = std::max(wo_local.z, kMinCos);
    const glm::vec3 h = basis.to_world(sample_vndf(glm::normalize(wo_local), ggx_alpha(s.roughness), u1, u2));
    wi = 2.0f * glm::dot(wo, h) * h - wo;
  } else {
    const float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
    wi = basis.to_world(glm::vec3(r * std::cos(phi), r * std::sin(phi),
                                  std::sqrt(std::max(0.0f, 1.0f - u1))));
  }
  if (glm::dot(n, wi) <= 0.0f) return out;
  out.wi = glm::normalize(wi);
  out.pdf = brdf_pdf(s, n, wo, out.wi, tables);
  return out;
}

float gloss_code(const scene::Specular& spec) {
  if (!spec.metal && !(spec.f0 > 0.0f)) return 0.0f;
  const int r = int(std::lround(std::clamp(spec.roughness, 0.0f, 1.0f) * 255.0f));
  if (spec.metal) return float(r + RP_GLOSS_METAL);
  const int f = std::clamp(int(std::lround(spec.f0 * RP_GLOSS_F0_SCALE)), 1, 255);
  return float(r + 256 * f);
}

scene::Specular decode_gloss(float code) {
  const int c = int(code);
  scene::Specular s;
  if (c == 0) return s;
  s.roughness = float(c & 255) / 255.0f;
  s.metal = c >= RP_GLOSS_METAL;
  s.f0 = s.metal ? 0.0f : float((c >> 8) & 255) / RP_GLOSS_F0_SCALE;
  return s;
}

float voxel_base_weight(float code, const BrdfTables& tables) {
  const scene::Specular spec = decode_gloss(code);
  if (code == 0.0f || spec.metal) return 1.0f;
  const glm::vec3 f0(spec.f0);
  const TableEntry t = tables.lookup(1.0f, spec.roughness);  // E_avg, S_avg: any mu
  return 1.0f - coat_albedo_avg(f0, t, ms_factor(f0, t.e_avg)).x;
}

}  // namespace rp::shading
