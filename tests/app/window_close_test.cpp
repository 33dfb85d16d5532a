// Issue 8.4, "the window closed mid-run": `rolypoly run --frames 0 --record` in a window on a
// private Xvfb server is closed the way a window manager closes it (WM_DELETE_WINDOW, sent to
// the window that xdotool finds), after it has shown frames for a while. Checks: exit code 0,
// "window closed after N frames", the --record log is complete (N frame marks) and replays to
// the same pictures (the replay's last frame equals the window's --capture).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>

#include "cli_runner.h"
#include "support/image_metrics.h"
#include "x11_close.h"

namespace rp::test {
namespace {

using Clock = std::chrono::steady_clock;

// A private X server (Xvfb, 24-bit screen: GLFW needs an RGBA8 visual). -displayfd lets Xvfb
// pick a free display and say which once it accepts connections.
class XvfbServer {
 public:
  XvfbServer() {
    int fds[2];
    if (pipe(fds) != 0) return;
    pid_ = fork();
    if (pid_ == 0) {
      close(fds[0]);
      const int null_fd = open("/dev/null", O_WRONLY);
      dup2(null_fd, STDOUT_FILENO);
      dup2(null_fd, STDERR_FILENO);
      const std::string fd = std::to_string(fds[1]);
      execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "640x480x24", "-nolisten",
             "tcp", static_cast<char*>(nullptr));
      _exit(127);
    }
    close(fds[1]);
    std::string number;
    char c = 0;
    while (pid_ > 0 && read(fds[0], &c, 1) == 1 && c != '\n') number += c;
    close(fds[0]);
    if (!number.empty()) display_ = ":" + number;
  }
  ~XvfbServer() {
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    waitpid(pid_, nullptr, 0);
  }
  XvfbServer(const XvfbServer&) = delete;
  XvfbServer& operator=(const XvfbServer&) = delete;
  const std::string& display() const { return display_; }  // "" when it did not start

 private:
  pid_t pid_ = -1;
  std::string display_;
};

// `command` through /bin/sh in the background; returns its pid.
pid_t spawn(const std::string& command) {
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

// The exit status of `pid`, waiting at most `limit`; kills it and returns -1 after that.
int wait_exit(pid_t pid, std::chrono::seconds limit) {
  const auto end = Clock::now() + limit;
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (Clock::now() > end) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// stdout of a short shell command.
std::string output_of(const std::string& command) {
  std::string out;
  if (std::FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[512];
    while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
    pclose(pipe);
  }
  return out;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(WindowClose, ClosedMidRunExitsCleanlyAndTheRecordingReplays) {
  for (const char* program : {"Xvfb", "xdotool"})
    if (!have_program(program))
      GTEST_SKIP() << program << " not installed (tools/setup.sh installs xvfb and xdotool)";
  XvfbServer x;
  ASSERT_FALSE(x.display().empty()) << "Xvfb did not start";
  const std::string env = "DISPLAY=" + x.display() + " ";
  TempDir dir;
  const std::string log = (dir / "session.log").string();
  const std::string args = " --size 64 --marbles --fireball --seed 5";
  const pid_t app = spawn(env + shell_quote(ROLYPOLY_BINARY) + " run --frames 0" + args +
                          " --record " + shell_quote(log) + " --capture " +
                          shell_quote((dir / "window.png").string()) + " >" +
                          shell_quote((dir / "out.txt").string()) + " 2>" +
                          shell_quote((dir / "err.txt").string()));

  // The window, then its title's frame rate: it has been showing frames for >= 0.5 s.
  const std::string id = output_of(env + "timeout 60 xdotool search --sync --name '^rolypoly'");
  ASSERT_FALSE(id.empty()) << "no rolypoly window appeared: " << read_text(dir / "err.txt");
  const unsigned long window = std::stoul(id);  // the first id (one window)
  std::string title;
  for (const auto end = Clock::now() + std::chrono::seconds(120);
       title.find("fps") == std::string::npos && Clock::now() < end;
       std::this_thread::sleep_for(std::chrono::milliseconds(100)))
    title = output_of(env + "xdotool getwindowname " + std::to_string(window) + " 2>/dev/null");
  ASSERT_NE(title.find("fps"), std::string::npos)
      << "the window never showed its frame rate; stderr: " << read_text(dir / "err.txt");

  ASSERT_EQ(send_wm_delete_window(x.display(), window), "");
  const int exit_code = wait_exit(app, std::chrono::seconds(60));
  const std::string out = read_text(dir / "out.txt"), err = read_text(dir / "err.txt");
  ASSERT_EQ(exit_code, 0) << "stdout:\n" << out << "stderr:\n" << err;

  std::smatch m;
  ASSERT_TRUE(std::regex_search(out, m, std::regex("window closed after (\\d+) frames"))) << out;
  const int frames = std::stoi(m[1]);
  EXPECT_GT(frames, 1) << out;
  const std::string text = read_text(log);
  int marks = 0;
  std::string line;
  for (std::istringstream lines(text); std::getline(lines, line);)
    marks += line.size() > 6 && line.compare(line.size() - 6, 6, " frame") == 0;
  EXPECT_EQ(marks, frames) << "the log must hold one frame mark per frame shown";
  EXPECT_NE(out.find("recorded"), std::string::npos) << out;

  // The log replays headless (its frame marks set the frame count) to what the window showed.
  CommandResult replay = run_rolypoly("render" + args + " --replay " + shell_quote(log) +
                                      " --out " + shell_quote((dir / "replay").string()));
  ASSERT_EQ(replay.exit_code, 0) << replay.err;
  const auto pngs = files_with_suffix(dir / "replay", ".png");
  ASSERT_EQ(pngs.size(), size_t(frames));
  const Rgba8Image shown = load_png((dir / "window.png").string());
  const Rgba8Image last = load_png((dir / "replay" / pngs.back()).string());
  EXPECT_EQ(shown.rgba, last.rgba) << "the window's last frame differs from the replay's";
}

}  // namespace
}  // namespace rp::test
