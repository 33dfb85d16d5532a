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
 * Global size (ceil(width / 4), ceil(height / 2)); lane k of a work-item is pixel
 * (4 i + (k & 3), 2 j + (k >> 2)). Lanes past the image's edge repeat its last column / row
 * (their results are not stored), so the quads at the edge pool with copies of real pixels.
 */
#include "shared/types.h"
#include "common/math.h"
#include "common/random.h"
#include "common/direct_light.h"
#include "common/indirect_simd.h"
#include "common/soft_shadow.h"

__kernel void shadow_visibility(__global const FrameConstants* restrict frame,
                                __global const float4* restrict normal_depth,
                                __global const float4* restrict position,
                                __global const float* restrict shadow,
                                __global const float* restrict shadow_mips,
                                __global float* restrict visibility) {
  const uint width = frame->width, height = frame->height;
  const uint x0 = 4u * (uint)get_global_id(0), y0 = 2u * (uint)get_global_id(1);
  if (x0 >= width || y0 >= height) return;
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
  const float8 v = rp_shadow8(frame, shadow, shadow_mips, px, py, pz, nx, ny, nz, c, xs, ys);
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
