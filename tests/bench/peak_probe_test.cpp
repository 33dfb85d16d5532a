// The device peak probe (kernels/probe.cl, bench/src/peak_probe.cpp) on the test device.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "bench/src/peak_probe.h"
#include "cl/error.h"
#include "support/cl_fixture.h"

namespace rp::bench {
namespace {

TEST(PeakProbe, BufferSizeFollowsTheDevice) {
  rp::cl::DeviceInfo info;
  info.max_alloc_bytes = 1ull << 30;
  info.global_mem_bytes = 16ull << 30;
  EXPECT_EQ(probe_buffer_bytes(info), size_t(256) << 20);
  info.max_alloc_bytes = (100ull << 20) + 123;
  EXPECT_EQ(probe_buffer_bytes(info), size_t(100) << 20);
  info.global_mem_bytes = 64ull << 20;
  EXPECT_EQ(probe_buffer_bytes(info), size_t(8) << 20);
}

TEST(PeakProbe, SmallCopyIsVerifiedAndPlausible) {
  // 4 MiB per buffer, 2 launches: the function reads the copy back and throws on a mismatch.
  const double gbps = measure_bandwidth_gbps(rp::test::context(), rp::test::programs(),
                                             4u << 20, 2);
  EXPECT_TRUE(std::isfinite(gbps));
  EXPECT_GT(gbps, 0.1);
  EXPECT_LT(gbps, 5000.0);
}

TEST(PeakProbe, SmallComputeIsVerifiedAndPlausible) {
  const double gflops =
      measure_gflops(rp::test::context(), rp::test::programs(), 1000, 2, 5.0);
  EXPECT_TRUE(std::isfinite(gflops));
  EXPECT_GT(gflops, 0.1);
  EXPECT_LT(gflops, 1e6);
}

TEST(PeakProbe, RejectsEmptyRequests) {
  EXPECT_THROW(measure_bandwidth_gbps(rp::test::context(), rp::test::programs(), 100, 1),
               rp::cl::Error);
  EXPECT_THROW(measure_gflops(rp::test::context(), rp::test::programs(), 64, 0, 1.0),
               rp::cl::Error);
}

TEST(PeakProbe, CachedCopyIsVerifiedAndPlausible) {
  const double gbps = measure_cached_bandwidth_gbps(rp::test::context(), rp::test::programs(),
                                                    64u << 10, 16u << 20, 2);
  EXPECT_TRUE(std::isfinite(gbps));
  EXPECT_GT(gbps, 0.1);
  EXPECT_LT(gbps, 1e5);
  EXPECT_THROW(measure_cached_bandwidth_gbps(rp::test::context(), rp::test::programs(),
                                             48u << 10, 1u << 20, 1),
               rp::cl::Error)
      << "not a power of two";
}

TEST(PeakProbe, ImplausibleLaunchTimesAreNotMeasurements) {
  // rusticl's timestamps gave 1 ns for a 512 MiB copy (536870912 GB/s): not a measurement.
  EXPECT_FALSE(plausible_launch(1e-6, 512.0 * (1 << 20), 1e15));
  EXPECT_FALSE(plausible_launch(0.0, 1e6, 1e15));
  EXPECT_FALSE(plausible_launch(0.01, 1e12, 1e15)) << "1e12 B in 10 us = 100 PB/s";
  EXPECT_TRUE(plausible_launch(10.0, 512.0 * (1 << 20), 1e15));
}

TEST(PeakProbe, CacheWorkingSetsStayBelowTheStream) {
  EXPECT_EQ(cache_working_sets(256u << 20).size(), 4u);
  for (size_t ws : cache_working_sets(4u << 20)) EXPECT_LT(ws, size_t(8) << 20);
  EXPECT_EQ(cache_working_sets(4u << 20).size(), 3u);
}

TEST(PeakProbe, MeasurePeakIsInAPlausibleRange) {
  const DevicePeak peak = measure_peak(rp::test::context(), rp::test::programs());
  EXPECT_TRUE(peak.bandwidth_note.empty()) << peak.bandwidth_note;
  EXPECT_TRUE(peak.compute_note.empty()) << peak.compute_note;
  ASSERT_EQ(peak.levels.size(), cache_working_sets(probe_buffer_bytes(rp::test::context().info)).size() + 1);
  EXPECT_EQ(peak.levels.back().gbps, peak.bandwidth_gbps) << "the last level is the DRAM stream";
  for (size_t i = 1; i < peak.levels.size(); ++i)
    EXPECT_GT(peak.levels[i].working_set_bytes, peak.levels[i - 1].working_set_bytes);
  ASSERT_TRUE(std::isfinite(peak.bandwidth_gbps) && std::isfinite(peak.gflops));
  EXPECT_GE(peak.bandwidth_gbps, 0.5);
  EXPECT_LE(peak.bandwidth_gbps, 500.0);
  EXPECT_GE(peak.gflops, 1.0);
  EXPECT_LE(peak.gflops, 100000.0);
  std::printf("peak: %.1f GB/s, %.1f GFLOP/s on %s (%s timing)\n", peak.bandwidth_gbps,
              peak.gflops, rp::test::context().info.name.c_str(),
              rp::cl::timing_name(peak.timing));
  for (const BandwidthLevel& l : peak.levels)
    std::printf("  working set %.0f KiB: %.1f GB/s\n", l.working_set_bytes / 1024, l.gbps);
}

}  // namespace
}  // namespace rp::bench
