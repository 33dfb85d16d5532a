// `rolypoly bench --quality pathtraced --scene FILE`: the path tracer's seconds and Mrays/s per
// frame on a scene file's still frame (the demo's counterpart is pathtrace_bench_command,
// src/app/pathtrace_command.cpp), with the same table and JSON (schema
// "rolypoly-pathtrace-bench/1") plus "scene_file" (bench/src/scene_file_facts.h).
#pragma once

#include "app/commands.h"
#include "app/scene_input.h"
#include "bench/src/bench_matrix.h"

namespace rp::app {

int pathtrace_file_bench_command(const CommonOptions& common, const BenchOptions& options,
                                 const FileScene& scene, const SceneFileFacts& facts);

}  // namespace rp::app
