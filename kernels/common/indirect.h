/* Reduced-resolution indirect light (the fast quality mode), shared by the indirect
 * pass (kernels/indirect.cl: trace, filter + accumulate) and the light pass's upsampling
 * (kernels/light.cl, light_compose). OpenCL C only.
 *
 * Grid: one low-resolution sample per RP_INDIRECT_SCALE x RP_INDIRECT_SCALE block of
 * full-resolution pixels; lr_width = ceil(width / 4), lr_height = ceil(height / 4) (a partial
 * last block clamps its sample pixel to the image).
 *
 * Per frame f (FrameConstants.frame_index):
 *   sample pixel: every block takes the full-resolution pixel at offset O(f) inside it, O(f) the
 *     cell holding value f mod 16 in the 4x4 Bayer matrix (well spread over 4, 8, 16 frames), so
 *     small objects and edges get samples over time;
 *   cone: sample (i, j) traces cone k = (B(i, j) + 7 f) mod 16 of the 16-cone set
 *     (common/cone_trace.h), B the 4x4 Bayer matrix: every 4x4 window of samples holds all 16
 *     directions every frame, and a sample cycles through all 16 in 16 frames (7 is odd);
 *   level jitter: u = fract(hash(i, j) + 0.618034 f) in [0, 1) (a per-sample start, then the
 *     golden-ratio sequence over frames) for rp_cone_trace_jittered.
 *
 * Geometry weight of a sample with unit normal n_s and plane offset d_s = dot(n_s, p_s) seen from
 * a receiver at p with unit normal n (rp_indirect_geometry_weight8):
 *   w = max(dot(n, n_s), 0)^8 * max(1 - (dist / (2 sigma))^2, 0)^2,  dist = dot(n_s, p) - d_s,
 * sigma = RP_INDIRECT_PLANE_SIGMA low-resolution pixels at the receiver's view depth (world size
 * of one pixel = view depth * pixel_scale, pixel_scale = 2 / (height * P[1][1]) from the
 * projection). Same plane and orientation: 1; across a crease or a depth edge (more than two
 * sigma off the plane): 0 (a polynomial falloff: no exp, no division).
 *
 * Low-resolution data is planar: one float plane per channel, planes `plane` floats apart in one
 * buffer. Each plane is padded so that 5x5 filter taps and 2x2 upsampling taps never need a
 * bounds check: sample (i, j) sits at (j + RP_INDIRECT_PAD) * stride + i + RP_INDIRECT_PAD, with
 * RP_INDIRECT_PAD = 2 rows and columns of zeros around the lr_width x lr_height interior
 * (stride = round_up(lr_width, 8) + 8, plane = stride * (lr_height + 4); the host computes both,
 * src/passes/indirect.cpp). Padding has geometry 0, so every weight that reaches it is 0. The
 * kernels that read the planes process 8 samples or pixels of a row per work-item
 * (common/indirect_simd.h).
 */
#ifndef ROLYPOLY_COMMON_INDIRECT_H
#define ROLYPOLY_COMMON_INDIRECT_H

#include "common/random.h"

#define RP_INDIRECT_SCALE 4
#define RP_INDIRECT_PAD 2

/* 1: the sample pixel rotates over the 16 pixels of its block (Bayer order); 0: every block
 * samples its pixel (1, 1). Measured at 128x128 (static demo, 40 frames): rotating costs
 * flicker (mean |frame - previous| 0.689 vs 0.645 codes, the reference 0.635) through blocks
 * whose sample alternates between surfaces at edges, and gains nothing in PSNR (37.15 vs
 * 37.21 dB). */
#ifndef RP_INDIRECT_ROTATE_SAMPLE
#define RP_INDIRECT_ROTATE_SAMPLE 0
#endif

/* Plane-distance tolerance, in low-resolution pixels at the receiver's depth. */
#ifndef RP_INDIRECT_PLANE_SIGMA
#define RP_INDIRECT_PLANE_SIGMA 1.0f
#endif

/* 4x4 Bayer (ordered dither) matrix, row-major: B(x, y) = RP_BAYER4[y * 4 + x]. */
__constant uchar RP_BAYER4[16] = {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};
/* Its inverse: the cell y * 4 + x holding value v. */
__constant uchar RP_BAYER4_CELL[16] = {0, 10, 2, 8, 5, 15, 7, 13, 1, 11, 3, 9, 4, 14, 6, 12};

/* Offset (x, y) in 0..3 of the sample pixel inside its block at frame f: cell & 3, cell >> 2. */
inline uint rp_indirect_sample_cell(uint frame) {
#if RP_INDIRECT_ROTATE_SAMPLE
  return RP_BAYER4_CELL[frame & 15u];
#else
  (void)frame;
  return 5u; /* cell (1, 1) */
#endif
}

/* Cone of the 16-cone set that sample (i, j) traces at frame f. */
inline uint rp_indirect_cone_index(uint i, uint j, uint frame) {
  return ((uint)RP_BAYER4[(j & 3u) * 4u + (i & 3u)] + 7u * frame) & 15u;
}

/* Level jitter in [0, 1) of sample (i, j) at frame f. */
inline float rp_indirect_level_jitter(uint i, uint j, uint frame) {
  const float start = rp_hash_to_unit(rp_hash_u32(i ^ rp_hash_u32(j ^ 0x9e3779b9u)));
  const float u = start + 0.618034f * (float)(frame & 1023u);
  return u - floor(u);
}

/* Second jitter in [0, 1) of sample (i, j) at frame f (the plastic-number sequence, so the
 * pair of jitters covers the unit square evenly over frames). */
inline float rp_indirect_position_jitter(uint i, uint j, uint frame) {
  const float start = rp_hash_to_unit(rp_hash_u32(j ^ rp_hash_u32(i ^ 0x85ebca6bu)));
  const float u = start + 0.754877666f * (float)(frame & 1023u);
  return u - floor(u);
}

/* Index of sample (i, j) in a padded plane (-RP_INDIRECT_PAD <= i, j; see the header). */
inline int rp_indirect_index(int i, int j, int stride) {
  return (j + RP_INDIRECT_PAD) * stride + i + RP_INDIRECT_PAD;
}

/* Geometry weight w (see the header) of eight samples with normals (sx, sy, sz) and plane
 * offsets sd for eight receivers at (px, py, pz) with normals (nx, ny, nz); inv_sigma = 1 / sigma. */
inline float8 rp_indirect_geometry_weight8(float8 nx, float8 ny, float8 nz, float8 px, float8 py,
                                           float8 pz, float8 sx, float8 sy, float8 sz, float8 sd,
                                           float8 inv_sigma) {
  float8 wn = fmax(nx * sx + ny * sy + nz * sz, 0.0f);
  wn *= wn;
  wn *= wn;
  wn *= wn;
  const float8 dist = (sx * px + sy * py + sz * pz - sd) * inv_sigma;
  const float8 wp = fmax(1.0f - 0.25f * dist * dist, 0.0f);
  return wn * (wp * wp);
}

/* 1 / sigma for receivers at view depth `depth` (see the header). */
inline float8 rp_indirect_inv_sigma8(float8 depth, float pixel_scale) {
  return 1.0f / fmax(depth * (pixel_scale * (RP_INDIRECT_SCALE * RP_INDIRECT_PLANE_SIGMA)), 1.0e-6f);
}

#endif
