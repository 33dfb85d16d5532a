// Timing statistics behind the render summary, the window title and the bench.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "app/pass_stats.h"
#include "app/progress.h"

namespace rp::app {
namespace {

TEST(PassStats, SummarizeOddCountTakesMiddleValue) {
  TimeSummary s = summarize({5.0, 1.0, 3.0});
  EXPECT_DOUBLE_EQ(s.median_ms, 3.0);
  EXPECT_DOUBLE_EQ(s.min_ms, 1.0);
  EXPECT_DOUBLE_EQ(s.max_ms, 5.0);
}

TEST(PassStats, SummarizeEvenCountAveragesTheTwoMiddleValues) {
  TimeSummary s = summarize({4.0, 1.0, 2.0, 10.0});
  EXPECT_DOUBLE_EQ(s.median_ms, 3.0);
  EXPECT_DOUBLE_EQ(s.min_ms, 1.0);
  EXPECT_DOUBLE_EQ(s.max_ms, 10.0);
}

TEST(PassStats, NinetyFifthPercentileIsTheNearestRank) {
  std::vector<double> ms;
  for (int i = 20; i >= 1; --i) ms.push_back(double(i));  // 1..20, unordered
  EXPECT_DOUBLE_EQ(summarize(ms).p95_ms, 19.0);            // ceil(0.95 * 20) = 19th smallest
  ms.push_back(100.0);                                     // 21 samples: the 20th smallest
  EXPECT_DOUBLE_EQ(summarize(ms).p95_ms, 20.0);
  EXPECT_DOUBLE_EQ(summarize({5.0, 1.0, 3.0}).p95_ms, 5.0);  // 3 samples: the largest
  EXPECT_DOUBLE_EQ(summarize({7.0}).p95_ms, 7.0);
}

TEST(PassStats, SummarizeRejectsNoSamples) {
  EXPECT_THROW(summarize({}), std::invalid_argument);
}

TEST(PassStats, CollectsPerPassAndFrameTimes) {
  PassStats stats;
  stats.add({{"light", 10.0}, {"visibility", 2.0}}, 13.0);
  stats.add({{"light", 30.0}, {"visibility", 4.0}}, 35.0);
  stats.add({{"light", 20.0}, {"visibility", 3.0}}, 24.0);
  EXPECT_EQ(stats.frames(), 3u);
  EXPECT_DOUBLE_EQ(stats.pass("light").median_ms, 20.0);
  EXPECT_DOUBLE_EQ(stats.pass("visibility").max_ms, 4.0);
  EXPECT_DOUBLE_EQ(stats.frame().median_ms, 24.0);
  EXPECT_DOUBLE_EQ(stats.pass_means().at("light"), 20.0);
  EXPECT_THROW(stats.pass("taa"), std::invalid_argument);
  stats.clear();
  EXPECT_EQ(stats.frames(), 0u);
}

TEST(PassStats, PassNamesFollowThePipelineThenAlphabet) {
  PassStats stats;
  stats.add({{"tone_map", 1.0}, {"zeta_debug", 1.0}, {"gbuffer", 1.0}, {"alpha_debug", 1.0},
             {"visibility", 1.0}, {"light", 1.0}},
            1.0);
  std::vector<std::string> expected = {"visibility", "gbuffer",    "light",
                                       "tone_map",   "alpha_debug", "zeta_debug"};
  EXPECT_EQ(stats.pass_names(), expected);
}

TEST(BenchReport, MedianLineListsPassesInPipelineOrder) {
  PassStats stats;
  stats.add({{"visibility", 1.5}, {"light", 7.25}}, 9.0);
  EXPECT_EQ(median_line(stats), "visibility 1.50 ms, light 7.25 ms");
}

TEST(Progress, LineShowsFractionDone) {
  EXPECT_EQ(ProgressBar::render_line("render", 1, 4, 8), "render [##......] 1/4");
  EXPECT_EQ(ProgressBar::render_line("render", 4, 4, 8), "render [########] 4/4");
  EXPECT_EQ(ProgressBar::render_line("render", 9, 4, 8), "render [########] 4/4");
  EXPECT_EQ(ProgressBar::render_line("x", 0, 0, 2), "x [##] 0/0");
}

}  // namespace
}  // namespace rp::app
