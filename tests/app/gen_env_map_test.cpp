// tools/gen_env_map: the three maps that split the cones' sky light (tools/cone_light_split.sh)
// read back through the renderer's own loader with the radiance their names promise; bad
// arguments are refused and write nothing.
#include <gtest/gtest.h>

#include <string>

#include "support/cli_runner.h"
#include "truth/environment.h"

namespace rp::test {
namespace {

// The tool's exit status, run in `dir`.
int run_tool(const TempDir& dir, const std::string& args) {
  return run_program_in(ROLYPOLY_GEN_ENV_MAP, dir.path(), args).exit_code;
}

// Texel (x, y)'s red channel (the maps are grey).
float texel(const scene::EnvironmentMap& m, int x, int y) {
  return m.rgb[(size_t(y) * size_t(m.width) + size_t(x)) * 3];
}

// The map of `kind`, written by the tool into `dir` and read back by the renderer's loader.
scene::EnvironmentMap generated(const TempDir& dir, const std::string& kind) {
  const int status = run_tool(dir, kind + ".hdr " + kind);
  EXPECT_EQ(status, 0) << kind;
  return status == 0 ? truth::load_environment_map(dir / (kind + ".hdr"))
                     : scene::EnvironmentMap{};
}

TEST(GenEnvMap, ConstantMapIsOneEverywhere) {
  const TempDir dir;
  const scene::EnvironmentMap m = generated(dir, "const");
  EXPECT_EQ(m.width, 64);
  EXPECT_EQ(m.height, 32);
  for (float v : m.rgb) ASSERT_EQ(v, 1.0f);
}

TEST(GenEnvMap, UpperMapIsOneAboveTheHorizonOnly) {
  const TempDir dir;
  const scene::EnvironmentMap m = generated(dir, "upper");
  EXPECT_EQ(m.height, 32);
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x)
      ASSERT_EQ(texel(m, x, y), y < m.height / 2 ? 1.0f : 0.0f) << x << ", " << y;
}

TEST(GenEnvMap, SunMapHasOneBrightPatch) {
  const TempDir dir;
  const scene::EnvironmentMap m = generated(dir, "sun");
  EXPECT_EQ(m.width, 256);
  EXPECT_EQ(m.height, 128);
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
  const CommandResult r = run_program_in(ROLYPOLY_GEN_ENV_MAP, dir.path(), "x.hdr cloudy");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Contains(r.err, "usage: gen_env_map"));
  EXPECT_EQ(run_tool(dir, "--sun x.hdr"), 2);
  EXPECT_EQ(run_tool(dir, "--help"), 0);
  EXPECT_TRUE(entries(dir.path()).empty());
}

}  // namespace
}  // namespace rp::test
