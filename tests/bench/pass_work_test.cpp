// The per-pass work model (bench/src/pass_work.cpp): scaling properties that follow from the
// kernels' structure, and one pass computed by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "bench/src/pass_work.h"

namespace rp::bench {
namespace {

WorkParams base() {
  WorkParams p{};
  p.width = 256;
  p.height = 192;
  p.voxel_resolution = 64;
  p.shadow_size = 512;
  p.triangles = 5000;
  p.instance_triangles = 20000;
  p.voxel_triangles = 9000;
  p.shadow_triangles = 8000;
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
    EXPECT_GT(w.footprint, 0.0) << pass;
    EXPECT_LE(w.footprint, w.bytes) << pass << ": unique bytes cannot exceed requested bytes";
  }
  EXPECT_EQ(modelled_passes().size(), 10u);
}

// ---- cache-aware roofline -------------------------------------------------------
const std::vector<BandwidthLevel> kLevels = {
    {32 << 10, 200.0}, {2 << 20, 150.0}, {16 << 20, 100.0}, {512 << 20, 30.0}};

TEST(Roofline, SmallFootprintGetsTheFastestLevel) {
  EXPECT_DOUBLE_EQ(bandwidth_ceiling_gbps(kLevels, 1e6, 16 << 10), 200.0);
}

TEST(Roofline, StreamingPassGetsTheLevelItsFootprintFitsIn) {
  // Every byte requested once (bytes == footprint): the footprint's level limits.
  EXPECT_DOUBLE_EQ(bandwidth_ceiling_gbps(kLevels, 1 << 20, 1 << 20), 150.0);
  EXPECT_DOUBLE_EQ(bandwidth_ceiling_gbps(kLevels, 8 << 20, 8 << 20), 100.0);
  EXPECT_DOUBLE_EQ(bandwidth_ceiling_gbps(kLevels, 64e6, 64e6), 30.0);
  // Larger than every level: the DRAM stream (the last level).
  EXPECT_DOUBLE_EQ(bandwidth_ceiling_gbps(kLevels, 4e9, 4e9), 30.0);
}

TEST(Roofline, GatherWithReuseCanExceedTheDramStreamButNotTheFastestLevel) {
  // 10x reuse of a DRAM-sized footprint: footprint / 30 GB/s vs bytes / 200 GB/s.
  const double c = bandwidth_ceiling_gbps(kLevels, 10 * 64e6, 64e6);
  EXPECT_DOUBLE_EQ(c, 200.0);  // 640e6/200 = 3.2 ms > 64e6/30 = 2.13 ms
  const double d = bandwidth_ceiling_gbps(kLevels, 2 * 64e6, 64e6);
  EXPECT_NEAR(d, 60.0, 1e-9);  // 2x reuse: the DRAM footprint limits, 128e6 B / 2.13 ms
  EXPECT_EQ(bandwidth_ceiling_gbps({}, 1e6, 1e6), 0.0);
  EXPECT_EQ(bandwidth_ceiling_gbps(kLevels, 0, 0), 0.0);
}

TEST(Roofline, EfficiencyIsNeverAboveOne) {
  PassWork w{1e9, 1e9, 1e8};  // 1 GB requested over 100 MB (DRAM-sized), 1 GFLOP
  // 100 ms: 10 GB/s against a ceiling of min(200, 1e9 B / (1e8 / 30 GB/s)) = 200 GB/s.
  PassEfficiency e = pass_efficiency(w, 100.0, kLevels, 50.0);
  EXPECT_DOUBLE_EQ(e.gbytes_per_s, 10.0);
  EXPECT_DOUBLE_EQ(e.ceiling_gbps, 200.0);
  EXPECT_DOUBLE_EQ(e.bandwidth_fraction, 0.05);
  EXPECT_DOUBLE_EQ(e.compute_fraction, 10.0 / 50.0);
  // 1 ms: 1000 GB/s, 1000 GFLOP/s: the model cannot be right there: NaN (not shown), never > 1.
  e = pass_efficiency(w, 1.0, kLevels, 50.0);
  EXPECT_TRUE(std::isnan(e.bandwidth_fraction));
  EXPECT_TRUE(std::isnan(e.compute_fraction));
  // Not measured: 0.
  e = pass_efficiency(w, 100.0, {}, 0.0);
  EXPECT_EQ(e.bandwidth_fraction, 0.0);
  EXPECT_EQ(e.compute_fraction, 0.0);
  EXPECT_DOUBLE_EQ(e.gbytes_per_s, 10.0);
  // No time: nothing divided.
  e = pass_efficiency(w, 0.0, kLevels, 50.0);
  EXPECT_EQ(e.gbytes_per_s, 0.0);
  EXPECT_EQ(e.bandwidth_fraction, 0.0);
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

TEST(PassWork, VoxelizeScalesWithVoxelizedTriangles) {
  WorkParams p = base();
  p.voxel_triangles = 1000;
  const PassWork a = pass_work("voxelize", p);
  p.voxel_triangles = 3000;
  const PassWork b = pass_work("voxelize", p);
  p.voxel_triangles = 5000;
  const PassWork c = pass_work("voxelize", p);
  EXPECT_GT(b.bytes, a.bytes);
  // Affine in the triangle count: equal steps add equal work.
  EXPECT_NEAR(c.bytes - b.bytes, b.bytes - a.bytes, 1e-6 * c.bytes);
  EXPECT_NEAR(c.flops - b.flops, b.flops - a.flops, 1e-6 * c.flops);
  // Independent of the screen size.
  p.width *= 2;
  EXPECT_EQ(pass_work("voxelize", p).bytes, c.bytes);
  // The camera's triangles do not count (the voxelizer may take mesh proxies).
  p.instance_triangles *= 7;
  EXPECT_EQ(pass_work("voxelize", p).bytes, c.bytes);
}

// The shadow map draws the casters' shadow triangles (mesh proxies), the camera every mesh.
TEST(PassWork, ShadowMapAndVisibilityCountTheirOwnTriangles) {
  WorkParams p = base();
  const PassWork shadow = pass_work("shadow_map", p), camera = pass_work("visibility", p);
  p.instance_triangles *= 3;
  EXPECT_EQ(pass_work("shadow_map", p).bytes, shadow.bytes);
  EXPECT_GT(pass_work("visibility", p).bytes, camera.bytes);
  p.shadow_triangles *= 3;
  EXPECT_GT(pass_work("shadow_map", p).bytes, shadow.bytes);
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
}  // namespace rp::bench
