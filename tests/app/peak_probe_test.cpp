// The device peak probe (kernels/probe.cl, src/app/peak_probe.cpp) on the test device.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "app/peak_probe.h"
#include "cl/error.h"
#include "support/cl_fixture.h"

namespace rp::app {
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

TEST(PeakProbe, MeasurePeakIsInAPlausibleRange) {
  const DevicePeak peak = measure_peak(rp::test::context(), rp::test::programs());
  ASSERT_TRUE(std::isfinite(peak.bandwidth_gbps) && std::isfinite(peak.gflops));
  EXPECT_GE(peak.bandwidth_gbps, 0.5);
  EXPECT_LE(peak.bandwidth_gbps, 500.0);
  EXPECT_GE(peak.gflops, 1.0);
  EXPECT_LE(peak.gflops, 100000.0);
  std::printf("peak: %.1f GB/s, %.1f GFLOP/s on %s\n", peak.bandwidth_gbps, peak.gflops,
              rp::test::context().info.name.c_str());
}

}  // namespace
}  // namespace rp::app
