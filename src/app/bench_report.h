// Bench output: the human-readable timing tables and the JSON documents (schemas
// "rolypoly-bench/1" for one device and size, "rolypoly-bench/2" for the device x size x voxels
// matrix; both documented in README.md; keep them stable, add a new schema id to change one).
#pragma once

#include <cstdint>
#include <string>

#include "app/bench_matrix.h"
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

inline constexpr const char* kBenchMatrixSchema = "rolypoly-bench/2";

// The matrix as JSON text (schema "rolypoly-bench/2", layout in README.md: devices -> runs ->
// passes; 2-space indent, newline at the end).
std::string matrix_json(const BenchMatrix& matrix);
// Parses matrix_json's output back (round trip). Throws std::runtime_error for another schema
// and nlohmann::json's exceptions for malformed text or missing fields.
BenchMatrix parse_matrix_json(const std::string& text);

// For stdout: per device and run the per-pass median/min/max (and efficiency where measured),
// then a summary of frame medians, fps and the fitted scaling exponents.
std::string matrix_table(const BenchMatrix& matrix);
// Markdown summary (bench/results/*.md, README): one row per device and run with every pass's
// median ms, the frame median/min/max and fps; then the scaling exponents.
std::string matrix_markdown(const BenchMatrix& matrix);

// One line "visibility 1.23 ms, gbuffer 0.45 ms, ..." of per-pass medians.
std::string median_line(const PassStats& stats);

}  // namespace rp::app
