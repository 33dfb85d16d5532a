// The per-pass work model (src/app/pass_work.cpp): scaling properties that follow from the
// kernels' structure, and one pass computed by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "app/pass_work.h"

namespace rp::app {
namespace {

WorkParams base() {
  WorkParams p{};
  p.width = 256;
  p.height = 192;
  p.voxel_resolution = 64;
  p.shadow_size = 512;
  p.triangles = 5000;
  p.instance_triangles = 20000;
  p.spheres = 40;
  p.taa = p.bloom = p.motion_blur = true;
  return p;
}

TEST(PassWork, EveryModelledPassIsPositiveAndFinite) {
  for (const std::string& pass : modelled_passes()) {
    const PassWork w = pass_work(pass, base());
    EXPECT_GT(w.bytes, 0.0) << pass;
    EXPECT_GT(w.flops, 0.0) << pass;
    EXPECT_TRUE(std::isfinite(w.bytes) && std::isfinite(w.flops)) << pass;
  }
  EXPECT_EQ(modelled_passes().size(), 10u);
}

TEST(PassWork, UnknownPassIsZero) {
  for (const char* name : {"", "debug_view", "visibility_host", "Light"}) {
    const PassWork w = pass_work(name, base());
    EXPECT_EQ(w.bytes, 0.0) << name;
    EXPECT_EQ(w.flops, 0.0) << name;
  }
}

TEST(PassWork, ToneMapByHand) {
  // One work-item per byte: 4 floats read + 4 bytes written per pixel; 17 flops per byte item
  // (exposure 1, x/(1+x) 2, two sqrt + five mad 12, v*255+d 2).
  WorkParams p = base();
  p.width = 3;
  p.height = 5;
  const PassWork w = pass_work("tone_map", p);
  EXPECT_EQ(w.bytes, 15.0 * (16 + 4));
  EXPECT_EQ(w.flops, 15.0 * 4 * 17);
}

TEST(PassWork, LightScalesLinearlyWithPixels) {
  WorkParams p = base();
  const PassWork a = pass_work("light", p);
  p.width *= 2;
  p.height *= 3;
  const PassWork b = pass_work("light", p);
  EXPECT_DOUBLE_EQ(b.bytes, 6 * a.bytes);
  EXPECT_DOUBLE_EQ(b.flops, 6 * a.flops);
  // Independent of the geometry.
  p.instance_triangles *= 4;
  EXPECT_DOUBLE_EQ(pass_work("light", p).bytes, b.bytes);
}

TEST(PassWork, LightComposeCountsGBufferShadowUpsampleAndOutput) {
  // Fast mode, one pixel: 4 GBuffer float4 planes (64 B) + shadow tap (4) + hdr (16) + 2x2
  // low-resolution taps of 7 floats (112) = 196 B; the reference mode is not modelled.
  WorkParams p = base();
  p.width = 1;
  p.height = 1;
  EXPECT_EQ(pass_work("light", p).bytes, 196.0);
  p.reference_quality = true;
  EXPECT_EQ(pass_work("light", p).bytes, 0.0);
  EXPECT_EQ(pass_work("indirect_trace", p).bytes, 0.0);
}

TEST(PassWork, VoxelizeScalesWithDrawnTriangles) {
  WorkParams p = base();
  p.instance_triangles = 1000;
  const PassWork a = pass_work("voxelize", p);
  p.instance_triangles = 3000;
  const PassWork b = pass_work("voxelize", p);
  p.instance_triangles = 5000;
  const PassWork c = pass_work("voxelize", p);
  EXPECT_GT(b.bytes, a.bytes);
  // Affine in the triangle count: equal steps add equal work.
  EXPECT_NEAR(c.bytes - b.bytes, b.bytes - a.bytes, 1e-6 * c.bytes);
  EXPECT_NEAR(c.flops - b.flops, b.flops - a.flops, 1e-6 * c.flops);
  // Independent of the screen size.
  p.width *= 2;
  EXPECT_EQ(pass_work("voxelize", p).bytes, c.bytes);
}

TEST(PassWork, VoxelMipsScalesWithVoxelCount) {
  WorkParams p = base();
  p.voxel_resolution = 32;
  const PassWork a = pass_work("voxel_mips", p);
  p.voxel_resolution = 64;
  const PassWork b = pass_work("voxel_mips", p);
  p.voxel_resolution = 128;
  const PassWork c = pass_work("voxel_mips", p);
  // R^3 up to the 1-voxel tail of the chain (< 0.1 %).
  EXPECT_NEAR(b.bytes / a.bytes, 8.0, 0.01);
  EXPECT_NEAR(c.bytes / b.bytes, 8.0, 0.01);
  EXPECT_NEAR(c.flops / b.flops, 8.0, 0.01);
  // Level 1 of R = 2: one voxel, 8 children read, 6 written: 224 B, 6 x 52 flops.
  p.voxel_resolution = 2;
  EXPECT_EQ(pass_work("voxel_mips", p).bytes, 224.0);
  EXPECT_EQ(pass_work("voxel_mips", p).flops, 312.0);
}

TEST(PassWork, PostProcessingIsZeroWhenDisabled) {
  WorkParams p = base();
  for (const char* pass : {"taa", "bloom", "motion_blur"})
    EXPECT_GT(pass_work(pass, p).bytes, 0.0) << pass;
  p.taa = p.bloom = p.motion_blur = false;
  for (const char* pass : {"taa", "bloom", "motion_blur"}) {
    EXPECT_EQ(pass_work(pass, p).bytes, 0.0) << pass;
    EXPECT_EQ(pass_work(pass, p).flops, 0.0) << pass;
  }
  EXPECT_GT(pass_work("tone_map", p).bytes, 0.0);  // always runs
}

TEST(PassWork, ShadowMapFollowsShadowSizeNotScreen) {
  WorkParams p = base();
  const PassWork a = pass_work("shadow_map", p);
  p.width *= 2;
  EXPECT_EQ(pass_work("shadow_map", p).bytes, a.bytes);
  p.shadow_size *= 2;
  EXPECT_GT(pass_work("shadow_map", p).bytes, a.bytes);
}

TEST(PassWork, TaaByHand) {
  // 5 hdr taps (80) + 5 depths (20) + velocity (8) + 4 history taps (64) + 2 writes (32).
  WorkParams p = base();
  p.width = 2;
  p.height = 2;
  EXPECT_EQ(pass_work("taa", p).bytes, 4.0 * 204);
}

}  // namespace
}  // namespace rp::app
