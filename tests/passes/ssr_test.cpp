// Screen-space reflections' min-Z pyramid (kernels/ssr.cl, ssr_min_z; layout in
// kernels/common/ssr.h) against a C++ min over each cell's pixels, on an odd-sized random depth
// buffer (13 x 10: the last cells of a level hold one column or row), levels 1 .. 3 packed in
// one buffer as IndirectPass builds them: exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "cl/kernel_args.h"
#include "cl/launch_log.h"
#include "cl/program_cache.h"
#include "passes/indirect.h"
#include "render/gpu_types.h"
#include "support/cl_fixture.h"

namespace {

TEST(Ssr, MinZPyramidHoldsEachCellsNearestDepth) {
  constexpr uint32_t kW = 13, kH = 10, kTop = 3;
  std::vector<float> depth(kW * kH);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (float& d : depth) d = u(rng) < 0.2f ? 1.0f : u(rng);  // some background (1)
  auto& ctx = rp::test::context();
  ::cl::Buffer src(ctx.context, CL_MEM_READ_WRITE, depth.size() * 4);
  ctx.queue.enqueueWriteBuffer(src, CL_TRUE, 0, depth.size() * 4, depth.data());
  ::cl::Buffer hiz(ctx.context, CL_MEM_READ_WRITE, 64 * 4);
  ::cl::Kernel k = rp::test::programs().kernel("ssr.cl", "ssr_min_z");
  uint32_t sw = kW, sh = kH, src_off = 0, dst_off = 0;
  std::vector<uint32_t> offsets, widths, heights;
  for (uint32_t level = 1; level <= kTop; ++level) {
    const uint32_t dw = (sw + 1) / 2, dh = (sh + 1) / 2;
    rp::cl::bind_args(k, level == 1 ? src : hiz, hiz,
                      rp::gpu::MinZLevel{src_off, sw, sh, dst_off, dw, dh, 0u, 0u});
    rp::cl::note_kernel_launch(k);  // launched here, not through a Profiler
    ctx.queue.enqueueNDRangeKernel(k, ::cl::NullRange, ::cl::NDRange(dw, dh));
    offsets.push_back(dst_off);
    widths.push_back(dw);
    heights.push_back(dh);
    src_off = dst_off;
    dst_off += dw * dh;
    sw = dw;
    sh = dh;
  }
  std::vector<float> got(dst_off);
  ctx.queue.enqueueReadBuffer(hiz, CL_TRUE, 0, got.size() * 4, got.data());
  for (uint32_t level = 1; level <= kTop; ++level) {
    const uint32_t cell = 1u << level;
    for (uint32_t y = 0; y < heights[level - 1]; ++y)
      for (uint32_t x = 0; x < widths[level - 1]; ++x) {
        float want = 1.0f;
        for (uint32_t py = y * cell; py < std::min((y + 1) * cell, kH); ++py)
          for (uint32_t px = x * cell; px < std::min((x + 1) * cell, kW); ++px)
            want = std::min(want, depth[py * kW + px]);
        EXPECT_EQ(got[offsets[level - 1] + y * widths[level - 1] + x], want)
            << "level " << level << " cell " << x << "," << y;
      }
  }
  EXPECT_EQ(widths[0], 7u);
  EXPECT_EQ(heights[2], 2u);
}

TEST(Ssr, TopLevelKeepsCellsOfAtLeastTwo) {
  EXPECT_EQ(rp::passes::IndirectPass::ssr_top_level(720, 720), 6u);
  EXPECT_EQ(rp::passes::IndirectPass::ssr_top_level(16, 16), 3u);
  EXPECT_EQ(rp::passes::IndirectPass::ssr_top_level(13, 10), 2u);
  EXPECT_EQ(rp::passes::IndirectPass::ssr_top_level(1, 1), 0u);
}

}  // namespace
