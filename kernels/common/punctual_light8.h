/* A loaded scene's punctual lights for eight surface points at once (OpenCL C only): the
 * lane-parallel form of common/punctual_light.h's rp_punctual_direct for the light pass
 * (light_pass = 1), used by the punctual light pass (kernels/punctual_light.cl). The same
 * formulas, written out on float8 in the scalar functions' order: direction and attenuation,
 * the receiver's texel size, push and bias, the view's projection and the stored-depth
 * comparison are vector arithmetic; only the 4 texel reads per lane are gathered lane by
 * lane. A point light's lanes seen through different cube faces (near the cube's edges) take
 * the scalar function lane by lane.
 */
#ifndef ROLYPOLY_COMMON_PUNCTUAL_LIGHT8_H
#define ROLYPOLY_COMMON_PUNCTUAL_LIGHT8_H

#include "common/punctual_light.h"

/* Row `row` (x, y, z or w) of M * (p, 1) for eight points: (c0 x + c1 y + c2 z) + c3, as
 * rp_mat4_mul_point. */
#define RP_PUNCTUAL8_ROW(m, row, x, y, z) \
  ((m).c[0].row * (x) + (m).c[1].row * (y) + (m).c[2].row * (z) + (m).c[3].row)

/* The visibility (rp_punctual_visibility, light_pass = 1) of the lanes in `on`, all
 * seen through view V, with receiver texel size `texel` and slope tan_theta; lanes outside the
 * view are lit (1), lanes not in `on` get 1 too. */
inline float8 rp_punctual_view_visibility8(__global const float* shadow,
                                           __global const ShadowViewGpu* V, float8 px,
                                           float8 py, float8 pz, float8 nx, float8 ny,
                                           float8 nz, float8 texel, float8 tan_theta, int8 on) {
  const float8 qx = px + nx * texel, qy = py + ny * texel, qz = pz + nz * texel;
  const rp_mat4 vp = V->view_proj;
  const float8 cx = RP_PUNCTUAL8_ROW(vp, x, qx, qy, qz), cy = RP_PUNCTUAL8_ROW(vp, y, qx, qy, qz);
  const float8 cz = RP_PUNCTUAL8_ROW(vp, z, qx, qy, qz), cw = RP_PUNCTUAL8_ROW(vp, w, qx, qy, qz);
  const float8 ndc_x = cx / cw, ndc_y = cy / cw, ndc_z = cz / cw;
  const int8 inside = on & (cw > 0.0f) & (fabs(ndc_x) <= 1.0f) & (fabs(ndc_y) <= 1.0f) &
                      (ndc_z <= 1.0f);
  if (!any(inside)) return (float8)(1.0f);
  const float near = V->depth.x, far = V->depth.y;
  float8 lin;
  if (V->depth.z != 0.0f) { /* rp_punctual_linear of the orthographic view */
    const float8 d = ndc_z * 0.5f + 0.5f;
    lin = select(near + d * (far - near), (float8)(3.0e38f), d >= 1.0f);
  } else {
    lin = cw;
  }
  /* rp_punctual_stored of lin - texel rp_punctual_bias_texels(tan_theta, 1) */
  const float8 biased =
      lin - texel * (RP_PUNCTUAL_BIAS_LIGHT_PASS + RP_PUNCTUAL_BIAS_SLOPE_LIGHT_PASS * tan_theta);
  float8 receiver;
  if (V->depth.z != 0.0f) {
    receiver = (biased - near) / (far - near);
  } else {
    const float8 z_ndc = ((far + near) - 2.0f * near * far / biased) / (far - near);
    receiver = select((float8)(-INFINITY), z_ndc * 0.5f + 0.5f, biased > near);
  }
  const float size = (float)V->size;
  const float8 x = (ndc_x * 0.5f + 0.5f) * size - 0.5f, y = (0.5f - ndc_y * 0.5f) * size - 0.5f;
  const float8 fx0 = floor(x), fy0 = floor(y);
  const float8 fx = x - fx0, fy = y - fy0;
  float xa[8], ya[8], fxa[8], fya[8], ra[8], vis[8];
  int ina[8];
  vstore8(fx0, 0, xa);
  vstore8(fy0, 0, ya);
  vstore8(fx, 0, fxa);
  vstore8(fy, 0, fya);
  vstore8(receiver, 0, ra);
  vstore8(select((int8)(0), (int8)(1), inside), 0, ina);
  for (int q = 0; q < 8; ++q) {
    vis[q] = 1.0f;
    if (!ina[q]) continue;
    /* one bilinear comparison, as rp_punctual_visibility */
    const int x0 = (int)xa[q], y0 = (int)ya[q];
    const float t00 = rp_punctual_tap(shadow, V, x0, y0, ra[q]);
    const float t10 = rp_punctual_tap(shadow, V, x0 + 1, y0, ra[q]);
    const float t01 = rp_punctual_tap(shadow, V, x0, y0 + 1, ra[q]);
    const float t11 = rp_punctual_tap(shadow, V, x0 + 1, y0 + 1, ra[q]);
    vis[q] = mix(mix(t00, t10, fxa[q]), mix(t01, t11, fxa[q]), fya[q]);
  }
  return vload8(0, vis);
}

/* Light i's direct irradiance factor (rp_punctual_direct, light_pass = 1) at the eight points
 * p with unit normals n, for the lanes in `on`: intensity * cos * attenuation * visibility into
 * (kr, kg, kb), the direction towards the light into (lx, ly, lz) ((0, 1, 0) where a point
 * light sits on the point). 0 elsewhere and where the surface faces away. Returns false when
 * no lane receives light (facing away, out of reach or in its shadow). */
inline bool rp_punctual_direct8(__global const FrameConstants* frame,
                                __global const float* shadow, uint i, float8 px, float8 py,
                                float8 pz, float8 nx, float8 ny, float8 nz, int8 on,
                                float8* kr, float8* kg, float8* kb, float8* lx, float8* ly,
                                float8* lz) {
  __global const PunctualLightGpu* L = &frame->punctual[i];
  const float8 zero = 0.0f;
  float8 atten;
  if (L->type == RP_LIGHT_DIRECTIONAL) {
    atten = 1.0f;
    *lx = -L->direction.x;
    *ly = -L->direction.y;
    *lz = -L->direction.z;
  } else {
    const float8 tx = L->position_range.x - px, ty = L->position_range.y - py,
                 tz = L->position_range.z - pz;
    const float8 d2 = tx * tx + ty * ty + tz * tz;
    const int8 away = d2 > 0.0f;
    const float8 inv_d = rsqrt(d2);
    *lx = select((float8)(0.0f), tx * inv_d, away);
    *ly = select((float8)(1.0f), ty * inv_d, away);
    *lz = select((float8)(0.0f), tz * inv_d, away);
    float8 a = 1.0f / d2;
    const float range = L->position_range.w;
    if (range > 0.0f) {
      const float8 r = d2 * inv_d / range;
      a *= clamp(1.0f - (r * r) * (r * r), 0.0f, 1.0f);
    }
    if (L->type == RP_LIGHT_SPOT) {
      const float8 cos_a =
          -(*lx * L->direction.x + *ly * L->direction.y + *lz * L->direction.z);
      const float8 t = L->cone.y > 0.0f
                           ? clamp((cos_a - L->cone.x) * L->cone.y, 0.0f, 1.0f)
                           : select(zero, (float8)(1.0f), cos_a >= L->cone.x);
      a *= t * t;
    }
    atten = select(zero, a, away);
  }
  const float8 c = nx * *lx + ny * *ly + nz * *lz;
  const int8 lit = on & (c > 0.0f) & (atten > 0.0f);
  if (!any(lit)) return false;
  float8 vis = 1.0f;
  if (L->view_count != 0u) {
    __global const ShadowViewGpu* V = &frame->shadow_views[L->first_view];
    /* the receiver's clip w in its view: a texel's size scales with it */
    float8 w0;
    if (L->type == RP_LIGHT_POINT) {
      const float8 ax = fabs(px - L->position_range.x), ay = fabs(py - L->position_range.y),
                   az = fabs(pz - L->position_range.z);
      w0 = fmax(ax, fmax(ay, az)); /* every face has the same projection */
    } else {
      w0 = V->depth.z != 0.0f ? (float8)(1.0f)
                              : fabs(RP_PUNCTUAL8_ROW(V->view_proj, w, px, py, pz));
    }
    const float8 texel = w0 * V->depth.w;
    const float8 cc = fmax(c, 1.0e-4f);
    const float8 tan_theta = fmin(sqrt(fmax(1.0f - cc * cc, 0.0f)) / cc, 8.0f);
    if (L->type != RP_LIGHT_POINT) {
      vis = rp_punctual_view_visibility8(shadow, V, px, py, pz, nx, ny, nz, texel, tan_theta,
                                         lit);
    } else {
      /* the face that sees the pushed point (near a cube edge the push may cross) */
      const float8 dx = px + nx * texel - L->position_range.x;
      const float8 dy = py + ny * texel - L->position_range.y;
      const float8 dz = pz + nz * texel - L->position_range.z;
      const float8 ax = fabs(dx), ay = fabs(dy), az = fabs(dz);
      const int8 face = select(select(select((int8)(5), (int8)(4), dz >= 0.0f),
                                      select((int8)(3), (int8)(2), dy >= 0.0f), ay >= az),
                               select((int8)(1), (int8)(0), dx >= 0.0f),
                               (ax >= ay) & (ax >= az));
      int fa[8], la[8];
      vstore8(face, 0, fa);
      vstore8(select((int8)(0), (int8)(1), lit), 0, la);
      int first = -1;
      bool one_face = true;
      for (int q = 0; q < 8; ++q) {
        if (!la[q]) continue;
        if (first < 0) first = fa[q];
        one_face = one_face && fa[q] == first;
      }
      if (one_face) {
        vis = rp_punctual_view_visibility8(shadow, V + first, px, py, pz, nx, ny, nz, texel,
                                           tan_theta, lit);
      } else {
        float pa[3][8], na[3][8], l3[3][8], va[8];
        vstore8(px, 0, pa[0]);
        vstore8(py, 0, pa[1]);
        vstore8(pz, 0, pa[2]);
        vstore8(nx, 0, na[0]);
        vstore8(ny, 0, na[1]);
        vstore8(nz, 0, na[2]);
        vstore8(*lx, 0, l3[0]);
        vstore8(*ly, 0, l3[1]);
        vstore8(*lz, 0, l3[2]);
        for (int q = 0; q < 8; ++q)
          va[q] = la[q] ? rp_punctual_visibility(
                              frame, shadow, L, (float3)(pa[0][q], pa[1][q], pa[2][q]),
                              (float3)(na[0][q], na[1][q], na[2][q]),
                              (float3)(l3[0][q], l3[1][q], l3[2][q]), 1)
                        : 1.0f;
        vis = vload8(0, va);
      }
    }
  }
  /* every lit lane in the light's shadow: nothing to add (the caller skips the surface model,
   * whose terms would all be scaled by 0) */
  if (!any(lit & (vis > 0.0f))) return false;
  const float8 k = select(zero, c * atten * vis, lit);
  *kr = L->intensity.x * k;
  *kg = L->intensity.y * k;
  *kb = L->intensity.z * k;
  return true;
}

#undef RP_PUNCTUAL8_ROW

#endif
