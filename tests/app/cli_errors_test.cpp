// The built binary's answers that need no rendering: device list, usage errors, unknown device,
// no display. Each runs `rolypoly` as a user would and checks exit code and message.
#include <gtest/gtest.h>

#include "support/cli_runner.h"

namespace rp::test {
namespace {

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

// An index too large for size_t printed "stoul" (exit 1); a large index that fits
// is an unknown device like any other.
TEST(CliErrors, HugeDeviceIndexNamesTheOption) {
  TempDir dir;
  CommandResult r = run_rolypoly("render --device 99999999999999999999 --size 8 --out " +
                                 shell_quote((dir / "out").string()));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "--device: 99999999999999999999 is not a device index"));
  EXPECT_FALSE(Contains(r.err, "stoul"));
  CommandResult big = run_rolypoly("render --device 123456789 --size 8 --frames 1 --out " +
                                   shell_quote((dir / "out").string()));
  EXPECT_EQ(big.exit_code, 1) << big.err;
  EXPECT_TRUE(Contains(big.err, "no OpenCL device with index 123456789"));
}

// Empty values were once accepted silently (--record "" recorded nothing).
TEST(CliErrors, EmptyValuesAreUsageErrors) {
  for (const char* args : {"render --voxels ''", "bench --json ''", "run --record ''",
                           "render --video ''", "render --out ''"}) {
    CommandResult r = run_rolypoly(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_TRUE(Contains(r.err, "needs a value; an empty one is not allowed")) << args;
  }
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
