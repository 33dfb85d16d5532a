#include <cstdio>

#include "app/commands.h"
#include "cl/context.h"

namespace rp::app {

int devices_command() {
  std::vector<rp::cl::DeviceInfo> devices = rp::cl::list_devices();
  std::printf("OpenCL devices (choose one with --device <index> or part of its name):\n");
  int platform = -1;
  for (const rp::cl::DeviceInfo& d : devices) {
    if (d.platform_index != platform) {
      platform = d.platform_index;
      std::printf("platform %d: %s\n", platform, d.platform_name.c_str());
    }
    std::printf("  [%d] %s\n", d.index, d.name.c_str());
    std::printf("      type %s, %u compute units, global memory %llu MiB, local memory %llu KiB\n",
                d.type.c_str(), d.compute_units,
                static_cast<unsigned long long>(d.global_mem_bytes >> 20),
                static_cast<unsigned long long>(d.local_mem_bytes >> 10));
    std::printf("      %s, %s\n", d.version.c_str(), d.c_version.c_str());
  }
  return 0;
}

}  // namespace rp::app
