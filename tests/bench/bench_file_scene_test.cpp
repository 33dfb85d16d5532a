// `rolypoly bench --scene FILE` (bench/src/bench_scene.h): the frame-time bench, the
// visibility comparison and the path tracer's bench on a small scene file, what the JSON
// records of the scene, and the options a file refuses (exit 2, naming the option).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/src/bench_report.h"
#include "bench/src/scene_file_facts.h"
#include "bench_test_scene.h"
#include "cli/cli.h"
#include "passes/pass_names.h"
#include "support/cli_runner.h"

namespace rp::test {
namespace {

namespace pass_name = rp::passes::pass_name;

cli::CliParse parse(const std::vector<std::string>& words) {
  std::vector<const char*> argv = {"rolypoly"};
  for (const std::string& w : words) argv.push_back(w.c_str());
  argv.push_back(nullptr);
  return cli::parse_cli(int(argv.size() - 1), argv.data());
}

void expect_scene_fields(const nlohmann::json& f, const std::filesystem::path& file,
                         const BenchTestScene& scene) {
  EXPECT_EQ(f.at("path"), file.string());
  EXPECT_EQ(f.at("content_hash").get<std::string>().size(), 16u);
  EXPECT_EQ(f.at("triangles"), scene.triangles);
  EXPECT_EQ(f.at("meshes"), scene.meshes);
  EXPECT_EQ(f.at("instances"), scene.instances);
  EXPECT_EQ(f.at("materials"), scene.materials.size());
  EXPECT_EQ(f.at("textures"), scene.textures);
  EXPECT_EQ(f.at("lights"), scene.lights);
  EXPECT_FALSE(f.at("lamp").get<bool>());
}

TEST(BenchFileScene, MatrixRecordsTheSceneInItsJson) {
  TempDir dir;
  const std::filesystem::path file = dir / "room.glb";
  const BenchTestScene scene = write_bench_test_scene(file);
  const auto json = dir / "b.json", md = dir / "b.md";
  const CommandResult r = run_rolypoly(
      "bench --scene " + shell_quote(file.string()) + " --size 24 --voxels 32 --frames 2 " +
      "--warmup 1 --json " + shell_quote(json.string()) + " --markdown " +
      shell_quote(md.string()));
  ASSERT_EQ(r.exit_code, 0) << r.command << "\n" << r.out << r.err;
  EXPECT_TRUE(Contains(r.out, "scene " + file.string() + " ("));
  EXPECT_TRUE(Contains(r.out, "scene file, shadows"));
  EXPECT_TRUE(Contains(r.out, "24x24, 32^3 voxels"));

  const nlohmann::json j = nlohmann::json::parse(read_all(json));
  EXPECT_EQ(j.at("schema"), "rolypoly-bench/3");
  EXPECT_EQ(j.at("scene"), "file");
  expect_scene_fields(j.at("scene_file"), file, scene);
  const nlohmann::json& run = j.at("devices").at(0).at("runs").at(0);
  EXPECT_EQ(run.at("frames"), 2);
  EXPECT_EQ(run.at("scene").at("instances"), scene.instances);
  EXPECT_EQ(run.at("scene").at("instance_triangles"), scene.triangles);
  EXPECT_EQ(run.at("scene").at("spheres"), 0);
  for (const char* pass : {pass_name::kVisibility, pass_name::kGBuffer, pass_name::kVoxelize,
                           pass_name::kLight})
    EXPECT_TRUE(run.at("passes").contains(pass)) << pass;
  EXPECT_TRUE(Contains(read_all(md), "Scene: " + file.string()));
}

TEST(BenchFileScene, CompareVisibilityAndPathTracedBenchTakeAFile) {
  TempDir dir;
  const std::filesystem::path file = dir / "room.gltf";
  const BenchTestScene scene = write_bench_test_scene(file);
  const CommandResult v = run_rolypoly("bench --scene " + shell_quote(file.string()) +
                                       " --compare-visibility --size 16 --frames 1 --warmup 0");
  ASSERT_EQ(v.exit_code, 0) << v.command << "\n" << v.out << v.err;
  EXPECT_TRUE(Contains(v.out, "embree / raster"));

  const auto json = dir / "pt.json";
  const CommandResult p = run_rolypoly(
      "bench --quality pathtraced --scene " + shell_quote(file.string()) +
      " --size 16 --spp 2 --bounces 2 --frames 2 --warmup 0 --json " + shell_quote(json.string()));
  ASSERT_EQ(p.exit_code, 0) << p.command << "\n" << p.out << p.err;
  EXPECT_TRUE(Contains(p.out, "path traced 16x16, 2 spp, 2 bounces"));
  const nlohmann::json j = nlohmann::json::parse(read_all(json));
  EXPECT_EQ(j.at("schema"), "rolypoly-pathtrace-bench/1");
  EXPECT_EQ(j.at("scene"), "file");
  expect_scene_fields(j.at("scene_file"), file, scene);
  ASSERT_EQ(j.at("runs").size(), 2u);
  EXPECT_GT(j.at("runs").at(0).at("rays").get<uint64_t>(), 16u * 16u * 2u);
  // The same frame twice: the same rays.
  EXPECT_EQ(j.at("runs").at(0).at("rays"), j.at("runs").at(1).at("rays"));
}

TEST(BenchFileScene, DemoIsTheDefaultScene) {
  const cli::CliParse r = parse({"bench", "--scene", "demo", "--size", "16"});
  ASSERT_TRUE(std::holds_alternative<cli::ParsedCommand>(r));
  EXPECT_EQ(std::get<cli::ParsedCommand>(r).bench.scene, "default");
  // The demo keeps its simulation options and its report's thresholds.
  for (const std::vector<std::string>& ok :
       {std::vector<std::string>{"bench", "--scene", "demo", "--seed", "3", "--marbles"},
        {"bench", "--accuracy", "--scene", "default", "--require-wall-hue"},
        {"bench", "--scene", "busy", "--fireball"}})
    EXPECT_TRUE(std::holds_alternative<cli::ParsedCommand>(parse(ok))) << ok.back();
}

TEST(BenchFileScene, OptionsOfTheDemoAreRefusedForAFile) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> refused = {
      {{"--seed", "3"}, "--seed"},
      {{"--marbles"}, "--marbles"},
      {{"--fireball"}, "--fireball"},
      {{"--replay", "log.txt"}, "--replay"},
      {{"--assets", "x"}, "--assets"},
      {{"--quality-report"}, "--quality-report"},
      {{"--accuracy", "--require-wall-hue"}, "--require-wall-hue"},
      {{"--accuracy", "--min-direct-psnr-floor", "30"}, "--min-direct-psnr-floor"},
      {{"--accuracy", "--max-penumbra-error", "0.25"}, "--max-penumbra-error"},
      {{"--accuracy", "--marbles"}, "--marbles"},
  };
  for (const auto& [extra, name] : refused) {
    std::vector<std::string> words = {"bench", "--scene", "room.gltf"};
    words.insert(words.end(), extra.begin(), extra.end());
    const cli::CliParse r = parse(words);
    ASSERT_TRUE(std::holds_alternative<cli::CliExit>(r)) << name;
    const cli::CliExit& e = std::get<cli::CliExit>(r);
    EXPECT_EQ(e.exit_code, 2) << name;
    EXPECT_TRUE(Contains(e.message, name + " ")) << name;
    EXPECT_TRUE(Contains(e.message, "scene file")) << name;
    EXPECT_TRUE(Contains(e.message, "(--scene room.gltf)")) << name;
  }
  // What a file does take: the matrix, the path tracer, the report and its other thresholds.
  for (const std::vector<std::string>& ok :
       {std::vector<std::string>{"--sizes", "16,32", "--voxels", "32,64", "--chart", "c.svg"},
        {"--quality", "pathtraced", "--spp", "4"},
        {"--accuracy", "--max-indirect-l1", "0.5", "--max-indirect-bias", "0.5",
         "--max-region-bias", "0.5", "--max-indirect-l1-single", "0.5", "--min-psnr-taa", "20",
         "--min-albedo-psnr", "20"}}) {
    std::vector<std::string> words = {"bench", "--scene", "room.gltf"};
    words.insert(words.end(), ok.begin(), ok.end());
    EXPECT_TRUE(std::holds_alternative<cli::ParsedCommand>(parse(words))) << ok.front();
  }
  // Still refused: the busy animation in the reports that take one scene frame.
  for (const char* mode : {"--accuracy", "--quality=pathtraced"})
    EXPECT_TRUE(std::holds_alternative<cli::CliExit>(parse({"bench", "--scene", "busy", mode})))
        << mode;

  // End to end: the message on stderr, exit 2, before the file is even opened.
  const CommandResult r = run_rolypoly("bench --scene /nonexistent/room.glb --seed 5");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "--seed applies to the simulated demo, not to a scene file"));
}

TEST(BenchFileScene, AMissingOrMalformedFileIsAUsageError) {
  TempDir dir;
  write_plain(dir / "bad.gltf", "{\"asset\": {\"version\": \"1.0\"}}");
  for (const std::string& f : {(dir / "bad.gltf").string(), (dir / "missing.glb").string()}) {
    const CommandResult r =
        run_rolypoly("bench --scene " + shell_quote(f) + " --size 16 --frames 1 --warmup 0");
    EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
    EXPECT_TRUE(Contains(r.err, f)) << "the message names the file";
  }
}

TEST(BenchFileScene, SceneFileFieldsRoundTripThroughTheJson) {
  bench::BenchMatrix m;
  m.command = "rolypoly bench --scene a.glb";
  m.scene = "file";
  m.file = bench::SceneFileFacts{"a.glb", "0123456789abcdef", 60, 3, 3, 5, 1, 2, true};
  const bench::BenchMatrix back = bench::parse_matrix_json(bench::matrix_json(m));
  EXPECT_EQ(back.scene, "file");
  ASSERT_TRUE(back.file.has_value());
  EXPECT_EQ(back.file->path, "a.glb");
  EXPECT_EQ(back.file->content_hash, "0123456789abcdef");
  EXPECT_EQ(back.file->triangles, 60u);
  EXPECT_EQ(back.file->materials, 5u);
  EXPECT_EQ(back.file->textures, 1u);
  EXPECT_EQ(back.file->lights, 2u);
  EXPECT_TRUE(back.file->lamp);
  EXPECT_TRUE(Contains(bench::matrix_markdown(m), "Scene: a.glb (60 triangles, 5 materials, 1 "
                                                "texture, 2 lights and the demo's lamp"));
  m.file.reset();  // the demo's documents have no such field
  EXPECT_FALSE(nlohmann::json::parse(bench::matrix_json(m)).contains("scene_file"));
  EXPECT_FALSE(bench::parse_matrix_json(bench::matrix_json(m)).file.has_value());
}

TEST(BenchFileScene, ContentHashFollowsTheFileAndTheFilesItNames) {
  TempDir dir;
  const std::filesystem::path gltf = dir / "s.gltf";
  write_plain(dir / "data.bin", "0123");
  write_plain(gltf, R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "data.bin",
                       "byteLength": 4}], "images": [{"uri": "data:image/png;base64,AAAA"}]})");
  const std::string first = bench::scene_file_hash(gltf.string());
  EXPECT_EQ(first.size(), 16u);
  EXPECT_EQ(first, bench::scene_file_hash(gltf.string()));
  write_plain(dir / "data.bin", "0124");  // the same .gltf, another buffer
  const std::string second = bench::scene_file_hash(gltf.string());
  EXPECT_NE(first, second);
  std::filesystem::remove(dir / "data.bin");
  EXPECT_NE(second, bench::scene_file_hash(gltf.string()));
  EXPECT_THROW(bench::scene_file_hash((dir / "none.gltf").string()), std::runtime_error);
}

}  // namespace
}  // namespace rp::test
