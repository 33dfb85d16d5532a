// The `H` key cycles `run`'s shadow mode (hard, pcf, pcss, vssm, hard, ...), and the
// window title names the mode in use ("rolypoly | 4.1 fps | shadows pcss | ..."). Driven on a
// private Xvfb with xdotool: start on pcss (the default), press H twice, read the title after
// each press, then close the window with Esc.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "support/cli_runner.h"
#include "xvfb_server.h"

namespace rp::test {
namespace {

// The window's title once it names `mode` (the title refreshes about twice a second); the last
// title read when that did not happen within 60 s.
std::string wait_for_title_with(const std::string& display, unsigned long window,
                                const std::string& mode) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::string title;
  while (std::chrono::steady_clock::now() < deadline) {
    title = output_of("DISPLAY=" + display + " xdotool getwindowname " +
                      std::to_string(window) + " 2>/dev/null");
    if (title.find("shadows " + mode + " |") != std::string::npos) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  return title;
}

// Focus, then a real key press through XTEST (no window manager here: windowactivate needs one,
// and GLFW ignored events sent to the window with `key --window`).
void press(const std::string& display, unsigned long window, const std::string& key) {
  output_of("DISPLAY=" + display + " xdotool windowfocus --sync " + std::to_string(window) +
            " key " + key + " 2>&1");
}

TEST(ShadowKey, HCyclesTheShadowModeShownInTheTitle) {
  for (const char* program : {"Xvfb", "xdotool"})
    if (!have_program(program)) GTEST_SKIP() << program << " not installed (tools/setup.sh)";
  XvfbServer x;
  ASSERT_FALSE(x.display().empty()) << "Xvfb did not start";
  TempDir dir;
  const pid_t pid =
      spawn_shell("exec env DISPLAY=" + x.display() + " " + shell_quote(ROLYPOLY_BINARY) +
                  " run --frames 0 --size 48 >" + shell_quote((dir / "out.txt").string()) +
                  " 2>" + shell_quote((dir / "err.txt").string()));
  const unsigned long window = wait_for_rolypoly_window(x.display());
  ASSERT_NE(window, 0ul) << read_text(dir / "err.txt");
  EXPECT_NE(wait_for_title_with(x.display(), window, "pcss").find("shadows pcss |"),
            std::string::npos);
  press(x.display(), window, "h");
  EXPECT_NE(wait_for_title_with(x.display(), window, "vssm").find("shadows vssm |"),
            std::string::npos)
      << "H after pcss";
  press(x.display(), window, "h");
  EXPECT_NE(wait_for_title_with(x.display(), window, "hard").find("shadows hard |"),
            std::string::npos)
      << "H after vssm wraps around";
  press(x.display(), window, "Escape");
  EXPECT_EQ(wait_exit(pid, std::chrono::seconds(60)), 0) << read_text(dir / "err.txt");
}

}  // namespace
}  // namespace rp::test
