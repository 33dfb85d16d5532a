// The bench matrix without a device: power-law fits against hand-computed exponents, device
// selection, the per-device skip on OpenCL errors, the JSON round trip and the SVG's structure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/src/bench_chart.h"
#include "bench/src/bench_matrix.h"
#include "bench/src/bench_report.h"
#include "cl/error.h"

namespace rp::bench {
namespace {

using app::TimeSummary;

TEST(BenchFit, ExactPowerLawGivesItsExponentAndFactor) {
  // time = 3 ms * x^1.5 at four points.
  std::vector<double> x = {1e4, 4e4, 16e4, 1e6}, y;
  for (double v : x) y.push_back(3.0 * std::pow(v, 1.5));
  PowerFit f = fit_power_law(x, y);
  EXPECT_NEAR(f.k, 1.5, 1e-12);
  EXPECT_NEAR(f.a / 3.0, 1.0, 1e-9);
  EXPECT_NEAR(f.r2, 1.0, 1e-12);
  EXPECT_EQ(f.points, 4u);
}

TEST(BenchFit, LeastSquaresOnLogsOfInexactData) {
  // Points (1,1), (2,2), (4,3): log x = 0, L, 2L (L = ln 2), log y = 0, L, ln 3. The slope is
  // sum(dx dy) / sum(dx^2) = (L ln 3) / (2 L^2) = ln 3 / (2 ln 2).
  PowerFit f = fit_power_law({1.0, 2.0, 4.0}, {1.0, 2.0, 3.0});
  EXPECT_NEAR(f.k, std::log(3.0) / (2.0 * std::log(2.0)), 1e-12);
  EXPECT_LT(f.r2, 1.0);
  EXPECT_GT(f.r2, 0.9);
}

TEST(BenchFit, RejectsTooFewOrNonPositivePoints) {
  EXPECT_THROW(fit_power_law({1.0}, {1.0}), std::invalid_argument);
  EXPECT_THROW(fit_power_law({2.0, 2.0}, {1.0, 3.0}), std::invalid_argument);
  EXPECT_THROW(fit_power_law({1.0, 2.0}, {0.0, 3.0}), std::invalid_argument);
}

RunResult run(uint32_t size, uint32_t voxels, double frame_ms) {
  RunResult r;
  r.width = r.height = size;
  r.voxels = voxels;
  r.frames = 3;
  r.frame = {frame_ms, frame_ms * 0.9, frame_ms * 1.2};
  r.passes = {{"visibility", {frame_ms / 4, frame_ms / 5, frame_ms / 3}, {}},
              {"light", {frame_ms / 2, frame_ms / 3, frame_ms}, {}}};
  return r;
}

TEST(BenchFit, ScalingPerVoxelResolutionAndPerSize) {
  // Pixels x4 -> time x4 (k = 1); voxel count x8 (32^3 -> 64^3) -> time x2 (k = 1/3).
  DeviceResult d;
  d.runs = {run(256, 32, 10.0), run(512, 32, 40.0), run(256, 64, 20.0), run(512, 64, 80.0)};
  fit_scaling(d);
  ASSERT_EQ(d.pixel_scaling.size(), 2u);
  EXPECT_EQ(d.pixel_scaling[0].voxels, 32u);
  EXPECT_NEAR(d.pixel_scaling[0].fit.k, 1.0, 1e-12);
  EXPECT_NEAR(d.pixel_scaling[1].fit.k, 1.0, 1e-12);
  ASSERT_EQ(d.voxel_scaling.size(), 2u);
  EXPECT_EQ(d.voxel_scaling[0].width, 256u);
  EXPECT_NEAR(d.voxel_scaling[0].fit.k, 1.0 / 3.0, 1e-12);
  EXPECT_EQ(d.voxel_scaling[0].fit.points, 2u);
}

TEST(BenchFit, NoFitFromASingleValue) {
  DeviceResult d;
  d.runs = {run(256, 32, 10.0)};
  fit_scaling(d);
  EXPECT_TRUE(d.pixel_scaling.empty());
  EXPECT_TRUE(d.voxel_scaling.empty());
}

std::vector<rp::cl::DeviceInfo> fake_devices() {
  rp::cl::DeviceInfo cpu, gpu;
  cpu.index = 0;
  cpu.name = "pthread-cpu";
  cpu.type = "CPU";
  cpu.platform_name = "Portable Computing Language";
  gpu.index = 1;
  gpu.name = "NVIDIA GeForce Test";
  gpu.type = "GPU";
  gpu.platform_name = "NVIDIA CUDA";
  return {cpu, gpu};
}

std::vector<int> indices(const std::vector<rp::cl::DeviceInfo>& list) {
  std::vector<int> out;
  for (const auto& d : list) out.push_back(d.index);
  return out;
}

TEST(BenchDevices, AllIndicesAndNameParts) {
  auto all = fake_devices();
  EXPECT_EQ(indices(select_devices("all", all)), (std::vector<int>{0, 1}));
  EXPECT_EQ(indices(select_devices("1", all)), (std::vector<int>{1}));
  EXPECT_EQ(indices(select_devices("geforce,0", all)), (std::vector<int>{1, 0}));
  EXPECT_EQ(indices(select_devices("0,0,portable", all)), (std::vector<int>{0}));
  try {
    select_devices("0,quantum", all);
    FAIL() << "no error for an unknown device";
  } catch (const rp::cl::Error& e) {
    EXPECT_NE(std::string(e.what()).find("quantum"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("NVIDIA GeForce Test"), std::string::npos) << e.what();
  }
  EXPECT_THROW(select_devices("0,,1", all), rp::cl::Error);
  EXPECT_THROW(select_devices("7", all), rp::cl::Error);
}

std::string read_all(std::FILE* f) {
  std::rewind(f);
  std::string text;
  char buf[256];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);
  return text;
}

TEST(BenchMatrixRun, FailingDeviceIsSkippedWithItsMessageAndTheNextRuns) {
  MatrixPlan plan;
  plan.devices = fake_devices();
  plan.sizes = {{16, 16}, {32, 32}};
  plan.voxels = {32};
  int calls = 0;
  MeasureRun measure = [&](const rp::cl::DeviceInfo& d, uint32_t w, uint32_t, uint32_t v) {
    ++calls;
    // Device 0 fails on its second run (a build failure at a later size, like a GPU out of
    // memory): its first run must not survive.
    if (d.index == 0 && w == 32) throw rp::cl::BuildError("light.cl failed to build", "log");
    return run(w, v, double(w));
  };
  BenchMatrix m;
  std::FILE* log = std::tmpfile();
  ASSERT_NE(log, nullptr);
  run_matrix(plan, measure, nullptr, m, log);
  std::string text = read_all(log);
  std::fclose(log);

  EXPECT_EQ(calls, 4);
  ASSERT_EQ(m.devices.size(), 2u);
  EXPECT_FALSE(m.devices[0].ok());
  EXPECT_NE(m.devices[0].skipped.find("light.cl failed to build"), std::string::npos);
  EXPECT_TRUE(m.devices[0].runs.empty());
  EXPECT_TRUE(m.devices[1].ok());
  ASSERT_EQ(m.devices[1].runs.size(), 2u);
  EXPECT_EQ(m.devices[1].pixel_scaling.size(), 1u);
  EXPECT_EQ(m.devices_ok(), 1u);
  EXPECT_NE(text.find("device [0] pthread-cpu (CPU) skipped: light.cl failed to build"),
            std::string::npos)
      << text;
}

TEST(BenchMatrixRun, OtherExceptionsAreNotSwallowed) {
  MatrixPlan plan;
  plan.devices = fake_devices();
  plan.sizes = {{16, 16}};
  plan.voxels = {32};
  MeasureRun measure = [](const rp::cl::DeviceInfo&, uint32_t, uint32_t, uint32_t) -> RunResult {
    throw std::runtime_error("texture missing");
  };
  BenchMatrix m;
  EXPECT_THROW(run_matrix(plan, measure, nullptr, m, nullptr), std::runtime_error);
}

BenchMatrix sample_matrix() {
  BenchMatrix m;
  m.command = "rolypoly bench --devices all --sizes 256,512";
  m.scene = "busy";
  m.seed = 42;
  m.bounces = 2;
  m.frames = 3;
  m.warmup = 1;
  m.sizes = {{256, 256}, {512, 512}};
  m.voxels = {32, 64};
  DeviceResult ok;
  ok.index = 0;
  ok.name = "pthread <AMD> & \"friends\"";
  ok.type = "CPU";
  ok.platform = "Portable Computing Language";
  ok.compute_units = 2;
  ok.peak_bandwidth_gbps = 30.5;
  ok.peak_gflops = 1.0 / 3.0;
  ok.runs = {run(256, 32, 10.0), run(512, 32, 41.0), run(256, 64, 1.0 / 7.0),
             run(512, 64, 80.0)};
  ok.runs[1].spheres = 2079;
  ok.runs[1].instances = 13;
  ok.runs[1].instance_triangles = 12345;
  ok.runs[1].voxel_triangles = 2345;
  ok.runs[1].shadow_triangles = 345;
  ok.runs[1].frame_memory = {{"visibility", 123456789012ull}, {"gbuffer", 7}, {"post", 0}};
  ok.runs[1].passes[1].efficiency = {1e9, 2e9, 3.5, 0.1, 0.25, 1e-3};
  fit_scaling(ok);
  DeviceResult bad;
  bad.index = 1;
  bad.name = "Broken GPU";
  bad.type = "GPU";
  bad.platform = "Vendor";
  bad.compute_units = 80;
  bad.skipped = "visibility.cl failed to build\n--- build log ---\nerror: \"x\"";
  m.devices = {ok, bad};
  return m;
}

void expect_summary_eq(const TimeSummary& a, const TimeSummary& b) {
  EXPECT_EQ(a.median_ms, b.median_ms);
  EXPECT_EQ(a.min_ms, b.min_ms);
  EXPECT_EQ(a.max_ms, b.max_ms);
  EXPECT_EQ(a.p95_ms, b.p95_ms);
}

void expect_fit_eq(const PowerFit& a, const PowerFit& b) {
  EXPECT_EQ(a.k, b.k);
  EXPECT_EQ(a.a, b.a);
  EXPECT_EQ(a.r2, b.r2);
  EXPECT_EQ(a.points, b.points);
}

TEST(BenchJson, MatrixRoundTripsExactly) {
  const BenchMatrix m = sample_matrix();
  const std::string text = matrix_json(m);
  const BenchMatrix p = parse_matrix_json(text);
  EXPECT_EQ(p.command, m.command);
  EXPECT_EQ(p.scene, m.scene);
  EXPECT_EQ(p.seed, m.seed);
  EXPECT_EQ(p.bounces, 2u);
  EXPECT_EQ(p.frames, m.frames);
  EXPECT_EQ(p.warmup, m.warmup);
  EXPECT_EQ(p.sizes, m.sizes);
  EXPECT_EQ(p.voxels, m.voxels);
  ASSERT_EQ(p.devices.size(), m.devices.size());
  for (size_t i = 0; i < m.devices.size(); ++i) {
    const DeviceResult &a = p.devices[i], &b = m.devices[i];
    EXPECT_EQ(a.index, b.index);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.type, b.type);
    EXPECT_EQ(a.platform, b.platform);
    EXPECT_EQ(a.compute_units, b.compute_units);
    EXPECT_EQ(a.skipped, b.skipped);
    EXPECT_EQ(a.peak_bandwidth_gbps, b.peak_bandwidth_gbps);
    EXPECT_EQ(a.peak_gflops, b.peak_gflops);
    ASSERT_EQ(a.runs.size(), b.runs.size());
    for (size_t r = 0; r < b.runs.size(); ++r) {
      const RunResult &x = a.runs[r], &y = b.runs[r];
      EXPECT_EQ(x.width, y.width);
      EXPECT_EQ(x.height, y.height);
      EXPECT_EQ(x.voxels, y.voxels);
      EXPECT_EQ(x.frames, y.frames);
      EXPECT_EQ(x.spheres, y.spheres);
      EXPECT_EQ(x.instances, y.instances);
      EXPECT_EQ(x.instance_triangles, y.instance_triangles);
      EXPECT_EQ(x.voxel_triangles, y.voxel_triangles);
      EXPECT_EQ(x.shadow_triangles, y.shadow_triangles);
      EXPECT_EQ(x.frame_memory, y.frame_memory) << "parts and their order kept";
      expect_summary_eq(x.frame, y.frame);
      ASSERT_EQ(x.passes.size(), y.passes.size());
      for (size_t q = 0; q < y.passes.size(); ++q) {
        EXPECT_EQ(x.passes[q].name, y.passes[q].name) << "pipeline order kept";
        expect_summary_eq(x.passes[q].ms, y.passes[q].ms);
        const PassEfficiency &e = x.passes[q].efficiency, &f = y.passes[q].efficiency;
        EXPECT_EQ(e.bytes, f.bytes);
        EXPECT_EQ(e.flops, f.flops);
        EXPECT_EQ(e.gbytes_per_s, f.gbytes_per_s);
        EXPECT_EQ(e.gflops_per_s, f.gflops_per_s);
        EXPECT_EQ(e.bandwidth_fraction, f.bandwidth_fraction);
        EXPECT_EQ(e.compute_fraction, f.compute_fraction);
      }
    }
    ASSERT_EQ(a.pixel_scaling.size(), b.pixel_scaling.size());
    for (size_t s = 0; s < b.pixel_scaling.size(); ++s) {
      EXPECT_EQ(a.pixel_scaling[s].voxels, b.pixel_scaling[s].voxels);
      expect_fit_eq(a.pixel_scaling[s].fit, b.pixel_scaling[s].fit);
    }
    ASSERT_EQ(a.voxel_scaling.size(), b.voxel_scaling.size());
    for (size_t s = 0; s < b.voxel_scaling.size(); ++s) {
      EXPECT_EQ(a.voxel_scaling[s].width, b.voxel_scaling[s].width);
      EXPECT_EQ(a.voxel_scaling[s].height, b.voxel_scaling[s].height);
      expect_fit_eq(a.voxel_scaling[s].fit, b.voxel_scaling[s].fit);
    }
  }
  EXPECT_EQ(matrix_json(p), text) << "writing the parsed document gives the same text";
}

TEST(BenchJson, OtherSchemaIsRejected) {
  EXPECT_THROW(parse_matrix_json(R"({"schema": "rolypoly-bench/1"})"), std::runtime_error);
}

TEST(BenchReport, TableAndMarkdownNameEveryDeviceAndTheSkip) {
  const BenchMatrix m = sample_matrix();
  std::string table = matrix_table(m), md = matrix_markdown(m);
  EXPECT_NE(table.find("Broken GPU (GPU) (Vendor): skipped"), std::string::npos) << table;
  EXPECT_NE(table.find("512x512, 32^3 voxels, 3 frames: frame 41.00 ms median"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("frame ~ voxels^"), std::string::npos) << table;
  // Markdown rows all have the header's column count.
  size_t header_cells = 0;
  size_t line_start = 0;
  while (line_start < md.size()) {
    size_t end = md.find('\n', line_start);
    std::string line = md.substr(line_start, end - line_start);
    line_start = end + 1;
    if (line.empty()) break;  // end of the first table
    size_t cells = size_t(std::count(line.begin(), line.end(), '|'));
    if (header_cells == 0) header_cells = cells;
    EXPECT_EQ(cells, header_cells) << line;
  }
  EXPECT_EQ(header_cells, 3u + 2u + 4u + 1u);  // device, size, voxels, 2 passes, 4 frame columns
}

// Element names must nest and close: a tiny structural check (no attributes parsed).
::testing::AssertionResult WellFormedTags(const std::string& xml) {
  std::vector<std::string> open;
  size_t pos = 0;
  while ((pos = xml.find('<', pos)) != std::string::npos) {
    size_t end = xml.find('>', pos);
    if (end == std::string::npos) return ::testing::AssertionFailure() << "unclosed '<'";
    std::string tag = xml.substr(pos + 1, end - pos - 1);
    pos = end + 1;
    if (tag.empty()) return ::testing::AssertionFailure() << "empty tag";
    if (tag[0] == '?' || tag[0] == '!') continue;
    if (tag[0] == '/') {
      std::string name = tag.substr(1);
      if (open.empty() || open.back() != name)
        return ::testing::AssertionFailure() << "</" << name << "> closes nothing open";
      open.pop_back();
      continue;
    }
    if (tag.back() == '/') continue;
    open.push_back(tag.substr(0, tag.find(' ')));
  }
  if (!open.empty()) return ::testing::AssertionFailure() << "<" << open.back() << "> not closed";
  return ::testing::AssertionSuccess();
}

TEST(BenchChart, SvgIsWellFormedAndNamesTheDevices) {
  const std::string svg = matrix_svg(sample_matrix());
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  EXPECT_TRUE(WellFormedTags(svg));
  // The device name is escaped, never raw (it holds <, >, & and ").
  EXPECT_NE(svg.find("pthread &lt;AMD&gt; &amp; &quot;friends&quot;"), std::string::npos);
  EXPECT_EQ(svg.find("<AMD>"), std::string::npos);
  EXPECT_NE(svg.find("Broken GPU"), std::string::npos) << "the skipped device is listed";
  // One stacked bar segment per pass and run (2 passes x 4 runs), one polyline per series.
  EXPECT_GE(std::count(svg.begin(), svg.end(), '\n'), 20);
  size_t polylines = 0;
  for (size_t p = 0; (p = svg.find("<polyline", p)) != std::string::npos; ++p) ++polylines;
  EXPECT_EQ(polylines, 4u) << "2 voxel resolutions + 2 sizes, one device";
}

TEST(BenchChart, XmlEscape) {
  EXPECT_EQ(xml_escape("a<b>&\"'"), "a&lt;b&gt;&amp;&quot;&apos;");
}

}  // namespace
}  // namespace rp::bench
