/* Screen-space reflections' min-Z pyramid (layout and use in common/ssr.h).
 * ssr_min_z: level k >= 1 from level k - 1, one cell per work-item: the smallest z01 of its
 * 2x2 children (children past the edge of an odd-sized level repeat the edge). src + src_off:
 * level k - 1 of src_w x src_h (the visibility buffer's depth for k = 1), dst + dst_off: level k
 * of dst_w x dst_h, dst_w = ceil(src_w / 2), dst_h likewise (offsets in floats; levels >= 1
 * share one buffer, so the source and the destination may be the same buffer, at disjoint
 * ranges). Run once per level, finest first. */
#include "shared/types.h"
#include "shared/pass_params.h"

__kernel void ssr_min_z(__global const float* src, __global float* dst, const MinZLevel level) {
  const uint src_off = level.src_offset, src_w = level.src_width, src_h = level.src_height;
  const uint dst_off = level.dst_offset, dst_w = level.dst_width, dst_h = level.dst_height;
  const uint x = (uint)get_global_id(0), y = (uint)get_global_id(1);
  if (x >= dst_w || y >= dst_h) return;
  src += src_off;
  const uint x0 = 2u * x, y0 = 2u * y;
  const uint x1 = min(x0 + 1u, src_w - 1u), y1 = min(y0 + 1u, src_h - 1u);
  const float a = fmin(src[y0 * src_w + x0], src[y0 * src_w + x1]);
  const float b = fmin(src[y1 * src_w + x0], src[y1 * src_w + x1]);
  dst[dst_off + y * dst_w + x] = fmin(a, b);
}
