// The one place kernels are enqueued: each launch records a profiling event under its pass name,
// so the app, the tests and the bench all read the same per-pass times.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include <CL/opencl.hpp>

namespace rp::cl {

// Smallest multiple of `local` that is >= n (OpenCL 1.2 needs uniform work-groups).
inline size_t round_up(size_t n, size_t local) { return (n + local - 1) / local * local; }

// Milliseconds per pass name for one frame (sum over the pass's launches).
using PassTimes = std::map<std::string, double>;

class Profiler {
 public:
  explicit Profiler(::cl::CommandQueue queue) : queue_(std::move(queue)) {}

  // Enqueues `kernel` on the queue; `local` may be ::cl::NullRange. Throws rp::cl::Error naming
  // the pass and kernel when the launch fails.
  void enqueue(const std::string& pass, const ::cl::Kernel& kernel, const ::cl::NDRange& global,
               const ::cl::NDRange& local = ::cl::NullRange);

  // Records an already enqueued command (a buffer write or copy) under `pass`.
  void record(const std::string& pass, const ::cl::Event& event);

  // Waits for everything recorded since the last call and returns the per-pass times (device
  // execution time, CL_PROFILING_COMMAND_START..END). Clears the recorded events.
  PassTimes collect();

  ::cl::CommandQueue& queue() { return queue_; }

 private:
  ::cl::CommandQueue queue_;
  std::vector<std::pair<std::string, ::cl::Event>> events_;
};

}  // namespace rp::cl
