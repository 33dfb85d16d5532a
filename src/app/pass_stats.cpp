#include "app/pass_stats.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string_view>

#include "passes/pass_names.h"

namespace rp::app {

int pipeline_rank(const std::string& pass) {
  const auto& order = passes::pass_name::kPipelineOrder;
  for (size_t i = 0; i < order.size(); ++i)
    if (order[i] == pass) return static_cast<int>(i);
  return static_cast<int>(order.size());
}

TimeSummary summarize(std::vector<double> samples) {
  if (samples.empty()) throw std::invalid_argument("summarize: no samples");
  std::sort(samples.begin(), samples.end());
  size_t n = samples.size();
  TimeSummary s;
  s.min_ms = samples.front();
  s.max_ms = samples.back();
  const size_t rank = (95 * n + 99) / 100;  // ceil(0.95 n), >= 1
  s.p95_ms = samples[rank - 1];
  s.median_ms = n % 2 == 1 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
  return s;
}

void PassStats::add(const rp::cl::PassTimes& passes, double frame_ms) {
  for (const auto& [name, ms] : passes) pass_ms_[name].push_back(ms);
  frame_ms_.push_back(frame_ms);
}

std::vector<std::string> PassStats::pass_names() const {
  std::vector<std::string> names;
  for (const auto& entry : pass_ms_) names.push_back(entry.first);
  // std::map iterates alphabetically, so a stable sort by rank keeps unknown names alphabetical.
  std::stable_sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) {
    return pipeline_rank(a) < pipeline_rank(b);
  });
  return names;
}

TimeSummary PassStats::pass(const std::string& name) const {
  auto it = pass_ms_.find(name);
  if (it == pass_ms_.end()) throw std::invalid_argument("no timings for pass '" + name + "'");
  return summarize(it->second);
}

TimeSummary PassStats::frame() const { return summarize(frame_ms_); }

std::map<std::string, double> PassStats::pass_means() const {
  std::map<std::string, double> means;
  for (const auto& [name, ms] : pass_ms_) {
    double sum = 0.0;
    for (double v : ms) sum += v;
    means[name] = ms.empty() ? 0.0 : sum / double(ms.size());
  }
  return means;
}

void PassStats::clear() {
  pass_ms_.clear();
  frame_ms_.clear();
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
