// Bench output: the human-readable timing tables and the JSON document (schema
// "rolypoly-bench/3" for the device x size x voxels matrix, documented in README.md; keep it
// stable, add a new schema id to change it). /3 added the timing method, the
// bandwidth levels and the per-pass footprint and ceiling, and measures bandwidth_fraction
// against the pass's cache-aware ceiling; a fraction the model would put above 1 is null.
#pragma once

#include <cstdint>
#include <string>

#include "app/pass_stats.h"
#include "bench/src/bench_matrix.h"

namespace rp::bench {

inline constexpr const char* kBenchMatrixSchema = "rolypoly-bench/3";
// The previous layout, still read by parse_matrix_json (its fractions are of the DRAM stream).
inline constexpr const char* kBenchMatrixSchemaV2 = "rolypoly-bench/2";

// The matrix as JSON text (schema "rolypoly-bench/3", layout in README.md: devices -> runs ->
// passes; 2-space indent, newline at the end).
std::string matrix_json(const BenchMatrix& matrix);
// Parses matrix_json's output back (round trip; /2 documents too, missing fields at their
// defaults). Throws std::runtime_error for another schema
// and nlohmann::json's exceptions for malformed text or missing fields.
BenchMatrix parse_matrix_json(const std::string& text);

// For stdout: per device and run the per-pass median/min/max (and efficiency where measured),
// then a summary of frame medians, fps and the fitted scaling exponents.
std::string matrix_table(const BenchMatrix& matrix);
// Markdown summary (bench/results/*.md, README): one row per device and run with every pass's
// median ms, the frame median/min/max and fps; then the scaling exponents.
std::string matrix_markdown(const BenchMatrix& matrix);

}  // namespace rp::bench
