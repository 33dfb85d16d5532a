#include "bench/src/bench_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "bench/src/scene_file_facts.h"

namespace rp::bench {

using app::TimeSummary;
using app::pipeline_rank;

namespace {

nlohmann::ordered_json summary_json(const TimeSummary& s) {
  nlohmann::ordered_json j;
  j["median_ms"] = s.median_ms;
  j["min_ms"] = s.min_ms;
  j["max_ms"] = s.max_ms;
  j["p95_ms"] = s.p95_ms;
  return j;
}

using Json = nlohmann::ordered_json;

Json fit_json(const PowerFit& f) {
  return {{"k", f.k}, {"a_ms", f.a}, {"r2", f.r2}, {"points", f.points}};
}

PowerFit parse_fit(const Json& j) {
  PowerFit f;
  f.k = j.at("k");
  f.a = j.at("a_ms");
  f.r2 = j.at("r2");
  f.points = j.at("points");
  return f;
}

// A number, or NaN for null (a fraction not shown).
double number_or_nan(const Json& j) { return j.is_null() ? std::nan("") : j.get<double>(); }

TimeSummary parse_summary(const Json& j) {
  // files written before the 95th percentile was recorded read it as the maximum
  const double max_ms = j.at("max_ms").get<double>();
  return {j.at("median_ms").get<double>(), j.at("min_ms").get<double>(), max_ms,
          j.value("p95_ms", max_ms)};
}

Json run_json(const RunResult& r) {
  Json j;
  j["size"] = {r.width, r.height};
  j["voxels"] = r.voxels;
  j["frames"] = r.frames;
  j["timing"] = r.timing;
  j["gi_volume"] = r.gi_volume;
  j["render_scale"] = r.render_scale;
  j["render_size"] = {r.render_width, r.render_height};
  j["render_scale_range"] = {r.scale_min, r.scale_max};
  j["render_scale_changes"] = r.scale_changes;
  if (r.gi_volume == "svo")
    j["octree_memory"] = {{"device_bytes", r.octree_device_bytes},
                          {"peak_bytes", r.octree_peak_bytes},
                          {"pool_bytes", r.octree_pool_bytes},
                          {"node_bytes", r.octree_node_bytes},
                          {"brick_bytes", r.octree_brick_bytes},
                          {"fragments", r.octree_fragments},
                          {"fragment_bytes", r.octree_fragment_bytes}};
  if (!r.frame_memory.empty()) {  // [part, bytes] pairs in the renderer's order
    Json memory = Json::array();
    for (const auto& [part, bytes] : r.frame_memory) memory.push_back({part, bytes});
    j["frame_memory"] = memory;
  }
  j["scene"] = {{"spheres", r.spheres},
                {"instances", r.instances},
                {"instance_triangles", r.instance_triangles},
                {"voxel_triangles", r.voxel_triangles},
                {"shadow_triangles", r.shadow_triangles}};
  Json passes = Json::object();
  for (const PassResult& p : r.passes) {
    Json e = summary_json(p.ms);
    e["bytes"] = p.efficiency.bytes;
    e["flops"] = p.efficiency.flops;
    e["footprint_bytes"] = p.efficiency.footprint;
    e["gbytes_per_s"] = p.efficiency.gbytes_per_s;
    e["gflops_per_s"] = p.efficiency.gflops_per_s;
    e["bandwidth_ceiling_gbps"] = p.efficiency.ceiling_gbps;
    // NaN (the model would exceed the ceiling) is written as null.
    e["bandwidth_fraction"] = p.efficiency.bandwidth_fraction;
    e["compute_fraction"] = p.efficiency.compute_fraction;
    passes[p.name] = e;
  }
  j["passes"] = passes;
  Json frame = summary_json(r.frame);
  frame["fps"] = r.fps();
  j["frame"] = frame;
  return j;
}

RunResult parse_run(const Json& j) {
  RunResult r;
  r.width = j.at("size").at(0);
  r.height = j.at("size").at(1);
  r.voxels = j.at("voxels");
  r.frames = j.at("frames");
  r.timing = j.value("timing", std::string("device"));
  r.gi_volume = j.value("gi_volume", std::string("dense"));  // older files: dense
  r.render_scale = j.value("render_scale", 1.0f);  // files before the render scale: 1
  r.render_width = j.contains("render_size") ? j.at("render_size").at(0).get<uint32_t>() : r.width;
  r.render_height = j.contains("render_size") ? j.at("render_size").at(1).get<uint32_t>() : r.height;
  if (j.contains("render_scale_range")) {  // files before it: the last frame's scale
    r.scale_min = j.at("render_scale_range").at(0).get<float>();
    r.scale_max = j.at("render_scale_range").at(1).get<float>();
  } else {
    r.scale_min = r.scale_max = r.render_scale;
  }
  r.scale_changes = j.value("render_scale_changes", 0u);
  if (j.contains("octree_memory")) {
    const Json& m = j.at("octree_memory");
    r.octree_device_bytes = m.at("device_bytes");
    r.octree_peak_bytes = m.at("peak_bytes");
    r.octree_pool_bytes = m.at("pool_bytes");
    r.octree_node_bytes = m.value("node_bytes", uint64_t(0));
    r.octree_brick_bytes = m.value("brick_bytes", uint64_t(0));
    r.octree_fragments = m.value("fragments", uint64_t(0));
    r.octree_fragment_bytes = m.value("fragment_bytes", uint64_t(0));
  }
  if (j.contains("frame_memory"))  // files before it: none
    for (const Json& part : j.at("frame_memory"))
      r.frame_memory.emplace_back(part.at(0).get<std::string>(), part.at(1).get<uint64_t>());
  r.spheres = j.at("scene").at("spheres");
  r.instances = j.at("scene").at("instances");
  r.instance_triangles = j.at("scene").at("instance_triangles");
  // files written before mesh proxies: every triangle was voxelized and drawn into the map
  r.voxel_triangles = j.at("scene").value("voxel_triangles", r.instance_triangles);
  r.shadow_triangles = j.at("scene").value("shadow_triangles", r.instance_triangles);
  for (const auto& [name, e] : j.at("passes").items()) {
    PassResult p{name, parse_summary(e), {}};
    p.efficiency.bytes = e.at("bytes");
    p.efficiency.flops = e.at("flops");
    p.efficiency.gbytes_per_s = e.at("gbytes_per_s");
    p.efficiency.gflops_per_s = e.at("gflops_per_s");
    p.efficiency.footprint = e.value("footprint_bytes", 0.0);
    p.efficiency.ceiling_gbps = e.value("bandwidth_ceiling_gbps", 0.0);
    p.efficiency.bandwidth_fraction = number_or_nan(e.at("bandwidth_fraction"));
    p.efficiency.compute_fraction = number_or_nan(e.at("compute_fraction"));
    r.passes.push_back(p);
  }
  r.frame = parse_summary(j.at("frame"));
  return r;
}

std::string format(const char* fmt, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, a);
  return buf;
}

std::string size_text(uint32_t w, uint32_t h) {
  return str_cat(std::to_string(w), "x", std::to_string(h));
}

// Pass names over every run of every device, in pipeline order.
std::vector<std::string> all_pass_names(const BenchMatrix& m) {
  std::set<std::string> seen;
  std::vector<std::string> names;
  for (const DeviceResult& d : m.devices)
    for (const RunResult& r : d.runs)
      for (const PassResult& p : r.passes)
        if (seen.insert(p.name).second) names.push_back(p.name);
  std::stable_sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) {
    return pipeline_rank(a) < pipeline_rank(b);
  });
  return names;
}

// "12.3%"; "-" for NaN (the model would exceed its ceiling: not shown); "" for 0 (not
// measured).
std::string percent_text(double fraction) {
  if (std::isnan(fraction)) return "-";
  if (fraction <= 0.0) return "";
  return format("%.1f%%", 100.0 * fraction);
}

std::string bytes_text(double bytes) {
  if (bytes >= double(1 << 20)) return format("%.0f MiB", bytes / double(1 << 20));
  return format("%.0f KiB", bytes / 1024.0);
}

std::string scaling_text(const DeviceResult& d) {
  std::string out;
  for (const PixelScaling& s : d.pixel_scaling)
    out += str_cat("  frame ~ pixels^", format("%.2f", s.fit.k), " at ", std::to_string(s.voxels),
                   "^3 voxels (r2 ", format("%.3f", s.fit.r2), ", ", std::to_string(s.fit.points),
                   " sizes)\n");
  for (const VoxelScaling& s : d.voxel_scaling)
    out += str_cat("  frame ~ voxels^", format("%.2f", s.fit.k), " at ",
                   size_text(s.width, s.height), " (voxel count = resolution^3; r2 ",
                   format("%.3f", s.fit.r2), ", ", std::to_string(s.fit.points),
                   " resolutions)\n");
  return out;
}

}  // namespace

std::string matrix_json(const BenchMatrix& m) {
  Json j;
  j["schema"] = kBenchMatrixSchema;
  j["command"] = m.command;
  j["scene"] = m.scene;
  if (m.file) j["scene_file"] = scene_file_json<Json>(*m.file);
  j["seed"] = m.seed;
  j["bounces"] = m.bounces;
  j["frames"] = m.frames;
  j["warmup"] = m.warmup;
  Json sizes = Json::array();
  for (const auto& [w, h] : m.sizes) sizes.push_back({w, h});
  j["sizes"] = sizes;
  j["voxels"] = m.voxels;
  Json devices = Json::array();
  for (const DeviceResult& d : m.devices) {
    Json dj;
    dj["index"] = d.index;
    dj["name"] = d.name;
    dj["type"] = d.type;
    dj["platform"] = d.platform;
    dj["compute_units"] = d.compute_units;
    dj["skipped"] = d.ok() ? Json(nullptr) : Json(d.skipped);
    dj["timing"] = d.timing;
    Json levels = Json::array();
    for (const BandwidthLevel& l : d.bandwidth_levels)
      levels.push_back({{"working_set_bytes", l.working_set_bytes}, {"gbps", l.gbps}});
    dj["peak"] = {{"bandwidth_gbps", d.peak_bandwidth_gbps},
                  {"gflops", d.peak_gflops},
                  {"bandwidth_levels", levels},
                  {"bandwidth_note", d.bandwidth_note.empty() ? Json(nullptr) : Json(d.bandwidth_note)},
                  {"compute_note", d.compute_note.empty() ? Json(nullptr) : Json(d.compute_note)}};
    Json runs = Json::array();
    for (const RunResult& r : d.runs) runs.push_back(run_json(r));
    dj["runs"] = runs;
    Json pixels = Json::array(), voxels = Json::array();
    for (const PixelScaling& s : d.pixel_scaling) {
      Json e = fit_json(s.fit);
      e["voxels"] = s.voxels;
      pixels.push_back(e);
    }
    for (const VoxelScaling& s : d.voxel_scaling) {
      Json e = fit_json(s.fit);
      e["size"] = {s.width, s.height};
      voxels.push_back(e);
    }
    dj["scaling"] = {{"pixels", pixels}, {"voxels", voxels}};
    devices.push_back(dj);
  }
  j["devices"] = devices;
  return j.dump(2) + "\n";
}

BenchMatrix parse_matrix_json(const std::string& text) {
  Json j = Json::parse(text);
  if (j.at("schema") != kBenchMatrixSchema && j.at("schema") != kBenchMatrixSchemaV2)
    throw std::runtime_error(str_cat("not a ", kBenchMatrixSchema, " document (schema ",
                                     j.at("schema").dump(), ")"));
  BenchMatrix m;
  m.command = j.at("command");
  m.scene = j.at("scene");
  if (j.contains("scene_file")) m.file = parse_scene_file_json(j.at("scene_file"));
  m.seed = j.at("seed");
  m.bounces = j.value("bounces", 1u);
  m.frames = j.at("frames");
  m.warmup = j.at("warmup");
  for (const Json& s : j.at("sizes")) m.sizes.push_back({s.at(0), s.at(1)});
  m.voxels = j.at("voxels").get<std::vector<uint32_t>>();
  for (const Json& dj : j.at("devices")) {
    DeviceResult d;
    d.index = dj.at("index");
    d.name = dj.at("name");
    d.type = dj.at("type");
    d.platform = dj.at("platform");
    d.compute_units = dj.at("compute_units");
    if (!dj.at("skipped").is_null()) d.skipped = dj.at("skipped");
    d.timing = dj.value("timing", std::string("device"));
    const Json& peak = dj.at("peak");
    d.peak_bandwidth_gbps = peak.at("bandwidth_gbps");
    d.peak_gflops = peak.at("gflops");
    if (peak.contains("bandwidth_levels"))
      for (const Json& l : peak.at("bandwidth_levels"))
        d.bandwidth_levels.push_back({l.at("working_set_bytes"), l.at("gbps")});
    if (peak.contains("bandwidth_note") && !peak.at("bandwidth_note").is_null())
      d.bandwidth_note = peak.at("bandwidth_note");
    if (peak.contains("compute_note") && !peak.at("compute_note").is_null())
      d.compute_note = peak.at("compute_note");
    for (const Json& r : dj.at("runs")) d.runs.push_back(parse_run(r));
    for (const Json& e : dj.at("scaling").at("pixels"))
      d.pixel_scaling.push_back({e.at("voxels").get<uint32_t>(), parse_fit(e)});
    for (const Json& e : dj.at("scaling").at("voxels"))
      d.voxel_scaling.push_back(
          {e.at("size").at(0).get<uint32_t>(), e.at("size").at(1).get<uint32_t>(), parse_fit(e)});
    m.devices.push_back(std::move(d));
  }
  return m;
}

std::string matrix_table(const BenchMatrix& m) {
  std::string out;
  for (const DeviceResult& d : m.devices) {
    out += str_cat("device ", d.label(), " (", d.platform, ")");
    if (!d.ok()) {
      out += ": skipped (error above)\n";
      continue;
    }
    out += "\n";
    if (d.timing == "host")
      out += "  host timing: this device's profiling timestamps are unusable; each pass is timed "
             "on the host with a finish after it (launch overhead included)\n";
    if (d.peak_bandwidth_gbps > 0.0 || d.peak_gflops > 0.0 || !d.bandwidth_note.empty() ||
        !d.compute_note.empty()) {
      out += "  measured peak: ";
      out += d.peak_bandwidth_gbps > 0.0 ? str_cat(format("%.1f", d.peak_bandwidth_gbps), " GB/s")
                                          : std::string("bandwidth not measured");
      out += ", ";
      out += d.peak_gflops > 0.0 ? str_cat(format("%.1f", d.peak_gflops), " GFLOP/s")
                                  : std::string("compute not measured");
      out += "\n";
      if (d.bandwidth_levels.size() > 1) {
        out += "  copy bandwidth by working set:";
        for (const BandwidthLevel& l : d.bandwidth_levels)
          out += str_cat(" ", bytes_text(l.working_set_bytes), " ", format("%.1f", l.gbps),
                         " GB/s;");
        out.back() = '\n';
      }
      if (!d.bandwidth_note.empty()) out += str_cat("  (", d.bandwidth_note, ")\n");
      if (!d.compute_note.empty()) out += str_cat("  (", d.compute_note, ")\n");
    }
    for (const RunResult& r : d.runs) {
      char line[200];
      std::snprintf(line, sizeof line,
                    "  %s, %u^3 voxels, %u frames: frame %.2f ms median (95th percentile "
                    "%.2f, min %.2f, max %.2f), %.2f fps%s\n",
                    size_text(r.width, r.height).c_str(), r.voxels, r.frames, r.frame.median_ms,
                    r.frame.p95_ms, r.frame.min_ms, r.frame.max_ms, r.fps(),
                    r.timing == "host" ? ", passes host-timed" : "");
      out += line;
      bool eff = false;
      for (const PassResult& p : r.passes)
        eff = eff || p.efficiency.bytes > 0.0 || p.efficiency.flops > 0.0;
      std::snprintf(line, sizeof line, "    %-16s %10s %10s %10s", "pass", "median ms", "min ms",
                    "max ms");
      out += line;
      if (eff) {
        std::snprintf(line, sizeof line, " %9s %9s %6s %9s %6s", "GB/s", "ceil GB/s", "%bw",
                      "GFLOP/s", "%flop");
        out += line;
      }
      out += "\n";
      for (const PassResult& p : r.passes) {
        std::snprintf(line, sizeof line, "    %-16s %10.3f %10.3f %10.3f", p.name.c_str(),
                      p.ms.median_ms, p.ms.min_ms, p.ms.max_ms);
        out += line;
        const PassEfficiency& e = p.efficiency;
        if (eff && (e.bytes > 0.0 || e.flops > 0.0)) {
          std::snprintf(line, sizeof line, " %9.2f %9.1f %6s %9.2f %6s", e.gbytes_per_s,
                        e.ceiling_gbps, percent_text(e.bandwidth_fraction).c_str(),
                        e.gflops_per_s, percent_text(e.compute_fraction).c_str());
          out += line;
        }
        out += "\n";
      }
    }
    out += scaling_text(d);
  }
  out += "(%bw: achieved GB/s over the pass's cache-aware ceiling, %flop: over the measured "
         "GFLOP/s; \"-\": the work model would put the pass above its ceiling, so no figure)\n";
  return out;
}

std::string matrix_markdown(const BenchMatrix& m) {
  std::vector<std::string> names = all_pass_names(m);
  std::string out;
  if (m.file) out = str_cat("Scene: ", describe_scene_file(*m.file), "\n\n");
  out += "| device | size | voxels |";
  std::string rule = "|---|---|---|";
  for (const std::string& n : names) {
    out += str_cat(" ", n, " |");
    rule += "---:|";
  }
  out += " frame median | frame min | frame max | fps |\n";
  rule += "---:|---:|---:|---:|\n";
  out += rule;
  for (const DeviceResult& d : m.devices) {
    if (!d.ok()) {
      out += str_cat("| ", d.label(), " | skipped | |", std::string(names.size() + 4, '|'), "\n");
      continue;
    }
    for (const RunResult& r : d.runs) {
      out += str_cat("| ", d.label(), " | ", size_text(r.width, r.height), " | ",
                     std::to_string(r.voxels), "^3 |");
      for (const std::string& n : names) {
        const PassResult* p = r.pass(n);
        out += p ? str_cat(" ", format("%.2f", p->ms.median_ms), " |") : std::string(" |");
      }
      out += str_cat(" ", format("%.1f", r.frame.median_ms), " | ", format("%.1f", r.frame.min_ms),
                     " | ", format("%.1f", r.frame.max_ms), " | ", format("%.2f", r.fps()),
                     " |\n");
    }
  }
  out += "\nMilliseconds (medians per pass: OpenCL device time; frame: wall clock).";
  for (const DeviceResult& d : m.devices)
    if (d.timing == "host")
      out += str_cat(" ", d.label(), ": passes timed on the host (finish after each pass; the "
                                     "device's profiling timestamps are unusable).");
  out += "\n\n";
  out += "| device | scaling | at | exponent k | r2 | points |\n|---|---|---|---:|---:|---:|\n";
  for (const DeviceResult& d : m.devices) {
    for (const PixelScaling& s : d.pixel_scaling)
      out += str_cat("| ", d.label(), " | frame ~ pixels^k | ", std::to_string(s.voxels),
                     "^3 voxels | ", format("%.2f", s.fit.k), " | ", format("%.3f", s.fit.r2),
                     " | ", std::to_string(s.fit.points), " |\n");
    for (const VoxelScaling& s : d.voxel_scaling)
      out += str_cat("| ", d.label(), " | frame ~ voxels^k | ", size_text(s.width, s.height),
                     " | ", format("%.2f", s.fit.k), " | ", format("%.3f", s.fit.r2), " | ",
                     std::to_string(s.fit.points), " |\n");
  }
  return out;
}

}  // namespace rp::bench
