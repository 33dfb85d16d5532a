#include "cl/profiler.h"

#include "cl/error.h"

namespace rp::cl {

void Profiler::enqueue(const std::string& pass, const ::cl::Kernel& kernel,
                       const ::cl::NDRange& global, const ::cl::NDRange& local) {
  ::cl::Event event;
  try {
    queue_.enqueueNDRangeKernel(kernel, ::cl::NullRange, global, local, nullptr, &event);
  } catch (const ::cl::Error& e) {
    std::string name = kernel.getInfo<CL_KERNEL_FUNCTION_NAME>();
    while (!name.empty() && name.back() == '\0') name.pop_back();
    throw Error("pass '" + pass + "': launching kernel '" + name + "' failed: " +
                error_name(e.err()));
  }
  events_.emplace_back(pass, std::move(event));
}

void Profiler::record(const std::string& pass, const ::cl::Event& event) {
  events_.emplace_back(pass, event);
}

PassTimes Profiler::collect() {
  PassTimes times;
  if (events_.empty()) return times;
  events_.back().second.wait();
  queue_.finish();
  for (auto& [pass, event] : events_) {
    cl_ulong start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
    cl_ulong end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
    times[pass] += static_cast<double>(end - start) * 1e-6;
  }
  events_.clear();
  return times;
}

}  // namespace rp::cl
