/* The lamp's visibility per pixel (the first kernel of the light pass; kernels/light.cl
 * multiplies its direct light by it): rp_shadow8 (common/soft_shadow.h) in the mode
 * -DRP_SHADOW_MODE picks, on a 4x2 block of pixels per work-item, so that pcss pools the
 * blocker searches of each 2x2 quad (soft_shadow.h, step 2).
 *
 * Inputs: the GBuffer's position (xyz world, w = 1 covered / 0 background) and normal_depth
 * (xyz unit normal) planes, float4 per pixel; the shadow map (two planes, render::ShadowMap)
 * and its mips (shared/shadow_mips.h; pcss and vssm only, others may pass any buffer).
 * Output: visibility, one float per pixel in [0, 1], row-major width x height; 1 outside the
 * shadow frustum, on surfaces facing away from the lamp and on background pixels (the light
 * pass gives those no lamp light anyway).
 * Lane k of the work-item for chunk (i, j) is pixel (4 i + (k & 3), 2 j + (k >> 2)). Lanes past
 * the image's edge repeat its last column / row (their results are not stored), so the quads at
 * the edge pool with copies of real pixels.
 *
 * Chunks: cx = ceil(width / 4) by ceil(height / 2) 4x2 blocks. `pass` picks which:
 *   RP_SHADOW_PASS_ALL (0): every chunk; global size (cx, ceil(height / 2)).
 *   RP_SHADOW_PASS_BLACK (1): the chunks with (i + j + frame_index) even (a checkerboard of
 *     chunks that alternates every frame), computed in full; each also writes its consensus
 *     to `consensus` (one uchar per chunk, row-major, cx per row): RP_SHADOW_ALL_LIT when all
 *     eight lanes came out exactly 1, RP_SHADOW_ALL_DARK when all came out exactly 0, else
 *     RP_SHADOW_MIXED. Global size (ceil(cx / 2), ceil(height / 2)): item (g, j) is chunk
 *     i = 2 g + ((j + frame_index) & 1).
 *   RP_SHADOW_PASS_WHITE (2): the other chunks, after pass 1, from the verdicts of their edge
 *     neighbours that exist (left, right, above, below: all black chunks):
 *     - all RP_SHADOW_MIP_LIT (step 1 of pcss found nothing in front of any of their
 *       receivers over the union of their cones, a region that reaches past the chunk between
 *       them): written as 1 without looking at the chunk's pixels;
 *     - all lit (some by the search), or all umbra: the chunk's own one-tap test
 *       (rp_shadow8_hard: the hard mode's tap) must agree on every pixel, which catches a
 *       small umbra inside the chunk or a small lit gap in an umbra; then 1 (0) is written;
 *     - otherwise, or when the one-tap test disagrees: computed in full.
 *     A soft shadow's edge, or any shadow that reaches a neighbour, makes a neighbour mixed or
 *     disagree. What can still be missed is a shadow smaller than the chunk (4x2 pixels) that
 *     touches no neighbour and that the one tap, with its biases, does not see (a ball a few
 *     shadow-map texels wide on the floor: SoftShadow.PcssCheckerboardMisses...), and only
 *     every other frame (the checkerboard alternates). The demo's smallest casters (marbles,
 *     r = 0.04, 20 texels of the 1024^2 map) cast shadows tens of pixels wide at 720x720; the
 *     accuracy report's direct section (16 frames averaged, 128x128 and 360x360) came out the
 *     same as without the checkerboard. On the busy 720x720 frame the visibility kernel's CPU
 *     time fell about 10 % (perf cpu-clock: 10.6 -> 9.5 ms per frame, both threads).
 * A filled 0 lands only where the neighbours are umbra; on a pixel facing away from the lamp
 * (which a full evaluation gives 1) it changes nothing: the light pass gives those no lamp
 * light.
 */
#include "shared/types.h"
#include "common/math.h"
#include "common/random.h"
#include "common/direct_light.h"
#include "common/indirect_simd.h"
#include "common/soft_shadow.h"

#define RP_SHADOW_PASS_ALL 0u
#define RP_SHADOW_PASS_BLACK 1u
#define RP_SHADOW_PASS_WHITE 2u
#define RP_SHADOW_MIXED 0
#define RP_SHADOW_ALL_LIT 1
#define RP_SHADOW_ALL_DARK 2
#define RP_SHADOW_MIP_LIT 3 /* all lit, decided by pcss's step 1 (the min mip) */

/* Writes v to the chunk's pixels inside the image (rows r0 and r0 + width). */
inline void shadow_store_chunk(__global float* restrict visibility, uint width, uint height,
                               uint x0, uint y0, float8 v) {
  const uint r0 = y0 * width;
  if (x0 + 4u <= width) {
    vstore4(v.lo, 0, visibility + r0 + x0);
    if (y0 + 1u < height) vstore4(v.hi, 0, visibility + r0 + width + x0);
  } else {
    for (uint k = 0; x0 + k < width; ++k) {
      visibility[r0 + x0 + k] = rp_lane8(v, k);
      if (y0 + 1u < height) visibility[r0 + width + x0 + k] = rp_lane8(v, k + 4u);
    }
  }
}

__kernel void shadow_visibility(__global const FrameConstants* restrict frame,
                                __global const float4* restrict normal_depth,
                                __global const float4* restrict position,
                                __global const float* restrict shadow,
                                __global const float* restrict shadow_mips,
                                __global float* restrict visibility, uint pass,
                                __global uchar* restrict consensus) {
  const uint width = frame->width, height = frame->height;
  const uint cx = (width + 3u) / 4u, cy = (height + 1u) / 2u;
  const uint cj = (uint)get_global_id(1);
  uint ci = (uint)get_global_id(0);
  if (pass != RP_SHADOW_PASS_ALL)
    ci = 2u * ci + ((cj + frame->frame_index + (pass == RP_SHADOW_PASS_WHITE ? 1u : 0u)) & 1u);
  const uint x0 = 4u * ci, y0 = 2u * cj;
  if (x0 >= width || y0 >= height) return;
  int agreed = RP_SHADOW_MIXED; /* the white pass's neighbours' common verdict */
  if (pass == RP_SHADOW_PASS_WHITE) {
    /* the edge neighbours that exist (all black chunks, written by pass 1) */
    int mip = 1, lit = 1, dark = 1;
#define RP_SHADOW_NEIGHBOUR(index)                          \
  do {                                                      \
    const int c_ = consensus[index];                        \
    mip &= c_ == RP_SHADOW_MIP_LIT;                         \
    lit &= c_ == RP_SHADOW_MIP_LIT || c_ == RP_SHADOW_ALL_LIT; \
    dark &= c_ == RP_SHADOW_ALL_DARK;                       \
  } while (0)
    if (ci > 0u) RP_SHADOW_NEIGHBOUR(cj * cx + ci - 1u);
    if (ci + 1u < cx) RP_SHADOW_NEIGHBOUR(cj * cx + ci + 1u);
    if (cj > 0u) RP_SHADOW_NEIGHBOUR((cj - 1u) * cx + ci);
    if (cj + 1u < cy) RP_SHADOW_NEIGHBOUR((cj + 1u) * cx + ci);
#undef RP_SHADOW_NEIGHBOUR
    if (mip) { /* see the header: no blocker in front of the neighbours' cones */
      shadow_store_chunk(visibility, width, height, x0, y0, (float8)(1.0f));
      return;
    }
    agreed = lit ? RP_SHADOW_ALL_LIT : (dark ? RP_SHADOW_ALL_DARK : RP_SHADOW_MIXED);
  }
  const uint8 lane = (uint8)(0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u);
  const uint8 xs = min(x0 + (lane & 3u), (uint8)(width - 1u));
  const uint8 ys = min(y0 + (lane >> 2), (uint8)(height - 1u));
  /* two rows of four float4 pixels per plane: one 16-float vector load per row (clamped
   * per pixel at the right and bottom edges) */
  const uint r0 = y0 * width, r1 = min(y0 + 1u, height - 1u) * width;
  float16 pa, pb, na, nb;
  if (x0 + 4u <= width) {
    pa = vload16(0, (__global const float*)(position + r0 + x0));
    pb = vload16(0, (__global const float*)(position + r1 + x0));
    na = vload16(0, (__global const float*)(normal_depth + r0 + x0));
    nb = vload16(0, (__global const float*)(normal_depth + r1 + x0));
  } else {
    const uint l = width - 1u;
    pa = (float16)(position[r0 + x0], position[r0 + min(x0 + 1u, l)],
                   position[r0 + min(x0 + 2u, l)], position[r0 + min(x0 + 3u, l)]);
    pb = (float16)(position[r1 + x0], position[r1 + min(x0 + 1u, l)],
                   position[r1 + min(x0 + 2u, l)], position[r1 + min(x0 + 3u, l)]);
    na = (float16)(normal_depth[r0 + x0], normal_depth[r0 + min(x0 + 1u, l)],
                   normal_depth[r0 + min(x0 + 2u, l)], normal_depth[r0 + min(x0 + 3u, l)]);
    nb = (float16)(normal_depth[r1 + x0], normal_depth[r1 + min(x0 + 1u, l)],
                   normal_depth[r1 + min(x0 + 2u, l)], normal_depth[r1 + min(x0 + 3u, l)]);
  }
  const float8 px = (float8)(pa.s048c, pb.s048c), py = (float8)(pa.s159d, pb.s159d);
  const float8 pz = (float8)(pa.s26ae, pb.s26ae), cov = (float8)(pa.s37bf, pb.s37bf);
  const float8 nx = (float8)(na.s048c, nb.s048c), ny = (float8)(na.s159d, nb.s159d);
  const float8 nz = (float8)(na.s26ae, nb.s26ae);
  /* cos(theta) towards the lamp centre (light.cl's direct term); 0 on background pixels */
  const float4 lp = frame->light_pos;
  const float8 lx = lp.x - px, ly = lp.y - py, lz = lp.z - pz;
  const float8 c = select((float8)(0.0f),
                          (nx * lx + ny * ly + nz * lz) * rsqrt(lx * lx + ly * ly + lz * lz),
                          cov != 0.0f);
  if (agreed != RP_SHADOW_MIXED) {
    /* the neighbours agree: fill, unless the chunk's own one-tap test says otherwise somewhere
     * (a small umbra inside the chunk, or a small lit gap in an umbra) */
    const float8 fill = agreed == RP_SHADOW_ALL_LIT ? (float8)(1.0f) : (float8)(0.0f);
    if (all(rp_shadow8_hard(frame, shadow, px, py, pz, nx, ny, nz, c) == fill)) {
      shadow_store_chunk(visibility, width, height, x0, y0, fill);
      return;
    }
  }
  int mip_lit;
  const float8 v =
      rp_shadow8(frame, shadow, shadow_mips, px, py, pz, nx, ny, nz, c, xs, ys, &mip_lit);
  shadow_store_chunk(visibility, width, height, x0, y0, v);
  if (pass == RP_SHADOW_PASS_BLACK)
    consensus[cj * cx + ci] = mip_lit            ? (uchar)RP_SHADOW_MIP_LIT
                              : all(v == 1.0f)   ? (uchar)RP_SHADOW_ALL_LIT
                              : all(v == 0.0f)   ? (uchar)RP_SHADOW_ALL_DARK
                                                 : (uchar)RP_SHADOW_MIXED;
}
