#include "app/host_memory.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <sys/resource.h>

namespace rp::app {
namespace {

// A "Name:   N kB" line of a /proc file, in bytes; 0 when absent.
uint64_t proc_kib(const char* file, const char* name) {
  std::FILE* f = std::fopen(file, "re");
  if (f == nullptr) return 0;
  char line[256];
  uint64_t value = 0;
  const size_t n = std::strlen(name);
  while (std::fgets(line, sizeof line, f) != nullptr) {
    if (std::strncmp(line, name, n) == 0 && line[n] == ':') {
      value = std::strtoull(line + n + 1, nullptr, 10) * 1024;
      break;
    }
  }
  std::fclose(f);
  return value;
}

// The soft limit `resource` in bytes, 0 when unlimited.
uint64_t soft_limit(int resource) {
  rlimit limit{};
  if (::getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return 0;
  return uint64_t(limit.rlim_cur);
}

std::string gib(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(uint64_t(1) << 30));
  return text;
}

}  // namespace

HostMemory host_memory() {
  HostMemory m;
  if (const uint64_t available = proc_kib("/proc/meminfo", "MemAvailable"); available > 0) {
    m.available_bytes = available;
    m.source = "the host has " + gib(available) + " available";
  }
  // What the process may still map under its own limits.
  const struct {
    int resource;
    const char* status_line;
    const char* name;
  } limits[] = {{RLIMIT_AS, "VmSize", "ulimit -v"}, {RLIMIT_DATA, "VmData", "ulimit -d"}};
  for (const auto& l : limits) {
    const uint64_t limit = soft_limit(l.resource);
    if (limit == 0) continue;
    const uint64_t used = proc_kib("/proc/self/status", l.status_line);
    const uint64_t left = limit > used ? limit - used : 0;
    if (m.available_bytes == 0 || left < m.available_bytes) {
      m.available_bytes = left;
      m.source = "the process may take " + gib(left) + " more (" + l.name + " " +
                 std::to_string(limit >> 10) + ")";
    }
  }
  return m;
}

void check_pathtrace_memory(uint32_t width, uint32_t height, const HostMemory& memory) {
  const uint64_t need = uint64_t(width) * height * kPathTraceBytesPerPixel;
  if (memory.available_bytes == 0 || need <= memory.available_bytes) return;
  const auto side =
      uint64_t(std::sqrt(double(memory.available_bytes) / double(kPathTraceBytesPerPixel)));
  std::string message = "--quality pathtraced at " + std::to_string(width) + "x" +
                        std::to_string(height) + " needs " + gib(need) + " of host memory (" +
                        std::to_string(kPathTraceBytesPerPixel) + " bytes per pixel), " +
                        memory.source;
  if (side == 0)
    message += "; not even a 1x1 image fits";
  else
    message += "; the largest square size that fits is about " + std::to_string(side) +
               " (--size " + std::to_string(side) + ")";
  throw std::runtime_error(message);
}

std::string memory_limit_note() {
  const uint64_t as = soft_limit(RLIMIT_AS), data = soft_limit(RLIMIT_DATA);
  if (as == 0 && data == 0) return "";
  const bool by_as = as != 0 && (data == 0 || as <= data);
  return std::string(" (this process may use at most ") +
         std::to_string((by_as ? as : data) >> 20) + " MiB: " +
         (by_as ? "ulimit -v" : "ulimit -d") + "; a lack of memory may be the cause)";
}

}  // namespace rp::app
