// --render-scale and --target-ms on the command line: a scaled render writes output-size frames;
// what the scale cannot serve (the path tracer, the light pass's terms read at the output size)
// is refused as a usage error before any device work.
#include <gtest/gtest.h>

#include <string>

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
