// tools/gen_load_scene's command line: help and mistakes get a message and an exit status, and
// never a scene written under the mistyped name.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <sys/wait.h>

#include "support/cli_runner.h"

namespace rp::test {
namespace {

// Runs the tool in `dir` with `args`; its exit status (-1 if it did not exit normally).
int run_tool(const TempDir& dir, const std::string& args) {
  const std::string command = "cd " + shell_quote(dir.path().string()) + " && " +
                              shell_quote(ROLYPOLY_GEN_LOAD_SCENE) + " " + args +
                              " > out.txt 2> err.txt";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(GenLoadSceneCli, HelpPrintsUsageAndWritesNothing) {
  const TempDir dir;
  EXPECT_EQ(run_tool(dir, "--help"), 0);
  EXPECT_TRUE(Contains(read_all(dir / "out.txt"), "usage: gen_load_scene OUT.glb"));
  EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{"err.txt", "out.txt"}));
}

TEST(GenLoadSceneCli, OptionsAndBadCountsAreRefused) {
  const TempDir dir;
  EXPECT_EQ(run_tool(dir, "-x"), 2);
  EXPECT_TRUE(Contains(read_all(dir / "err.txt"), "usage: gen_load_scene"));
  EXPECT_EQ(run_tool(dir, "out.glb 12abc"), 2);
  EXPECT_TRUE(Contains(read_all(dir / "err.txt"), "TRIANGLES 1000..50000000"));
  EXPECT_EQ(run_tool(dir, "out.glb 999"), 2);
  EXPECT_EQ(run_tool(dir, "out.glb 5000 0"), 2);
  EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{"err.txt", "out.txt"}));
}

}  // namespace
}  // namespace rp::test
