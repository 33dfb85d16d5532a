// The built binary's answers that need no rendering: device list, usage errors, unknown device,
// no display. Each runs `rolypoly` as a user would and checks exit code and message.
#include <gtest/gtest.h>

#include "cli_runner.h"

namespace rp::test {
namespace {

::testing::AssertionResult Contains(const std::string& text, const std::string& needle) {
  if (text.find(needle) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << needle << "' not found in:\n" << text;
}

TEST(CliErrors, DevicesListsThePoclDevice) {
  CommandResult r = run_rolypoly("devices");
  ASSERT_EQ(r.exit_code, 0) << r.command << "\n" << r.err;
  bool pocl = r.out.find("pthread") != std::string::npos ||
              r.out.find("Portable Computing Language") != std::string::npos;
  EXPECT_TRUE(pocl) << r.out;
  EXPECT_TRUE(Contains(r.out, "[0]"));
  EXPECT_TRUE(Contains(r.out, "compute units"));
  EXPECT_TRUE(Contains(r.out, "MiB"));
  EXPECT_TRUE(Contains(r.out, "OpenCL"));
}

TEST(CliErrors, UnknownOptionIsAUsageError) {
  CommandResult r = run_rolypoly("render --no-such-option");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_TRUE(Contains(r.err, "--no-such-option"));
}

TEST(CliErrors, UnknownSubcommandIsAUsageError) {
  CommandResult r = run_rolypoly("paint");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_TRUE(Contains(r.err, "paint"));
}

TEST(CliErrors, MissingSubcommandIsAUsageError) {
  CommandResult r = run_rolypoly("");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_TRUE(Contains(r.err, "subcommand"));
}

TEST(CliErrors, BadValueIsAUsageError) {
  CommandResult r = run_rolypoly("render --size 0");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_TRUE(Contains(r.err, "--size"));
}

TEST(CliErrors, HelpSucceedsAndNamesTheSubcommands) {
  CommandResult r = run_rolypoly("--help");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  for (const char* sub : {"devices", "render", "run", "bench"}) EXPECT_TRUE(Contains(r.out, sub));
}

TEST(CliErrors, UnknownDeviceListsTheDevices) {
  TempDir dir;
  CommandResult r = run_rolypoly("render --device nosuchdevice --size 8 --frames 1 --out " +
                                 shell_quote((dir / "out").string()));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_TRUE(Contains(r.err, "rolypoly: error:"));
  EXPECT_TRUE(Contains(r.err, "nosuchdevice"));
  EXPECT_TRUE(Contains(r.err, "[0]"));  // the list of devices to choose from
  EXPECT_TRUE(files_with_suffix(dir / "out", ".png").empty());
}

TEST(CliErrors, RunWithoutDisplaySaysSoAndPointsToRender) {
  CommandResult r = run_rolypoly("run --size 16 --frames 1", "env -u DISPLAY -u WAYLAND_DISPLAY");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(Contains(r.err, "rolypoly: error:"));
  EXPECT_TRUE(Contains(r.err, "no display"));
  EXPECT_TRUE(Contains(r.err, "rolypoly render"));
}

}  // namespace
}  // namespace rp::test
