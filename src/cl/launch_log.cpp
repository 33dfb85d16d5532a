#include "cl/launch_log.h"

#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <set>
#include <string>

#include "cl/kernel_args.h"

namespace rp::cl {
namespace {

struct LaunchLog {
  const char* path = std::getenv("ROLYPOLY_KERNEL_LOG");  // read once, before any launch
  std::mutex mutex;
  std::set<std::string> seen;
};

LaunchLog& launch_log() {
  static LaunchLog log;
  return log;
}

}  // namespace

void note_kernel_launch(const ::cl::Kernel& kernel) noexcept {
  LaunchLog& log = launch_log();
  if (log.path == nullptr || log.path[0] == '\0') return;
  try {
    const std::string name = kernel_name(kernel);
    const std::lock_guard<std::mutex> lock(log.mutex);
    if (!log.seen.insert(name).second) return;
    // Append mode: several processes (a test and the binary it runs) may share one file.
    if (std::FILE* f = std::fopen(log.path, "a")) {
      std::fprintf(f, "%s\n", name.c_str());
      std::fclose(f);
    }
  } catch (...) {
    // A failed query or allocation leaves the kernel out of the log; the launch goes on.
  }
}

}  // namespace rp::cl
