// Issue 18: signals during `render`. SIGINT / SIGTERM in the first fraction of a second (device
// set-up and kernel builds; LLVM inside PoCL deletes its temporary files on the signal, so the
// build in progress failed with "failed to build kernels/...cl" and exit 1) exit 130 / 143 with
// one line; a replayed frame mark millions of steps ahead shows progress and stops on the first
// SIGINT; replay steps beyond 2^31 - 1 are errors, not truncated.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.h"
#include "xvfb_server.h"  // wait_exit, read_text

namespace rp::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;


// rolypoly with `args`, stdout and stderr into files in `dir`; returns its pid.
pid_t start(const std::vector<std::string>& args, const TempDir& dir) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (!std::freopen((dir / "err.txt").c_str(), "w", stderr) ||
        !std::freopen((dir / "out.txt").c_str(), "w", stdout))
      _exit(99);
    std::vector<char*> argv{const_cast<char*>(ROLYPOLY_BINARY)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(ROLYPOLY_BINARY, argv.data());
    _exit(98);
  }
  return pid;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Signals at several moments of start-up: opening the device, building kernels (from PoCL's
// cache once an earlier test warmed it), the first frames. Each run: 128 + signal, exactly one
// line on stderr, no file but complete frames.
TEST(Signals, DuringStartUpExitWith128PlusSignalAndOneLine) {
  for (const int signal : {SIGINT, SIGTERM}) {
    for (const int delay_ms : {50, 120, 200, 300}) {
      SCOPED_TRACE((signal == SIGINT ? "SIGINT after " : "SIGTERM after ") +
                   std::to_string(delay_ms) + " ms");
      TempDir dir;
      const pid_t pid = start({"render", "--size", "32", "--frames", "100000", "--out",
                               (dir / "out").string()},
                              dir);
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
      ASSERT_EQ(kill(pid, signal), 0);
      const int code = wait_exit(pid, std::chrono::seconds(120));
      const std::string err = read_text(dir / "err.txt");
      EXPECT_EQ(code, 128 + signal) << err;
      const std::vector<std::string> lines = lines_of(err);
      ASSERT_EQ(lines.size(), 1u) << err;
      EXPECT_EQ(lines[0].rfind("rolypoly: error: interrupted", 0), 0u) << err;
      for (const std::string& name : {std::string(".tmp"), std::string(".partial")})
        EXPECT_TRUE(files_with_suffix(dir / "out", name).empty());
    }
  }
}

TEST(Signals, LongReplayShowsProgressAndStopsOnTheFirstSigint) {
  TempDir dir;
  std::ofstream(dir / "far.log") << "rolypoly-input 1\nstep 100000000 frame\n";
  const pid_t pid = start({"render", "--size", "32", "--replay", (dir / "far.log").string(),
                           "--out", (dir / "out").string()},
                          dir);
  // Progress appears about once a second while the one frame's steps are simulated.
  const auto end = Clock::now() + std::chrono::seconds(60);
  while (read_text(dir / "err.txt").find("steps simulated") == std::string::npos &&
         Clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const std::string progress = read_text(dir / "err.txt");
  EXPECT_NE(progress.find("rolypoly: replay: frame 0: "), std::string::npos) << progress;
  EXPECT_NE(progress.find(" of 100000000 steps simulated ("), std::string::npos) << progress;
  ASSERT_EQ(kill(pid, SIGINT), 0);
  const auto sent = Clock::now();
  EXPECT_EQ(wait_exit(pid, std::chrono::seconds(30)), 130);
  EXPECT_LT(Clock::now() - sent, std::chrono::seconds(5)) << "the first SIGINT must stop it";
  const std::string err = read_text(dir / "err.txt");
  EXPECT_NE(err.find("rolypoly: error: interrupted after 0 frames (no frame was written)"),
            std::string::npos)
      << err;
  EXPECT_TRUE(files_with_suffix(dir / "out", ".png").empty());
}

TEST(Signals, ReplayStepsBeyondTwoToThe31AreErrorsNotTruncated) {
  TempDir dir;
  std::ofstream(dir / "huge.log") << "rolypoly-input 1\nstep 4294967300 frame\n";
  CommandResult r = run_rolypoly("render --size 32 --replay " +
                                 shell_quote((dir / "huge.log").string()) + " --out " +
                                 shell_quote((dir / "out").string()));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("huge.log:2: step 4294967300 is out of range"), std::string::npos)
      << r.err;
  EXPECT_TRUE(files_with_suffix(dir / "out", ".png").empty());
}

}  // namespace
}  // namespace rp::test
