// run_cli (cli/cli.h): prints what parse_cli decided or runs the subcommand, and turns every
// exception into one "rolypoly: error: <message>" line and exit code 1.
#include "cli/cli.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <string_view>
#include <variant>

#include <fcntl.h>
#include <unistd.h>

#include "app/commands.h"
#include "app/host_memory.h"
#include "app/interrupt.h"
#include "app/printable.h"
#include "bench/src/bench_commands.h"
#include "cl/context.h"
#include "cl/error.h"
#include "cli/output_collisions.h"
#include "scene/asset_error.h"
#include "scene/gltf_loader.h"
#include "scene/input.h"

namespace rp::cli {
namespace {

using app::interrupt_signal_name;
using app::interrupted_exit_code;
using app::Interrupted;
using app::InterruptGuard;
using app::memory_limit_note;
using app::printable;

int report(const std::string& message) {
  std::fflush(stdout);
  std::fprintf(stderr, "rolypoly: error: %s\n", message.c_str());
  return 1;
}

// An error while a signal is pending is most likely the signal's consequence: LLVM inside PoCL
// deletes its temporary files on the signal, so the kernel build in progress fails with
// "failed to build kernels/...cl"; a wait for input stops (Interrupted). Name the interruption,
// with its exit code (128 + signal), instead: "interrupted by SIGHUP <while_doing>".
int report_interruption(const char* while_doing) {
  std::fflush(stdout);
  std::fprintf(stderr, "rolypoly: error: interrupted by %s %s\n", interrupt_signal_name(),
               while_doing);
  return interrupted_exit_code();
}

// An OpenCL failure: interrupted, or perhaps for lack of memory under a process limit (the ICD
// loader then finds "no OpenCL platform", a kernel build fails): say so.
int report_opencl(const std::string& message) {
  if (InterruptGuard::interrupted()) return report_interruption("while starting up; nothing was written");
  return report(message + memory_limit_note());
}

const char* command_name(ParsedCommand::Kind kind) {
  switch (kind) {
    case ParsedCommand::Kind::kDevices: return "devices";
    case ParsedCommand::Kind::kRender: return "render";
    case ParsedCommand::Kind::kRun: return "run";
    case ParsedCommand::Kind::kBench: return "bench";
    case ParsedCommand::Kind::kExport: return "export";
  }
  return "";
}

int execute(const ParsedCommand& command) {
  switch (command.kind) {
    case ParsedCommand::Kind::kDevices: return app::devices_command();
    case ParsedCommand::Kind::kRender: return app::render_command(command.common, command.render);
    case ParsedCommand::Kind::kRun: return app::run_command(command.common, command.run);
    case ParsedCommand::Kind::kBench: return bench::bench_command(command.common, command.bench);
    case ParsedCommand::Kind::kExport:
      return app::export_command(command.common, command.exporting);
  }
  return report("unknown subcommand kind");
}

int execute_reporting(const ParsedCommand& command) {
  try {
    rp::cl::ensure_pocl_cache_dir();  // before the first OpenCL call
    return execute(command);
  } catch (const Interrupted& e) {
    return report_interruption(e.what());
  } catch (const ::cl::Error& e) {
    // An OpenCL call that the code did not wrap in an rp::cl::Error.
    return report_opencl(std::string("OpenCL call ") + e.what() + " failed with " +
                         rp::cl::error_name(e.err()));
  } catch (const rp::cl::Error& e) {
    return report_opencl(e.what());
  } catch (const scene::SceneFileError& e) {
    report(e.what());
    return 2;  // a bad input file is a usage error, like a bad option
  } catch (const scene::AssetError& e) {
    return report(e.what());  // names the file and the system's reason (scene/textures.cpp)
  } catch (const scene::InputLogError& e) {
    return report(printable(e.what()));  // it quotes the log's words
  } catch (const std::bad_alloc&) {
    if (InterruptGuard::interrupted()) return report_interruption("while allocating memory; every file written is complete");
    return report("ran out of host memory" + memory_limit_note());
  } catch (const std::exception& e) {
    if (InterruptGuard::interrupted()) return report_interruption("during the work; every file written is complete");
    return report(e.what());
  }
}

}  // namespace

int run_cli(int argc, char** argv) {
  // First, so that no signal finds a disposition inherited from the launcher.
  app::install_signal_handlers();
  const CliParse parsed = parse_cli(argc, argv);
  if (const CliExit* done = std::get_if<CliExit>(&parsed)) {
    std::FILE* stream = done->exit_code == 0 ? stdout : stderr;
    std::fputs(done->message.c_str(), stream);
    std::fflush(stream);
    return done->exit_code;
  }
  const ParsedCommand& command = std::get<ParsedCommand>(parsed);
  // Before any work: two outputs that are one file, or an output that is an input.
  if (const std::string why = find_output_collision(command); !why.empty()) {
    std::fprintf(stderr, "rolypoly %s: %s\nRun with --help for more information.\n",
                 command_name(command.kind), printable(why).c_str());
    return 2;
  }
  const int code = execute_reporting(command);
  // A signal that arrived after the last check (the bench's tables printed into a pipe that
  // closed, an export) still ends the run as a signal does: with its exit code, after the
  // files, all complete.
  if (InterruptGuard::interrupted() && code != interrupted_exit_code()) {
    std::fflush(stdout);
    std::fprintf(stderr, "rolypoly: error: interrupted by %s at the end; every file written is "
                 "complete\n", interrupt_signal_name());
    return interrupted_exit_code();
  }
  return code;
}

}  // namespace rp::cli
