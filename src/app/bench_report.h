// Bench output: the human-readable timing table and the JSON document (schema
// "rolypoly-bench/1", documented in README.md; keep it stable, add a new schema id to change it).
#pragma once

#include <cstdint>
#include <string>

#include "app/pass_stats.h"

namespace rp::app {

struct BenchDevice {
  std::string name;
  std::string type;      // "GPU", "CPU", ...
  std::string platform;
  uint32_t compute_units = 0;
};

inline constexpr const char* kBenchSchema = "rolypoly-bench/1";

// {"schema", "device": {name, type, platform, compute_units}, "size": [w, h], "frames": N,
//  "passes": {"<pass>": {median_ms, min_ms, max_ms}}, "frame": {median_ms, min_ms, max_ms}}
// as text (2-space indent, newline at the end). `stats` must hold at least one frame.
std::string bench_json(const BenchDevice& device, uint32_t width, uint32_t height,
                       const PassStats& stats);

// Table of median/min/max ms per pass in pipeline order, then the frame line.
std::string timing_table(const PassStats& stats);

// One line "visibility 1.23 ms, gbuffer 0.45 ms, ..." of per-pass medians.
std::string median_line(const PassStats& stats);

}  // namespace rp::app
