// --render-scale and --target-ms on the command line: a scaled render writes output-size frames;
// what the scale cannot serve (the path tracer, the light pass's terms read at the output size)
// is refused as a usage error before any device work.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/image_metrics.h"

namespace rp::test {
namespace {

TEST(RenderScaleCli, ScaledFramesHaveTheOutputSize) {
  TempDir dir;
  const CommandResult r = run_rolypoly("render --size 40 --frames 3 --voxels 32 --shadow-size "
                                       "128 --render-scale 0.5 --out " +
                                       shell_quote(dir.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const Rgba8Image last = load_png((dir / "frame_0002.png").string());
  EXPECT_EQ(last.width, 40u);
  EXPECT_EQ(last.height, 40u);
}

// bench --target-ms records the scales its measured frames were rendered at: a target no frame
// can meet walks the scale down (a change at most every five frames), one every frame meets
// leaves it at the start.
TEST(RenderScaleCli, BenchRecordsTheScalesOfTheMeasuredFrames) {
  struct Case {
    const char* target;
    bool moves;
  };
  for (const Case c : {Case{"1", true}, Case{"10000", false}}) {
    TempDir dir;
    const std::string json = (dir / "bench.json").string();
    const CommandResult r = run_rolypoly(
        std::string("bench --size 48 --frames 14 --warmup 2 --voxels 32 --target-ms ") +
        c.target + " --json " + shell_quote(json));
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_TRUE(Contains(r.out, "the measured frames at scales")) << r.out;
    std::ifstream in(json);
    const nlohmann::json run = nlohmann::json::parse(in).at("devices").at(0).at("runs").at(0);
    const float lo = run.at("render_scale_range").at(0), hi = run.at("render_scale_range").at(1);
    const uint32_t changes = run.at("render_scale_changes");
    EXPECT_GE(lo, 0.5f);
    EXPECT_LE(lo, hi);
    EXPECT_LE(hi, 1.0f);
    if (c.moves) {
      EXPECT_GE(changes, 1u) << c.target;
      EXPECT_LT(lo, hi) << c.target;
      EXPECT_LE(changes, 3u) << c.target;  // at most every fifth frame
      EXPECT_FLOAT_EQ(float(run.at("render_scale")), lo) << "it went down to where it ended";
    } else {
      EXPECT_EQ(changes, 0u) << c.target;
      EXPECT_EQ(lo, 1.0f);
      EXPECT_EQ(hi, 1.0f);
    }
  }
}

TEST(RenderScaleCli, WhatTheScaleCannotServeIsAUsageError) {
  struct Case {
    std::string args, message;
  };
  const Case cases[] = {
      {"render --render-scale 0.7 --quality pathtraced --spp 1",
       "--render-scale applies to the real-time modes"},
      {"render --target-ms 30 --exr", "--target-ms applies to the final image; --exr reads"},
      {"bench --accuracy --target-ms 33", "--accuracy measures a fixed --render-scale"},
      {"render --render-scale 0.4", "--render-scale"},
      {"render --render-scale 1.5", "--render-scale"},
      {"run --target-ms 0", "--target-ms"},
  };
  for (const Case& c : cases) {
    const CommandResult r = run_rolypoly(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_TRUE(Contains(r.err, c.message)) << c.args;
    EXPECT_FALSE(Contains(r.err, "device")) << c.args;  // refused before any device work
  }
}

}  // namespace
}  // namespace rp::test
