// Signals. SIGINT / SIGTERM in the first fraction of a second (device set-up and kernel builds;
// LLVM inside PoCL deletes its temporary files on the signal, so the build in progress failed
// with "failed to build kernels/...cl" and exit 1) exit 130 / 143 with one line; a replayed
// frame mark millions of steps ahead shows progress and stops on the first SIGINT; replay steps
// beyond 2^31 - 1 are errors, not truncated. Every other terminating signal a user sends
// (SIGHUP from a closed terminal, SIGQUIT, SIGPIPE, SIGXFSZ, ...) ends the run the same way:
// 128 + N, one line, complete files only, no temporary (frames, video partials, the private
// PoCL cache); dispositions inherited from the launcher (SIGINT ignored in a script's
// background job) change nothing.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/cli_runner.h"
#include "xvfb_server.h"  // wait_exit, read_text

namespace rp::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;


// rolypoly with `args`, stdout and stderr into files in `dir`; returns its pid. `ignored`:
// signals set to SIG_IGN in the child before exec, as a launcher may leave them.
pid_t start(const std::vector<std::string>& args, const TempDir& dir,
            const std::vector<int>& ignored = {}) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (!std::freopen((dir / "err.txt").c_str(), "w", stderr) ||
        !std::freopen((dir / "out.txt").c_str(), "w", stdout))
      _exit(99);
    for (const int signal : ignored) ::signal(signal, SIG_IGN);
    std::vector<char*> argv{const_cast<char*>(ROLYPOLY_BINARY)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(ROLYPOLY_BINARY, argv.data());
    _exit(98);
  }
  return pid;
}

// Waits until `pid` has installed its signal handling (a signal before main() meets the
// default action, which no program can change): SIGXFSZ caught and SIGQUIT blocked, as
// install_signal_handlers leaves them. False after 10 s.
bool wait_for_handlers(pid_t pid) {
  const auto end = Clock::now() + std::chrono::seconds(10);
  const auto has = [](const std::string& status, const char* field, int signal) {
    const size_t at = status.find(field);
    if (at == std::string::npos) return false;
    const unsigned long long mask = std::strtoull(status.c_str() + at + std::strlen(field),
                                                  nullptr, 16);
    return ((mask >> (signal - 1)) & 1u) != 0;
  };
  while (Clock::now() < end) {
    const std::string status = read_text("/proc/" + std::to_string(pid) + "/status");
    if (has(status, "SigCgt:", SIGXFSZ) && has(status, "SigBlk:", SIGQUIT)) return true;
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  return false;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Signals at several moments of start-up (counted from the moment the handlers are in place):
// opening the device, building kernels (from PoCL's cache once an earlier test warmed it), the
// first frames. Each run: 128 + signal, exactly one line on stderr, no file but complete frames.
TEST(Signals, DuringStartUpExitWith128PlusSignalAndOneLine) {
  for (const int signal : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE}) {
    for (const int delay_ms : {0, 50, 150, 300}) {
      SCOPED_TRACE(std::string(strsignal(signal)) + " after " + std::to_string(delay_ms) +
                   " ms");
      TempDir dir;
      const pid_t pid = start({"render", "--size", "32", "--frames", "100000", "--out",
                               (dir / "out").string()},
                              dir);
      ASSERT_TRUE(wait_for_handlers(pid));
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

// Waits until `dir` holds at least `count` frames (kernel builds come first).
bool wait_for_frames(const fs::path& dir, size_t count) {
  const auto end = Clock::now() + std::chrono::seconds(120);
  while (files_with_suffix(dir, ".png").size() < count && Clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  return files_with_suffix(dir, ".png").size() >= count;
}

// Only complete frames remain: frame_NNNN.png (and .exr), no temporary, no partial video.
void expect_only_frames(const fs::path& dir) {
  for (const std::string& name : entries(dir))
    EXPECT_TRUE(name.size() == 14 && name.rfind("frame_", 0) == 0 &&
                name.compare(10, 4, ".png") == 0)
        << name;
}

// Every terminating signal a user can send, while frames are being written: 128 + N, one line
// naming how far it got, complete frames only. SIGHUP, SIGQUIT and SIGPIPE used to kill the
// process on the spot (no message, a .frame_NNNN.png.tmpPID left when it hit a write).
TEST(Signals, MidRenderEverySignalKeepsCompleteFramesOnly) {
  for (const int signal : {SIGHUP, SIGQUIT, SIGPIPE, SIGXFSZ, SIGUSR1}) {
    SCOPED_TRACE(strsignal(signal));
    TempDir dir;
    const pid_t pid = start({"render", "--size", "32", "--frames", "100000", "--out",
                             (dir / "out").string()},
                            dir);
    ASSERT_TRUE(wait_for_frames(dir / "out", 2)) << read_text(dir / "err.txt");
    ASSERT_EQ(kill(pid, signal), 0);
    EXPECT_EQ(wait_exit(pid, std::chrono::seconds(60)), 128 + signal);
    const std::vector<std::string> lines = lines_of(read_text(dir / "err.txt"));
    ASSERT_EQ(lines.size(), 1u) << read_text(dir / "err.txt");
    EXPECT_EQ(lines[0].rfind("rolypoly: error: interrupted after ", 0), 0u) << lines[0];
    expect_only_frames(dir / "out");
  }
}

// stdout into a pipe whose reader is gone (`rolypoly render | head -1`): the write fails and
// SIGPIPE arrives; the run ends as for any signal instead of dying without a word.
TEST(Signals, ClosedStdoutPipeEndsWithOneLine) {
  TempDir dir;
  const std::string command =
      "bash -c " + shell_quote(shell_quote(ROLYPOLY_BINARY) + " render --size 32 --frames 100000 "
                               "--out " + shell_quote((dir / "out").string()) + " 2>" +
                               shell_quote((dir / "err.txt").string()) +
                               " | true; echo ${PIPESTATUS[0]} >" +
                               shell_quote((dir / "code.txt").string()));
  ASSERT_EQ(std::system(command.c_str()), 0);
  EXPECT_EQ(read_text(dir / "code.txt"), "141\n");
  const std::vector<std::string> lines = lines_of(read_text(dir / "err.txt"));
  ASSERT_EQ(lines.size(), 1u) << read_text(dir / "err.txt");
  EXPECT_EQ(lines[0].rfind("rolypoly: error: interrupted", 0), 0u) << lines[0];
  expect_only_frames(dir / "out");
}

// A bench started with SIGINT and SIGQUIT ignored (what a shell script gives its background
// jobs) and then interrupted, during its kernel builds and while measuring, used to fail the
// build, record the device as skipped and replace the previous --json with that record.
TEST(Signals, InheritedIgnoredSigintStillStopsABenchAndKeepsItsJson) {
  for (const bool measuring : {false, true}) {
    SCOPED_TRACE(measuring ? "while measuring" : "during start-up");
    TempDir dir;
    const fs::path json = dir / "r.json";
    write_plain(json, "previous\n");
    const pid_t pid = start({"bench", "--size", "32", "--warmup", "0", "--frames", "1000000",
                             "--json", json.string()},
                            dir, {SIGINT, SIGQUIT});
    ASSERT_TRUE(wait_for_handlers(pid));
    if (measuring) {
      const auto end = Clock::now() + std::chrono::seconds(120);
      while (read_text(dir / "out.txt").find("bench: ") == std::string::npos &&
             Clock::now() < end)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      std::this_thread::sleep_for(std::chrono::seconds(3));
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    ASSERT_EQ(kill(pid, SIGINT), 0);
    EXPECT_EQ(wait_exit(pid, std::chrono::seconds(60)), 130) << read_text(dir / "err.txt");
    const std::vector<std::string> lines = lines_of(read_text(dir / "err.txt"));
    ASSERT_EQ(lines.size(), 1u) << read_text(dir / "err.txt");
    EXPECT_EQ(lines[0].rfind("rolypoly: error: interrupted by SIGINT", 0), 0u) << lines[0];
    EXPECT_EQ(read_text(json), "previous\n");
  }
}

// SIGHUP while ffmpeg encodes: its partial file is removed with it, the frames stay whole.
TEST(Signals, SighupDuringVideoLeavesNoPartialFile) {
  if (!have_program("ffmpeg")) GTEST_SKIP() << "ffmpeg not installed";
  TempDir dir;
  const fs::path out = dir / "out";
  const pid_t pid = start({"render", "--size", "32", "--frames", "100000", "--out", out.string(),
                           "--video", (dir / "v.mp4").string()},
                          dir);
  ASSERT_TRUE(wait_for_frames(out, 2)) << read_text(dir / "err.txt");
  ASSERT_EQ(kill(pid, SIGHUP), 0);
  EXPECT_EQ(wait_exit(pid, std::chrono::seconds(60)), 129) << read_text(dir / "err.txt");
  expect_only_frames(out);
  for (const std::string& name : entries(dir.path()))
    EXPECT_TRUE(name == "out" || name == "err.txt" || name == "out.txt") << name;
}

// The private PoCL cache (used when the configured one is unusable) goes with a SIGHUP during
// the (then cold) kernel builds.
TEST(Signals, SighupRemovesThePrivatePoclCache) {
  TempDir dir;
  write_plain(dir / "file", "not a folder");
  const pid_t pid = spawn_shell(
      "exec env POCL_CACHE_DIR=" + shell_quote((dir / "file" / "cache").string()) + " " +
      shell_quote(ROLYPOLY_BINARY) + " render --size 32 --out " +
      shell_quote((dir / "out").string()) + " >" + shell_quote((dir / "out.txt").string()) +
      " 2>" + shell_quote((dir / "err.txt").string()));
  ASSERT_TRUE(wait_for_handlers(pid));
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  ASSERT_EQ(kill(pid, SIGHUP), 0);
  EXPECT_EQ(wait_exit(pid, std::chrono::seconds(60)), 129) << read_text(dir / "err.txt");
  const std::string err = read_text(dir / "err.txt");
  const size_t at = err.find("using the temporary folder ");
  ASSERT_NE(at, std::string::npos) << err;
  const std::string folder = err.substr(at + 27, err.find(',', at) - at - 27);
  EXPECT_FALSE(fs::exists(folder)) << folder;
  // Ours: the warning and the interruption (a cold build also has clang's "N warnings").
  size_t ours = 0;
  for (const std::string& line : lines_of(err)) ours += line.rfind("rolypoly: ", 0) == 0;
  EXPECT_EQ(ours, 2u) << err;
}

// nohup: SIGHUP inherited as ignored stays ignored, and cannot break a kernel build.
TEST(Signals, NohupKeepsRunningThroughSighup) {
  TempDir dir;
  const pid_t pid = start({"render", "--size", "32", "--frames", "3", "--out",
                           (dir / "out").string()},
                          dir, {SIGHUP});
  for (const int delay_ms : {100, 200, 400}) {
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    kill(pid, SIGHUP);
  }
  EXPECT_EQ(wait_exit(pid, std::chrono::seconds(120)), 0) << read_text(dir / "err.txt");
  EXPECT_EQ(files_with_suffix(dir / "out", ".png").size(), 3u);
}

}  // namespace
}  // namespace rp::test
