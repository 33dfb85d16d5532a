// tools/gen_load_scene's command line: help and mistakes get a message and an exit status, and
// never a scene written under the mistyped name.
#include <gtest/gtest.h>

#include <string>

#include "support/cli_runner.h"

namespace rp::test {
namespace {

CommandResult run_tool(const TempDir& dir, const std::string& args) {
  return run_program_in(ROLYPOLY_GEN_LOAD_SCENE, dir.path(), args);
}

TEST(GenLoadSceneCli, HelpPrintsUsageAndWritesNothing) {
  const TempDir dir;
  const CommandResult r = run_tool(dir, "--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(Contains(r.out, "usage: gen_load_scene OUT.glb"));
  EXPECT_TRUE(entries(dir.path()).empty());
}

TEST(GenLoadSceneCli, OptionsAndBadCountsAreRefused) {
  const TempDir dir;
  const CommandResult option = run_tool(dir, "-x");
  EXPECT_EQ(option.exit_code, 2);
  EXPECT_TRUE(Contains(option.err, "usage: gen_load_scene"));
  const CommandResult junk = run_tool(dir, "out.glb 12abc");
  EXPECT_EQ(junk.exit_code, 2);
  EXPECT_TRUE(Contains(junk.err, "TRIANGLES 1000..50000000"));
  EXPECT_EQ(run_tool(dir, "out.glb 999").exit_code, 2);
  EXPECT_EQ(run_tool(dir, "out.glb 5000 0").exit_code, 2);
  EXPECT_TRUE(entries(dir.path()).empty());
}

}  // namespace
}  // namespace rp::test
