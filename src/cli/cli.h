// Command line of `rolypoly` (CLI11), in two steps: parse_cli (src/cli/cli_parse.cpp) builds the
// options, parses and runs every usage check without touching OpenCL, files or the terminal;
// run_cli (src/cli/cli.cpp) prints what parse_cli says or dispatches to the subcommand, and
// turns every error into one message on stderr. The split lets fuzz/ fuzz the whole command
// line without opening devices or rendering.
//
// Exit codes: 0 success; 1 runtime error ("rolypoly: error: <message>": no OpenCL platform,
// unknown device, kernel build failure with its build log, missing/corrupt texture, no display,
// unwritable output, a size, --voxels or scene the device's or the host's memory cannot hold,
// an allocation that fails, named by what it was for); 2 usage error
// (unknown option or subcommand, bad value or an empty one: "rolypoly: error: <CLI11's
// message>"; outputs that collide, found by run_cli before any work); 128 + N ended by signal N
// (SIGHUP 129, SIGINT 130, SIGQUIT 131, SIGPIPE 141, SIGTERM 143: app/interrupt.h; checked
// between frames, every written file is complete, `run --record` writes its log first).
#pragma once

#include <string>
#include <variant>

#include "app/commands.h"
#include "bench/src/bench_options.h"

namespace rp::cli {

// A command line that parsed: the subcommand and every option's value, checked and resolved
// (--size/--width/--height into `size`, --view/--level/--dir into common.view). Only the
// options struct of `kind` is meaningful; the others keep their defaults.
struct ParsedCommand {
  enum class Kind { kDevices, kRender, kRun, kBench, kExport };
  Kind kind = Kind::kDevices;
  app::CommonOptions common;
  app::RenderOptions render;  // frames_given set from the command line
  app::RunOptions run;
  bench::BenchOptions bench;    // command_line: "rolypoly" and the arguments joined by spaces
  app::ExportOptions exporting;
};

// A command line that ends before running anything: --help (exit code 0, the help text for
// stdout) or a usage error (exit code 2, "rolypoly...: <why>\nRun with --help for more
// information.\n" for stderr).
struct CliExit {
  int exit_code = 2;
  std::string message;  // ends with '\n'
};

using CliParse = std::variant<ParsedCommand, CliExit>;

// Builds the options, parses argv (argv[0] is the program name) and runs every usage check:
// unknown subcommand, CLI11's errors and validators, --level/--dir without --view voxels, bench
// option conflicts, --spp without --quality pathtraced (or bench --accuracy), --bounces 0
// without it, and what that mode cannot do; --env / --sky combinations (and on the demo's
// --accuracy).
// No OpenCL, no file, no output, no global state: the same argv always gives the same result. Never throws for any argv (only std::bad_alloc can escape).
CliParse parse_cli(int argc, const char* const* argv);

// parse_cli, then the PoCL cache folder and the subcommand; returns the process exit code.
int run_cli(int argc, char** argv);

}  // namespace rp::cli
