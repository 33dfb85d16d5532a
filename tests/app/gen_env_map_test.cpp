// tools/gen_env_map: the three maps that split the cones' sky light (tools/cone_light_split.sh)
// read back through the renderer's own loader with the radiance their names promise; bad
// arguments are refused and write nothing.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <sys/wait.h>

#include "support/cli_runner.h"
#include "truth/environment.h"

namespace rp::test {
namespace {

int run_tool(const TempDir& dir, const std::string& args) {
  const std::string command = "cd " + shell_quote(dir.path().string()) + " && " +
                              shell_quote(ROLYPOLY_GEN_ENV_MAP) + " " + args +
                              " > out.txt 2> err.txt";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Texel (x, y)'s red channel (the maps are grey).
float texel(const scene::EnvironmentMap& m, int x, int y) {
  return m.rgb[(size_t(y) * size_t(m.width) + size_t(x)) * 3];
}

TEST(GenEnvMap, ConstantMapIsOneEverywhere) {
  const TempDir dir;
  ASSERT_EQ(run_tool(dir, "const.hdr const"), 0);
  const scene::EnvironmentMap m = truth::load_environment_map(dir / "const.hdr");
  ASSERT_EQ(m.width, 64);
  ASSERT_EQ(m.height, 32);
  for (float v : m.rgb) ASSERT_EQ(v, 1.0f);
}

TEST(GenEnvMap, UpperMapIsOneAboveTheHorizonOnly) {
  const TempDir dir;
  ASSERT_EQ(run_tool(dir, "upper.hdr upper"), 0);
  const scene::EnvironmentMap m = truth::load_environment_map(dir / "upper.hdr");
  ASSERT_EQ(m.height, 32);
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x)
      ASSERT_EQ(texel(m, x, y), y < 16 ? 1.0f : 0.0f) << x << ", " << y;
}

TEST(GenEnvMap, SunMapHasOneBrightPatch) {
  const TempDir dir;
  ASSERT_EQ(run_tool(dir, "sun.hdr sun"), 0);
  const scene::EnvironmentMap m = truth::load_environment_map(dir / "sun.hdr");
  ASSERT_EQ(m.width, 256);
  ASSERT_EQ(m.height, 128);
  int bright = 0;
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      const float v = texel(m, x, y);
      if (v > 1.0f) {
        ++bright;
        EXPECT_NEAR(v, 2000.0f, 2000.0f / 256.0f) << x << ", " << y;  // one RGBE mantissa step
        EXPECT_TRUE((y == 34 || y == 35) && (x == 100 || x == 101)) << x << ", " << y;
      } else {
        EXPECT_NEAR(v, 1.0e-3f, 1.0e-3f / 128.0f) << x << ", " << y;
      }
    }
  EXPECT_EQ(bright, 4);
}

TEST(GenEnvMap, BadArgumentsAreRefusedAndWriteNothing) {
  const TempDir dir;
  EXPECT_EQ(run_tool(dir, "x.hdr cloudy"), 2);
  EXPECT_TRUE(Contains(read_all(dir / "err.txt"), "usage: gen_env_map"));
  EXPECT_EQ(run_tool(dir, "--sun x.hdr"), 2);
  EXPECT_EQ(run_tool(dir, "--help"), 0);
  EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{"err.txt", "out.txt"}));
}

}  // namespace
}  // namespace rp::test
