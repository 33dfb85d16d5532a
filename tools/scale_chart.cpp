// How each pass's time grows with the scene or the GI volume, from `rolypoly bench --json` files:
//   scale_chart triangles|voxels OUT.svg FILE.json...
// Every run of every file (one per scene file, or one per voxel resolution) is a point: x its
// instance triangles or its voxel resolution per side, y the pass medians and the frame median
// (ms). Writes a log-log chart to OUT.svg (the frame, and each pass that takes at least 5 % of
// some run's frame) and prints the table as Markdown, one row per run, with the fitted growth
// exponent (least squares slope of log ms on log x) in the last row. tools/scale_table.sh
// runs the benches.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/src/bench_chart.h"
#include "io/atomic_file.h"

namespace {

struct Run {
  double x = 0.0;
  std::string volume;              // dense or svo
  double frame_ms = 0.0;
  std::map<std::string, double> pass_ms;
  std::vector<std::string> order;  // passes in the file's order (the pipeline's)
};

// Least-squares slope of log(y) on log(x): the exponent of a power law through the points.
double growth_exponent(const std::vector<std::pair<double, double>>& points) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [x, y] : points) {
    if (!(x > 0.0) || !(y > 0.0)) continue;
    const double lx = std::log(x), ly = std::log(y);
    n += 1;
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  const double den = n * sxx - sx * sx;
  return n >= 2 && den > 0.0 ? (n * sxy - sx * sy) / den : NAN;
}

std::string x_text(double x, bool triangles) {
  char buf[32];
  if (triangles)
    std::snprintf(buf, sizeof buf, x >= 1e6 ? "%.2fM" : "%.0fk", x >= 1e6 ? x / 1e6 : x / 1e3);
  else
    std::snprintf(buf, sizeof buf, "%.0f^3", x);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4 || (std::string(argv[1]) != "triangles" && std::string(argv[1]) != "voxels")) {
    std::fprintf(stderr, "usage: scale_chart triangles|voxels OUT.svg BENCH.json...\n");
    return 2;
  }
  const bool triangles = std::string(argv[1]) == "triangles";
  std::vector<Run> runs;
  try {
    for (int i = 3; i < argc; ++i) {
      std::ifstream in(argv[i]);
      if (!in) throw std::runtime_error(std::string("cannot read ") + argv[i]);
      const nlohmann::json j = nlohmann::json::parse(in);
      for (const auto& r : j.at("devices").at(0).at("runs")) {
        Run run;
        run.x = triangles ? r.at("scene").at("instance_triangles").get<double>()
                          : r.at("voxels").get<double>();
        run.volume = r.value("gi_volume", "dense");
        run.frame_ms = r.at("frame").at("median_ms").get<double>();
        for (const auto& [name, p] : r.at("passes").items()) {
          run.pass_ms[name] = p.at("median_ms").get<double>();
          run.order.push_back(name);
        }
        runs.push_back(std::move(run));
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "scale_chart: %s\n", e.what());
    return 1;
  }
  if (runs.empty()) {
    std::fprintf(stderr, "scale_chart: the files hold no runs\n");
    return 1;
  }
  std::stable_sort(runs.begin(), runs.end(), [](const Run& a, const Run& b) {
    return a.volume != b.volume ? a.volume < b.volume : a.x < b.x;
  });
  // The passes shown: at least 5 % of some run's frame, in pipeline order.
  std::vector<std::string> shown;
  for (const Run& run : runs)
    for (const std::string& name : run.order)
      if (run.pass_ms.at(name) >= 0.05 * run.frame_ms &&
          std::find(shown.begin(), shown.end(), name) == shown.end())
        shown.push_back(name);

  // The table.
  std::printf("| %s | volume | frame |", triangles ? "triangles" : "voxels");
  for (const std::string& name : shown) std::printf(" %s |", name.c_str());
  std::printf("\n|---|---|---|");
  for (size_t i = 0; i < shown.size(); ++i) std::printf("---|");
  std::printf("\n");
  // NaN: the run has no such pass (the octree's passes in a dense run, and back).
  const auto ms_of = [](const Run& run, const std::string& name) {
    const auto it = run.pass_ms.find(name);
    return it == run.pass_ms.end() ? NAN : it->second;
  };
  const auto cell = [](double ms) {
    char buf[32];
    std::snprintf(buf, sizeof buf, std::isnan(ms) ? "-" : "%.1f", ms);
    return std::string(buf);
  };
  for (const Run& run : runs) {
    std::printf("| %s | %s | %.1f |", x_text(run.x, triangles).c_str(), run.volume.c_str(),
                run.frame_ms);
    for (const std::string& name : shown) std::printf(" %s |", cell(ms_of(run, name)).c_str());
    std::printf("\n");
  }
  std::vector<std::string> volumes;
  for (const Run& run : runs)
    if (std::find(volumes.begin(), volumes.end(), run.volume) == volumes.end())
      volumes.push_back(run.volume);
  for (const std::string& volume : volumes) {
    const auto points = [&](const std::string& name) {
      std::vector<std::pair<double, double>> p;
      for (const Run& run : runs)
        if (run.volume == volume)
          p.push_back({run.x, name.empty() ? run.frame_ms : ms_of(run, name)});
      return p;
    };
    const auto exponent = [](double e) {
      char buf[32];
      std::snprintf(buf, sizeof buf, std::isnan(e) ? "-" : "%.2f", e);
      return std::string(buf);
    };
    std::printf("| growth exponent | %s | %s |", volume.c_str(),
                exponent(growth_exponent(points(""))).c_str());
    for (const std::string& name : shown)
      std::printf(" %s |", exponent(growth_exponent(points(name))).c_str());
    std::printf("\n");
  }

  // The chart: one line per pass (and the frame) and volume.
  std::vector<rp::bench::Series> series;
  for (size_t v = 0; v < volumes.size(); ++v) {
    const std::string suffix = volumes.size() > 1 ? " (" + volumes[v] + ")" : "";
    const char* dash = v == 0 ? "" : "6,3";
    for (size_t k = 0; k <= shown.size(); ++k) {
      rp::bench::Series s;
      s.label = (k == 0 ? std::string("frame") : shown[k - 1]) + suffix;
      s.colour = k == 0 ? "#222" : rp::bench::chart_colour(k - 1);
      s.dash = dash;
      for (const Run& run : runs)
        if (run.volume == volumes[v]) {
          const double ms = k == 0 ? run.frame_ms : ms_of(run, shown[k - 1]);
          if (ms > 0.0) s.points.push_back({run.x, ms});  // false for NaN
        }
      if (!s.points.empty()) series.push_back(std::move(s));
    }
  }
  const double height = 520.0 + 16.0 * double(series.size());
  rp::bench::SvgWriter svg(760.0, height);
  svg.rect(0, 0, 760.0, height, "#ffffff");
  rp::bench::line_chart(svg, 80.0, 70.0, 640.0, 380.0,
                        triangles ? "Pass time against the scene's triangles"
                                  : "Pass time against the GI volume's resolution",
                        triangles ? "instance triangles (log)" : "voxels per side (log)", series,
                        [triangles](double x) { return x_text(x, triangles); });
  try {
    rp::io::write_file(argv[2], svg.finish());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "scale_chart: %s\n", e.what());
    return 1;
  }
  return 0;
}
