#include "bench/src/bench_matrix.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "cl/error.h"

namespace rp::bench {

using app::PassStats;

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string device_list(const std::vector<rp::cl::DeviceInfo>& all) {
  std::string out;
  for (const rp::cl::DeviceInfo& d : all)
    out += "  [" + std::to_string(d.index) + "] " + d.name + " (" + d.platform_name + ")\n";
  return out;
}

DeviceResult describe(const rp::cl::DeviceInfo& info) {
  DeviceResult r;
  r.index = info.index;
  r.name = info.name;
  r.type = info.type;
  r.platform = info.platform_name;
  r.compute_units = info.compute_units;
  return r;
}

}  // namespace

const PassResult* RunResult::pass(const std::string& name) const {
  for (const PassResult& p : passes)
    if (p.name == name) return &p;
  return nullptr;
}

RunResult make_run_result(uint32_t width, uint32_t height, uint32_t voxels,
                          const PassStats& stats) {
  RunResult r;
  r.width = width;
  r.height = height;
  r.voxels = voxels;
  r.frames = static_cast<uint32_t>(stats.frames());
  for (const std::string& name : stats.pass_names()) r.passes.push_back({name, stats.pass(name), {}});
  r.frame = stats.frame();
  return r;
}

PowerFit fit_power_law(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size()) throw std::invalid_argument("fit_power_law: x and y differ in size");
  const size_t n = x.size();
  double mx = 0.0, my = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (!(x[i] > 0.0) || !(y[i] > 0.0))
      throw std::invalid_argument("fit_power_law: values must be positive");
    mx += std::log(x[i]);
    my += std::log(y[i]);
  }
  if (n < 2) throw std::invalid_argument("fit_power_law: needs at least two points");
  mx /= double(n);
  my /= double(n);
  // Ordinary least squares of ly = log a + k lx: k = cov(lx, ly) / var(lx).
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (size_t i = 0; i < n; ++i) {
    double dx = std::log(x[i]) - mx, dy = std::log(y[i]) - my;
    sxx += dx * dx;
    sxy += dx * dy;
    syy += dy * dy;
  }
  if (sxx <= 0.0) throw std::invalid_argument("fit_power_law: needs two distinct x values");
  PowerFit f;
  f.k = sxy / sxx;
  f.a = std::exp(my - f.k * mx);
  f.r2 = syy > 0.0 ? (sxy * sxy) / (sxx * syy) : 1.0;  // all times equal: a flat line fits exactly
  f.points = static_cast<uint32_t>(n);
  return f;
}

std::string DeviceResult::label() const {
  return str_cat("[", std::to_string(index), "] ", name, " (", type, ")");
}

size_t BenchMatrix::devices_ok() const {
  return static_cast<size_t>(
      std::count_if(devices.begin(), devices.end(), [](const DeviceResult& d) { return d.ok(); }));
}

void fit_scaling(DeviceResult& device) {
  device.pixel_scaling.clear();
  device.voxel_scaling.clear();
  std::set<uint32_t> voxel_set;
  std::set<std::pair<uint32_t, uint32_t>> size_set;
  for (const RunResult& r : device.runs) {
    voxel_set.insert(r.voxels);
    size_set.insert({r.width, r.height});
  }
  for (uint32_t v : voxel_set) {
    std::vector<double> x, y;
    for (const RunResult& r : device.runs)
      if (r.voxels == v) {
        x.push_back(r.pixels());
        y.push_back(r.frame.median_ms);
      }
    if (std::set<double>(x.begin(), x.end()).size() >= 2)
      device.pixel_scaling.push_back({v, fit_power_law(x, y)});
  }
  for (const auto& [w, h] : size_set) {
    std::vector<double> x, y;
    for (const RunResult& r : device.runs)
      if (r.width == w && r.height == h) {
        x.push_back(double(r.voxels) * r.voxels * r.voxels);
        y.push_back(r.frame.median_ms);
      }
    if (std::set<double>(x.begin(), x.end()).size() >= 2)
      device.voxel_scaling.push_back({w, h, fit_power_law(x, y)});
  }
}

std::vector<rp::cl::DeviceInfo> select_devices(const std::string& spec,
                                               const std::vector<rp::cl::DeviceInfo>& all) {
  if (lower(spec) == "all") return all;
  std::vector<rp::cl::DeviceInfo> chosen;
  auto add = [&](const rp::cl::DeviceInfo& d) {
    for (const rp::cl::DeviceInfo& c : chosen)
      if (c.index == d.index) return;
    chosen.push_back(d);
  };
  size_t start = 0;
  while (start <= spec.size()) {
    size_t comma = spec.find(',', start);
    if (comma == std::string::npos) comma = spec.size();
    std::string token = spec.substr(start, comma - start);
    start = comma + 1;
    if (token.empty())
      throw rp::cl::Error("--devices: empty entry in '" + spec + "'; the devices are:\n" +
                          device_list(all));
    bool numeric = std::all_of(token.begin(), token.end(),
                               [](unsigned char c) { return std::isdigit(c) != 0; });
    bool found = false;
    for (const rp::cl::DeviceInfo& d : all) {
      bool match = numeric ? std::to_string(d.index) == token
                           : lower(d.name).find(lower(token)) != std::string::npos ||
                                 lower(d.platform_name).find(lower(token)) != std::string::npos;
      if (match) {
        add(d);
        found = true;
      }
    }
    if (!found)
      throw rp::cl::Error("--devices: no OpenCL device matches '" + token +
                          "'; the devices are:\n" + device_list(all));
  }
  return chosen;
}

void run_matrix(const MatrixPlan& plan, const MeasureRun& measure, const FinishDevice& finish,
                BenchMatrix& matrix, std::FILE* log) {
  matrix.devices.clear();
  for (const rp::cl::DeviceInfo& info : plan.devices) {
    DeviceResult result = describe(info);
    std::string error;
    try {
      for (uint32_t voxels : plan.voxels)
        for (const auto& [w, h] : plan.sizes) result.runs.push_back(measure(info, w, h, voxels));
      if (finish) finish(info, result);
    } catch (const rp::cl::Error& e) {
      error = e.what();
    } catch (const ::cl::Error& e) {
      error = std::string("OpenCL call ") + e.what() + " failed with " +
              rp::cl::error_name(e.err());
    }
    if (!error.empty()) {
      result.runs.clear();
      result.skipped = error;
      if (log) {
        std::fprintf(log, "device %s skipped: %s\n", result.label().c_str(), error.c_str());
        std::fflush(log);
      }
    } else {
      fit_scaling(result);
    }
    matrix.devices.push_back(std::move(result));
  }
}

}  // namespace rp::bench
