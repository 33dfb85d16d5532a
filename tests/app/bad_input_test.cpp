// Bad input: each case gives one "rolypoly: error: ..." message, a non-zero
// exit code and leaves no half-written file. Cases already covered elsewhere (unknown option,
// unknown device, corrupt texture, kernel build failure, malformed replay, no ffmpeg) live in
// cli_errors_test.cpp, renderer_cli_test.cpp and simulation_cli_test.cpp.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <thread>

#include <stb/stb_image.h>

#include "app/render_session.h"
#include "kernels/shared/shadow_mips.h"
#include "passes/indirect.h"
#include "render/frame_memory.h"
#include "scene/demo_scene.h"
#include "support/cli_runner.h"

namespace rp::test {
namespace {

namespace fs = std::filesystem;

// Every entry of `dir` (files and folders, hidden ones included).
std::vector<std::string> all_entries(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  if (!std::filesystem::exists(dir)) return names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  return names;
}

TEST(BadInput, NoOpenClPlatformSaysWhatToInstall) {
  TempDir dir;
  std::filesystem::create_directories(dir / "vendors");  // ocl-icd finds no driver here
  CommandResult r = run_rolypoly("render --size 8 --out " + shell_quote((dir / "out").string()),
                                 "OCL_ICD_VENDORS=" + shell_quote((dir / "vendors").string()));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_TRUE(Contains(r.err, "rolypoly: error: no OpenCL platform found"));
  EXPECT_TRUE(Contains(r.err, "apt-get install pocl-opencl-icd"));
  EXPECT_TRUE(files_with_suffix(dir / "out", ".png").empty());
}

TEST(BadInput, ZeroNegativeAndNonNumericSizesSayWhatIsAllowed) {
  const std::pair<const char*, const char*> cases[] = {
      {"--size 0", "at least 1 pixel"},
      {"--size -5", "at least 1 pixel"},
      {"--width 0", "at least 1 pixel"},
      {"--height -1", "at least 1 pixel"},
      {"--size 12x", "not a whole number"},
      {"--size 99999", "above the limit of 16384"},
  };
  for (const auto& [args, why] : cases) {
    CommandResult r = run_rolypoly(std::string("render ") + args + " --out /nonexistent/x");
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_TRUE(Contains(r.err, "rolypoly: error: "));
    EXPECT_TRUE(Contains(r.err, std::string(args).substr(0, std::string(args).find(' '))));
    EXPECT_TRUE(Contains(r.err, why)) << args;
    EXPECT_TRUE(Contains(r.err, "give 1 to 16384 pixels")) << args;
  }
}

// --texture-filter (render, run, bench) takes three names; anything else is a usage error that
// names the option and the choices, before any device work.
TEST(BadInput, UnknownTextureFilterNamesTheChoices) {
  for (const char* command : {"render", "run", "bench"}) {
    for (const char* value : {"nearest", "Trilinear", "''"}) {
      const std::string out = std::string(command) == "render" ? " --out /nonexistent/x" : "";
      CommandResult r =
          run_rolypoly(std::string(command) + " --texture-filter " + value + out);
      EXPECT_EQ(r.exit_code, 2) << command << " " << value << "\n" << r.err;
      EXPECT_TRUE(Contains(r.err, "rolypoly: error: --texture-filter")) << command;
      EXPECT_TRUE(Contains(r.err, "{bilinear,trilinear,anisotropic}")) << command;
    }
  }
}

// --shadows takes hard, pcf, pcss or vssm in render, run and bench; anything else is one usage
// message naming the option and the choices (before any device or window is opened).
TEST(BadInput, UnknownShadowModeSaysWhichExist) {
  for (const char* sub : {"render --out /nonexistent/x", "run", "bench"})
    for (const char* bad : {"soft", "PCSS", "\"\""}) {
      CommandResult r = run_rolypoly(std::string(sub) + " --shadows " + bad);
      EXPECT_EQ(r.exit_code, 2) << sub << " " << bad << "\n" << r.err;
      EXPECT_TRUE(Contains(r.err, "rolypoly: error: --shadows: "));
      EXPECT_TRUE(Contains(r.err, "not in {hard,pcf,pcss,vssm}")) << sub << " " << bad;
      EXPECT_TRUE(r.out.empty()) << r.out;
    }
  CommandResult pt = run_rolypoly("render --quality pathtraced --shadows pcf --out /nonexistent/x");
  EXPECT_EQ(pt.exit_code, 2) << pt.err;
  EXPECT_TRUE(Contains(pt.err, "--shadows does not apply to --quality pathtraced"));
}

// The estimate: the image's buffers as the passes state them (tests/render/frame_memory_test.cpp
// holds those against real frames) as the window may switch them (every effect, both soft
// shadow modes' buffers), the dense volume and the scene's reserve written out by hand.
TEST(BadInput, DeviceMemoryEstimateCountsEveryBuffer) {
  render::RenderSettings s;
  s.width = s.height = 160;
  s.shadow_size = 64;
  s.voxel_resolution = 32;
  s.effects.taa = s.effects.bloom = s.effects.motion_blur = false;  // keys T, B, M turn them on
  s.shadows = render::ShadowMode::kHard;                            // key H switches
  const app::DeviceMemoryNeed need = app::estimate_device_memory(s);
  render::RenderSettings vssm = s;
  vssm.effects = render::Effects{};
  vssm.shadows = render::ShadowMode::kVssm;
  const uint64_t pixels = 25600;
  // vssm's buffers, and pcss's verdicts: a byte per 4x2-pixel chunk, 40 x 80 of them.
  const uint64_t frame = render::frame_memory(vssm, {}).total() + 40 * 80;
  EXPECT_EQ(need.image_bytes + need.shadow_bytes, frame);
  // The lamp's two depth planes, vssm's three mip planes, the raster's tile lists (4 x 4 tiles
  // of 16 texels: 3 lists of 2 uints each).
  EXPECT_EQ(need.shadow_bytes, 2 * 64 * 64 * 4 + 3 * uint64_t(gpu::rp_shadow_mip_total(64)) * 4 +
                                   16 * 3 * 2 * 4);
  const uint64_t voxels = 32 * 32 * 32;
  // Chain: level 0 (32^3) plus six volumes of 16^3, 8^3, 4^3, 2^3, 1: float4 each.
  const uint64_t chain = voxels + 6 * (4096 + 512 + 64 + 8 + 1);
  const uint64_t expected = frame + chain * 16 + voxels * 36 + (uint64_t(64) << 20);
  EXPECT_EQ(need.total_bytes, expected);
  // The largest single buffer: a float4 per pixel, or the voxel chain (here the chain).
  EXPECT_EQ(need.largest_buffer_bytes, std::max(pixels * 16, chain * 16));
  // The direct / indirect / specular views add three float4 per pixel.
  render::FrameMemoryOptions components;
  components.light_components = true;
  EXPECT_EQ(app::estimate_device_memory(s, components).total_bytes, expected + pixels * 48);
  // The reference mode keeps the previous frame's output (float4 per pixel) for its SSR and
  // has no low-resolution indirect planes.
  render::RenderSettings reference = s;
  reference.quality = render::Quality::kReference;
  EXPECT_EQ(app::estimate_device_memory(reference).total_bytes,
            expected + pixels * 16 - passes::IndirectPass::frame_bytes(160, 160));
}

TEST(BadInput, LargestSquareThatFitsIsTheBoundary) {
  const uint64_t global = uint64_t(6) << 30, max_alloc = uint64_t(1) << 30;
  const render::RenderSettings defaults;
  uint32_t s = app::largest_square_that_fits(global, max_alloc, defaults);
  ASSERT_GT(s, 1000u);
  auto fits = [&](uint32_t side) {
    render::RenderSettings at = defaults;
    at.width = at.height = side;
    app::DeviceMemoryNeed n = app::estimate_device_memory(at);
    return n.total_bytes <= global && n.largest_buffer_bytes <= max_alloc;
  };
  EXPECT_TRUE(fits(s));
  EXPECT_FALSE(fits(s + 1));
  // 1 GiB per buffer of 16 bytes per pixel limits the side to 8192.
  EXPECT_EQ(app::largest_square_that_fits(uint64_t(1) << 40, max_alloc, defaults), 8192u);
}

TEST(BadInput, CheckDeviceMemoryNamesTheNeedAndWhatFits) {
  cl::DeviceInfo device;
  device.name = "small";
  device.global_mem_bytes = uint64_t(2) << 30;
  device.max_alloc_bytes = uint64_t(1) << 30;
  const auto at = [](uint32_t side) {
    render::RenderSettings s;
    s.width = s.height = side;
    return s;
  };
  EXPECT_NO_THROW(app::check_device_memory(device, at(720)));
  try {
    app::check_device_memory(device, at(16384));
    FAIL() << "16384x16384 cannot fit 2 GiB";
  } catch (const cl::Error& e) {
    std::string m = e.what();
    EXPECT_TRUE(Contains(m, "16384x16384 needs "));
    EXPECT_TRUE(Contains(m, "GiB of device memory, the device has 2.0 GiB"));
    uint32_t s = app::largest_square_that_fits(device.global_mem_bytes, device.max_alloc_bytes,
                                               render::RenderSettings{});
    EXPECT_TRUE(Contains(m, "largest square size that fits is about " + std::to_string(s)));
  }
  device.global_mem_bytes = uint64_t(64) << 30;  // enough in total, but not in one buffer
  try {
    app::check_device_memory(device, at(10000));
    FAIL() << "a 1.5 GiB buffer is above the 1 GiB limit";
  } catch (const cl::Error& e) {
    EXPECT_TRUE(Contains(e.what(), "the device allows at most 1.0 GiB per buffer"));
    EXPECT_TRUE(Contains(e.what(), "about 8192"));
  }
}

// The binary: a size too large for this device fails before kernel builds or allocations.
TEST(BadInput, SizeTooLargeForTheDeviceSaysWhatFits) {
  CommandResult devices = run_rolypoly("devices");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(devices.out, m, std::regex("global memory ([0-9]+) MiB")))
      << devices.out;
  if (std::stoull(m[1].str()) > 40000)  // 16384^2 needs about 48 GiB: it might really fit
    GTEST_SKIP() << "device 0 has " << m[1].str() << " MiB: 16384x16384 might fit";
  TempDir dir;
  auto start = std::chrono::steady_clock::now();
  CommandResult r = run_rolypoly("render --size 16384 --out " + shell_quote((dir / "out").string()));
  double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_TRUE(Contains(r.err, "rolypoly: error: 16384x16384 needs "));
  EXPECT_TRUE(Contains(r.err, "largest square size that fits is about "));
  EXPECT_LT(seconds, 10.0) << "the check comes before the kernel builds";
  EXPECT_TRUE(files_with_suffix(dir / "out", ".png").empty());
}

TEST(BadInput, OutputFolderThatCannotBeWrittenFailsBeforeRendering) {
  TempDir dir;
  std::ofstream(dir / "a_file") << "not a folder";
  const std::pair<std::string, std::string> cases[] = {
      {(dir / "a_file" / "out").string(), "cannot create output folder"},
      {"/proc/rolypoly-out", "cannot create output folder"},
      {"/proc/self", "cannot write into output folder"},  // exists, but takes no new files
  };
  for (const auto& [out, why] : cases) {
    auto start = std::chrono::steady_clock::now();
    CommandResult r = run_rolypoly("render --size 8 --out " + shell_quote(out));
    double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.exit_code, 1) << out << "\n" << r.out << r.err;
    EXPECT_TRUE(Contains(r.err, "rolypoly: error: " + why + " " + out)) << out;
    EXPECT_TRUE(r.out.find("device") == std::string::npos) << "failed before the device";
    EXPECT_LT(seconds, 5.0) << out;
  }
}

TEST(BadInput, MissingTextureNamesTheFile) {
  TempDir dir;
  std::filesystem::path assets = dir / "assets";
  std::filesystem::copy(scene::default_asset_dir(), assets,
                        std::filesystem::copy_options::recursive);
  ASSERT_TRUE(std::filesystem::remove(assets / "wood.png")) << "the demo's floor texture";
  CommandResult r = run_rolypoly("render --size 8 --assets " + shell_quote(assets.string()) +
                                 " --out " + shell_quote((dir / "out").string()));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_TRUE(Contains(r.err, "rolypoly: error:"));
  EXPECT_TRUE(Contains(r.err, (assets / "wood.png").string()));
  // The system's reason, not stb_image's "can't fopen".
  EXPECT_TRUE(Contains(r.err, (assets / "wood.png").string() + ": No such file or directory"));
  EXPECT_TRUE(files_with_suffix(dir / "out", ".png").empty());
}

// A FIFO where a texture should be used to block the texture loader until a writer came.
TEST(BadInput, TextureThatIsAFifoIsRefusedWithoutWaiting) {
  TempDir dir;
  std::filesystem::path assets = dir / "assets";
  std::filesystem::copy(scene::default_asset_dir(), assets,
                        std::filesystem::copy_options::recursive);
  ASSERT_TRUE(std::filesystem::remove(assets / "wood.png"));
  ASSERT_EQ(::mkfifo((assets / "wood.png").c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  CommandResult r = run_rolypoly("render --size 8 --assets " + shell_quote(assets.string()) +
                                 " --out " + shell_quote((dir / "out").string()));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_TRUE(Contains(r.err, (assets / "wood.png").string() + ": is not a regular file"));
  EXPECT_LT(seconds, 30.0);  // no wait for a writer (the device set-up is most of it)
}

// Usage errors are found before any device work, with exit 2: the voxel view's --level used to
// fail after the kernel builds (exit 1), `bench --devices ,` once the device list was read.
TEST(BadInput, UsageErrorsFoundLateBeforeExitTwoAtOnce) {
  const std::pair<const char*, const char*> cases[] = {
      {"render --view voxels --level 31 --out /nonexistent/x",
       "rolypoly render: --level 31: --view voxels of the dense volume at 64^3 has levels 0 to 6"},
      {"run --view voxels --voxels 32 --level 6",
       "rolypoly run: --level 6: --view voxels of the dense volume at 32^3 has levels 0 to 5"},
      {"render --gi-volume svo --view voxels --level 8 --out /nonexistent/x",
       "--view voxels of the octree at 256^3 has levels 0 to 7"},
      {"bench --devices ,", "--devices: empty entry in ','"},
      {"bench --devices 0,", "--devices: empty entry in '0,'"},
  };
  for (const auto& [args, why] : cases) {
    const auto start = std::chrono::steady_clock::now();
    CommandResult r = run_rolypoly(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_TRUE(Contains(r.err, why)) << args;
    EXPECT_EQ(r.out, "") << args;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
              5.0)
        << args;
  }
}

// --replay names what is wrong with the file, with the system's reason, and never echoes more of
// the log than a terminal can take: a directory said "read error"; a NUL byte cut the message
// short; a 5 MB word was echoed whole, control characters and all.
TEST(BadInput, ReplayFileErrorsSayWhatIsWrong) {
  TempDir dir;
  const std::string out = " --out " + shell_quote((dir / "out").string());
  fs::create_directories(dir / "logdir");
  CommandResult r = run_rolypoly("render --replay " + shell_quote((dir / "logdir").string()) + out);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(Contains(r.err, "rolypoly: error: --replay: cannot read " +
                                  (dir / "logdir").string() + ": Is a directory"));
  r = run_rolypoly("render --replay " + shell_quote((dir / "missing.log").string()) + out);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(Contains(r.err, (dir / "missing.log").string() + ": No such file or directory"));

  write_plain(dir / "nul.log", std::string("rolypoly-input 1\nstep 1 key A\nstep 2 ke") + '\0' +
                                   "y B\n");
  r = run_rolypoly("render --replay " + shell_quote((dir / "nul.log").string()) + out);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err, "rolypoly: error: " + (dir / "nul.log").string() +
                       ":3: a NUL byte: this is a binary file, not an input log\n");

  write_plain(dir / "long.log", "rolypoly-input 1\nstep 1 " + std::string(5000000, 'x') +
                                    "\x1b[31m\x07 key A\n");
  r = run_rolypoly("render --replay " + shell_quote((dir / "long.log").string()) + out);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_LT(r.err.size(), 1000u);
  EXPECT_TRUE(Contains(r.err, (dir / "long.log").string() + ":2: unknown event 'xxxx"));
  EXPECT_TRUE(Contains(r.err, "bytes left out"));
  EXPECT_TRUE(Contains(r.err, "\\x1b[31m\\x07'"));
  for (const char c : r.err.substr(0, r.err.size() - 1))
    EXPECT_TRUE(c >= 0x20 && c < 0x7f) << "byte " << int(c);
  EXPECT_TRUE(files_with_suffix(dir / "out", ".png").empty());
}

// Option values are echoed cut and printable too.
TEST(BadInput, EchoedOptionValuesAreCutAndPrintable) {
  const std::string value = std::string(100000, '7') + "\x1b[2J";
  CommandResult r = run_rolypoly("render --out /nonexistent/x --size " + shell_quote(value));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_LT(r.err.size(), 1000u);
  EXPECT_TRUE(Contains(r.err, "bytes left out"));
  EXPECT_TRUE(Contains(r.err, "\\x1b[2J"));
  r = run_rolypoly("render --out /nonexistent/x --texture-filter " + shell_quote("a\x1b[31mb"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
}

// Ctrl-C during a headless render: the frames written so far are whole PNGs, no temporary file
// remains, exit code 130 and "interrupted after N frames".
TEST(BadInput, InterruptDuringRenderKeepsCompleteFramesOnly) {
  TempDir dir;
  const std::filesystem::path out = dir / "out", err_file = dir / "err.txt";
  pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (!std::freopen(err_file.c_str(), "w", stderr) || !std::freopen("/dev/null", "w", stdout))
      _exit(99);
    execl(ROLYPOLY_BINARY, ROLYPOLY_BINARY, "render", "--frames", "1000", "--size", "32",
          "--out", out.c_str(), static_cast<char*>(nullptr));
    _exit(98);
  }
  // Wait (up to a minute: kernel builds come first) until a few frames exist.
  auto start = std::chrono::steady_clock::now();
  while (files_with_suffix(out, ".png").size() < 3 &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_GE(files_with_suffix(out, ".png").size(), 3u);
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by a signal, not by the handler";
  EXPECT_EQ(WEXITSTATUS(status), 130);

  std::ifstream err_in(err_file);
  std::string err((std::istreambuf_iterator<char>(err_in)), std::istreambuf_iterator<char>());
  std::vector<std::string> pngs = files_with_suffix(out, ".png");
  EXPECT_LT(pngs.size(), 1000u);
  EXPECT_TRUE(Contains(err, "rolypoly: error: interrupted after " + std::to_string(pngs.size()) +
                                " frames"));
  for (const std::string& entry : all_entries(out))  // only frame_NNNN.png, nothing else
    EXPECT_TRUE(std::regex_match(entry, std::regex("frame_[0-9]{4}\\.png"))) << entry;
  for (size_t i = 0; i < pngs.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04zu.png", i);
    EXPECT_TRUE(std::filesystem::exists(out / name)) << "frames are numbered without gaps";
    int w = 0, h = 0, channels = 0;
    unsigned char* pixels = stbi_load((out / name).c_str(), &w, &h, &channels, 4);
    EXPECT_NE(pixels, nullptr) << name << " does not decode";
    EXPECT_EQ(w, 32);
    EXPECT_EQ(h, 32);
    stbi_image_free(pixels);
  }
}

}  // namespace
}  // namespace rp::test
