/* Light pass (SPEC 6.5): GBuffer + shadow map + voxel radiance chain -> HDR radiance (float4 per
 * pixel, rgb linear, a = 1 covered / 0 background).
 *
 *   L_out = albedo * I * cos(theta) / d^2 * falloff(l.y) * shadow      (direct, point lamp)
 *         + albedo * D(p, n)                                             (indirect, cone traced)
 *         + emission
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
 *   RP_LIGHT_SPLIT=1: also writes the direct lamp term (rgb, a = covered) and the indirect term
 *     (rgb, a = covered) into two extra float4 buffers, for the debug views; emission is in
 *     neither. The default build writes only hdr.
 *
 * The direct term (lamp falloff from l.y, shadow-map projection, bias and taps) is
 * common/direct_light.h, shared with the voxelizer; the formulas are documented there.
 *
 * Shadow (shadow map = FrameConstants.light_view_proj depth, z_ndc * 0.5 + 0.5, 1.0 = empty;
 * texel rows top to bottom like the camera image, types.h): the receiver is pushed along its
 * normal by RP_SHADOW_NORMAL_OFFSET texels and compared in linear light depth (clip w) with a
 * bias of (RP_SHADOW_DEPTH_BIAS + filter radius * tan(theta)) texels, where one texel is its
 * world size at the receiver's distance. Default filter: ONE tap at a Poisson-disk point
 * (radius RP_SHADOW_RADIUS texels; RP_POISSON_DISK, common/random.h) rotated by one of 16
 * angles k * 22.5 degrees, point and angle chosen by a hash of (pixel, frame_index) (top 4 bits,
 * next 4 bits), so the noise is deterministic and changes per frame for TAA to average (256
 * offsets; a table rather than sin/cos keeps the code vectorizable). -DRP_SHADOW_PCF5=1: the
 * 5x5 PCF reference (25 taps, one texel apart). Points outside the shadow frustum are lit.
 * Both kernels compute the direct term with the same code (light_direct), so the quality modes
 * differ only in their indirect light.
 */
#include "shared/types.h"
#include "common/math.h"
#include "common/random.h"
#include "common/direct_light.h"
#include "common/cone_trace.h"
#include "common/indirect.h"
#include "common/indirect_simd.h"

#ifndef RP_SHADOW_NORMAL_OFFSET
#define RP_SHADOW_NORMAL_OFFSET 1.0f
#endif
#ifndef RP_SHADOW_DEPTH_BIAS
#define RP_SHADOW_DEPTH_BIAS 1.0f
#endif
#ifndef RP_SHADOW_RADIUS
#define RP_SHADOW_RADIUS 1.5f
#endif
#ifndef RP_SHADOW_PCF5
#define RP_SHADOW_PCF5 0
#endif
#ifndef RP_LIGHT_SPLIT
#define RP_LIGHT_SPLIT 0
#endif

#if RP_SHADOW_PCF5
#define RP_SHADOW_FILTER_REACH 2.83f /* farthest 5x5 tap, texels */
#else
#define RP_SHADOW_FILTER_REACH RP_SHADOW_RADIUS
#endif

/* cos(2 pi k / 16), k = 0..15; sin(2 pi k / 16) = cos(2 pi (k - 4) / 16). */
__constant float RP_LIGHT_COS16[16] = {
    1.0f,  0.923879533f,  0.707106781f,  0.382683432f,  0.0f, -0.382683432f, -0.707106781f,
    -0.923879533f, -1.0f, -0.923879533f, -0.707106781f, -0.382683432f, 0.0f, 0.382683432f,
    0.707106781f,  0.923879533f};

/* Direct lamp factor cos(theta) / d^2 * falloff(l.y) * shadow at point p with unit normal n,
 * pixel (x, y): the formulas of common/direct_light.h (rp_direct_unshadowed, rp_shadow_lookup,
 * one tap), in the operation order of light_direct8 below so both kernels light alike.
 * Multiply by albedo * light_intensity. */
inline float light_direct(__global const FrameConstants* restrict frame,
                          __global const float* restrict shadow, float px, float py, float pz,
                          float nx, float ny, float nz, uint x, uint y) {
  const float3 p = (float3)(px, py, pz), n = (float3)(nx, ny, nz);
#if RP_SHADOW_PCF5
  (void)x;
  (void)y;
  float c;
  const float k = rp_direct_unshadowed(frame->light_pos.xyz, p, n, &c);
  const RpShadowLookup s = rp_shadow_lookup(frame, p, n, c, RP_SHADOW_NORMAL_OFFSET,
                                            RP_SHADOW_DEPTH_BIAS, RP_SHADOW_FILTER_REACH);
  float lit = 0.0f;
  for (int j = -2; j <= 2; ++j)
    for (int i = -2; i <= 2; ++i) lit += rp_shadow_tap(shadow, &s, (float2)((float)i, (float)j));
  return c > 0.0f ? k * lit * (1.0f / 25.0f) : 0.0f;
#else
  const float4 lp = frame->light_pos;
  const float lx = lp.x - px, ly = lp.y - py, lz = lp.z - pz;
  const float inv_d = rsqrt(lx * lx + ly * ly + lz * lz);
  const float c = (nx * lx + ny * ly + nz * lz) * inv_d;
  const float s = clamp(ly * inv_d, 0.0f, 1.0f);
  const float falloff = mad(s, mad(s, 0.204f, 0.446f), 0.35f); /* rp_lamp_falloff */
  const float k = c > 0.0f ? c * (inv_d * inv_d) * falloff : 0.0f;
  const rp_mat4 m = frame->light_view_proj;
  const int isize = (int)frame->shadow_size;
  const float size = (float)isize;
  const float w0 = m.c[0].w * px + m.c[1].w * py + m.c[2].w * pz + m.c[3].w;
  const float row0 = sqrt(m.c[0].x * m.c[0].x + m.c[1].x * m.c[1].x + m.c[2].x * m.c[2].x);
  const float texel = fabs(w0) * (2.0f / (size * row0));
  const float cc = fmax(c, 1.0e-4f);
  const float tan_theta = fmin(sqrt(fmax(1.0f - cc * cc, 0.0f)) / cc, RP_DIRECT_MAX_SLOPE);
  const float3 q = p + n * (texel * RP_SHADOW_NORMAL_OFFSET);
  const float4 clip = rp_mat4_mul_point(m, q);
  const bool front = clip.w > 0.0f;
  const float iw = 1.0f / (front ? clip.w : 1.0f);
  const float ndx = clip.x * iw, ndy = clip.y * iw, ndz = clip.z * iw;
  const bool inside = front && fabs(ndx) <= 1.0f && fabs(ndy) <= 1.0f && ndz <= 1.0f;
  const float receiver =
      clip.w - texel * (RP_SHADOW_DEPTH_BIAS + RP_SHADOW_FILTER_REACH * tan_theta);
  /* one Poisson tap rotated by one of 16 angles */
  const uint h = rp_hash_pixel(x, y, frame->frame_index);
  const float2 dp = RP_POISSON_DISK[h >> 28];
  const uint angle = (h >> 24) & 15u;
  const float ca = RP_LIGHT_COS16[angle], sa = RP_LIGHT_COS16[(angle + 12u) & 15u];
  const float ox = (ca * dp.x - sa * dp.y) * RP_SHADOW_RADIUS;
  const float oy = (sa * dp.x + ca * dp.y) * RP_SHADOW_RADIUS;
  const float sx = clamp((ndx * 0.5f + 0.5f) * size + ox, 0.0f, size - 1.0f);
  const float sy = clamp((0.5f - ndy * 0.5f) * size + oy, 0.0f, size - 1.0f);
  const float d = shadow[(int)sy * isize + (int)sx];
  /* lin >= receiver with lin = 2 n f / den (rp_shadow_linear_depth), den > 0 for d in [0, 1]:
   * compared without the division; an empty texel (d >= 1) is lit */
  const float near = frame->clip.z, far = frame->clip.w;
  const float den = (far + near) - (d * 2.0f - 1.0f) * (far - near);
  const bool lit = d >= 1.0f || 2.0f * near * far >= receiver * den;
  return (lit || !inside) ? k : 0.0f;
#endif
}

/* Default: voxels, the radiance chain (shared/voxel_layout.h) of voxel_resolution^3 at level 0
 * with voxel_levels levels. */
__kernel void light_shade(__global const FrameConstants* restrict frame,
                          __global const float4* restrict albedo_plane,
                          __global const float4* restrict normal_depth_plane,
                          __global const float4* restrict position_plane,
                          __global const float4* restrict emission_plane,
                          __global const float* restrict shadow,
                          __global const float4* restrict voxels,
                          const uint voxel_resolution,
                          const uint voxel_levels,
#if RP_LIGHT_SPLIT
                          __global float4* restrict direct_out,
                          __global float4* restrict indirect_out,
#endif
                          __global float4* restrict hdr) {
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
#endif
    return;
  }
  const float3 albedo = albedo_plane[pixel].xyz;
  const float3 n = normal_depth_plane[pixel].xyz;
  const float3 p = pos.xyz;
  const float k = light_direct(frame, shadow, p.x, p.y, p.z, n.x, n.y, n.z, x, y);
  const float3 direct = albedo * (frame->light_intensity.xyz * k);
  const float3 indirect = albedo * rp_cone_diffuse16(voxels, voxel_resolution, voxel_levels, p, n);
  hdr[pixel] = (float4)(direct + indirect + emission_plane[pixel].xyz, 1.0f);
#if RP_LIGHT_SPLIT
  direct_out[pixel] = (float4)(direct, 1.0f);
  indirect_out[pixel] = (float4)(indirect, 1.0f);
#endif
}

/* RP_POISSON_DISK (common/random.h) and RP_LIGHT_COS16 as registers for shuffle lookups. */
#define RP_LIGHT_DISK_X                                                                     \
  ((float16)(0.3972f, 0.9056f, -0.7300f, -0.0751f, -0.4080f, -0.3577f, 0.5044f, 0.4689f,     \
             0.1092f, 0.8308f, -0.7750f, -0.4490f, -0.0158f, 0.0188f, 0.5436f, -0.3392f))
#define RP_LIGHT_DISK_Y                                                                     \
  ((float16)(0.6871f, -0.0336f, -0.2740f, -0.5619f, 0.8898f, 0.4519f, 0.2503f, -0.8088f,     \
             -0.0942f, 0.5409f, 0.2014f, -0.8619f, -0.9943f, 0.9827f, -0.2779f, -0.0255f))
#define RP_LIGHT_COS16_V                                                                    \
  ((float16)(1.0f, 0.923879533f, 0.707106781f, 0.382683432f, 0.0f, -0.382683432f,            \
             -0.707106781f, -0.923879533f, -1.0f, -0.923879533f, -0.707106781f,              \
             -0.382683432f, 0.0f, 0.382683432f, 0.707106781f, 0.923879533f))

/* Direct lamp factor of light_direct on eight pixels (x0 + k, y), the same formulas lane by
 * lane (one rotated Poisson tap; the 5x5 PCF variant calls light_direct per lane). */
inline float8 light_direct8(__global const FrameConstants* restrict frame,
                            __global const float* restrict shadow, float8 px, float8 py,
                            float8 pz, float8 nx, float8 ny, float8 nz, uint x0, uint y) {
#if RP_SHADOW_PCF5
  float k[8];
  for (uint i = 0; i < 8u; ++i)
    k[i] = light_direct(frame, shadow, rp_lane8(px, i), rp_lane8(py, i), rp_lane8(pz, i),
                        rp_lane8(nx, i), rp_lane8(ny, i), rp_lane8(nz, i), x0 + i, y);
  return vload8(0, k);
#else
  const float4 lp = frame->light_pos;
  const float8 lx = lp.x - px, ly = lp.y - py, lz = lp.z - pz;
  const float8 inv_d = rsqrt(lx * lx + ly * ly + lz * lz);
  const float8 c = (nx * lx + ny * ly + nz * lz) * inv_d;
  const float8 s = fmin(fmax(ly * inv_d, (float8)(0.0f)), (float8)(1.0f));
  const float8 falloff = mad(s, mad(s, 0.204f, 0.446f), 0.35f); /* rp_lamp_falloff */
  const float8 k = select((float8)(0.0f), c * (inv_d * inv_d) * falloff, c > 0.0f);
  const rp_mat4 m = frame->light_view_proj;
  const int isize = (int)frame->shadow_size;
  const float size = (float)isize;
  const float8 w0 = m.c[0].w * px + m.c[1].w * py + m.c[2].w * pz + m.c[3].w;
  const float row0 = sqrt(m.c[0].x * m.c[0].x + m.c[1].x * m.c[1].x + m.c[2].x * m.c[2].x);
  const float8 texel = fabs(w0) * (2.0f / (size * row0));
  const float8 cc = fmax(c, 1.0e-4f);
  const float8 tan_theta = fmin(sqrt(fmax(1.0f - cc * cc, 0.0f)) / cc, RP_DIRECT_MAX_SLOPE);
  const float8 off = texel * RP_SHADOW_NORMAL_OFFSET;
  const float8 qx = px + nx * off, qy = py + ny * off, qz = pz + nz * off;
  const float8 cx = m.c[0].x * qx + m.c[1].x * qy + m.c[2].x * qz + m.c[3].x;
  const float8 cy = m.c[0].y * qx + m.c[1].y * qy + m.c[2].y * qz + m.c[3].y;
  const float8 cz = m.c[0].z * qx + m.c[1].z * qy + m.c[2].z * qz + m.c[3].z;
  const float8 cw = m.c[0].w * qx + m.c[1].w * qy + m.c[2].w * qz + m.c[3].w;
  const int8 front = cw > 0.0f;
  const float8 iw = 1.0f / select((float8)(1.0f), cw, front);
  const float8 ndx = cx * iw, ndy = cy * iw, ndz = cz * iw;
  const int8 inside = front & (fabs(ndx) <= 1.0f) & (fabs(ndy) <= 1.0f) & (ndz <= 1.0f);
  const float8 receiver =
      cw - texel * (RP_SHADOW_DEPTH_BIAS + RP_SHADOW_FILTER_REACH * tan_theta);
  /* one Poisson tap rotated by one of 16 angles: rp_hash_pixel per lane; the tables are
   * looked up with shuffle (a register permute, not 8 loads) */
  const uint8 lane = (uint8)(0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u);
  const uint8 h = rp_hash8_u32((x0 + lane) ^ rp_hash_u32(y ^ rp_hash_u32(frame->frame_index)));
  const uint8 point = h >> 28, angle = (h >> 24) & 15u;
  const float8 dx = shuffle(RP_LIGHT_DISK_X, point), dy = shuffle(RP_LIGHT_DISK_Y, point);
  const float8 ca = shuffle(RP_LIGHT_COS16_V, angle);
  const float8 sa = shuffle(RP_LIGHT_COS16_V, (angle + 12u) & 15u);
  const float8 ox = (ca * dx - sa * dy) * RP_SHADOW_RADIUS;
  const float8 oy = (sa * dx + ca * dy) * RP_SHADOW_RADIUS;
  const float8 hi = (float8)(size - 1.0f), lo = (float8)(0.0f);
  const float8 sx = fmin(fmax((ndx * 0.5f + 0.5f) * size + ox, lo), hi);
  const float8 sy = fmin(fmax((0.5f - ndy * 0.5f) * size + oy, lo), hi);
  const int8 idx = convert_int8(sy) * isize + convert_int8(sx);
  const float8 d = (float8)(shadow[idx.s0], shadow[idx.s1], shadow[idx.s2], shadow[idx.s3],
                            shadow[idx.s4], shadow[idx.s5], shadow[idx.s6], shadow[idx.s7]);
  /* lin >= receiver with lin = 2 n f / den (rp_shadow_linear_depth), den > 0 for d in [0, 1]:
   * compared without the division; an empty texel (d >= 1) is lit */
  const float near = frame->clip.z, far = frame->clip.w;
  const float8 den = (far + near) - (d * 2.0f - 1.0f) * (far - near);
  /* one mask of plain comparisons: oclgrind 21.10 evaluated the equivalent
   * select(0, k, lit | (inside == 0)) wrongly for one pixel of a 16x16 frame (PoCL and the
   * scalar light_direct agree) */
  const int8 shadowed = inside & (d < 1.0f) & (2.0f * near * far < receiver * den);
  return select(k, (float8)(0.0f), shadowed);
#endif
}

/* lr_irradiance (history: r, g, b, age planes) and lr_geom (normal x, y, z, plane offset): the
 * indirect pass's padded planes (common/indirect.h), lr_width x lr_height samples, row stride
 * lr_stride, planes lr_plane floats apart; pixel_scale: world size of one pixel per unit of view
 * depth. The GBuffer, hdr and the split outputs are float4 per pixel, passed as floats. Eight
 * pixels of a row per work-item (common/indirect_simd.h): global size (ceil(width / 8), height)
 * rounded up to the work-group. */
__kernel void light_compose(__global const FrameConstants* restrict frame,
                            __global const float* restrict albedo,
                            __global const float* restrict normal_depth,
                            __global const float* restrict position,
                            __global const float* restrict emission,
                            __global const float* restrict shadow,
                            __global const float* restrict lr_irradiance,
                            __global const float* restrict lr_geom,
                            const uint lr_width,
                            const uint lr_height,
                            const uint lr_stride,
                            const uint lr_plane,
                            const float pixel_scale,
#if RP_LIGHT_SPLIT
                            __global float* restrict direct_out,
                            __global float* restrict indirect_out,
#endif
                            __global float* restrict hdr) {
  const uint x0 = 8u * (uint)get_global_id(0), y = (uint)get_global_id(1);
  const uint width = frame->width;
  if (x0 >= width || y >= frame->height) return;
  const uint lanes = min(8u, width - x0);
  const uint row = 4u * y * width;
  float8 px, py, pz, cov, nx, ny, nz, depth;
  rp_load8_float4(position, row, x0, lanes, &px, &py, &pz, &cov);
  rp_load8_float4(normal_depth, row, x0, lanes, &nx, &ny, &nz, &depth);
  const int8 covered = cov != 0.0f;
  const float8 k = light_direct8(frame, shadow, px, py, pz, nx, ny, nz, x0, y);

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
#undef RP_LIGHT_TAPS

  float8 ar, ag, ab, aw, er, eg, eb, ew;
  rp_load8_float4(albedo, row, x0, lanes, &ar, &ag, &ab, &aw);
  rp_load8_float4(emission, row, x0, lanes, &er, &eg, &eb, &ew);
  const float4 li = frame->light_intensity;
  const float8 dr = ar * (li.x * k), dg = ag * (li.y * k), db = ab * (li.z * k);
  const float8 jr = ar * irr[0], jg = ag * irr[1], jb = ab * irr[2];
  const float8 cv = select(zero, one, covered);
  rp_store8_float4(hdr, row, x0, lanes, select(zero, dr + jr + er, covered),
                   select(zero, dg + jg + eg, covered), select(zero, db + jb + eb, covered), cv);
#if RP_LIGHT_SPLIT
  rp_store8_float4(direct_out, row, x0, lanes, select(zero, dr, covered), select(zero, dg, covered),
                   select(zero, db, covered), cv);
  rp_store8_float4(indirect_out, row, x0, lanes, select(zero, jr, covered),
                   select(zero, jg, covered), select(zero, jb, covered), cv);
#endif
}
