// A second OpenCL implementation in CI: Mesa's rusticl on llvmpipe (Debian package
// mesa-opencl-icd, devices only with RUSTICL_ENABLE=llvmpipe, which this test's environment
// sets) renders the same small frame as PoCL, to PSNR >= 60 dB. Label `rusticl`, run by the
// plain ctest. Without the package the test is skipped, except under CI=true (tools/setup.sh
// installs it there), where a missing rusticl device fails.
//
// rusticl compiles every kernel for minutes on first use (clang to SPIR-V to NIR to llvmpipe's
// LLVM, the slow part: at each kernel's first launch); Mesa's shader cache
// (~/.cache/mesa_shader_cache, or MESA_SHADER_CACHE_DIR) keeps the builds, so the kernel tests
// that run on rusticl after this frame (rusticl.kernel_tests) and later runs on a machine whose
// home folder persists skip them (measured: 6.4 s for a 128x128 frame with a warm cache).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <string>

#include "support/cli_runner.h"
#include "support/image_metrics.h"

namespace rp::test {
namespace {

bool in_ci() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::string(ci) == "true";
}

// True when `rolypoly devices` lists a rusticl device; a skip or a failure otherwise.
bool rusticl_listed(std::string& why) {
  CommandResult r = run_rolypoly("devices");
  if (r.exit_code != 0) {
    why = "rolypoly devices failed: " + r.err;
    return false;
  }
  if (r.out.find("rusticl") == std::string::npos) {
    why = "no rusticl device (apt-get install mesa-opencl-icd; RUSTICL_ENABLE=llvmpipe):\n" +
          r.out;
    return false;
  }
  return true;
}

TEST(Rusticl, DevicesListsIt) {
  std::string why;
  if (!rusticl_listed(why)) {
    if (in_ci()) FAIL() << why;
    GTEST_SKIP() << why;
  }
  CommandResult r = run_rolypoly("devices");
  EXPECT_NE(r.out.find("llvmpipe"), std::string::npos) << r.out;
}

TEST(Rusticl, FrameMatchesPocl) {
  std::string why;
  if (!rusticl_listed(why)) {
    if (in_ci()) FAIL() << why;
    GTEST_SKIP() << why;
  }
  TempDir dir;
  const std::string args = "render --size 64 --frames 1 --voxels 32 --shadow-size 128 --out ";
  CommandResult pocl =
      run_rolypoly(args + shell_quote((dir / "pocl").string()) + " --device 'Portable Computing'");
  ASSERT_EQ(pocl.exit_code, 0) << pocl.command << "\n" << pocl.out << pocl.err;
  const auto t0 = std::chrono::steady_clock::now();
  CommandResult mesa =
      run_rolypoly(args + shell_quote((dir / "rusticl").string()) + " --device rusticl");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(mesa.exit_code, 0) << mesa.command << "\n" << mesa.out << mesa.err;
  std::printf("rusticl: first frame (kernel builds included) %.1f s\n%s", seconds,
              mesa.out.c_str());
  const Rgba8Image a = load_png((dir / "pocl" / "frame_0000.png").string());
  const Rgba8Image b = load_png((dir / "rusticl" / "frame_0000.png").string());
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  const double psnr = psnr_rgb8(a.rgba, b.rgba);
  std::printf("rusticl vs PoCL: PSNR %.1f dB\n", psnr);
  EXPECT_GE(psnr, 60.0);
}

}  // namespace
}  // namespace rp::test
