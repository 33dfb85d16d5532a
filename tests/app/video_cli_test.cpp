// `render --video` with the real ffmpeg (the shell used to mangle its command line:
// exit 141, no video), and failures that must leave no file: an unwritable folder, an ffmpeg
// that cannot encode the container, and an ffmpeg that quits while frames are still coming.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "support/cli_runner.h"

namespace rp::test {
namespace {

namespace fs = std::filesystem;

// Every entry of `dir` (not recursive) whose name contains "partial": ffmpeg's temporary file.
std::vector<std::string> partial_files(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().filename().string().find("partial") != std::string::npos)
      names.push_back(entry.path().filename().string());
  return names;
}

std::string output_of(const std::string& command) {
  std::string out;
  if (std::FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[256];
    while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
    pclose(pipe);
  }
  return out;
}

TEST(VideoCli, EncodesEveryFrameWithTheRealFfmpeg) {
  for (const char* program : {"ffmpeg", "ffprobe"})
    if (!have_program(program))
      GTEST_SKIP() << program << " not installed (tools/setup.sh installs ffmpeg)";
  TempDir dir;
  // A space and parentheses in the name: the old shell command line broke on them.
  const fs::path video = dir / "clip (1).mp4";
  CommandResult r = run_rolypoly("render --size 64 --frames 10 --video " +
                                 shell_quote(video.string()) + " --out " +
                                 shell_quote((dir / "f").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("wrote " + video.string()), std::string::npos) << r.out;
  ASSERT_TRUE(fs::is_regular_file(video));
  const std::string frames =
      output_of("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                "stream=nb_read_frames,width,height -of default=nw=1 " +
                shell_quote(video.string()));
  EXPECT_NE(frames.find("nb_read_frames=10"), std::string::npos) << frames;
  EXPECT_NE(frames.find("width=64"), std::string::npos) << frames;
  EXPECT_TRUE(partial_files(dir.path()).empty());
}

TEST(VideoCli, OddSizesArePaddedToEven) {
  if (!have_program("ffmpeg") || !have_program("ffprobe")) GTEST_SKIP() << "no ffmpeg";
  TempDir dir;
  const fs::path video = dir / "odd.mp4";
  CommandResult r = run_rolypoly("render --width 33 --height 17 --frames 2 --video " +
                                 shell_quote(video.string()) + " --out " +
                                 shell_quote((dir / "f").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string info = output_of(
      "ffprobe -v error -select_streams v:0 -show_entries stream=width,height -of "
      "default=nw=1 " + shell_quote(video.string()));
  EXPECT_NE(info.find("width=34"), std::string::npos) << info;
  EXPECT_NE(info.find("height=18"), std::string::npos) << info;
}

TEST(VideoCli, UnwritableFolderFailsBeforeRenderingAndLeavesNoFile) {
  if (!have_program("ffmpeg")) GTEST_SKIP() << "no ffmpeg";
  TempDir dir;
  std::ofstream(dir / "file") << "not a folder";
  CommandResult r = run_rolypoly("render --size 32 --frames 2 --video " +
                                 shell_quote((dir / "file" / "v.mp4").string()) + " --out " +
                                 shell_quote((dir / "f").string()));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("Not a directory"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("device"), std::string::npos) << "failed only after opening the device";
  EXPECT_TRUE(files_with_suffix(dir / "f", ".png").empty());
}

// The output path rules (io/output_path.h): a symlink is followed, the link stays a link; a
// FIFO (or device) is refused before rendering: ffmpeg finishes an mp4 with seeks.
TEST(VideoCli, SymlinksAreFollowedAndFifosRefused) {
  if (!have_program("ffmpeg")) GTEST_SKIP() << "no ffmpeg";
  TempDir dir;
  fs::create_directories(dir / "real");
  fs::create_symlink(dir / "real" / "v.mp4", dir / "link.mp4");
  CommandResult r = run_rolypoly("render --size 32 --frames 2 --video " +
                                 shell_quote((dir / "link.mp4").string()) + " --out " +
                                 shell_quote((dir / "f").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(dir / "link.mp4"));
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / "real" / "v.mp4")));
  EXPECT_GT(fs::file_size(dir / "real" / "v.mp4"), 0u);
  EXPECT_TRUE(partial_files(dir / "real").empty());

  const fs::path fifo = dir / "pipe.mp4";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0644), 0);
  r = run_rolypoly("render --size 32 --frames 2 --video " + shell_quote(fifo.string()) +
                   " --out " + shell_quote((dir / "g").string()));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("must go to a regular file"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_TRUE(partial_files(dir.path()).empty());
}

TEST(VideoCli, FfmpegThatCannotEncodeIsNamedAndLeavesNoFile) {
  if (!have_program("ffmpeg")) GTEST_SKIP() << "no ffmpeg";
  TempDir dir;
  CommandResult r = run_rolypoly("render --size 32 --frames 3 --video " +
                                 shell_quote((dir / "v.nosuchformat").string()) + " --out " +
                                 shell_quote((dir / "f").string()));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("ffmpeg exited with status"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no video was written"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "v.nosuchformat"));
  EXPECT_TRUE(partial_files(dir.path()).empty());
}

// An "ffmpeg" that reads a little and quits: the next write hits a closed pipe (EPIPE), which
// used to kill rolypoly with SIGPIPE (exit 141) without a word.
TEST(VideoCli, FfmpegQuittingMidStreamIsAnErrorNotSigpipe) {
  TempDir dir;
  fs::create_directories(dir / "bin");
  {
    std::ofstream script(dir / "bin" / "ffmpeg");
    script << "#!/bin/sh\nhead -c 100 >/dev/null\necho 'gave up early' >&2\nexit 3\n";
  }
  fs::permissions(dir / "bin" / "ffmpeg", fs::perms::owner_all);
  CommandResult r = run_rolypoly("render --size 64 --frames 4 --video " +
                                     shell_quote((dir / "v.mp4").string()) + " --out " +
                                     shell_quote((dir / "f").string()),
                                 "PATH=" + shell_quote((dir / "bin").string()) + ":\"$PATH\"");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("ffmpeg exited with status 3: gave up early"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "v.mp4"));
  EXPECT_TRUE(partial_files(dir.path()).empty());
}

// A full disk: ffmpeg 5 prints "Error writing trailer ...: No space left on device" and still
// exits 0, which used to leave a truncated video and "wrote v.mp4". Needs a tiny tmpfs (root
// with mount rights; skipped elsewhere).
TEST(VideoCli, FullDiskIsAnErrorAndLeavesNoFile) {
  if (!have_program("ffmpeg")) GTEST_SKIP() << "no ffmpeg";
  TempDir dir;
  const fs::path tiny = dir / "tiny";
  fs::create_directories(tiny);
  if (std::system(("mount -t tmpfs -o size=4k tmpfs " + shell_quote(tiny.string()) +
                   " 2>/dev/null").c_str()) != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here";
  CommandResult r = run_rolypoly("render --size 128 --frames 20 --marbles --video " +
                                 shell_quote((tiny / "v.mp4").string()) + " --out " +
                                 shell_quote((dir / "f").string()));
  const bool left = !fs::is_empty(tiny);
  std::system(("umount " + shell_quote(tiny.string())).c_str());
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no video was written"), std::string::npos) << r.err;
  EXPECT_FALSE(left) << "the full file system must hold no (partial) video";
}

// Ctrl-C while encoding: the frames written so far stay, the unfinished video goes (ffmpeg runs
// in its own process group, so the terminal's Ctrl-C reaches rolypoly alone, which ends it).
TEST(VideoCli, InterruptRemovesTheUnfinishedVideo) {
  if (!have_program("ffmpeg")) GTEST_SKIP() << "no ffmpeg";
  TempDir dir;
  const fs::path out = dir / "f";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (!std::freopen((dir / "err.txt").c_str(), "w", stderr) ||
        !std::freopen("/dev/null", "w", stdout))
      _exit(99);
    execl(ROLYPOLY_BINARY, ROLYPOLY_BINARY, "render", "--size", "32", "--frames", "100000",
          "--video", (dir / "v.mp4").c_str(), "--out", out.c_str(), static_cast<char*>(nullptr));
    _exit(98);
  }
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (files_with_suffix(out, ".png").size() < 5 && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_GE(files_with_suffix(out, ".png").size(), 5u);
  EXPECT_FALSE(fs::exists(dir / "v.mp4"));
  EXPECT_TRUE(partial_files(dir.path()).empty());
}

}  // namespace
}  // namespace rp::test
