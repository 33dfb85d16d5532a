// "The window closed mid-run": `rolypoly run --frames 0 --record` in a window on a
// private Xvfb server is closed the way a window manager closes it (WM_DELETE_WINDOW, sent to
// the window that xdotool finds), after it has shown frames for a while. Checks: exit code 0,
// "window closed after N frames", the --record log is complete (N frame marks) and replays to
// the same pictures (the replay's last frame equals the window's --capture).
#include <gtest/gtest.h>

#include <chrono>
#include <regex>
#include <sstream>
#include <string>

#include "support/cli_runner.h"
#include "support/image_metrics.h"
#include "x11_close.h"
#include "xvfb_server.h"

namespace rp::test {
namespace {

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
  const pid_t app = spawn_shell(env + shell_quote(ROLYPOLY_BINARY) + " run --frames 0" + args +
                                " --record " + shell_quote(log) + " --capture " +
                                shell_quote((dir / "window.png").string()) + " >" +
                                shell_quote((dir / "out.txt").string()) + " 2>" +
                                shell_quote((dir / "err.txt").string()));

  // The window, then its title's frame rate: it has been showing frames for >= 0.5 s.
  const unsigned long window = wait_for_rolypoly_window(x.display());
  ASSERT_NE(window, 0ul) << "no rolypoly window showed its frame rate; stderr: "
                         << read_text(dir / "err.txt");

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
