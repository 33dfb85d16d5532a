// `rolypoly bench --accuracy` end to end at a tiny size: the report, its files, the truth cache
// and the thresholds' exit code; and the cache key's sensitivity.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "app/truth_cache.h"
#include "cli_runner.h"
#include "scene/demo_scene.h"

namespace rp::app {
namespace {

using rp::test::run_rolypoly;
using rp::test::shell_quote;
using rp::test::TempDir;

TEST(AccuracyCli, WritesTheReportAndReusesTheCachedTruth) {
  TempDir dir;
  const std::string args = "bench --accuracy --size 24 --spp 4 --truth-cache " +
                           shell_quote((dir / "cache").string()) + " --out " +
                           shell_quote((dir / "out").string()) + " --json " +
                           shell_quote((dir / "acc.json").string());
  const rp::test::CommandResult first = run_rolypoly(args);
  ASSERT_EQ(first.exit_code, 0) << first.command << "\n" << first.out << first.err;
  EXPECT_NE(first.out.find("indirect bias ceiling"), std::string::npos) << first.out;
  EXPECT_EQ(first.out.find("from the cache"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "accuracy_side_by_side.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "accuracy_indirect_heat.png"));
  EXPECT_EQ(rp::test::files_with_suffix(dir / "cache", ".exr").size(), 2u);  // 1 and 64 bounces

  std::ifstream in(dir / "acc.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["schema"], "rolypoly-accuracy/1");
  EXPECT_EQ(j["width"], 24);
  for (const char* mode : {"fast", "reference"})
    for (const char* vs : {"vs_one_bounce", "vs_many_bounces"}) {
      const nlohmann::json& m = j["modes"][mode][vs];
      EXPECT_TRUE(m["final_psnr_db"].is_number()) << mode << vs;
      EXPECT_GE(m["indirect"]["image"]["rel_l1"].get<double>(), 0.0);
      EXPECT_TRUE(m["indirect"].contains("ceiling"));
      EXPECT_TRUE(m["incoming_indirect"].contains("left_wall"));
      // The direct light is the same model in both: it agrees far better than the indirect.
      EXPECT_LT(std::abs(m["direct"]["bias"].get<double>()), 0.1) << mode << vs;
    }
  // Many bounces carry more light than one.
  EXPECT_GT(j["truth"]["many"]["incoming_indirect"]["right_wall"]["rgb"][0].get<double>(),
            j["truth"]["one"]["incoming_indirect"]["right_wall"]["rgb"][0].get<double>());

  const rp::test::CommandResult second = run_rolypoly(args + " --max-indirect-l1 0.0001");
  EXPECT_EQ(second.exit_code, 3) << second.out << second.err;  // missed on purpose
  EXPECT_NE(second.out.find("(from the cache)"), std::string::npos) << second.out;
  EXPECT_NE(second.out.find("max_indirect_l1 0.000: MISSED"), std::string::npos) << second.out;
  const rp::test::CommandResult third = run_rolypoly(args + " --max-indirect-l1 1000");
  EXPECT_EQ(third.exit_code, 0) << third.out << third.err;
}

TEST(AccuracyCli, UsageErrors) {
  for (const char* args :
       {"bench --out x", "bench --max-indirect-l1 0.1", "bench --accuracy --sizes 16,32",
        "bench --accuracy --quality-report", "bench --accuracy --bounces 3",
        "bench --accuracy --max-indirect-bias nan", "bench --accuracy --quality pathtraced"}) {
    const rp::test::CommandResult r = run_rolypoly(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
  }
}

TEST(TruthCache, KeyFollowsEverythingTheImageDependsOn) {
  const scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  const scene::FrameScene frame = scene::make_demo_frame(assets);
  truth::PathTraceSettings s;
  const std::string key = truth_key(assets, frame, s);
  EXPECT_EQ(key.size(), 16u);
  EXPECT_EQ(key, truth_key(assets, frame, s));
  s.threads = 7;  // not part of the image
  EXPECT_EQ(key, truth_key(assets, frame, s));
  truth::PathTraceSettings more = s;
  more.spp += 1;
  EXPECT_NE(key, truth_key(assets, frame, more));
  more = s;
  more.bounces = 2;
  EXPECT_NE(key, truth_key(assets, frame, more));
  scene::FrameScene moved = frame;
  moved.instances.back().model[3][0] += 1e-3f;
  EXPECT_NE(key, truth_key(assets, moved, s));
  scene::SceneAssets recoloured = assets;
  recoloured.textures[0].rgba[0] ^= 1;
  EXPECT_NE(key, truth_key(recoloured, frame, s));
}

}  // namespace
}  // namespace rp::app
