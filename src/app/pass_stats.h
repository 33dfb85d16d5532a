// Per-pass timing statistics over many frames (median, 95th percentile, min, max in
// milliseconds), shared by
// `render` (summary line), `run` (window title) and `bench` (table and JSON).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "cl/profiler.h"

namespace rp::app {

struct TimeSummary {
  double median_ms = 0.0;  // middle value; mean of the two middle values for an even count
  double min_ms = 0.0;
  double max_ms = 0.0;
  // Nearest rank: the smallest sample at least 95 % of the samples do not exceed (the
  // ceil(0.95 n)-th smallest): how slow the slow frames of a held frame rate are.
  double p95_ms = 0.0;
};

// Summary of `samples` (must not be empty; throws std::invalid_argument otherwise).
TimeSummary summarize(std::vector<double> samples);

class PassStats {
 public:
  // One frame: device ms per pass (from rp::cl::Profiler::collect) and the frame's wall-clock ms.
  void add(const rp::cl::PassTimes& passes, double frame_ms);

  size_t frames() const { return frame_ms_.size(); }

  // Pass names in pipeline order (visibility, gbuffer, ..., tone_map); passes this file does
  // not know come after, alphabetically.
  std::vector<std::string> pass_names() const;

  // Summary of one pass over the frames it appeared in.
  TimeSummary pass(const std::string& name) const;
  TimeSummary frame() const;

  // Mean ms per pass over all frames (the window title's short-window average).
  std::map<std::string, double> pass_means() const;

  void clear();

 private:
  std::map<std::string, std::vector<double>> pass_ms_;
  std::vector<double> frame_ms_;
};

// One line "visibility 1.23 ms, gbuffer 0.45 ms, ..." of per-pass medians.
std::string median_line(const PassStats& stats);

// Rank of a pass in the frame's pipeline (passes::pass_name::kPipelineOrder); unknown names
// rank last.
int pipeline_rank(const std::string& pass);

}  // namespace rp::app
