// The `bench` subcommand's options, declared on the command line's CLI11 app, and the checks
// that run after a parse: which options go together (--devices or --device, --sizes or --size,
// what --accuracy, --quality-report, --compare-visibility and --quality pathtraced each run
// with), what a scene file cannot take, and the sky, render-scale and octree checks shared with
// render and run (app/cli_options.h). No device, file or terminal is touched.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "app/cli_options.h"
#include "bench/src/bench_options.h"

namespace rp::bench {

class BenchCli {
 public:
  // Adds the subcommand "bench" to `app`; its options write into `common` and `options`, which
  // must outlive this object.
  BenchCli(CLI::App& app, app::CommonOptions& common, BenchOptions& options);

  CLI::App* command() const { return command_; }

  // After a parse that chose "bench": "" when the options go together (and then `options` is
  // complete: size, voxel default of the octree, --accuracy's spp, the command line for the
  // JSON), else why not, for the usage message.
  std::string finish(int argc, const char* const* argv);

 private:
  app::CommonOptions& common_;
  BenchOptions& options_;
  app::SizeArgs size_;
  CLI::App* command_ = nullptr;
  CLI::Option* devices_ = nullptr;  // --devices
  CLI::Option* sizes_ = nullptr;    // --sizes
};

}  // namespace rp::bench
