// Limits and inputs that used to hang or misfire: a file-size limit (ulimit -f) killed the
// process by SIGXFSZ with a partial temporary left; a path-traced size beyond the host's memory
// was allocated until std::bad_alloc; `--replay` on a FIFO without a writer hung and ignored
// SIGTERM; an endless device was read until memory ran out.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include "support/cli_runner.h"
#include "xvfb_server.h"  // spawn_shell, wait_exit, read_text

namespace rp::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// rolypoly under bash with `limits` applied first (e.g. "ulimit -f 16").
CommandResult run_limited(const std::string& limits, const std::string& args) {
  return run_rolypoly(args, "bash -c " + shell_quote(limits + "; exec \"$0\" \"$@\"") + " ");
}

// The path tracer needs no OpenCL device, so no PoCL cache write meets the limit first.
TEST(Limits, FileSizeLimitIsAWriteErrorNamingTheFile) {
  TempDir dir;
  const fs::path out = dir / "out";
  // 16 blocks of 1 KiB: less than one 64x64 EXR of five float layers.
  const CommandResult r = run_limited(
      "ulimit -f 16", "render --quality pathtraced --spp 1 --size 64 --frames 2 --out " +
                          shell_quote(out.string()));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(Contains(r.err, "rolypoly: error: cannot write EXR " +
                                  (out / "frame_0000.exr").string()));
  EXPECT_TRUE(Contains(r.err, "File too large"));
  EXPECT_TRUE(entries(out).empty()) << "no temporary, no partial file";
}

TEST(Limits, PathTracedSizeBeyondTheHostMemoryIsRefusedBeforeAllocating) {
  // 4 GiB of address space: 16384^2 at 200 bytes per pixel (50 GiB) cannot fit, whatever the
  // machine; the message names the limit and the largest size that fits under it.
  for (const char* command : {"render --quality pathtraced --out /nonexistent/x",
                              "bench --quality pathtraced"}) {
    SCOPED_TRACE(command);
    const auto start = Clock::now();
    const CommandResult r =
        run_limited("ulimit -v 4194304", std::string(command) + " --size 16384");
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(Contains(r.err, "rolypoly: error: --quality pathtraced at 16384x16384 needs "
                                "50.0 GiB of host memory (200 bytes per pixel)"));
    // The limit, unless the host has even less available.
    EXPECT_TRUE(r.err.find("(ulimit -v 4194304)") != std::string::npos ||
                r.err.find(" GiB available; ") != std::string::npos)
        << r.err;
    EXPECT_TRUE(Contains(r.err, "the largest square size that fits is about "));
    EXPECT_LT(seconds_since(start), 10.0);
  }
  // Without a limit: the host's available memory (where 50 GiB are available it really runs:
  // `timeout` ends it, and it passes).
  const CommandResult r = run_rolypoly(
      "render --quality pathtraced --size 16384 --out /nonexistent/x", "timeout -s KILL 20");
  if (r.exit_code == 1) {
    EXPECT_TRUE(Contains(r.err, "GiB available; the largest square size that fits is about "));
  }
}

TEST(Limits, ReplayFromAFifoWithoutWriterStopsOnTheFirstSigterm) {
  TempDir dir;
  const fs::path fifo = dir / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const pid_t pid = spawn_shell("exec " + shell_quote(ROLYPOLY_BINARY) + " render --size 16 " +
                                "--replay " + shell_quote(fifo.string()) + " --out " +
                                shell_quote((dir / "out").string()) + " 2>" +
                                shell_quote((dir / "err.txt").string()) + " >/dev/null");
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  const auto sent = Clock::now();
  EXPECT_EQ(wait_exit(pid, std::chrono::seconds(10)), 143) << read_text(dir / "err.txt");
  EXPECT_LT(seconds_since(sent), 2.0) << "the first SIGTERM must stop it";
  const std::string err = read_text(dir / "err.txt");
  EXPECT_TRUE(Contains(err, "rolypoly: --replay " + fifo.string() +
                                ": it is a FIFO (named pipe); waiting for data"));
  EXPECT_TRUE(Contains(err, "rolypoly: error: interrupted by SIGTERM while waiting for "
                            "--replay " + fifo.string()));
}

// A pipe with a writer is still a fine input (`--replay <(...)`), up to its end.
TEST(Limits, ReplayFromAPipeIsReadToItsEnd) {
  TempDir dir;
  const std::string command =
      "bash -c " +
      shell_quote(shell_quote(ROLYPOLY_BINARY) +
                  " render --size 16 --out " + shell_quote((dir / "out").string()) +
                  " --replay <(printf 'rolypoly-input 1\\nstep 4 frame\\nstep 8 frame\\n') "
                  ">/dev/null 2>" + shell_quote((dir / "err.txt").string()));
  EXPECT_EQ(std::system(command.c_str()), 0) << read_text(dir / "err.txt");
  EXPECT_EQ(files_with_suffix(dir / "out", ".png").size(), 2u) << "two frame marks, two frames";
}

TEST(Limits, EndlessDeviceAsReplayIsBounded) {
  const auto start = Clock::now();
  const CommandResult r = run_rolypoly("render --size 16 --replay /dev/zero --out /nonexistent/x");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(Contains(r.err, "--replay: cannot read /dev/zero: larger than 256 MiB"));
  EXPECT_LT(seconds_since(start), 30.0);
}

}  // namespace
}  // namespace rp::test
