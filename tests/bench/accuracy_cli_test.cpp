// `rolypoly bench --accuracy` end to end at a tiny size: the report, its files, the truth cache
// and the thresholds' exit code; and the cache key's sensitivity.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "app/truth_cache.h"
#include "scene/demo_scene.h"
#include "support/cli_runner.h"

namespace rp::bench {
namespace {

using rp::test::run_rolypoly;
using rp::test::shell_quote;
using rp::test::TempDir;
using app::truth_key;

TEST(AccuracyCli, WritesTheReportAndReusesTheCachedTruth) {
  TempDir dir;
  const std::string args = "bench --accuracy --size 24 --spp 4 --truth-cache " +
                           shell_quote((dir / "cache").string()) + " --out " +
                           shell_quote((dir / "out").string()) + " --json " +
                           shell_quote((dir / "acc.json").string());
  const rp::test::CommandResult first = run_rolypoly(args);
  ASSERT_EQ(first.exit_code, 0) << first.command << "\n" << first.out << first.err;
  for (const char* text : {"indirect bias ceiling", "fast/N", "ref/N", "fast/1", "ref/1",
                           "final PSNR, TAA (dB)", "final PSNR, first frame (dB)",
                           "right_wall reference N",
                           "left_wall  sign of R - B: fast N as truth N"})
    EXPECT_NE(first.out.find(text), std::string::npos) << text << "\n" << first.out;
  EXPECT_EQ(first.out.find("from the cache"), std::string::npos);
  EXPECT_EQ(first.out.find("threshold"), std::string::npos) << "none asked for";
  for (const char* png : {"accuracy_side_by_side.png", "accuracy_indirect_heat.png",
                          "accuracy_final_taa.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / png)) << png;
  // 1 and 64 bounces; the direct section's area lamp (two seeds) and point lamp at 0 bounces.
  EXPECT_EQ(rp::test::files_with_suffix(dir / "cache", ".exr").size(), 5u);
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "accuracy_direct_side_by_side.png"));
  for (const char* text : {"direct light against the area-lamp truth", "(truth noise)", "hard ",
                           "vssm ", "albedo view ("})
    EXPECT_NE(first.out.find(text), std::string::npos) << text << "\n" << first.out;

  std::ifstream in(dir / "acc.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["schema"], "rolypoly-accuracy/4");
  EXPECT_EQ(j["width"], 24);
  EXPECT_FALSE(j.contains("thresholds"));
  EXPECT_TRUE(j["passed"].get<bool>());
  const nlohmann::json& cfg = j["configurations"];
  for (const char* key : {"fast_many", "reference_many", "fast_one", "reference_one"}) {
    const nlohmann::json& m = cfg[key];
    const bool many = std::string(key).ends_with("many");
    EXPECT_EQ(m["bounces"], many ? 64 : 1) << key;
    EXPECT_EQ(m["truth"], many ? "many" : "one") << key;
    EXPECT_EQ(m["quality"], std::string(key).starts_with("fast") ? "fast" : "reference");
    EXPECT_FALSE(m["taa"].get<bool>());
    EXPECT_GE(m["frames"].get<int>(), 1);
    EXPECT_TRUE(m["final_psnr_db"].is_number()) << key;
    EXPECT_GE(m["indirect"]["image"]["rel_l1"].get<double>(), 0.0);
    EXPECT_TRUE(m["indirect"].contains("ceiling"));
    EXPECT_TRUE(m["incoming_indirect"]["left_wall"].contains("same_hue_sign_as_truth"));
    EXPECT_TRUE(m["leaks"]["leak_pixels"].is_number());
    // The direct light is the same model in both: it agrees far better than the indirect.
    EXPECT_LT(std::abs(m["direct"]["bias"].get<double>()), 0.1) << key;
  }
  EXPECT_EQ(cfg["fast_one"]["frames"], 128);
  EXPECT_EQ(cfg["reference_one"]["frames"], 1);
  const nlohmann::json& taa = cfg["fast_many_taa"];
  EXPECT_TRUE(taa["taa"].get<bool>());
  EXPECT_FALSE(taa["bloom"].get<bool>());
  EXPECT_EQ(taa["bounces"], 64);
  EXPECT_GT(taa["final_psnr_db"].get<double>(), 5.0);
  const nlohmann::json& first_frame = cfg["fast_first_frame"];
  EXPECT_EQ(first_frame["frames"], 1);
  EXPECT_TRUE(first_frame["taa"].get<bool>());
  EXPECT_GT(first_frame["final_psnr_db"].get<double>(), 5.0);
  EXPECT_NEAR(first_frame["gap_to_taa_db"].get<double>(),
              taa["final_psnr_db"].get<double>() - first_frame["final_psnr_db"].get<double>(),
              1e-9);
  // Many bounces carry more light than one.
  EXPECT_GT(j["truth"]["many"]["incoming_indirect"]["right_wall"]["rgb"][0].get<double>(),
            j["truth"]["one"]["incoming_indirect"]["right_wall"]["rgb"][0].get<double>());
  EXPECT_LT(j["truth"]["one"]["indirect_vs_many"]["bias"].get<double>(), -0.1);
  // The direct section: every shadow mode, the truth's lamp model, its noise, both lines.
  const nlohmann::json& direct = j["direct"];
  EXPECT_EQ(direct["truth"]["lamp"], "area");
  EXPECT_EQ(direct["truth"]["bounces"], 0);
  EXPECT_EQ(direct["truth"]["spp"], 16);  // 4 x --spp
  EXPECT_TRUE(direct["truth"]["noise_psnr_db"]["floor"].is_number());
  for (const char* mode : {"hard", "pcf", "pcss", "vssm"}) {
    EXPECT_TRUE(direct["modes"][mode]["direct_psnr_db"]["image"].is_number()) << mode;
    EXPECT_TRUE(direct["modes"][mode]["albedo_psnr_db"]["image"].is_number()) << mode;
    EXPECT_TRUE(direct["modes"][mode]["penumbra"].contains("tumbler")) << mode;
    EXPECT_TRUE(direct["modes"][mode]["penumbra"].contains("marble")) << mode;
    const nlohmann::json& parts = direct["modes"][mode]["penumbra_breakdown"]["parts"];
    EXPECT_EQ(parts["open_floor"]["pixels"].get<int>() +
                  parts["floor_beside_objects"]["pixels"].get<int>() +
                  parts["objects"]["pixels"].get<int>(),
              direct["pixels"]["penumbra"].get<int>())
        << mode;
    EXPECT_EQ(direct["modes"][mode]["penumbra_breakdown"]["open_floor_by_lamp_fraction"].size(),
              10u)
        << mode;
  }
  EXPECT_NE(first.out.find("penumbra by part: open floor"), std::string::npos) << first.out;
  EXPECT_TRUE(direct["lines"]["tumbler"]["length"].is_number());
  EXPECT_TRUE(direct["default_shadows"].is_string());

  // Every threshold, two missed on purpose; the truths come from the cache.
  const rp::test::CommandResult second = run_rolypoly(
      args + " --max-indirect-l1 0.0001 --max-indirect-bias 1000 --max-region-bias 1000 "
             "--max-indirect-l1-single 1000 --min-psnr-taa 1000 --max-first-frame-gap 1000 "
             "--require-wall-hue "
             "--min-direct-psnr-floor 1000 --max-penumbra-error 1000 --min-albedo-psnr 0");
  EXPECT_EQ(second.exit_code, 3) << second.out << second.err;
  EXPECT_NE(second.out.find("(from the cache)"), std::string::npos) << second.out;
  EXPECT_NE(second.out.find("threshold max_indirect_l1 "), std::string::npos) << second.out;
  EXPECT_NE(second.out.find("limit 0.0001: MISSED"), std::string::npos) << second.out;
  std::ifstream in2(dir / "acc.json");
  const nlohmann::json j2 = nlohmann::json::parse(in2);
  EXPECT_FALSE(j2["passed"].get<bool>());
  for (const char* name : {"max_indirect_l1", "max_indirect_bias", "max_region_bias",
                           "max_indirect_l1_single", "min_psnr_taa", "max_first_frame_gap",
                           "require_wall_hue"}) {
    const nlohmann::json& th = j2["thresholds"][name];
    EXPECT_TRUE(th["limit"].is_number()) << name;
    EXPECT_TRUE(th["passed"].is_boolean()) << name;
    EXPECT_TRUE(th.contains("value")) << name;
  }
  EXPECT_FALSE(j2["thresholds"]["max_indirect_l1"]["passed"].get<bool>());
  EXPECT_TRUE(j2["thresholds"]["max_indirect_bias"]["passed"].get<bool>());
  EXPECT_TRUE(j2["thresholds"]["max_region_bias"]["passed"].get<bool>());
  EXPECT_TRUE(j2["thresholds"]["max_region_bias"]["region"].is_string());
  EXPECT_FALSE(j2["thresholds"]["min_psnr_taa"]["passed"].get<bool>());
  EXPECT_NE(second.out.find("threshold min_psnr_taa"), std::string::npos) << second.out;
  EXPECT_EQ(j2["thresholds"]["min_psnr_taa"]["value"].get<double>(),
            j2["configurations"]["fast_many_taa"]["final_psnr_db"].get<double>());
  EXPECT_TRUE(j2["thresholds"]["max_first_frame_gap"]["passed"].get<bool>());
  EXPECT_EQ(j2["thresholds"]["max_first_frame_gap"]["value"].get<double>(),
            j2["configurations"]["fast_first_frame"]["gap_to_taa_db"].get<double>());
  EXPECT_TRUE(j2["thresholds"]["require_wall_hue"]["walls"]["left_wall"].contains("fast_one"));
  EXPECT_FALSE(j2["thresholds"]["min_direct_psnr_floor"]["passed"].get<bool>());
  EXPECT_EQ(j2["thresholds"]["min_direct_psnr_floor"]["value"].get<double>(),
            j2["direct"]["modes"][j2["direct"]["default_shadows"].get<std::string>()]
              ["direct_psnr_db"]["floor"].get<double>());
  EXPECT_TRUE(j2["thresholds"]["min_albedo_psnr"]["passed"].get<bool>());
  // At 24x24 a penumbra width may have no figure (null, a miss) or one (met under 1000).
  EXPECT_TRUE(j2["thresholds"].contains("max_penumbra_error"));

  const rp::test::CommandResult third = run_rolypoly(
      args + " --max-indirect-l1 1000 --max-indirect-l1-single 1000 --min-psnr-taa 0");
  EXPECT_EQ(third.exit_code, 0) << third.out << third.err;
  EXPECT_NE(third.out.find("threshold min_psnr_taa"), std::string::npos) << third.out;
  EXPECT_EQ(third.out.find("MISSED"), std::string::npos) << third.out;

  // --marbles adds the marble section (its own frame and truth) and leaves the main section's
  // figures as they are (the renders are deterministic).
  EXPECT_FALSE(j.contains("marbles"));
  const rp::test::CommandResult fourth = run_rolypoly(args + " --marbles");
  ASSERT_EQ(fourth.exit_code, 0) << fourth.out << fourth.err;
  EXPECT_NE(fourth.out.find("marbles: demo + 16 marbles at rest"), std::string::npos)
      << fourth.out;
  EXPECT_NE(fourth.out.find("indirect bias floor_by_marbles"), std::string::npos) << fourth.out;
  EXPECT_EQ(rp::test::files_with_suffix(dir / "cache", ".exr").size(), 6u);
  for (const char* png : {"accuracy_marbles_side_by_side.png", "accuracy_marbles_heat.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / png)) << png;
  std::ifstream in4(dir / "acc.json");
  const nlohmann::json j4 = nlohmann::json::parse(in4);
  EXPECT_EQ(j4["configurations"], j["configurations"]);
  EXPECT_EQ(j4["region_pixels"], j["region_pixels"]);
  EXPECT_FALSE(j["region_pixels"].contains("marbles"));
  // --render-scale: only the finished frame with TAA is rendered at it (the light terms and
  // the shadow modes' direct light are compared at the output size, so they stay as they are).
  const rp::test::CommandResult fifth = run_rolypoly(args + " --render-scale 0.5");
  ASSERT_EQ(fifth.exit_code, 0) << fifth.out << fifth.err;
  std::ifstream in5(dir / "acc.json");
  const nlohmann::json j5 = nlohmann::json::parse(in5);
  for (const char* key : {"fast_many", "reference_many", "fast_one", "reference_one"})
    EXPECT_EQ(j5["configurations"][key], j["configurations"][key]) << key;
  EXPECT_EQ(j5["configurations"]["fast_many_taa"]["render_scale"], 0.5);
  EXPECT_EQ(j["configurations"]["fast_many_taa"]["render_scale"], 1.0);
  EXPECT_GT(j5["configurations"]["fast_many_taa"]["final_psnr_db"].get<double>(), 5.0);
  EXPECT_EQ(j5["direct"]["modes"]["pcss"]["direct_psnr_db"],
            j["direct"]["modes"]["pcss"]["direct_psnr_db"]);
  const nlohmann::json& marbles = j4["marbles"];
  EXPECT_EQ(marbles["truth"]["bounces"], 64);
  EXPECT_FALSE(marbles["truth"]["from_cache"].get<bool>());
  EXPECT_TRUE(marbles["region_pixels"].contains("floor_by_marbles"));
  for (const char* key : {"fast_many", "reference_many"}) {
    EXPECT_TRUE(marbles["configurations"][key]["final_psnr_db"].is_number()) << key;
    EXPECT_TRUE(marbles["configurations"][key]["indirect"].contains("marbles")) << key;
    EXPECT_TRUE(marbles["configurations"][key]["region_psnr_db"].contains("floor_by_marbles"));
  }
  EXPECT_EQ(marbles["configurations"]["fast_many"]["frames"], 128);
  EXPECT_EQ(marbles["configurations"]["reference_many"]["frames"], 32);
}

TEST(AccuracyCli, UsageErrors) {
  for (const char* args :
       {"bench --out x", "bench --max-indirect-l1 0.1", "bench --max-region-bias 0.1",
        "bench --max-indirect-l1-single 0.1", "bench --min-psnr-taa 30",
        "bench --require-wall-hue", "bench --accuracy --sizes 16,32",
        "bench --accuracy --quality-report", "bench --accuracy --bounces 3",
        "bench --accuracy --max-indirect-bias nan", "bench --accuracy --min-psnr-taa -1",
        "bench --accuracy --max-region-bias x", "bench --accuracy --quality pathtraced",
        "bench --min-direct-psnr-floor 35", "bench --max-penumbra-error 0.25",
        "bench --min-albedo-psnr 20", "bench --accuracy --lamp area",
        "bench --accuracy --max-penumbra-error -1", "bench --accuracy --target-ms 33"}) {
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
  more = s;
  more.lamp = truth::LampModel::kArea;
  EXPECT_NE(key, truth_key(assets, frame, more));
}

}  // namespace
}  // namespace rp::bench
