// "Nothing lost, nothing destroyed", through the binary: a full disk (injected with
// ROLYPOLY_FAIL_WRITE_AFTER everywhere, real on a tiny tmpfs where root may mount one) stops
// render, bench and run with the file and the reason, keeps complete files and leaves no partial
// one; bench checks its outputs before measuring; devices, FIFOs and symlinks given as outputs
// are written, not replaced.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/image_metrics.h"
#include "tiny_tmpfs.h"
#include "xvfb_server.h"

namespace rp::test {
namespace {

constexpr const char* kTinyBench = "bench --size 16 --voxels 32 --frames 1 --warmup 0";

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

std::string fail_after(size_t bytes) {
  return "ROLYPOLY_FAIL_WRITE_AFTER=" + std::to_string(bytes);
}

mode_t file_type(const std::filesystem::path& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0 ? (st.st_mode & S_IFMT) : 0;
}

// Reads a FIFO without ever blocking the test: opened non-blocking before the writer starts
// (so the writer's open succeeds), drained until the writer is gone and finish() was called.
class FifoReader {
 public:
  explicit FifoReader(const std::filesystem::path& fifo)
      : fd_(::open(fifo.c_str(), O_RDONLY | O_NONBLOCK)), thread_([this] { loop(); }) {}
  ~FifoReader() {
    if (thread_.joinable()) finish();
  }
  std::string finish() {
    done_ = true;
    thread_.join();
    ::close(fd_);
    return data_;
  }

 private:
  void loop() {
    char buffer[65536];
    for (;;) {
      const bool last = done_;  // read once more after the writer ended
      ssize_t n;
      while ((n = ::read(fd_, buffer, sizeof buffer)) > 0) data_.append(buffer, size_t(n));
      if (last || fd_ < 0) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  int fd_;
  std::atomic<bool> done_{false};
  std::string data_;
  std::thread thread_;
};

TEST(OutputIntegrityCli, RenderStopsAtAFullDiskKeepingCompleteFrames) {
  TempDir dir;
  const auto good = dir / "good", full = dir / "full";
  CommandResult ok =
      run_rolypoly("render --size 32 --frames 2 --out " + shell_quote(good.string()));
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const std::string frame0 = read_all(good / "frame_0000.png");
  // The disk fills 100 bytes into the second frame, whose older version must survive.
  std::filesystem::create_directories(full);
  write_plain(full / "frame_0001.png", "frame 1 of an earlier run");
  CommandResult r = run_rolypoly("render --size 32 --frames 3 --out " + shell_quote(full.string()),
                                 fail_after(frame0.size() + 100));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "cannot write " + (full / "frame_0001.png").string() +
                                  ": No space left on device"))
      << r.err;
  EXPECT_FALSE(contains(r.out, "wrote")) << r.out;
  EXPECT_EQ(read_all(full / "frame_0000.png"), frame0);
  EXPECT_EQ(read_all(full / "frame_0001.png"), "frame 1 of an earlier run");
  EXPECT_EQ(entries(full), (std::vector<std::string>{"frame_0000.png", "frame_0001.png"}));
}

TEST(OutputIntegrityCli, RenderOnATinyTmpfsLeavesOnlyWholeFrames) {
  TinyTmpfs disk(20);  // room for about two 64x64 frames
  if (!disk.ok()) GTEST_SKIP() << disk.reason();
  const auto out = disk.path() / "frames";
  CommandResult r = run_rolypoly("render --size 64 --frames 4 --out " + shell_quote(out.string()));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, ": No space left on device")) << r.err;
  const std::vector<std::string> names = entries(out);
  ASSERT_LT(names.size(), 4u);
  // The first frame that did not fit is named; every one before it is whole.
  EXPECT_TRUE(contains(r.err, "frame_000" + std::to_string(names.size()) + ".png")) << r.err;
  for (const std::string& name : names) {
    ASSERT_EQ(name.rfind("frame_", 0), 0u) << "no temporary may remain: " << name;
    const Rgba8Image image = load_png((out / name).string());
    EXPECT_EQ(image.width, 64) << name << " is not a whole PNG";
  }
}

TEST(OutputIntegrityCli, RenderExrReportsAFullDisk) {
  TempDir dir;
  CommandResult r = run_rolypoly("render --size 16 --frames 1 --exr --out " +
                                     shell_quote(dir.path().string()),
                                 fail_after(0));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "cannot write EXR " + (dir / "frame_0000.exr").string() +
                                  ": No space left on device"))
      << r.err;
  EXPECT_TRUE(entries(dir.path()).empty());
}

TEST(OutputIntegrityCli, BenchFilesReportAFullDiskAndKeepTheOldFiles) {
  TempDir dir;
  for (const std::string option : {"--json", "--markdown", "--chart"}) {
    const auto file = dir / ("report" + option.substr(2));
    write_plain(file, "old " + option);
    CommandResult r = run_rolypoly(std::string(kTinyBench) + " " + option + " " +
                                       shell_quote(file.string()),
                                   fail_after(0));
    EXPECT_EQ(r.exit_code, 1) << option << ": " << r.err;
    EXPECT_TRUE(contains(r.err, "cannot write " + file.string() + ": No space left on device"))
        << r.err;
    EXPECT_EQ(read_all(file), "old " + option);
  }
  EXPECT_EQ(entries(dir.path()),
            (std::vector<std::string>{"reportchart", "reportjson", "reportmarkdown"}));
}

TEST(OutputIntegrityCli, BenchChecksItsOutputsBeforeMeasuring) {
  TempDir dir;
  std::filesystem::create_directories(dir / "folder");
  struct Case {
    std::string args, message;
  };
  const std::string tiny = kTinyBench;
  const std::vector<Case> cases = {
      {tiny + " --json " + shell_quote((dir / "folder").string()),
       "--json: cannot write " + (dir / "folder").string() + ": it is a directory"},
      {tiny + " --chart /proc/rolypoly/chart.svg",
       "--chart: cannot create output folder /proc/rolypoly"},
      {tiny + " --markdown /proc/self/summary.md",
       "--markdown: cannot write into output folder /proc/self"},
      {"bench --accuracy --size 16 --out /proc/rolypoly",
       "cannot create output folder /proc/rolypoly"},
  };
  for (const Case& c : cases) {
    CommandResult r = run_rolypoly(c.args);
    EXPECT_EQ(r.exit_code, 1) << c.args << ": " << r.err;
    EXPECT_TRUE(contains(r.err, c.message)) << r.err;
    EXPECT_EQ(r.out, "") << "nothing may run before the check: " << c.args;
  }
}

TEST(OutputIntegrityCli, RunChecksRecordAndCaptureBeforeOpeningTheWindow) {
  // No display on purpose: the path is refused before the window (and its error) is reached.
  TempDir dir;
  for (const std::string option : {"--record", "--capture"}) {
    CommandResult r =
        run_rolypoly("run --size 32 " + option + " " + shell_quote(dir.path().string()),
                     "env -u DISPLAY -u WAYLAND_DISPLAY");
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(contains(r.err, option + ": cannot write " + dir.path().string() +
                                    ": it is a directory"))
        << r.err;
  }
}

TEST(OutputIntegrityCli, BenchWritesIntoFifosDevicesAndThroughSymlinks) {
  TempDir dir;
  const auto fifo = dir / "json.fifo", link = dir / "chart.svg", null_link = dir / "null";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::filesystem::create_directories(dir / "real");
  write_plain(dir / "real" / "chart.svg", "old chart");
  std::filesystem::create_symlink("real/chart.svg", link);
  std::filesystem::create_symlink("/dev/null", null_link);
  FifoReader reader(fifo);
  CommandResult r = run_rolypoly(std::string(kTinyBench) + " --json " + shell_quote(fifo.string()) +
                                 " --chart " + shell_quote(link.string()) + " --markdown " +
                                 shell_quote(null_link.string()));
  const std::string json = reader.finish();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_FALSE(json.empty()) << "the FIFO's reader got nothing";
  EXPECT_EQ(nlohmann::json::parse(json).at("schema"), "rolypoly-bench/3");
  EXPECT_EQ(file_type(fifo), mode_t(S_IFIFO));
  EXPECT_EQ(file_type(link), mode_t(S_IFLNK));
  EXPECT_EQ(read_all(dir / "real" / "chart.svg").rfind("<?xml", 0), 0u);
  EXPECT_EQ(file_type(null_link), mode_t(S_IFLNK));
  EXPECT_EQ(file_type("/dev/null"), mode_t(S_IFCHR));
  EXPECT_EQ(entries(dir / "real"), std::vector<std::string>{"chart.svg"});
}

TEST(OutputIntegrityCli, BenchJsonToStdoutKeepsItsPlaceInTheOutput) {
  // run_rolypoly sends stdout to a file, as `> file` does: the JSON comes between the bench's
  // lines and "wrote /dev/stdout", neither overwriting them nor overwritten.
  CommandResult r = run_rolypoly(std::string(kTinyBench) + " --json /dev/stdout");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("bench: ", 0), 0u) << r.out;
  const size_t open = r.out.find("\n{\n"), close = r.out.rfind("\n}\n");
  ASSERT_NE(open, std::string::npos) << r.out;
  ASSERT_NE(close, std::string::npos) << r.out;
  EXPECT_EQ(nlohmann::json::parse(r.out.substr(open + 1, close + 2 - open)).at("schema"),
            "rolypoly-bench/3");
  EXPECT_EQ(r.out.substr(close + 3), "wrote /dev/stdout\n");
}

TEST(OutputIntegrityCli, BenchJsonToDevFullFailsAndKeepsTheDevice) {
  TempDir dir;
  // Through a link of ours: were the device ever replaced again, the damage would show here.
  std::filesystem::create_symlink("/dev/full", dir / "full");
  CommandResult r = run_rolypoly(std::string(kTinyBench) + " --json " +
                                 shell_quote((dir / "full").string()));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "cannot write " + (dir / "full").string() +
                                  ": No space left on device"))
      << r.err;
  EXPECT_EQ(file_type("/dev/full"), mode_t(S_IFCHR));
  EXPECT_EQ(file_type(dir / "full"), mode_t(S_IFLNK));
}

TEST(OutputIntegrityCli, RunRecordAndCaptureReportAFullDisk) {
  if (!have_program("Xvfb")) GTEST_SKIP() << "Xvfb is not installed";
  // Our own server (xvfb-run's clean-up of its temporary folder failed now and then, exit 5)
  XvfbServer x;
  if (x.display().empty()) GTEST_SKIP() << "Xvfb did not start";
  TempDir dir;
  for (const std::string option : {"--record", "--capture"}) {
    const auto file = dir / (option.substr(2) + ".out");
    CommandResult r = run_rolypoly("run --size 32 --frames 2 " + option + " " +
                                       shell_quote(file.string()),
                                   fail_after(0) + " DISPLAY=" + x.display());
    EXPECT_EQ(r.exit_code, 1) << option << ": " << r.out << r.err;
    EXPECT_TRUE(contains(r.err, "cannot write " + file.string() + ": No space left on device"))
        << r.err;
    EXPECT_FALSE(contains(r.out, "captured")) << r.out;
  }
  EXPECT_TRUE(entries(dir.path()).empty());
}

}  // namespace
}  // namespace rp::test
