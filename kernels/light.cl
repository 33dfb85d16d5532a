/* Light pass (SPEC 6.5): GBuffer + shadow map + voxel radiance chain -> HDR radiance (float4 per
 * pixel, rgb linear, a = 1 covered / 0 background).
 *
 *   L_out = (albedo * w_d + spec) * I * cos(theta) / d^2 * falloff(l.y) * shadow   (direct)
 *         + albedo * w_i * D(p, n) + E_spec(mu_o) * R(p, r)                (indirect, cone traced)
 *         + emission
 *
 * The surface model (common/brdf.h; the GBuffer's emission.w carries the gloss code):
 * w_d the lamp's diffuse weight, spec = pi f_spec toward the view (lamp-widened GGX + Kulla-
 * Conty), E_spec(mu_o) the coat's albedo toward the view and w_i = 1 - E_spec(mu_o) (0 for a
 * metal). Matte pixels (code 0): w_d = w_i = 1, spec = E_spec = 0, the Lambertian pass as it
 * was. R(p, r) is the radiance arriving along the mirror direction r = reflect(-v, n) through
 * one cone as wide as the coat's lobe (common/spec_cone.h): per pixel in
 * light_shade (quadrilinear, half-diameter steps), from the indirect pass's low-resolution
 * samples in light_compose (upsampled like D, this frame's cones only). For sharp coats
 * (roughness < 0.34) both modes first try a screen-space reflection (common/ssr.h; in
 * light_shade per pixel at level 0, reading ssr_depth (the visibility buffer's z01),
 * ssr_prev_hdr (the previous frame's light output, a copy: hdr is written here) and
 * ssr_velocity (the GBuffer's); ssr_history 0: none of them is read). Pixels whose
 * eight-pixel chunk has no coated surface skip the surface model entirely.
 *
 * I = FrameConstants.light_intensity.rgb (radiant intensity), l = unit vector from the surface to
 * the lamp centre, d its distance. Background pixels: 0.
 * D(p, n) is the indirect irradiance over pi, so albedo * D is the Lambertian indirect radiance in
 * the same units as the voxels' radiance; by kernel:
 *   default (the reference quality mode): rp_cone_diffuse16 (common/cone_trace.h), the mean of
 *     the 16-cone set traced per pixel with quarter-diameter steps;
 *   light_compose (the fast mode): a joint-bilateral upsample of the indirect pass's
 *     accumulated low-resolution irradiance (kernels/indirect.cl): the 2x2 blocks around the
 *     pixel (block histories sit at the block centres, 4 i + 2 in pixels), bilinear weights
 *     times geometry weights (normal, plane distance) of the blocks' current samples; when those
 *     sum below 1e-4 (no sample on the pixel's surface nearby) the block with the largest
 *     geometry weight, and when every geometry weight is 0 the plain bilinear mean.
 * Kernels: light_shade (the reference mode: direct + 16 cones per pixel + emission) and
 * light_compose (the fast mode: direct + upsampled indirect + emission). light_compose works on
 * eight pixels of a row per work-item in float8 arithmetic (common/indirect_simd.h), so it runs
 * 8-wide on PoCL; light_shade is per-pixel code (its cost is the cones).
 *
 * Variants (-D):
 *   RP_LIGHT_PRT=1: the sky's diffuse light comes from precomputed radiance transfer
 *     (kernels/prt.cl): `prt_irradiance` (float4 per pixel, rgb E / pi) is added to D, whose
 *     cones then carry no diffuse sky (SkyGpu.diffuse_cones = 0); reflection cones keep it.
 *   RP_LIGHT_SPLIT=1: also writes the direct lamp term (rgb, a = covered), the indirect term
 *     (rgb, a = covered) and the specular part of both (rgb, a = covered) into
 *     direct_out, indirect_out and specular_out (float4 each), for the debug views and the
 *     accuracy report; emission is in none. The default build writes only hdr.
 * Every variant takes the same arguments (bound by one call on the host); a variant reads
 * none of the buffers it does not use.
 *
 * The direct term (lamp falloff from l.y, shadow-map projection, bias and taps) is
 * common/direct_light.h, shared with the voxelizer; the formulas are documented there.
 *
 * Shadow: `visibility`, one float per pixel, written just before by the light pass's first
 * kernel (kernels/shadow_visibility.cl: common/soft_shadow.h in the mode RenderSettings::shadows
 * picks; the formulas, the PCSS penumbra derivation for the lamp cap and the biases are
 * documented there). Both kernels compute the unshadowed direct term with the same code
 * (light_direct8; light_shade calls it with its pixel in every lane and keeps lane 0) and
 * multiply it by the visibility, so the quality modes differ only in their indirect light.
 */
#include "shared/types.h"
#include "shared/pass_params.h"
#include "common/math.h"
#include "common/random.h"
#include "common/direct_light.h"
#include "common/cone_trace.h"
#include "common/indirect.h"
#include "common/indirect_simd.h"
#include "common/brdf.h"
#include "common/spec_cone.h"
/* The reference mode's screen-space reflections (light_shade): the march of
 * common/ssr.h at level 0 only (the reference mode builds no min-Z pyramid), so every pixel the
 * ray crosses is tested, one pixel per step: enough steps to cross a 2048-pixel screen
 * diagonally; every ray is marched, also those turned towards the camera; the colour at a hit
 * is averaged over the coat's lobe there (rp_ssr_footprint). */
#define RP_SSR_MAX_ITER 4096
#define RP_SSR_MAX_TOWARDS_CAMERA 2.0f
#define RP_SSR_FOOTPRINT 1
#include "common/ssr.h"

#ifndef RP_LIGHT_SPLIT
#define RP_LIGHT_SPLIT 0
#endif
#ifndef RP_LIGHT_PRT
#define RP_LIGHT_PRT 0
#endif

inline float8 light_direct8(__global const FrameConstants* restrict frame, float8 px, float8 py,
                            float8 pz, float8 nx, float8 ny, float8 nz);

/* The demo's lamp shines (a file scene without it has intensity 0): otherwise its factor is 0
 * and the lamp visibility is neither computed (LightPass) nor read. */
inline bool rp_lamp_on(__global const FrameConstants* restrict frame) {
  return any(frame->light_intensity.xyz != 0.0f);
}

/* Surface-model weights of eight lanes (common/brdf.h) for the lamp at frame->light_pos seen
 * from camera_pos: w* lamp diffuse weight, s* lamp specular (pi f), e* coat albedo toward the
 * view, i* indirect diffuse weight. Chunks without a coated lane skip the model (w = i = 1,
 * s = e = 0); without the lamp only e and i are computed (w = 1, s = 0). */
inline void light_surface8(__global const FrameConstants* restrict frame,
                           __global const float4* restrict brdf_table, float8 code, float8 ar,
                           float8 ag, float8 ab, float8 px, float8 py, float8 pz, float8 nx,
                           float8 ny, float8 nz, float8* wr, float8* wg, float8* wb, float8* sr,
                           float8* sg, float8* sb, float8* er, float8* eg, float8* eb,
                           float8* ir, float8* ig, float8* ib) {
  const float8 zero = 0.0f, one = 1.0f;
  if (!any(code != 0.0f)) {
    *wr = *wg = *wb = *ir = *ig = *ib = one;
    *sr = *sg = *sb = *er = *eg = *eb = zero;
    return;
  }
  const float4 lp = frame->light_pos, cam = frame->camera_pos;
  if (!rp_lamp_on(frame)) {
    /* no lamp (a file scene): its weights are scaled by 0; only the view's part is needed */
    float8 vx = cam.x - px, vy = cam.y - py, vz = cam.z - pz;
    const float8 inv_v = rsqrt(vx * vx + vy * vy + vz * vz);
    rp_brdf_view8(brdf_table, code, ar, ag, ab, nx, ny, nz, vx * inv_v, vy * inv_v, vz * inv_v,
                  er, eg, eb);
    *wr = *wg = *wb = one;
    *sr = *sg = *sb = zero;
    const int8 metal = convert_int8(code) >= RP_GLOSS_METAL;
    *ir = select(1.0f - *er, zero, metal);
    *ig = select(1.0f - *eg, zero, metal);
    *ib = select(1.0f - *eb, zero, metal);
    return;
  }
  float8 lx = lp.x - px, ly = lp.y - py, lz = lp.z - pz;
  const float8 inv_l = rsqrt(lx * lx + ly * ly + lz * lz);
  lx *= inv_l;
  ly *= inv_l;
  lz *= inv_l;
  float8 vx = cam.x - px, vy = cam.y - py, vz = cam.z - pz;
  const float8 inv_v = rsqrt(vx * vx + vy * vy + vz * vz);
  vx *= inv_v;
  vy *= inv_v;
  vz *= inv_v;
  /* the lamp disk's radius over twice its distance (common/direct_light.h's disk model) */
  const float8 dy = RP_CEILING_Y - py, dx = lp.x - px, dz = lp.z - pz;
  const float8 widen = 0.5f * sqrt(rp_lamp_disk_a2(lp)) * rsqrt(dx * dx + dy * dy + dz * dz);
  rp_brdf_lamp8(brdf_table, code, ar, ag, ab, nx, ny, nz, vx, vy, vz, lx, ly, lz, widen, wr, wg,
                wb, sr, sg, sb, er, eg, eb);
  const int8 metal = convert_int8(code) >= RP_GLOSS_METAL;
  *ir = select(1.0f - *er, zero, metal);
  *ig = select(1.0f - *eg, zero, metal);
  *ib = select(1.0f - *eb, zero, metal);
}

/* Default: voxels, the radiance chain (shared/voxel_layout.h) of voxel_resolution^3 at level 0
 * with voxel_levels levels. */
__kernel void light_shade(__global const FrameConstants* restrict frame,
                          __global const float4* restrict albedo_plane,
                          __global const float4* restrict normal_depth_plane,
                          __global const float4* restrict position_plane,
                          __global const float4* restrict emission_plane,
                          __global const float* restrict visibility,
                          __global const float4* restrict brdf_table,
                          __global const float4* restrict voxels,
                          __global const float4* restrict sky,
                          __global const float* restrict ssr_depth,
                          __global const float4* restrict ssr_prev_hdr,
                          __global const float2* restrict ssr_velocity,
                          __global const float4* restrict prt_irradiance,
                          __global float4* restrict direct_out,
                          __global float4* restrict indirect_out,
                          __global float4* restrict specular_out,
                          __global float4* restrict hdr,
                          const LightShadeParams params) {
  const uint voxel_resolution = params.voxel_resolution, voxel_levels = params.voxel_levels;
  const uint ssr_history = params.ssr_history;
  const uint x = (uint)get_global_id(0), y = (uint)get_global_id(1);
  const uint width = frame->width;
  if (x >= width || y >= frame->height) return;
  const uint pixel = y * width + x;

  const float4 pos = position_plane[pixel];
  if (pos.w == 0.0f) {
    hdr[pixel] = (float4)(0.0f);
#if RP_LIGHT_SPLIT
    direct_out[pixel] = (float4)(0.0f);
    indirect_out[pixel] = (float4)(0.0f);
    specular_out[pixel] = (float4)(0.0f);
#endif
    return;
  }
  const float3 albedo = albedo_plane[pixel].xyz;
  const float3 n = normal_depth_plane[pixel].xyz;
  const float3 p = pos.xyz;
  const float4 emission = emission_plane[pixel];
  /* the unshadowed lamp factor with the pixel in every lane (light_compose's formulas), lane 0
   * kept, times the pixel's visibility */
  const float k = rp_lamp_on(frame)
                      ? light_direct8(frame, (float8)(p.x), (float8)(p.y), (float8)(p.z),
                                      (float8)(n.x), (float8)(n.y), (float8)(n.z)).s0 *
                            visibility[pixel]
                      : 0.0f;
  /* the surface model with the pixel in every lane; lane 0 kept */
  float8 w[3], sp[3], e[3], iw[3];
  light_surface8(frame, brdf_table, (float8)(emission.w), (float8)(albedo.x), (float8)(albedo.y),
                 (float8)(albedo.z), (float8)(p.x), (float8)(p.y), (float8)(p.z), (float8)(n.x),
                 (float8)(n.y), (float8)(n.z), &w[0], &w[1], &w[2], &sp[0], &sp[1], &sp[2],
                 &e[0], &e[1], &e[2], &iw[0], &iw[1], &iw[2]);
  const float3 lamp = frame->light_intensity.xyz * k;
  const float3 spec_direct = (float3)(sp[0].s0, sp[1].s0, sp[2].s0) * lamp;
  const float3 direct = albedo * (float3)(w[0].s0, w[1].s0, w[2].s0) * lamp + spec_direct;
  float3 irr = rp_cone_diffuse16(frame, sky, voxels, voxel_resolution, voxel_levels, p, n);
#if RP_LIGHT_PRT
  irr += prt_irradiance[pixel].xyz;
#endif
  /* the coat's share, weighted by E_spec(mu_o): the screen-space reflection (common/ssr.h,
   * level 0, the previous frame's output at the hit) with confidence c, and the reflection cone
   * (common/spec_cone.h) for the rest, cone + c (ssr - cone), as in the fast mode's
   * indirect_trace; the cone is not traced where c = 1 */
  float3 spec_indirect = (float3)(0.0f);
  if (emission.w != 0.0f) {
    const float3 v = normalize(frame->camera_pos.xyz - p);
    const float3 r = 2.0f * fmax(dot(n, v), 0.0f) * n - v;
    const float4 ssr = rp_ssr(frame, ssr_depth, ssr_depth, normal_depth_plane, ssr_prev_hdr,
                              ssr_velocity, 0u, ssr_history, p, r,
                              rp_brdf_code_roughness(emission.w));
    float3 refl = ssr.xyz;
    if (ssr.w < 1.0f) {
      const float3 cone =
          rp_spec_cone(frame, sky, voxels, voxel_resolution, voxel_levels, emission.w, p, n, 1);
      refl = cone + ssr.w * (ssr.xyz - cone);
    }
    spec_indirect = (float3)(e[0].s0, e[1].s0, e[2].s0) * refl;
  }
  const float3 indirect = albedo * (float3)(iw[0].s0, iw[1].s0, iw[2].s0) * irr + spec_indirect;
  hdr[pixel] = (float4)(direct + indirect + emission.xyz, 1.0f);
#if RP_LIGHT_SPLIT
  direct_out[pixel] = (float4)(direct, 1.0f);
  indirect_out[pixel] = (float4)(indirect, 1.0f);
  specular_out[pixel] = (float4)(spec_direct + spec_indirect, 1.0f);
#endif
}

/* Unshadowed direct lamp factor on eight points: cos(theta) / (d_disk^2 + a^2) * falloff(l.y)
 * (common/direct_light.h's disk model, rp_lamp_falloff's formulas lane by lane); 0 where the
 * surface faces away. The shadow pass's visibility multiplies it. */
inline float8 light_direct8(__global const FrameConstants* restrict frame, float8 px, float8 py,
                            float8 pz, float8 nx, float8 ny, float8 nz) {
  const float4 lp = frame->light_pos;
  const float8 lx = lp.x - px, ly = lp.y - py, lz = lp.z - pz;
  const float8 dy = RP_CEILING_Y - py;
  const float8 d2 = lx * lx + dy * dy + lz * lz;
  const float8 inv_d = rsqrt(lx * lx + ly * ly + lz * lz);
  const float8 c = (nx * lx + ny * ly + nz * lz) * inv_d;
  const float8 s = fmin(fmax(ly * inv_d, (float8)(0.0f)), (float8)(1.0f));
  const float8 falloff = mad(s, mad(s, 0.204f, 0.446f), 0.35f); /* rp_lamp_falloff */
  return select((float8)(0.0f), c * falloff / (d2 + rp_lamp_disk_a2(lp)), c > 0.0f);
}

/* lr_irradiance (history: r, g, b, age planes), lr_geom (normal x, y, z, plane offset) and
 * lr_specular (reflection cone r, g, b): the indirect pass's padded planes (common/indirect.h),
 * laid out as `planes` says (shared/pass_params.h LowResPlanes). The GBuffer, hdr and the
 * split outputs are float4 per pixel, passed as floats. Eight pixels of a row per work-item
 * (common/indirect_simd.h): global size (ceil(width / 8), height) rounded up to the
 * work-group. */
__kernel void light_compose(__global const FrameConstants* restrict frame,
                            __global const float* restrict albedo,
                            __global const float* restrict normal_depth,
                            __global const float* restrict position,
                            __global const float* restrict emission,
                            __global const float* restrict visibility,
                            __global const float4* restrict brdf_table,
                            __global const float* restrict lr_irradiance,
                            __global const float* restrict lr_geom,
                            __global const float* restrict lr_specular,
                            __global const float* restrict prt_irradiance,
                            __global float* restrict direct_out,
                            __global float* restrict indirect_out,
                            __global float* restrict specular_out,
                            __global float* restrict hdr,
                            const LowResPlanes planes) {
  const uint lr_stride = planes.stride, lr_plane = planes.plane;
  const float pixel_scale = planes.pixel_scale;
  const uint x0 = 8u * (uint)get_global_id(0), y = (uint)get_global_id(1);
  const uint width = frame->width;
  if (x0 >= width || y >= frame->height) return;
  const uint lanes = min(8u, width - x0);
  const uint row = 4u * y * width;
  float8 px, py, pz, cov, nx, ny, nz, depth;
  rp_load8_float4(position, row, x0, lanes, &px, &py, &pz, &cov);
  rp_load8_float4(normal_depth, row, x0, lanes, &nx, &ny, &nz, &depth);
  const int8 covered = cov != 0.0f;
  float8 k = 0.0f;
  if (rp_lamp_on(frame)) {
    float8 vis;
    if (lanes == 8u) {
      vis = vload8(0, visibility + y * width + x0);
    } else {
      float v[8];
      for (uint q = 0; q < 8u; ++q) v[q] = visibility[y * width + x0 + min(q, lanes - 1u)];
      vis = vload8(0, v);
    }
    k = light_direct8(frame, px, py, pz, nx, ny, nz) * vis;
  }

  /* Joint-bilateral upsample from the block centres (4 i + 2 in pixels: where the accumulated
   * history lives, kernels/indirect.cl): pixel x + 0.5 lies at u = (x - 1.5) / 4. The 8 pixels'
   * 2x2 footprints lie in 4 block columns c0 .. c0 + 3 (x0 is a multiple of 8), read once per
   * row and plane and picked per lane. */
  const int st = (int)lr_stride, pl = (int)lr_plane;
  const int c0 = ((int)x0 - 2) >> 2; /* floor((x0 - 1.5) / 4), arithmetic shift */
  const float8 ux = (convert_float8((int)x0 + (int8)(0, 1, 2, 3, 4, 5, 6, 7)) - 1.5f) *
                    (1.0f / RP_INDIRECT_SCALE);
  const float8 ux0 = floor(ux);
  const float8 fx = ux - ux0;
  const int8 a = convert_int8(ux0) - c0; /* 0, 1 or 2: the lane's left column in c0 .. c0 + 3 */
  const float uyf = ((float)y - 1.5f) * (1.0f / RP_INDIRECT_SCALE);
  const int j0 = (int)floor(uyf);
  const float fy = uyf - (float)j0;
  const int r0 = rp_indirect_index(c0, j0, st), r1 = r0 + st;
  const int8 a0 = a == 0, a1 = a == 1;
/* Left and right tap of each lane from the 4 columns of a plane row at r. */
#define RP_LIGHT_TAPS(P, R, L, RT)                                               \
  {                                                                             \
    const float4 v = vload4(0, (P) + (R));                                      \
    L = select(select((float8)(v.z), (float8)(v.y), a1), (float8)(v.x), a0);    \
    RT = select(select((float8)(v.w), (float8)(v.z), a1), (float8)(v.y), a0);   \
  }
  float8 g[4][4]; /* [plane][tap]: taps 00, 10, 01, 11 */
  for (int q = 0; q < 4; ++q) {
    RP_LIGHT_TAPS(lr_geom + q * pl, r0, g[q][0], g[q][1]);
    RP_LIGHT_TAPS(lr_geom + q * pl, r1, g[q][2], g[q][3]);
  }
  const float8 inv_sigma = rp_indirect_inv_sigma8(depth, pixel_scale);
  float8 gw[4];
  for (int t = 0; t < 4; ++t)
    gw[t] = rp_indirect_geometry_weight8(nx, ny, nz, px, py, pz, g[0][t], g[1][t], g[2][t],
                                         g[3][t], inv_sigma);
  const float8 b00 = (1.0f - fx) * (1.0f - fy), b10 = fx * (1.0f - fy);
  const float8 b01 = (1.0f - fx) * fy, b11 = fx * fy;
  float8 w00 = b00 * gw[0], w10 = b10 * gw[1], w01 = b01 * gw[2], w11 = b11 * gw[3];
  const float8 wsum = w00 + w10 + w01 + w11;
  /* Fallbacks: the best geometric match (first of equals), else plain bilinear. */
  const float8 best = fmax(fmax(gw[0], gw[1]), fmax(gw[2], gw[3]));
  const int8 blend = wsum >= 1.0e-4f;
  /* masks are combined from comparisons, never negated with ~ (oclgrind 21.10 mis-evaluates
   * negated vector masks) */
  const int8 pick = (wsum < 1.0e-4f) & (best > 0.0f);
  const int8 is0 = gw[0] == best, is1 = (gw[1] == best) & (gw[0] != best);
  const int8 is2 = (gw[2] == best) & (gw[0] != best) & (gw[1] != best);
  const int8 is3 = (gw[3] == best) & (gw[0] != best) & (gw[1] != best) & (gw[2] != best);
  const float8 one = 1.0f, zero = 0.0f;
  const float8 inv_w = 1.0f / fmax(wsum, 1.0e-4f);
  w00 = select(select(b00, select(zero, one, is0), pick), w00 * inv_w, blend);
  w10 = select(select(b10, select(zero, one, is1), pick), w10 * inv_w, blend);
  w01 = select(select(b01, select(zero, one, is2), pick), w01 * inv_w, blend);
  w11 = select(select(b11, select(zero, one, is3), pick), w11 * inv_w, blend);
  float8 irr[3];
  for (int q = 0; q < 3; ++q) {
    float8 t00, t10, t01, t11;
    RP_LIGHT_TAPS(lr_irradiance + q * pl, r0, t00, t10);
    RP_LIGHT_TAPS(lr_irradiance + q * pl, r1, t01, t11);
    irr[q] = w00 * t00 + w10 * t10 + w01 * t01 + w11 * t11;
  }
#if RP_LIGHT_PRT
  {
    float8 pr, pg, pb, pw;
    rp_load8_float4(prt_irradiance, row, x0, lanes, &pr, &pg, &pb, &pw);
    irr[0] += pr;
    irr[1] += pg;
    irr[2] += pb;
  }
#endif

  float8 ar, ag, ab, aw, er, eg, eb, ew;
  rp_load8_float4(albedo, row, x0, lanes, &ar, &ag, &ab, &aw);
  rp_load8_float4(emission, row, x0, lanes, &er, &eg, &eb, &ew);
  /* the reflection cones' radiance (this frame's, not accumulated: kernels/indirect.cl),
   * upsampled with the irradiance's weights; chunks without a coated pixel skip it */
  float8 spc[3] = {(float8)(0.0f), (float8)(0.0f), (float8)(0.0f)};
  if (any(ew != 0.0f)) {
    for (int q = 0; q < 3; ++q) {
      float8 t00, t10, t01, t11;
      RP_LIGHT_TAPS(lr_specular + q * pl, r0, t00, t10);
      RP_LIGHT_TAPS(lr_specular + q * pl, r1, t01, t11);
      spc[q] = w00 * t00 + w10 * t10 + w01 * t01 + w11 * t11;
    }
  }
#undef RP_LIGHT_TAPS
  float8 wr, wg, wb, sr, sg, sb, vr, vg, vb, ir, ig, ib; /* the surface model (see top) */
  light_surface8(frame, brdf_table, ew, ar, ag, ab, px, py, pz, nx, ny, nz, &wr, &wg, &wb, &sr,
                 &sg, &sb, &vr, &vg, &vb, &ir, &ig, &ib);
  const float4 li = frame->light_intensity;
  const float8 lr = li.x * k, lg = li.y * k, lb = li.z * k;
  const float8 spr = sr * lr + vr * spc[0], spg = sg * lg + vg * spc[1],
               spb = sb * lb + vb * spc[2]; /* specular: direct + indirect */
  const float8 dr = ar * wr * lr + sr * lr, dg = ag * wg * lg + sg * lg,
               db = ab * wb * lb + sb * lb;
  const float8 jr = ar * ir * irr[0] + vr * spc[0], jg = ag * ig * irr[1] + vg * spc[1],
               jb = ab * ib * irr[2] + vb * spc[2];
  const float8 cv = select(zero, one, covered);
  rp_store8_float4(hdr, row, x0, lanes, select(zero, dr + jr + er, covered),
                   select(zero, dg + jg + eg, covered), select(zero, db + jb + eb, covered), cv);
#if RP_LIGHT_SPLIT
  rp_store8_float4(direct_out, row, x0, lanes, select(zero, dr, covered), select(zero, dg, covered),
                   select(zero, db, covered), cv);
  rp_store8_float4(indirect_out, row, x0, lanes, select(zero, jr, covered),
                   select(zero, jg, covered), select(zero, jb, covered), cv);
  rp_store8_float4(specular_out, row, x0, lanes, select(zero, spr, covered),
                   select(zero, spg, covered), select(zero, spb, covered), cv);
#endif
}
