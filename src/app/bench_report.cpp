#include "app/bench_report.h"

#include <cstdio>

#include <nlohmann/json.hpp>

namespace rp::app {
namespace {

nlohmann::ordered_json summary_json(const TimeSummary& s) {
  nlohmann::ordered_json j;
  j["median_ms"] = s.median_ms;
  j["min_ms"] = s.min_ms;
  j["max_ms"] = s.max_ms;
  return j;
}

std::string row(const std::string& name, const TimeSummary& s) {
  char line[160];
  std::snprintf(line, sizeof line, "%-16s %10.3f %10.3f %10.3f\n", name.c_str(), s.median_ms,
                s.min_ms, s.max_ms);
  return line;
}

}  // namespace

std::string bench_json(const BenchDevice& device, uint32_t width, uint32_t height,
                       const PassStats& stats) {
  nlohmann::ordered_json j;
  j["schema"] = kBenchSchema;
  j["device"] = {{"name", device.name},
                 {"type", device.type},
                 {"platform", device.platform},
                 {"compute_units", device.compute_units}};
  j["size"] = {width, height};
  j["frames"] = stats.frames();
  nlohmann::ordered_json passes = nlohmann::ordered_json::object();
  for (const std::string& name : stats.pass_names()) passes[name] = summary_json(stats.pass(name));
  j["passes"] = passes;
  j["frame"] = summary_json(stats.frame());
  return j.dump(2) + "\n";
}

std::string timing_table(const PassStats& stats) {
  char header[160];
  std::snprintf(header, sizeof header, "%-16s %10s %10s %10s\n", "pass", "median ms", "min ms",
                "max ms");
  std::string out = header;
  for (const std::string& name : stats.pass_names()) out += row(name, stats.pass(name));
  out += row("frame", stats.frame());
  return out;
}

std::string median_line(const PassStats& stats) {
  std::string out;
  for (const std::string& name : stats.pass_names()) {
    char part[96];
    std::snprintf(part, sizeof part, "%s%s %.2f ms", out.empty() ? "" : ", ", name.c_str(),
                  stats.pass(name).median_ms);
    out += part;
  }
  return out;
}

}  // namespace rp::app
