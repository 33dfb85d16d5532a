// `rolypoly bench` end to end on the machine's OpenCL device(s) at tiny sizes: the matrix, the
// busy scene, the chart, and a device whose kernels fail to build (reported and skipped).
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <string>
#include <iterator>

#include <nlohmann/json.hpp>

#include "passes/pass_names.h"
#include "support/cli_runner.h"

namespace rp::test {
namespace {

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(BenchCli, MatrixOfTwoSizesWritesJsonChartAndMarkdown) {
  TempDir dir;
  auto json = dir / "m.json", svg = dir / "m.svg", md = dir / "m.md";
  CommandResult r = run_rolypoly(
      "bench --devices 0 --sizes 16,32 --voxels 32 --frames 1 --warmup 0 --json " +
      shell_quote(json.string()) + " --chart " + shell_quote(svg.string()) + " --markdown " +
      shell_quote(md.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(Contains(r.out, "16x16, 32^3 voxels"));
  EXPECT_TRUE(Contains(r.out, "32x32, 32^3 voxels"));
  EXPECT_TRUE(Contains(r.out, "frame ~ pixels^"));
  EXPECT_TRUE(Contains(r.out, "fps"));

  nlohmann::json j = nlohmann::json::parse(read_text(json));
  EXPECT_EQ(j.at("schema"), "rolypoly-bench/3");
  EXPECT_EQ(j.at("scene"), "default");
  EXPECT_EQ(j.at("sizes"), nlohmann::json::parse("[[16,16],[32,32]]"));
  EXPECT_EQ(j.at("voxels"), nlohmann::json::parse("[32]"));
  ASSERT_EQ(j.at("devices").size(), 1u);
  const nlohmann::json& d = j.at("devices").at(0);
  EXPECT_EQ(d.at("index"), 0);
  EXPECT_TRUE(d.at("skipped").is_null());
  ASSERT_EQ(d.at("runs").size(), 2u);
  EXPECT_EQ(d.at("runs").at(0).at("size"), nlohmann::json::parse("[16,16]"));
  EXPECT_EQ(d.at("runs").at(1).at("size"), nlohmann::json::parse("[32,32]"));
  for (const auto& run : d.at("runs")) {
    EXPECT_EQ(run.at("voxels"), 32);
    EXPECT_EQ(run.at("frames"), 1);
    EXPECT_TRUE(run.at("passes").contains(rp::passes::pass_name::kLight));
    EXPECT_TRUE(run.at("passes").contains(rp::passes::pass_name::kVoxelize));
  }
  ASSERT_EQ(d.at("scaling").at("pixels").size(), 1u);
  EXPECT_EQ(d.at("scaling").at("pixels").at(0).at("points"), 2);
  EXPECT_TRUE(d.at("scaling").at("voxels").empty()) << "one voxel resolution: no voxel fit";
  EXPECT_TRUE(Contains(j.at("command").get<std::string>(), "--sizes 16,32"));

  std::string chart = read_text(svg);
  EXPECT_EQ(chart.rfind("<?xml", 0), 0u);
  EXPECT_TRUE(Contains(chart, "</svg>"));
  std::string name = d.at("name");
  EXPECT_TRUE(Contains(chart, name.substr(0, 12))) << "the device is named (maybe shortened)";
  EXPECT_TRUE(Contains(read_text(md), "| 16x16 | 32^3 |"));
}

// No efficiency figure above 100 % for any pass on this machine. The busy scene at
// the sizes the issue found impossible figures at (gbuffer and bloom running out of cache at
// 256 and 720), every effect on: every fraction is null (not shown) or within [0, 1], the
// peak's bandwidth levels are measured, and the table shows no figure above 100 %.
void expect_no_impossible_fraction(const nlohmann::json& j) {
  for (const auto& d : j.at("devices")) {
    ASSERT_TRUE(d.at("skipped").is_null()) << d.at("skipped");
    EXPECT_GT(d.at("peak").at("bandwidth_gbps").get<double>(), 0.0);
    EXPECT_GT(d.at("peak").at("gflops").get<double>(), 0.0);
    EXPECT_GE(d.at("peak").at("bandwidth_levels").size(), 2u);
    for (const auto& run : d.at("runs"))
      for (const auto& [name, p] : run.at("passes").items())
        for (const char* key : {"bandwidth_fraction", "compute_fraction"}) {
          const nlohmann::json& f = p.at(key);
          if (f.is_null()) continue;
          EXPECT_GE(f.get<double>(), 0.0) << name << " " << key;
          EXPECT_LE(f.get<double>(), 1.0) << name << " " << key << " at " << run.at("size");
        }
  }
}

bool table_has_percent_above_100(const std::string& out) {
  // Every "NNN.N%" in the table: none may read above 100.
  for (size_t at = out.find('%'); at != std::string::npos; at = out.find('%', at + 1)) {
    size_t b = at;
    while (b > 0 && (std::isdigit(static_cast<unsigned char>(out[b - 1])) || out[b - 1] == '.'))
      --b;
    if (b < at && std::stod(out.substr(b, at - b)) > 100.0) return true;
  }
  return false;
}

TEST(BenchCli, NoEfficiencyFigureAbove100Percent) {
  TempDir dir;
  auto json = dir / "eff.json";
  CommandResult r = run_rolypoly("bench --scene busy --sizes 256,720 --frames 2 --warmup 1 "
                                 "--json " + shell_quote(json.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_FALSE(table_has_percent_above_100(r.out)) << r.out;
  nlohmann::json j = nlohmann::json::parse(read_text(json));
  expect_no_impossible_fraction(j);
  EXPECT_EQ(j.at("devices").at(0).at("timing"), "device") << "PoCL's timestamps are usable";
  EXPECT_EQ(j.at("devices").at(0).at("runs").at(0).at("gi_volume"), "dense");
  EXPECT_FALSE(j.at("devices").at(0).at("runs").at(0).contains("octree_memory"));
  // The voxelizer takes the tumblers' proxy at 64^3 and the shadow map leaves out the
  // non-casters (the box, the lamp cap), so both count fewer triangles than the camera.
  const nlohmann::json& scene = j.at("devices").at(0).at("runs").at(0).at("scene");
  EXPECT_LT(scene.at("voxel_triangles").get<int>(), scene.at("instance_triangles").get<int>());
  EXPECT_LT(scene.at("shadow_triangles").get<int>(), scene.at("instance_triangles").get<int>());
  EXPECT_GT(scene.at("shadow_triangles").get<int>(), 0);
}

// The octree's runs say so in the JSON, with the octree path's measured device memory.
TEST(BenchCli, OctreeRunNamesItsVolumeAndMemory) {
  TempDir dir;
  auto json = dir / "svo.json";
  CommandResult r = run_rolypoly("bench --size 64 --frames 1 --warmup 0 --gi-volume svo "
                                 "--json " + shell_quote(json.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(Contains(r.out, "octree device memory")) << r.out;
  nlohmann::json j = nlohmann::json::parse(read_text(json));
  const nlohmann::json& run = j.at("devices").at(0).at("runs").at(0);
  EXPECT_EQ(run.at("gi_volume"), "svo");
  EXPECT_EQ(run.at("voxels"), 256);
  const nlohmann::json& m = run.at("octree_memory");
  EXPECT_GT(m.at("pool_bytes").get<uint64_t>(), 1u << 20);
  EXPECT_GT(m.at("device_bytes").get<uint64_t>(), m.at("pool_bytes").get<uint64_t>());
  EXPECT_GE(m.at("peak_bytes").get<uint64_t>(), m.at("device_bytes").get<uint64_t>());
}

// A device whose timestamps are unusable (forced here with ROLYPOLY_TIMING=host, what the check
// picks on Mesa rusticl) times every pass on the host, says so in the table and the JSON, and
// still shows no impossible figure.
TEST(BenchCli, HostTimingIsLabelledAndPlausible) {
  TempDir dir;
  auto json = dir / "host.json";
  CommandResult r = run_rolypoly("bench --scene busy --size 64 --voxels 32 --frames 2 "
                                 "--warmup 1 --json " + shell_quote(json.string()),
                                 "ROLYPOLY_TIMING=host");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(Contains(r.out, "host timing"));
  EXPECT_TRUE(Contains(r.out, "passes host-timed"));
  EXPECT_FALSE(table_has_percent_above_100(r.out)) << r.out;
  nlohmann::json j = nlohmann::json::parse(read_text(json));
  const nlohmann::json& d = j.at("devices").at(0);
  EXPECT_EQ(d.at("timing"), "host");
  EXPECT_EQ(d.at("runs").at(0).at("timing"), "host");
  for (const auto& [name, p] : d.at("runs").at(0).at("passes").items())
    EXPECT_GE(p.at("median_ms").get<double>(), 0.0) << name;
  const nlohmann::json& light = d.at("runs").at(0).at("passes").at(rp::passes::pass_name::kLight);
  EXPECT_GT(light.at("median_ms").get<double>(), 0.0);
  expect_no_impossible_fraction(j);
}

TEST(BenchCli, BusySceneKeepsTheParticleBudgetFull) {
  TempDir dir;
  auto json = dir / "busy.json";
  CommandResult r = run_rolypoly("bench --scene busy --size 16 --voxels 32 --frames 1 "
                                 "--warmup 1 --json " + shell_quote(json.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  nlohmann::json j = nlohmann::json::parse(read_text(json));
  EXPECT_EQ(j.at("scene"), "busy");
  const nlohmann::json& run = j.at("devices").at(0).at("runs").at(0);
  // 2048 particles + up to 30 marbles + the fireball, all drawn as spheres.
  EXPECT_GE(run.at("scene").at("spheres").get<int>(), 2048 + 1);
  EXPECT_LE(run.at("scene").at("spheres").get<int>(), 2048 + 31);
}

TEST(BenchCli, DeviceWithABrokenKernelIsSkippedWithTheMessage) {
  TempDir dir;
  std::filesystem::path kernels = dir / "kernels";
  std::filesystem::copy(
      std::filesystem::path(ROLYPOLY_TEST_DATA_DIR).parent_path().parent_path() / "kernels",
      kernels, std::filesystem::copy_options::recursive);
  std::filesystem::path broken = kernels / "visibility.cl";
  ASSERT_TRUE(std::filesystem::exists(broken));
  std::string source = read_text(broken);
  std::ofstream(broken, std::ios::trunc) << "this is not OpenCL C (\n" << source;
  auto json = dir / "skip.json";
  CommandResult r = run_rolypoly("bench --devices all --size 16 --voxels 32 --frames 1 "
                                 "--warmup 0 --json " + shell_quote(json.string()),
                                 "ROLYPOLY_KERNEL_DIR=" + shell_quote(kernels.string()));
  // Every device fails here, so the exit code is 1; each failure is reported, not fatal.
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_TRUE(Contains(r.err, "device [0] "));
  EXPECT_TRUE(Contains(r.err, "skipped: "));
  EXPECT_TRUE(Contains(r.err, "visibility.cl"));
  EXPECT_TRUE(Contains(r.err, "no device completed the bench"));
  EXPECT_TRUE(Contains(r.out, ": skipped"));
  nlohmann::json j = nlohmann::json::parse(read_text(json));  // written even then
  for (const auto& d : j.at("devices")) {
    ASSERT_TRUE(d.at("skipped").is_string());
    EXPECT_TRUE(Contains(d.at("skipped").get<std::string>(), "visibility.cl"));
    EXPECT_TRUE(d.at("runs").empty());
  }
}

TEST(BenchCli, ConflictingDeviceAndSizeOptionsAreUsageErrors) {
  CommandResult both = run_rolypoly("bench --devices all --device 0 --frames 1");
  EXPECT_EQ(both.exit_code, 2) << both.out << both.err;
  EXPECT_TRUE(Contains(both.err, "--devices and --device"));
  CommandResult sizes = run_rolypoly("bench --sizes 16 --size 32 --frames 1");
  EXPECT_EQ(sizes.exit_code, 2) << sizes.out << sizes.err;
  CommandResult voxels = run_rolypoly("bench --voxels 32,48 --frames 1");
  EXPECT_EQ(voxels.exit_code, 2) << voxels.out << voxels.err;
  CommandResult unknown = run_rolypoly("bench --devices no-such-device --size 16 --frames 1");
  EXPECT_EQ(unknown.exit_code, 1) << unknown.out << unknown.err;
  EXPECT_TRUE(Contains(unknown.err, "no-such-device"));
}

}  // namespace
}  // namespace rp::test
