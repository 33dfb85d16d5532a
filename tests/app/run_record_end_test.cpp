// `run --record` keeps its log however the session ends. It used to be written only when the
// window closed (Esc, close button): SIGINT, SIGTERM, SIGHUP, SIGQUIT and a lost X connection
// (Xlib ends the process inside its I/O error handler) lost the whole recording. Each case runs
// `run --frames 0 --record` on a private Xvfb until the title shows a frame rate, ends it, and
// checks the exit code, the one-line message and that the log holds a frame mark per frame.
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <regex>
#include <sstream>
#include <string>
#include <utility>

#include "support/cli_runner.h"
#include "xvfb_server.h"

namespace rp::test {
namespace {

int frame_marks(const std::string& log) {
  int marks = 0;
  std::string line;
  for (std::istringstream lines(log); std::getline(lines, line);)
    marks += line.size() > 6 && line.compare(line.size() - 6, 6, " frame") == 0;
  return marks;
}

struct Session {
  TempDir dir;
  std::string log = (dir / "session.log").string();
  pid_t pid = -1;

  // `exec env`: the pid is rolypoly's own, so signals reach it and not a shell.
  explicit Session(const std::string& display) {
    pid = spawn_shell("exec env DISPLAY=" + display + " " + shell_quote(ROLYPOLY_BINARY) +
                      " run --frames 0 --size 48 --marbles --record " + shell_quote(log) + " >" +
                      shell_quote((dir / "out.txt").string()) + " 2>" +
                      shell_quote((dir / "err.txt").string()));
  }
  std::string out() const { return read_text(dir / "out.txt"); }
  std::string err() const { return read_text(dir / "err.txt"); }
};

bool have_x_tools() { return have_program("Xvfb") && have_program("xdotool"); }

// SIGHUP (the terminal or ssh session closed) and SIGQUIT used to kill the session with no log.
TEST(RunRecordEnd, SignalsWriteTheLogAndExit128PlusSignal) {
  if (!have_x_tools()) GTEST_SKIP() << "Xvfb or xdotool not installed (tools/setup.sh)";
  const std::pair<int, const char*> signals[] = {
      {SIGINT, "SIGINT"}, {SIGTERM, "SIGTERM"}, {SIGHUP, "SIGHUP"}, {SIGQUIT, "SIGQUIT"}};
  for (const auto& [signal, signal_name] : signals) {
    const std::string name = signal_name;
    SCOPED_TRACE(name);
    XvfbServer x;
    ASSERT_FALSE(x.display().empty()) << "Xvfb did not start";
    Session s(x.display());
    ASSERT_NE(wait_for_rolypoly_window(x.display()), 0ul) << s.err();
    ASSERT_EQ(kill(s.pid, signal), 0);
    EXPECT_EQ(wait_exit(s.pid, std::chrono::seconds(60)), 128 + signal) << s.err();
    std::smatch m;
    const std::string err = s.err();
    ASSERT_TRUE(std::regex_search(
        err, m,
        std::regex("rolypoly: error: interrupted by " + name +
                   " after (\\d+) frames \\(the --record log is complete\\)")))
        << err;
    const int frames = std::stoi(m[1]);
    EXPECT_GT(frames, 1);
    EXPECT_EQ(frame_marks(read_text(s.log)), frames) << "one frame mark per frame shown";
    EXPECT_NE(s.out().find("recorded"), std::string::npos) << s.out();
  }
}

TEST(RunRecordEnd, LostDisplayWritesTheLogBeforeExiting) {
  if (!have_x_tools()) GTEST_SKIP() << "Xvfb or xdotool not installed (tools/setup.sh)";
  XvfbServer x;
  ASSERT_FALSE(x.display().empty()) << "Xvfb did not start";
  Session s(x.display());
  ASSERT_NE(wait_for_rolypoly_window(x.display()), 0ul) << s.err();
  x.kill_now();  // the X server dies: every X call of rolypoly fails from now on
  EXPECT_EQ(wait_exit(s.pid, std::chrono::seconds(60)), 1) << s.err();
  std::smatch m;
  const std::string err = s.err();
  ASSERT_TRUE(std::regex_search(
      err, m,
      std::regex("rolypoly: error: lost the connection to the display after (\\d+) frames; "
                 "writing the --record log")))
      << err;
  const int frames = std::stoi(m[1]);
  EXPECT_GT(frames, 1);
  // The frame being presented when the connection broke was rendered and marked, not shown.
  const int marks = frame_marks(read_text(s.log));
  EXPECT_GE(marks, frames);
  EXPECT_LE(marks, frames + 1);
  EXPECT_NE(s.out().find("recorded"), std::string::npos) << s.out();
}

}  // namespace
}  // namespace rp::test
