// The simulation through the command line: replayed input logs reproduce frames exactly, a
// recorded interactive session replays frame for frame, and bad logs or a missing ffmpeg are
// reported clearly.
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "support/cli_runner.h"
#include "support/image_metrics.h"

namespace {

using rp::test::run_rolypoly;
using rp::test::shell_quote;
using rp::test::TempDir;

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Marbles on at once, a fireball a few frames later and a drag across a tumbler (the centre
// tumbler's body is at about pixel (32, 44) of a 64x64 frame).
const char* kSession =
    "rolypoly-input 1\n"
    "step 0 key S\n"
    "step 8 key F\n"
    "step 12 mouse_down 32 44 64 64\n"
    "step 16 mouse_move 38 44 64 64\n"
    "step 20 mouse_move 44 46 64 64\n"
    "step 24 mouse_up 44 46 64 64\n";

TEST(SimulationCli, ReplayedSessionRendersIdenticallyTwice) {
  TempDir dir;
  write_file(dir / "session.log", kSession);
  std::string args = "render --size 64 --frames 10 --seed 7 --replay " +
                     shell_quote((dir / "session.log").string()) + " --out ";
  auto a = run_rolypoly(args + shell_quote((dir / "a").string()));
  auto b = run_rolypoly(args + shell_quote((dir / "b").string()));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  for (int i = 0; i < 10; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", i);
    EXPECT_EQ(read_file(dir / "a" / name), read_file(dir / "b" / name)) << name;
  }
  // The input changed the picture: marbles appeared between frame 0 and frame 9.
  EXPECT_NE(read_file(dir / "a" / "frame_0000.png"), read_file(dir / "a" / "frame_0009.png"));
}

TEST(SimulationCli, SeedsGiveDifferentMarbles) {
  TempDir dir;
  auto a = run_rolypoly("render --size 48 --frames 3 --marbles --seed 1 --out " +
                        shell_quote((dir / "a").string()));
  auto b = run_rolypoly("render --size 48 --frames 3 --marbles --seed 2 --out " +
                        shell_quote((dir / "b").string()));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_NE(read_file(dir / "a" / "frame_0002.png"), read_file(dir / "b" / "frame_0002.png"));
}

TEST(SimulationCli, MalformedReplayNamesTheLine) {
  TempDir dir;
  write_file(dir / "bad.log", "rolypoly-input 1\nstep 3 key S\nstep 2 jump\n");
  auto r = run_rolypoly("render --size 32 --frames 1 --replay " +
                        shell_quote((dir / "bad.log").string()) + " --out " +
                        shell_quote((dir / "out").string()));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad.log:3"), std::string::npos) << r.err;
  EXPECT_TRUE(rp::test::files_with_suffix(dir / "out", ".png").empty());
}

TEST(SimulationCli, VideoWithoutFfmpegIsAClearError) {
  TempDir dir;
  // An empty PATH entry list: ffmpeg cannot be found whether or not it is installed.
  auto r = run_rolypoly("render --size 32 --frames 1 --video " +
                            shell_quote((dir / "v.mp4").string()) + " --out " +
                            shell_quote((dir / "out").string()),
                        "PATH=/nonexistent");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("ffmpeg"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "v.mp4"));
}

TEST(SimulationCli, RecordedWindowSessionReplaysFrameForFrame) {
  if (!rp::test::have_program("xvfb-run")) GTEST_SKIP() << "xvfb-run is not installed";
  TempDir dir;
  std::string log = (dir / "rec.log").string();
  auto run = run_rolypoly("run --size 64 --frames 6 --marbles --seed 3 --record " +
                              shell_quote(log) + " --capture " +
                              shell_quote((dir / "window.png").string()),
                          "xvfb-run -a -s '-screen 0 640x480x24'");
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  std::string text = read_file(log);
  EXPECT_NE(text.find("frame"), std::string::npos) << text;
  // --frames is taken from the log's frame marks.
  auto replay = run_rolypoly("render --size 64 --marbles --seed 3 --replay " + shell_quote(log) +
                             " --out " + shell_quote((dir / "replay").string()));
  ASSERT_EQ(replay.exit_code, 0) << replay.err;
  auto frames = rp::test::files_with_suffix(dir / "replay", ".png");
  ASSERT_EQ(frames.size(), 6u);
  rp::test::Rgba8Image shown = rp::test::load_png((dir / "window.png").string());
  rp::test::Rgba8Image last = rp::test::load_png((dir / "replay" / frames.back()).string());
  EXPECT_EQ(shown.rgba, last.rgba);
}

TEST(SimulationCli, EffectSwitchesAreAcceptedAndCheckedForRange) {
  TempDir dir;
  auto ok = run_rolypoly("render --size 32 --frames 2 --no-taa --no-bloom --no-motion-blur "
                         "--out " + shell_quote((dir / "a").string()));
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  auto strength = run_rolypoly("render --size 32 --frames 1 --bloom-strength 0.3 --out " +
                               shell_quote((dir / "b").string()));
  EXPECT_EQ(strength.exit_code, 0) << strength.err;
  auto bad = run_rolypoly("render --size 32 --frames 1 --bloom-strength 2 --out " +
                          shell_quote((dir / "c").string()));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bloom-strength"), std::string::npos) << bad.err;
  // Bloom changes the picture (the lamp glows).
  auto off = run_rolypoly("render --size 32 --frames 1 --no-bloom --out " +
                          shell_quote((dir / "d").string()));
  ASSERT_EQ(off.exit_code, 0) << off.err;
  EXPECT_NE(read_file(dir / "b" / "frame_0000.png"), read_file(dir / "d" / "frame_0000.png"));
}

TEST(SimulationCli, BenchComparesBothVisibilityBackends) {
  auto r = run_rolypoly("bench --size 32 --frames 2 --warmup 1 --marbles --compare-visibility");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("raster (device)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("embree (host+upload)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("embree / raster"), std::string::npos) << r.out;
}

}  // namespace
