/* The surface model on the device: GGX specular coat with Kulla-Conty multiple
 * scattering over an energy-conserving Lambertian base. The formulas, their sources and the
 * units are in src/shading/brdf.h (the C++ reference the tests hold this against); the table
 * layout and the per-pixel gloss code in shared/brdf_layout.h. OpenCL C only; eight pixels at
 * once (float8 lanes, as light_compose works), light_shade passes its pixel in every lane.
 *
 * rp_brdf_lamp8 evaluates, for a lamp direction l and view direction v, per lane:
 *   diffuse weight  w_d = (1 - E_spec(mu_o)) (1 - E_spec(mu_i)) / (1 - E_spec_avg)  (metal: 0)
 *   specular        pi (D Vis F + f_ms)  (rolypoly's units: the lamp's radiance is this times
 *                   I * cos / (d^2 + a^2) * falloff * shadow, as albedo is for the diffuse)
 *   view albedo     E_spec(mu_o): the coat's share of light uniform over the hemisphere (the
 *                   indirect light's split until the reflection cone)
 * Lanes with gloss code 0 (no coat) get w_d = 1 and nothing else, so matte surfaces shade as
 * before the coats existed.
 *
 * The lamp's size widens the single-scattering lobe (the lamp is a disk of radius a at distance
 * d, so the light direction spans an angle ~a / d and the half vector half that, w = a / 2d):
 * alpha' = min(sqrt(alpha^2 + w^2), 1) (widths add in quadrature, as for a convolution), and
 * D = min(D_alpha, D_alpha'): the widened lobe's normalised peak where the lamp's image is,
 * the surface's own tails elsewhere (a widened GGX lobe's tails grow as alpha'^2). Measured
 * against the cap integrated as an area light (the path tracer's --lamp area, 160 000 stratified
 * directions, floor points seen from the default camera, F0 0.04): 0.93 .. 1.22 x truth at the
 * highlight's peak and in its tails for roughness 0.08, 0.25, 0.38; alpha + w (Karis 2013's
 * sum) gave 0.55 x at the peaks and 1.8 .. 170 x in the tails, no widening 0.93 .. 1.0 in the
 * tails but 1.3 .. 64 x at the peaks. Vis takes alpha'. The Kulla-Conty terms keep the
 * surface's own alpha (energy bookkeeping, not shape).
 * Cost per lane: two bilinear table lookups (8 float4 gathers), two D, one Vis, one Schlick.
 */
#ifndef ROLYPOLY_COMMON_BRDF_H
#define ROLYPOLY_COMMON_BRDF_H

#include "shared/brdf_layout.h"

#define RP_BRDF_PI 3.14159265358979f
#define RP_BRDF_MIN_ALPHA 1.0e-3f /* shading::kMinAlpha */
#define RP_BRDF_MIN_COS 1.0e-4f   /* shading::kMinCos */

/* Table entry (E, S, E_avg, S_avg) at (mu, roughness) per lane: bilinear like
 * shading::BrdfTables::lookup (mu between cell centres, roughness between nodes). */
inline void rp_brdf_table8(__global const float4* restrict table, float8 mu, float8 rough,
                           float8* e, float8* s, float8* e_avg, float8* s_avg) {
  const float n = (float)RP_BRDF_TABLE_SIZE;
  const float8 u = clamp(mu * n - 0.5f, 0.0f, n - 1.0f);
  const float8 w = clamp(rough * (n - 1.0f), 0.0f, n - 1.0f);
  const int8 i0 = min(convert_int8(u), (int8)(RP_BRDF_TABLE_SIZE - 2));
  const int8 j0 = min(convert_int8(w), (int8)(RP_BRDF_TABLE_SIZE - 2));
  const float8 ti = u - convert_float8(i0), tj = w - convert_float8(j0);
  float a_ti[8], a_tj[8], oe[8], os[8], oea[8], osa[8];
  int a_i[8], a_j[8];
  vstore8(ti, 0, a_ti);
  vstore8(tj, 0, a_tj);
  vstore8(i0, 0, a_i);
  vstore8(j0, 0, a_j);
  for (int k = 0; k < 8; ++k) {
    __global const float4* row = table + a_j[k] * RP_BRDF_TABLE_SIZE + a_i[k];
    const float4 v0 = mix(row[0], row[1], a_ti[k]);
    const float4 v1 = mix(row[RP_BRDF_TABLE_SIZE], row[RP_BRDF_TABLE_SIZE + 1], a_ti[k]);
    const float4 v = mix(v0, v1, a_tj[k]);
    oe[k] = v.x;
    os[k] = v.y;
    oea[k] = v.z;
    osa[k] = v.w;
  }
  *e = vload8(0, oe);
  *s = vload8(0, os);
  *e_avg = vload8(0, oea);
  *s_avg = vload8(0, osa);
}

/* One colour channel of the coat: Kulla-Conty's f_add and the coat albedo E_spec at the view,
 * the light and on average (src/shading/brdf.h). */
inline void rp_brdf_coat8(float8 f0, float8 eo, float8 so, float8 ei, float8 si, float8 e_avg,
                          float8 s_avg, float8* f_add, float8* spec_o, float8* spec_i,
                          float8* spec_avg) {
  const float8 fa = f0 + (1.0f - f0) * (1.0f / 21.0f);
  *f_add = fa * fa * e_avg / (1.0f - fa * (1.0f - e_avg));
  *spec_o = f0 * (eo - so) + so + (1.0f - eo) * *f_add;
  *spec_i = f0 * (ei - si) + si + (1.0f - ei) * *f_add;
  *spec_avg = f0 * (e_avg - s_avg) + s_avg + (1.0f - e_avg) * *f_add;
}

/* Specular cone aperture: tan of the half-angle of the cone that stands for
 * the coat's reflection lobe at roughness `rough` (GGX alpha = rough^2). GGX D falls to half
 * its peak at tan(theta_h) = alpha sqrt(sqrt 2 - 1) = 0.6436 alpha (D ~ 1 / (alpha^2 +
 * tan^2 theta_h)^2 near the peak); the reflected direction turns by twice the half vector's
 * angle, so the lobe's half width at half maximum is theta_c = 2 atan(0.6436 alpha):
 * tan theta_c = 1.2872 alpha / (1 - 0.41421 alpha^2). Clamped to [RP_SPEC_CONE_MIN_TAN,
 * RP_SPEC_CONE_MAX_TAN]: below 0.1 (5.7 degrees) a cone stays within one 64^3 voxel for its
 * first five voxels and the volume cannot show anything sharper (the sharp coats are screen-
 * space reflections' job), above 1 (45 degrees) the lobe is as wide as the diffuse light.
 * Demo: floor (0.38) 0.187, tumblers (0.25) 0.080 -> 0.1, marbles (0.08) 0.008 -> 0.1.
 * src/shading/brdf.h's spec_cone_tan is the C++ twin. */
#define RP_SPEC_CONE_MIN_TAN 0.1f
#define RP_SPEC_CONE_MAX_TAN 1.0f
inline float rp_brdf_spec_cone_tan(float rough) {
  const float a = fmax(rough * rough, RP_BRDF_MIN_ALPHA);
  return clamp(1.2872f * a / (1.0f - 0.41421f * a * a), RP_SPEC_CONE_MIN_TAN,
               RP_SPEC_CONE_MAX_TAN);
}

/* Roughness of gloss code `code` (shared/brdf_layout.h). */
inline float rp_brdf_code_roughness(float code) {
  return (float)((int)code & 255) * (1.0f / 255.0f);
}

/* Lamp shading of eight lanes (see the header). code: the GBuffer's gloss code; albedo a*:
 * the base colour (a metal's F0); n, v, l unit normal, view and light directions (l towards
 * the lamp centre, as the direct factor's cosine); widen = a / (2 d) of the lamp. Outputs:
 * w_d (diffuse weight), spec* (pi f_spec per channel), view* (E_spec(mu_o) per channel). */
inline void rp_brdf_lamp8(__global const float4* restrict table, float8 code, float8 ar,
                          float8 ag, float8 ab, float8 nx, float8 ny, float8 nz, float8 vx,
                          float8 vy, float8 vz, float8 lx, float8 ly, float8 lz, float8 widen,
                          float8* wr, float8* wg, float8* wb, float8* sr, float8* sg,
                          float8* sb, float8* er, float8* eg, float8* eb) {
  const int8 c = convert_int8(code);
  const int8 coated = c != 0, metal = c >= RP_GLOSS_METAL;
  const float8 rough = convert_float8(c & 255) * (1.0f / 255.0f);
  const float8 f0d = convert_float8((c >> 8) & 255) * (1.0f / RP_GLOSS_F0_SCALE);
  const float8 f0r = select(f0d, ar, metal), f0g = select(f0d, ag, metal),
               f0b = select(f0d, ab, metal);
  const float8 mo = fmax(nx * vx + ny * vy + nz * vz, RP_BRDF_MIN_COS);
  const float8 mi = fmax(nx * lx + ny * ly + nz * lz, RP_BRDF_MIN_COS);
  float8 eo, so, ei, si, e_avg, s_avg;
  rp_brdf_table8(table, mo, rough, &eo, &so, &e_avg, &s_avg);
  rp_brdf_table8(table, mi, rough, &ei, &si, &e_avg, &s_avg);

  /* single scattering with the lamp-widened lobe (see the header) */
  const float8 alpha = fmax(rough * rough, RP_BRDF_MIN_ALPHA);
  const float8 s2 = alpha * alpha;
  const float8 a2 = fmin(s2 + widen * widen, 1.0f); /* alpha'^2 */
  float8 hx = vx + lx, hy = vy + ly, hz = vz + lz;
  const float8 inv_h = rsqrt(fmax(hx * hx + hy * hy + hz * hz, 1.0e-12f));
  const float8 nh = fmax((nx * hx + ny * hy + nz * hz) * inv_h, 0.0f);
  const float8 vh = clamp((vx * hx + vy * hy + vz * hz) * inv_h, 0.0f, 1.0f);
  const float8 t = nh * nh * (a2 - 1.0f) + 1.0f, t0 = nh * nh * (s2 - 1.0f) + 1.0f;
  const float8 d = fmin(a2 / (RP_BRDF_PI * t * t), s2 / (RP_BRDF_PI * t0 * t0));
  const float8 vis = 0.5f / (mi * sqrt(mo * mo * (1.0f - a2) + a2) +
                             mo * sqrt(mi * mi * (1.0f - a2) + a2));
  const float8 m = 1.0f - vh, m2 = m * m, w5 = m2 * m2 * m;
  /* pi D Vis and pi (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg)) */
  const float8 lobe = RP_BRDF_PI * d * vis;
  const float8 ms = (1.0f - eo) * (1.0f - ei) / fmax(1.0f - e_avg, 1.0e-4f);

  float8 fadd, so_r, si_r, sa_r, so_g, si_g, sa_g, so_b, si_b, sa_b;
  const float8 zero = 0.0f, one = 1.0f;
#define RP_BRDF_CHANNEL(F0, SO, SI, SA, W, S, E)                                   \
  rp_brdf_coat8(F0, eo, so, ei, si, e_avg, s_avg, &fadd, &SO, &SI, &SA);            \
  *W = select(one, select((1.0f - SO) * (1.0f - SI) / (1.0f - SA), zero, metal), coated); \
  *S = select(zero, lobe * (F0 + (1.0f - F0) * w5) + ms * fadd, coated);             \
  *E = select(zero, SO, coated);
  RP_BRDF_CHANNEL(f0r, so_r, si_r, sa_r, wr, sr, er)
  RP_BRDF_CHANNEL(f0g, so_g, si_g, sa_g, wg, sg, eg)
  RP_BRDF_CHANNEL(f0b, so_b, si_b, sa_b, wb, sb, eb)
#undef RP_BRDF_CHANNEL
}

/* rp_brdf_lamp8's coat albedo toward the view alone (e*), for frames without the lamp: the
 * view's table entry and the same arithmetic (the table's E_avg does not vary with mu, so the
 * light's lookup, which rp_brdf_lamp8 takes it from, gives the same value). */
inline void rp_brdf_view8(__global const float4* restrict table, float8 code, float8 ar,
                          float8 ag, float8 ab, float8 nx, float8 ny, float8 nz, float8 vx,
                          float8 vy, float8 vz, float8* er, float8* eg, float8* eb) {
  const int8 c = convert_int8(code);
  const int8 coated = c != 0, metal = c >= RP_GLOSS_METAL;
  const float8 rough = convert_float8(c & 255) * (1.0f / 255.0f);
  const float8 f0d = convert_float8((c >> 8) & 255) * (1.0f / RP_GLOSS_F0_SCALE);
  const float8 f0r = select(f0d, ar, metal), f0g = select(f0d, ag, metal),
               f0b = select(f0d, ab, metal);
  const float8 mo = fmax(nx * vx + ny * vy + nz * vz, RP_BRDF_MIN_COS);
  float8 eo, so, e_avg, s_avg;
  rp_brdf_table8(table, mo, rough, &eo, &so, &e_avg, &s_avg);
  float8 fadd, so_r, si_r, sa_r, so_g, si_g, sa_g, so_b, si_b, sa_b;
  const float8 zero = 0.0f;
  rp_brdf_coat8(f0r, eo, so, eo, so, e_avg, s_avg, &fadd, &so_r, &si_r, &sa_r);
  *er = select(zero, so_r, coated);
  rp_brdf_coat8(f0g, eo, so, eo, so, e_avg, s_avg, &fadd, &so_g, &si_g, &sa_g);
  *eg = select(zero, so_g, coated);
  rp_brdf_coat8(f0b, eo, so, eo, so, e_avg, s_avg, &fadd, &so_b, &si_b, &sa_b);
  *eb = select(zero, so_b, coated);
}

#endif
