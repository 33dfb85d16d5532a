// `rolypoly bench --accuracy --scene FILE` (bench/src/accuracy_file.h) end to end on a small
// generated scene at 64x64: every material is a region with its figures, the PNGs and the
// JSON are written, the thresholds that apply to a file work, and the truths are cached per
// content of the file (the same path with other content is traced anew).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "bench_test_scene.h"
#include "support/cli_runner.h"

namespace rp::test {
namespace {

TEST(AccuracyFileScene, EveryMaterialIsARegion) {
  TempDir dir;
  const std::filesystem::path file = dir / "room.glb";
  const BenchTestScene scene = write_bench_test_scene(file);
  const std::string args = "bench --accuracy --scene " + shell_quote(file.string()) +
                           " --size 64 --spp 8 --voxels 32 --truth-cache " +
                           shell_quote((dir / "cache").string()) + " --out " +
                           shell_quote((dir / "out").string()) + " --json " +
                           shell_quote((dir / "acc.json").string());
  const CommandResult first = run_rolypoly(args);
  ASSERT_EQ(first.exit_code, 0) << first.command << "\n" << first.out << first.err;
  for (const char* text : {"accuracy at 64x64, scene ", "fast/N", "ref/N", "fast/1", "ref/1",
                           "final PSNR, TAA (dB)", "final PSNR, first frame (dB)",
                           "direct PSNR (dB) image", "albedo PSNR (dB)",
                           "indirect L1 image", "leak pixels (indirect)", "specular L1 floor",
                           "fast/N, its light averaged over TAA's 16 jitter positions"})
    EXPECT_NE(first.out.find(text), std::string::npos) << text << "\n" << first.out;
  for (const std::string& m : scene.materials) {
    EXPECT_NE(first.out.find("indirect bias " + m), std::string::npos) << m << "\n" << first.out;
    EXPECT_NE(first.out.find("direct PSNR (dB) " + m), std::string::npos) << m;
  }
  EXPECT_EQ(first.out.find("from the cache"), std::string::npos);
  for (const char* png : {"accuracy_side_by_side.png", "accuracy_indirect_heat.png",
                          "accuracy_final_taa.png", "accuracy_direct_jittered.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / png)) << png;

  const nlohmann::json j = nlohmann::json::parse(read_all(dir / "acc.json"));
  EXPECT_EQ(j["schema"], "rolypoly-accuracy-file/1");
  EXPECT_EQ(j["width"], 64);
  EXPECT_EQ(j["scene"]["path"], file.string());
  EXPECT_EQ(j["scene"]["triangles"], scene.triangles);
  EXPECT_EQ(j["scene"]["lights"], scene.lights);
  EXPECT_TRUE(j["passed"].get<bool>());
  EXPECT_FALSE(j.contains("thresholds"));
  // Every material of the file (in the file's order, which the exporter chooses) is a region
  // named after it and seen at this size.
  ASSERT_EQ(j["materials"].size(), scene.materials.size());
  for (const std::string& name : scene.materials) {
    nlohmann::json m;
    for (const nlohmann::json& e : j["materials"])
      if (e["name"] == name) m = e;
    ASSERT_TRUE(m.is_object()) << name << " is not in " << j["materials"];
    EXPECT_EQ(m["region"], name);
    EXPECT_GT(m["pixels"].get<uint64_t>(), 20u) << name << ": seen at 64x64";
    EXPECT_EQ(j["region_pixels"][name], m["pixels"]);
    EXPECT_EQ(m["coated"].get<bool>(), name == "floor") << name;
    EXPECT_EQ(m["emissive"].get<bool>(), name == "glow") << name;
  }
  // The truth's image: its regions are a part of what the camera sees.
  EXPECT_LE(j["region_pixels"]["image"].get<uint64_t>(), 64u * 64u);
  for (const char* key : {"fast_many", "reference_many", "fast_one", "reference_one"}) {
    const nlohmann::json& c = j["configurations"][key];
    const bool many = std::string(key).ends_with("many");
    EXPECT_EQ(c["bounces"], many ? 64 : 1) << key;
    EXPECT_TRUE(c["final_psnr_db"].is_number()) << key;
    EXPECT_TRUE(c["albedo_psnr_db"].is_number()) << key;
    EXPECT_TRUE(c["direct_psnr_db"]["image"].is_number()) << key;
    EXPECT_TRUE(c["leaks"]["leak_pixels"].is_number()) << key;
    for (const std::string& m : scene.materials) {
      EXPECT_TRUE(c["indirect"][m]["rel_l1"].is_number()) << key << " " << m;
      EXPECT_TRUE(c["indirect"][m]["bias"].is_number()) << key << " " << m;
      EXPECT_TRUE(c["direct_psnr_db"][m].is_number()) << key << " " << m;
      EXPECT_TRUE(c["leaks"]["regions"][m]["covered_pixels"].is_number()) << key << " " << m;
    }
    EXPECT_TRUE(c["specular"]["floor"]["rel_l1"].is_number()) << key;
    EXPECT_FALSE(c["specular"].contains("wall")) << "matte: no coat to measure";
    // The punctual lights are the same model in both: direct light agrees closely.
    EXPECT_GT(c["direct_psnr_db"]["image"].get<double>(), 20.0) << key;
  }
  EXPECT_TRUE(j["configurations"]["fast_many_taa"]["taa"].get<bool>());
  EXPECT_GT(j["configurations"]["fast_many_taa"]["final_psnr_db"].get<double>(), 10.0);
  EXPECT_EQ(j["configurations"]["fast_first_frame"]["frames"], 1);
  EXPECT_GT(j["configurations"]["fast_first_frame"]["final_psnr_db"].get<double>(), 10.0);
  // The light averaged over TAA's jitter: per material, and closer to the truth's pixel
  // averages than one unjittered frame, whose edges alias.
  const nlohmann::json& jit = j["configurations"]["fast_many_jittered"];
  EXPECT_EQ(jit["averaged_frames"], 16);
  EXPECT_TRUE(jit["jitter"].get<bool>());
  for (const std::string& m : scene.materials) {
    EXPECT_TRUE(jit["direct_by_region"][m]["bias"].is_number()) << m;
    EXPECT_TRUE(jit["indirect"][m]["rel_l1"].is_number()) << m;
  }
  const nlohmann::json& single = j["configurations"]["fast_many"];
  EXPECT_GT(jit["direct_psnr_db"]["image"].get<double>(),
            single["direct_psnr_db"]["image"].get<double>());
  EXPECT_GT(jit["albedo_psnr_db"].get<double>(), single["albedo_psnr_db"].get<double>());
  EXPECT_EQ(j["images"]["direct_jittered"],
            (dir / "out" / "accuracy_direct_jittered.png").string());
  // Both truths in the file's own folder of the cache.
  const std::string folder = "scene-" + j["scene"]["content_hash"].get<std::string>();
  EXPECT_EQ(files_with_suffix(dir / "cache" / folder, ".exr").size(), 2u);

  // The thresholds a file takes: from the cache, two missed on purpose.
  const CommandResult second =
      run_rolypoly(args + " --max-indirect-l1 0.0001 --max-region-bias 1000 --min-psnr-taa "
                          "1000 --min-albedo-psnr 0 --max-indirect-l1-single 1000");
  EXPECT_EQ(second.exit_code, 3) << second.out << second.err;
  EXPECT_NE(second.out.find("(from the cache)"), std::string::npos) << second.out;
  EXPECT_NE(second.out.find("threshold max_region_bias"), std::string::npos) << second.out;
  const nlohmann::json j2 = nlohmann::json::parse(read_all(dir / "acc.json"));
  EXPECT_FALSE(j2["passed"].get<bool>());
  EXPECT_FALSE(j2["thresholds"]["max_indirect_l1"]["passed"].get<bool>());
  EXPECT_FALSE(j2["thresholds"]["min_psnr_taa"]["passed"].get<bool>());
  EXPECT_TRUE(j2["thresholds"]["max_region_bias"]["passed"].get<bool>());
  EXPECT_TRUE(j2["thresholds"]["min_albedo_psnr"]["passed"].get<bool>());
  EXPECT_TRUE(j2["thresholds"]["max_indirect_l1_single"]["passed"].get<bool>());
  bool named = false;
  for (const std::string& m : scene.materials)
    named = named || j2["thresholds"]["max_region_bias"]["region"] == m;
  EXPECT_TRUE(named) << j2["thresholds"]["max_region_bias"];
  // The renders are deterministic: the same figures as the first run.
  EXPECT_EQ(j2["configurations"], j["configurations"]);

  // The same path with a brighter spot light: the truth cache's key hashes the frame's meshes,
  // materials and camera but not a file's punctual lights; the file's content hash tells the
  // two apart, so both truths are traced anew (into a second folder).
  write_bench_test_scene(file, 2.0f);
  const CommandResult third = run_rolypoly(args);
  ASSERT_EQ(third.exit_code, 0) << third.out << third.err;
  EXPECT_EQ(third.out.find("from the cache"), std::string::npos) << third.out;
  const nlohmann::json j3 = nlohmann::json::parse(read_all(dir / "acc.json"));
  EXPECT_NE(j3["scene"]["content_hash"], j["scene"]["content_hash"]);
  EXPECT_EQ(files_with_suffix(dir / "cache" / folder, ".exr").size(), 2u);
  const std::string brighter = "scene-" + j3["scene"]["content_hash"].get<std::string>();
  EXPECT_EQ(files_with_suffix(dir / "cache" / brighter, ".exr").size(), 2u);
  // The real-time frame and the truth both see the brighter spot (an old truth would leave
  // the direct light far too bright).
  EXPECT_LT(std::abs(j3["configurations"]["fast_many"]["direct"]["bias"].get<double>()), 0.1);
}

// --truth-noise: a second many-bounce truth with the next seed, and the indirect L1 between
// the two per region, which must fall as the samples grow (Monte Carlo noise: about
// 1 / sqrt(spp), so a quarter of it at 16x the samples; the bound leaves room for the bias-free
// but not exactly Gaussian estimate at 8 spp).
TEST(AccuracyFileScene, TruthNoiseFallsWithSamples) {
  TempDir dir;
  const std::filesystem::path file = dir / "room.glb";
  const BenchTestScene scene = write_bench_test_scene(file);
  double image_noise[2] = {0.0, 0.0};
  std::string folder;
  for (int k = 0; k < 2; ++k) {
    const std::string spp = k == 0 ? "8" : "128";
    const CommandResult r = run_rolypoly(
        "bench --accuracy --truth-noise --scene " + shell_quote(file.string()) +
        " --size 48 --spp " + spp + " --voxels 32 --truth-cache " +
        shell_quote((dir / "cache").string()) + " --out " + shell_quote((dir / "out").string()) +
        " --json " + shell_quote((dir / "acc.json").string()));
    ASSERT_EQ(r.exit_code, 0) << r.command << "\n" << r.out << r.err;
    EXPECT_NE(r.out.find("the truth's own noise: indirect L1 against the 64-bounce truth of "
                         "seed 2"),
              std::string::npos)
        << r.out;
    const nlohmann::json j = nlohmann::json::parse(read_all(dir / "acc.json"));
    folder = "scene-" + j["scene"]["content_hash"].get<std::string>();
    const nlohmann::json& noise = j["truth"]["noise"];
    EXPECT_EQ(noise["seeds"], nlohmann::json::array({1, 2}));
    EXPECT_EQ(noise["truths"]["many"]["seed"], 2);
    EXPECT_EQ(noise["truths"]["many"]["spp"], std::stoi(spp));
    image_noise[k] = noise["indirect"]["image"]["rel_l1"].get<double>();
    EXPECT_GT(image_noise[k], 0.0) << "two seeds' truths are not the same image";
    for (const std::string& m : scene.materials)
      EXPECT_TRUE(noise["indirect"][m]["rel_l1"].is_number()) << m;
  }
  EXPECT_LT(image_noise[1], 0.45 * image_noise[0])
      << "8 spp: " << image_noise[0] << ", 128 spp: " << image_noise[1];
  // Both seeds' many-bounce truths and the one-bounce truth, at both sample counts.
  EXPECT_EQ(files_with_suffix(dir / "cache" / folder, ".exr").size(), 6u);
}

}  // namespace
}  // namespace rp::test
