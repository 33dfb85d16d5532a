// libFuzzer target: the command line's `bench --devices LIST` value (app::select_devices), which
// parse_cli only stores: the list is matched against the OpenCL devices when the bench runs.
// The rest of the command line is fuzzed by fuzz_cli (cli_fuzzer.cpp).
//
// The input is the LIST word (argv cannot hold NUL, so inputs with NUL are skipped). Findings:
// crashes, sanitizer reports, an exception other than rp::cl::Error, an error message that does
// not name --devices, and a result that is empty, holds a device twice or one not in the list,
// or is not the whole list for "all".
#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/src/bench_matrix.h"
#include "cl/error.h"

namespace {

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "fuzz_cli_devices: %s\n", what);
  std::abort();
}

rp::cl::DeviceInfo fake(int index, const char* platform, const char* name) {
  rp::cl::DeviceInfo d;
  d.index = index;
  d.platform_index = index / 2;
  d.platform_name = platform;
  d.name = name;
  return d;
}

// Two platforms, overlapping name fragments ("pocl" in both a platform and a device name).
const std::vector<rp::cl::DeviceInfo>& fake_devices() {
  static const std::vector<rp::cl::DeviceInfo> devices = {
      fake(0, "Portable Computing Language", "pthread-AMD EPYC 7B13"),
      fake(1, "Portable Computing Language", "cpu-pocl-debug"),
      fake(2, "NVIDIA CUDA", "NVIDIA H100 80GB HBM3"),
      fake(3, "Oclgrind", "Oclgrind Simulator"),
      fake(10, "Intel(R) OpenCL", "Intel(R) UHD Graphics 770"),
  };
  return devices;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string spec(reinterpret_cast<const char*>(data), size);
  if (spec.find('\0') != std::string::npos) return 0;
  const std::vector<rp::cl::DeviceInfo>& all = fake_devices();
  std::vector<rp::cl::DeviceInfo> chosen;
  try {
    chosen = rp::bench::select_devices(spec, all);
  } catch (const rp::cl::Error& e) {
    if (std::string(e.what()).find("--devices") == std::string::npos)
      finding("error message does not name --devices");
    return 0;
  }
  if (chosen.empty()) finding("no error, but no device chosen");
  for (size_t i = 0; i < chosen.size(); ++i) {
    const bool listed = std::any_of(all.begin(), all.end(), [&](const rp::cl::DeviceInfo& d) {
      return d.index == chosen[i].index && d.name == chosen[i].name;
    });
    if (!listed) finding("chose a device that is not in the list");
    for (size_t j = 0; j < i; ++j)
      if (chosen[j].index == chosen[i].index) finding("chose a device twice");
  }
  if (lower(spec) == "all" && chosen.size() != all.size()) finding("'all' did not choose every device");
  return 0;
}
