// The work `rolypoly bench` does, one entry per mode. Each returns the process exit code and
// throws on errors, as the app's commands do (app/commands.h).
#pragma once

#include <nlohmann/json_fwd.hpp>

#include "app/commands.h"
#include "app/scene_input.h"
#include "bench/src/bench_options.h"

namespace rp::bench {

// Timing tables per device and run, optional JSON, chart and Markdown. Exit code 0 when at
// least one device completed, 1 when every device was skipped.
int bench_command(const app::CommonOptions& common, const BenchOptions& options);
// The files a bench writes: `given`, with out/bench.json and out/bench.svg for --json and
// --chart when a device sweep (--devices) named none (bench/src/bench_command.cpp).
BenchOptions with_default_outputs(const BenchOptions& given);
// bench --accuracy: the real-time modes against the path-traced truth
// (bench/src/accuracy_report.h); exit 3 when a threshold (--max-indirect-l1 ...
// --require-wall-hue) is missed, 130 when interrupted.
int accuracy_command(const app::CommonOptions& common, const BenchOptions& options);
// bench --quality pathtraced: seconds and Mrays/s per path-traced frame, optional JSON (schema
// "rolypoly-pathtrace-bench/1"). file: a loaded scene file instead of the demo, with
// scene_file: its facts for the JSON ("scene_file").
int pathtrace_bench_command(const app::CommonOptions& common, const BenchOptions& options,
                            const app::FileScene* file = nullptr,
                            const nlohmann::ordered_json* scene_file = nullptr);

}  // namespace rp::bench
