#include "cl/context.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "cl/error.h"

namespace rp::cl {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back()))))
    s.pop_back();
  return s;
}

std::string type_name(cl_device_type t) {
  if (t & CL_DEVICE_TYPE_GPU) return "GPU";
  if (t & CL_DEVICE_TYPE_CPU) return "CPU";
  if (t & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  if (t & CL_DEVICE_TYPE_CUSTOM) return "custom";
  return "other";
}

std::string device_table(const std::vector<DeviceInfo>& devices) {
  std::ostringstream out;
  for (const DeviceInfo& d : devices)
    out << "  [" << d.index << "] " << d.name << " (" << d.type << ", " << d.platform_name << ")\n";
  return out.str();
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
  std::vector<::cl::Platform> platforms;
  try {
    ::cl::Platform::get(&platforms);
  } catch (const ::cl::Error&) {
    platforms.clear();  // the ICD loader reports "no platform" as an error
  }
  if (platforms.empty())
    throw Error(
        "no OpenCL platform found. Install an OpenCL driver, e.g. the CPU one: "
        "apt-get install pocl-opencl-icd (and check /etc/OpenCL/vendors)");
  std::vector<DeviceInfo> out;
  for (size_t p = 0; p < platforms.size(); ++p) {
    std::vector<::cl::Device> devices;
    try {
      platforms[p].getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const ::cl::Error&) {
      continue;  // a platform without devices reports CL_DEVICE_NOT_FOUND
    }
    for (const ::cl::Device& dev : devices) {
      DeviceInfo d;
      d.index = static_cast<int>(out.size());
      d.platform_index = static_cast<int>(p);
      d.platform_name = trim(platforms[p].getInfo<CL_PLATFORM_NAME>());
      d.name = trim(dev.getInfo<CL_DEVICE_NAME>());
      d.vendor = trim(dev.getInfo<CL_DEVICE_VENDOR>());
      cl_device_type t = dev.getInfo<CL_DEVICE_TYPE>();
      d.type = type_name(t);
      d.is_gpu = (t & CL_DEVICE_TYPE_GPU) != 0;
      d.is_cpu = (t & CL_DEVICE_TYPE_CPU) != 0;
      d.compute_units = dev.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
      d.global_mem_bytes = dev.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
      d.max_alloc_bytes = dev.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
      d.local_mem_bytes = dev.getInfo<CL_DEVICE_LOCAL_MEM_SIZE>();
      d.max_work_group_size = dev.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
      d.native_float_width = dev.getInfo<CL_DEVICE_NATIVE_VECTOR_WIDTH_FLOAT>();
      d.version = trim(dev.getInfo<CL_DEVICE_VERSION>());
      d.c_version = trim(dev.getInfo<CL_DEVICE_OPENCL_C_VERSION>());
      d.device = dev;
      out.push_back(std::move(d));
    }
  }
  remove_pocl_probe_files();  // PoCL initialised its devices above
  if (out.empty()) {
    // PoCL also reports no device when its cache folder is unusable (ensure_pocl_cache_dir
    // falls back to a temporary one, but that can fail too).
    const char* cache = std::getenv("POCL_CACHE_DIR");
    throw Error("OpenCL platforms were found but none has a device. Install a driver, e.g. "
                "apt-get install pocl-opencl-icd; with PoCL, check that its kernel cache "
                "folder (POCL_CACHE_DIR=" + std::string(cache ? cache : "") +
                ") can be written");
  }
  return out;
}

int cpu_span_lanes(const DeviceInfo& info) { return info.native_float_width >= 16 ? 16 : 8; }

DeviceInfo choose_device(const std::string& spec) {
  std::vector<DeviceInfo> devices = list_devices();
  if (spec.empty()) {
    for (const DeviceInfo& d : devices)
      if (d.is_gpu) return d;
    for (const DeviceInfo& d : devices)
      if (d.is_cpu) return d;
    return devices.front();
  }
  bool numeric = std::all_of(spec.begin(), spec.end(),
                             [](unsigned char c) { return std::isdigit(c) != 0; });
  if (numeric) {
    // from_chars, not std::stoul: an index beyond size_t is just another missing device
    // (stoul threw std::out_of_range, whose message is "stoul").
    size_t index = 0;
    const auto [end, ec] = std::from_chars(spec.data(), spec.data() + spec.size(), index);
    if (ec == std::errc() && end == spec.data() + spec.size() && index < devices.size())
      return devices[index];
    throw Error("no OpenCL device with index " + spec + "; the devices are:\n" +
                device_table(devices));
  }
  std::string needle = lower(spec);
  for (const DeviceInfo& d : devices)
    if (lower(d.name).find(needle) != std::string::npos ||
        lower(d.platform_name).find(needle) != std::string::npos)
      return d;
  throw Error("no OpenCL device matches '" + spec + "'; the devices are:\n" + device_table(devices));
}

Context Context::create(const std::string& device_spec) {
  return create(choose_device(device_spec));
}

Context Context::create(const DeviceInfo& info) {
  Context c;
  c.info = info;
  try {
    c.context = ::cl::Context(info.device);
    c.queue = ::cl::CommandQueue(c.context, info.device, CL_QUEUE_PROFILING_ENABLE);
  } catch (const ::cl::Error& e) {
    throw Error("cannot create an OpenCL context and queue on '" + info.name + "': " +
                e.what() + " (" + error_name(e.err()) + ")");
  }
  const char* forced = std::getenv("ROLYPOLY_TIMING");
  if (forced != nullptr && std::string(forced) == "host")
    c.timing = Timing::kHost;
  else if (forced != nullptr && std::string(forced) == "device")
    c.timing = Timing::kDevice;
  else
    c.timing = detect_timing(c.context, c.queue);
  return c;
}

Timing detect_timing(const ::cl::Context& context, const ::cl::CommandQueue& queue) {
  constexpr size_t kBytes = 4u << 20;
  try {
    ::cl::Buffer buffer(context, CL_MEM_READ_WRITE, kBytes);
    std::vector<::cl::Event> events(2);
    for (size_t i = 0; i < events.size(); ++i)
      queue.enqueueFillBuffer(buffer, cl_float(i), 0, kBytes, nullptr, &events[i]);
    queue.finish();
    std::vector<EventTimes> times;
    for (const ::cl::Event& e : events)
      times.push_back({e.getProfilingInfo<CL_PROFILING_COMMAND_QUEUED>(),
                       e.getProfilingInfo<CL_PROFILING_COMMAND_SUBMIT>(),
                       e.getProfilingInfo<CL_PROFILING_COMMAND_START>(),
                       e.getProfilingInfo<CL_PROFILING_COMMAND_END>()});
    return timestamps_usable(times, 100) ? Timing::kDevice : Timing::kHost;
  } catch (const ::cl::Error&) {
    return Timing::kHost;
  }
}

}  // namespace rp::cl
