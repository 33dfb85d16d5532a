// `render --quality pathtraced`, `bench --quality pathtraced` and `render --exr` through the
// built binary: the files they write, how their EXR layers add up, and their usage errors; and
// the host-side 8-bit encode and progress ETA they use.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/host_tone_map.h"
#include "app/progress.h"
#include "app/render_session.h"
#include "cl/context.h"
#include "support/cli_runner.h"
#include "support/image_metrics.h"
#include "truth/exr_io.h"

namespace rp::test {
namespace {

struct Layers {
  uint32_t width = 0, height = 0;
  std::vector<float> combined, direct, indirect, emission, albedo;
};

Layers read_layers(const std::filesystem::path& path) {
  Layers l;
  uint32_t w = 0, h = 0;
  l.combined = rp::truth::read_exr_layer(path, "", l.width, l.height);
  for (auto [name, dest] : {std::pair{"direct", &l.direct}, std::pair{"indirect", &l.indirect},
                            std::pair{"emission", &l.emission}, std::pair{"albedo", &l.albedo}}) {
    *dest = rp::truth::read_exr_layer(path, name, w, h);
    EXPECT_EQ(w, l.width) << name;
    EXPECT_EQ(h, l.height) << name;
  }
  return l;
}

// combined == direct + indirect + emission per channel within `relative` of the larger side
// plus `absolute`; every value finite and non-negative, albedo at most 1, and some light.
void expect_layers_add_up(const Layers& l, double relative, double absolute) {
  const size_t n = size_t(l.width) * l.height * 3;
  ASSERT_EQ(l.combined.size(), n);
  size_t bad = 0, lit = 0;
  for (size_t i = 0; i < n; ++i) {
    const double c = l.combined[i];
    const double sum = double(l.direct[i]) + l.indirect[i] + l.emission[i];
    for (auto [name, v] : {std::pair{"combined", l.combined[i]}, std::pair{"direct", l.direct[i]},
                           std::pair{"indirect", l.indirect[i]},
                           std::pair{"emission", l.emission[i]}, std::pair{"albedo", l.albedo[i]}})
      ASSERT_TRUE(std::isfinite(v) && v >= 0.0f)
          << name << " value " << v << " at float " << i;
    EXPECT_LE(l.albedo[i], 1.0f);
    if (std::abs(c - sum) > relative * std::max(std::abs(c), std::abs(sum)) + absolute && ++bad < 5)
      ADD_FAILURE() << "float " << i << ": combined " << c << " but direct + indirect + emission "
                    << sum;
    lit += c > 0.0 ? 1 : 0;
  }
  EXPECT_EQ(bad, 0u);
  EXPECT_GT(lit, n / 2) << "most of a Cornell box frame is lit";
}

TEST(PathtraceCli, RenderWritesPngAndExrWhoseLayersAddUp) {
  TempDir dir;
  CommandResult r = run_rolypoly("render --quality pathtraced --size 16 --spp 4 --bounces 1 "
                                 "--out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.command << "\n" << r.out << r.err;
  EXPECT_EQ(files_with_suffix(dir.path(), ""),
            (std::vector<std::string>{"frame_0000.exr", "frame_0000.png"}));
  EXPECT_TRUE(Contains(r.out, "path traced 16x16, 4 spp, 1 bounce: "));
  EXPECT_TRUE(Contains(r.out, "Mrays/s"));
  EXPECT_TRUE(Contains(r.out, (dir / "frame_0000.exr").string()));
  EXPECT_FALSE(Contains(r.out, "device ")) << "no OpenCL device is opened";

  const Layers l = read_layers(dir / "frame_0000.exr");
  EXPECT_EQ(l.width, 16u);
  EXPECT_EQ(l.height, 16u);
  expect_layers_add_up(l, 1e-5, 1e-9);

  // The PNG is the combined layer through the renderer's tone map and sRGB encode, no dither.
  const Rgba8Image png = load_png((dir / "frame_0000.png").string());
  ASSERT_EQ(png.width, 16);
  ASSERT_EQ(png.height, 16);
  for (size_t p = 0; p < 16 * 16; ++p) {
    for (size_t c = 0; c < 3; ++c)
      ASSERT_EQ(png.rgba[4 * p + c], rp::app::tone_map_code(l.combined[3 * p + c])) << p;
    ASSERT_EQ(png.rgba[4 * p + 3], 255);
  }
}

TEST(PathtraceCli, AlbedoViewIsSrgbWithoutToneMap) {
  TempDir dir;
  CommandResult r = run_rolypoly("render --quality pathtraced --size 8 --spp 1 --view albedo "
                                 "--bounces 0 --out " + shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(Contains(r.out, "8x8, 1 spp, 0 bounces"));
  uint32_t w = 0, h = 0;
  const std::vector<float> albedo = rp::truth::read_exr_layer(dir / "frame_0000.exr", "albedo", w, h);
  const Rgba8Image png = load_png((dir / "frame_0000.png").string());
  ASSERT_EQ(png.rgba.size(), size_t(w) * h * 4);
  for (size_t p = 0; p < size_t(w) * h; ++p)
    for (size_t c = 0; c < 3; ++c)
      ASSERT_EQ(png.rgba[4 * p + c], rp::app::srgb_code(albedo[3 * p + c])) << p;
}

TEST(PathtraceCli, UsageErrors) {
  for (const std::string& args : {std::string("render --spp 4"), std::string("bench --spp 4")}) {
    CommandResult r = run_rolypoly(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_TRUE(Contains(r.err, "--spp applies to --quality pathtraced")) << args;
  }
  CommandResult lamp = run_rolypoly("render --lamp area");
  EXPECT_EQ(lamp.exit_code, 2);
  EXPECT_TRUE(Contains(lamp.err, "--lamp applies to --quality pathtraced")) << lamp.err;
  CommandResult bad_lamp = run_rolypoly("render --quality pathtraced --lamp disc");
  EXPECT_EQ(bad_lamp.exit_code, 2) << bad_lamp.err;
  CommandResult zero = run_rolypoly("render --bounces 0");
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_TRUE(Contains(zero.err, "--bounces 0 applies to --quality pathtraced")) << zero.err;
  CommandResult view = run_rolypoly("render --quality pathtraced --view normal");
  EXPECT_EQ(view.exit_code, 2);
  EXPECT_TRUE(Contains(view.err, "--view normal is not available with --quality pathtraced; use "
                                 "final, direct, indirect or albedo"));
  CommandResult bench = run_rolypoly("bench --quality pathtraced --sizes 16,32");
  EXPECT_EQ(bench.exit_code, 2);
  EXPECT_TRUE(Contains(bench.err, "--quality pathtraced"));
}

TEST(PathtraceCli, BenchPrintsFramesAndWritesJson) {
  TempDir dir;
  const std::filesystem::path json_path = dir / "sub" / "pt.json";
  CommandResult r = run_rolypoly("bench --quality pathtraced --size 8 --spp 2 --frames 2 "
                                 "--bounces 1 --warmup 1 --json " +
                                 shell_quote(json_path.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(Contains(r.out, "Mrays/s"));
  EXPECT_TRUE(Contains(r.out, "median"));
  std::ifstream in(json_path);
  ASSERT_TRUE(in.good()) << "no JSON file written";
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("schema"), "rolypoly-pathtrace-bench/1");
  EXPECT_EQ(j.at("size"), nlohmann::json::array({8, 8}));
  EXPECT_EQ(j.at("spp"), 2);
  EXPECT_EQ(j.at("bounces"), 1);
  EXPECT_EQ(j.at("frames"), 2);
  EXPECT_EQ(j.at("warmup"), 1);
  ASSERT_EQ(j.at("runs").size(), 2u) << "measured frames only";
  for (const auto& run : j.at("runs")) {
    EXPECT_GT(run.at("seconds").get<double>(), 0.0);
    EXPECT_GT(run.at("rays").get<uint64_t>(), 8u * 8u * 2u);
    EXPECT_GT(run.at("mrays_per_s").get<double>(), 0.0);
  }
  EXPECT_GT(j.at("median").at("mrays_per_s").get<double>(), 0.0);
}

// SIGINT while a frame is path traced: the tracer is cancelled, nothing is written, exit 130.
TEST(PathtraceCli, InterruptCancelsTheFrameAndWritesNothing) {
  TempDir dir;
  const std::filesystem::path out = dir / "out", err_file = dir / "err.txt";
  pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (!std::freopen(err_file.c_str(), "w", stderr) || !std::freopen("/dev/null", "w", stdout))
      _exit(99);
    // Minutes of work on two cores (a row about a second): it can only end early by being
    // cancelled, which happens between rows.
    execl(ROLYPOLY_BINARY, ROLYPOLY_BINARY, "render", "--quality", "pathtraced", "--size", "512",
          "--spp", "10000", "--bounces", "1", "--out", out.c_str(), static_cast<char*>(nullptr));
    _exit(98);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // handler installed at start
  ASSERT_EQ(kill(pid, SIGINT), 0);
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  pid_t done = 0;
  while ((done = waitpid(pid, &status, WNOHANG)) == 0 &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(30))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (done == 0) {
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    FAIL() << "the path tracer did not stop within 30 s of SIGINT";
  }
  ASSERT_TRUE(WIFEXITED(status)) << "ended by the signal, not by the handler";
  EXPECT_EQ(WEXITSTATUS(status), 130);
  std::ifstream err_in(err_file);
  const std::string err((std::istreambuf_iterator<char>(err_in)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(Contains(err, "rolypoly: error: interrupted after 0 frames (no frame was written)"));
  EXPECT_TRUE(files_with_suffix(out, "").empty());
}

TEST(RenderExr, RealTimeLayersAddUpAndMatchTheAlbedoView) {
  TempDir dir;
  CommandResult r = run_rolypoly("render --exr --size 16 --no-taa --out " +
                                 shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.command << "\n" << r.out << r.err;
  EXPECT_EQ(files_with_suffix(dir.path(), ""),
            (std::vector<std::string>{"frame_0000.exr", "frame_0000.png"}));
  const Layers l = read_layers(dir / "frame_0000.exr");
  EXPECT_EQ(l.width, 16u);
  EXPECT_EQ(l.height, 16u);
  expect_layers_add_up(l, 1e-4, 1e-6);

  // With a view that does not need the components (albedo) they are still written, and the
  // EXR's albedo is what that view encodes (the kernels' sRGB polynomial is within 7e-6).
  TempDir view_dir;
  CommandResult v = run_rolypoly("render --exr --size 16 --no-taa --view albedo --out " +
                                 shell_quote(view_dir.path().string()));
  ASSERT_EQ(v.exit_code, 0) << v.out << v.err;
  const Layers a = read_layers(view_dir / "frame_0000.exr");
  expect_layers_add_up(a, 1e-4, 1e-6);
  const Rgba8Image png = load_png((view_dir / "frame_0000.png").string());
  ASSERT_EQ(png.rgba.size(), size_t(16) * 16 * 4);
  for (size_t p = 0; p < 16 * 16; ++p)
    for (size_t c = 0; c < 3; ++c)
      ASSERT_NEAR(int(png.rgba[4 * p + c]), int(rp::app::srgb_code(a.albedo[3 * p + c])), 1) << p;
}

// The kept components (48 bytes per pixel) count in the device memory check: a size between the
// largest that fits with them and the largest without fails at once, before any allocation.
TEST(RenderExr, MemoryCheckCountsTheKeptComponents) {
  const rp::cl::DeviceInfo device = rp::cl::choose_device("");
  const auto largest = [&](bool components) {
    rp::render::FrameMemoryOptions frame;
    frame.light_components = components;
    return rp::app::largest_square_that_fits(device.global_mem_bytes, device.max_alloc_bytes,
                                             rp::render::RenderSettings{}, frame);
  };
  const uint32_t with = largest(true), without = largest(false);
  // Halfway: a margin of a few per cent against the free memory PoCL reports changing.
  const uint32_t size = with + (without - with) / 2;
  if (device.global_mem_bytes == 0 || without > 16384 || without - with < 16)
    GTEST_SKIP() << "device memory " << device.global_mem_bytes << " bytes: no size to test";
  TempDir dir;
  const auto start = std::chrono::steady_clock::now();
  CommandResult r = run_rolypoly("render --exr --size " + std::to_string(size) + " --out " +
                                 shell_quote(dir.path().string()));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_TRUE(Contains(r.err, std::to_string(size) + "x" + std::to_string(size) + " needs "));
  EXPECT_LT(seconds, 10.0) << "the check comes before the kernel builds and allocations";
  EXPECT_TRUE(files_with_suffix(dir.path(), "").empty());
}

TEST(HostToneMap, MatchesTheRenderersOperatorAndCurve) {
  EXPECT_EQ(rp::app::tone_map_code(0.0f), 0);
  EXPECT_EQ(rp::app::tone_map_code(1.0f), 188);  // T = 0.5, sRGB 0.7354, 187.5 rounds up
  EXPECT_EQ(rp::app::tone_map_code(-1.0f), 0);
  EXPECT_EQ(rp::app::tone_map_code(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(rp::app::tone_map_code(std::numeric_limits<float>::infinity()), 255);
  EXPECT_EQ(rp::app::tone_map_code(1e6f), 255);
  EXPECT_EQ(rp::app::srgb_code(0.5f), 188);
  EXPECT_EQ(rp::app::srgb_code(0.001f), 3);  // linear segment: 12.92e-3 * 255 = 3.29
  EXPECT_EQ(rp::app::srgb_code(2.0f), 255);
  std::vector<uint8_t> rgba;
  rp::app::encode_rgba8({1.0f, 0.0f, 1e6f}, true, rgba);
  EXPECT_EQ(rgba, (std::vector<uint8_t>{188, 0, 255, 255}));
}

TEST(Progress, EtaFromTheRateSoFar) {
  using rp::app::ProgressBar;
  EXPECT_EQ(ProgressBar::eta_text(10.0, 1, 4), ", ETA 30s");
  EXPECT_EQ(ProgressBar::eta_text(60.0, 1, 3), ", ETA 2m00s");
  EXPECT_EQ(ProgressBar::eta_text(3600.0, 1, 2), ", ETA 1h00m");
  EXPECT_EQ(ProgressBar::eta_text(0.5, 1, 4), "") << "too early to tell";
  EXPECT_EQ(ProgressBar::eta_text(10.0, 0, 4), "");
  EXPECT_EQ(ProgressBar::eta_text(10.0, 4, 4), "");
}

}  // namespace
}  // namespace rp::test
