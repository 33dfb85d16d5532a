// run_cli (app/cli.h): prints what parse_cli decided or runs the subcommand, and turns every
// exception into one "rolypoly: error: <message>" line and exit code 1.
#include "app/cli.h"

#include <cstdio>
#include <exception>
#include <string>
#include <variant>

#include "app/commands.h"
#include "app/interrupt.h"
#include "cl/context.h"
#include "cl/error.h"
#include "scene/gltf_loader.h"

namespace rp::app {
namespace {

int report(const std::string& message) {
  std::fflush(stdout);
  std::fprintf(stderr, "rolypoly: error: %s\n", message.c_str());
  return 1;
}

// An OpenCL failure after SIGINT / SIGTERM is most likely the signal's consequence: LLVM inside
// PoCL deletes its temporary files on the signal, so the kernel build in progress fails with
// "failed to build kernels/...cl". Name the interruption, with its exit code (130 / 143),
// instead. Other errors (a file that cannot be written) are reported as they are.
int report_opencl(const std::string& message) {
  if (!InterruptGuard::interrupted()) return report(message);
  std::fflush(stdout);
  std::fprintf(stderr, "rolypoly: error: interrupted by %s while starting up; nothing was "
               "written\n", interrupt_signal_name());
  return interrupted_exit_code();
}

int execute(const ParsedCommand& command) {
  switch (command.kind) {
    case ParsedCommand::Kind::kDevices: return devices_command();
    case ParsedCommand::Kind::kRender: return render_command(command.common, command.render);
    case ParsedCommand::Kind::kRun: return run_command(command.common, command.run);
    case ParsedCommand::Kind::kBench: return bench_command(command.common, command.bench);
    case ParsedCommand::Kind::kExport: return export_command(command.common, command.exporting);
  }
  return report("unknown subcommand kind");
}

}  // namespace

int run_cli(int argc, char** argv) {
  const CliParse parsed = parse_cli(argc, argv);
  if (const CliExit* done = std::get_if<CliExit>(&parsed)) {
    std::FILE* stream = done->exit_code == 0 ? stdout : stderr;
    std::fputs(done->message.c_str(), stream);
    std::fflush(stream);
    return done->exit_code;
  }
  try {
    rp::cl::ensure_pocl_cache_dir();  // before the first OpenCL call
    return execute(std::get<ParsedCommand>(parsed));
  } catch (const ::cl::Error& e) {
    // An OpenCL call that the code did not wrap in an rp::cl::Error.
    return report_opencl(std::string("OpenCL call ") + e.what() + " failed with " +
                         rp::cl::error_name(e.err()));
  } catch (const rp::cl::Error& e) {
    return report_opencl(e.what());
  } catch (const scene::SceneFileError& e) {
    report(e.what());
    return 2;  // a bad input file is a usage error, like a bad option
  } catch (const std::exception& e) {
    return report(e.what());
  }
}

}  // namespace rp::app
