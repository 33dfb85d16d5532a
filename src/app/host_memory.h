// Host memory, checked before it is taken: the path tracer's image planes grow with the square
// of --size (16384^2 is about 50 GiB) and used to be allocated until std::bad_alloc. The limit
// is the smallest of what the system has available (MemAvailable) and what this process may
// still take (ulimit -v, ulimit -d).
#pragma once

#include <cstdint>
#include <string>

namespace rp::app {

struct HostMemory {
  uint64_t available_bytes = 0;  // 0 = unknown (no /proc, no limit): nothing is refused
  std::string source;            // "available on the host", "under the process's limit (ulimit -v)"
};

HostMemory host_memory();

// Bytes the path tracer takes per pixel: six float3 image planes (combined, direct, indirect,
// emission, albedo, specular: 72), the EXR of five of them in memory and read back to verify it
// (60 + 60), the 8-bit image and its PNG (4 + 4).
inline constexpr uint64_t kPathTraceBytesPerPixel = 72 + 60 + 60 + 4 + 4;

// Throws std::runtime_error before anything is allocated when a width x height path-traced frame
// needs more than `memory` holds: "--quality pathtraced at 16384x16384 needs 50.0 GiB of host
// memory (200 bytes per pixel), the host has 6.8 GiB available; the largest square size that
// fits is about 5800 (--size 5800)". Nothing when the memory is unknown.
void check_pathtrace_memory(uint32_t width, uint32_t height, const HostMemory& memory);

// " (this process may use at most N MiB: ulimit -v)" when a limit on the address space or the
// data segment is set, else "": added to failures that a lack of memory may explain (a driver
// that does not load, a kernel build, std::bad_alloc).
std::string memory_limit_note();

}  // namespace rp::app
