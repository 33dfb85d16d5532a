// The one place kernels are enqueued: each launch records a profiling event under its pass name,
// so the app, the tests and the bench all read the same per-pass times. On a device whose
// profiling timestamps cannot be trusted (Mesa rusticl returns zeros) the profiler times on the
// host instead: a finish after each launch, wall clock around it (Timing::kHost).
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <CL/opencl.hpp>

namespace rp::cl {

// Smallest multiple of `local` that is >= n (OpenCL 1.2 needs uniform work-groups).
inline size_t round_up(size_t n, size_t local) { return (n + local - 1) / local * local; }

// Milliseconds per pass name for one frame (sum over the pass's launches), in name order.
// The part of std::map<std::string, double>'s interface the app and tests use, stored inline:
// a frame's times cost no heap allocation, as long as pass names stay within
// std::string's short-string buffer (15 characters in libstdc++). At most kCapacity passes;
// one more throws std::length_error.
class PassTimes {
 public:
  using value_type = std::pair<std::string, double>;
  using iterator = value_type*;
  using const_iterator = const value_type*;
  static constexpr size_t kCapacity = 32;

  PassTimes() = default;
  // Like std::map's: {{"light", 3.0}, {"taa", 1.0}}; a repeated name keeps its first value.
  PassTimes(std::initializer_list<value_type> entries) {
    for (const value_type& e : entries)
      if (count(e.first) == 0) (*this)[e.first] = e.second;
  }

  // The pass's time, inserted as 0 when it is not there yet.
  double& operator[](std::string_view pass);
  // Throws std::out_of_range for a pass that is not there.
  double& at(std::string_view pass);
  double at(std::string_view pass) const;
  size_t count(std::string_view pass) const { return find(pass) != end() ? 1 : 0; }
  iterator find(std::string_view pass);
  const_iterator find(std::string_view pass) const;

  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  // Forgets the passes; their name strings keep their storage for the next frame.
  void clear() { size_ = 0; }
  iterator begin() { return entries_.data(); }
  iterator end() { return entries_.data() + size_; }
  const_iterator begin() const { return entries_.data(); }
  const_iterator end() const { return entries_.data() + size_; }

  friend bool operator==(const PassTimes& a, const PassTimes& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end());
  }

 private:
  std::array<value_type, kCapacity> entries_;
  size_t size_ = 0;
};

// How pass times are taken. kDevice: CL_PROFILING_COMMAND_START..END of each command's event
// (launches stay asynchronous). kHost: the queue is finished before and after every launch and
// the host's steady clock measured around it (launch overhead included, the device idles
// between passes): for devices whose timestamps are missing, zero or not monotonic.
enum class Timing { kDevice, kHost };

// "device" or "host" (tables and JSON).
const char* timing_name(Timing timing);

// The four profiling timestamps of one command (nanoseconds, CL_PROFILING_COMMAND_*).
struct EventTimes {
  uint64_t queued = 0, submit = 0, start = 0, end = 0;
};

// Whether the timestamps of commands run one after another on an in-order queue can be used:
// every start and end non-zero, end >= start, each command taking at least `min_ns` (the
// commands must be big enough that a real clock sees them take time), and each command
// starting no earlier than the previous one ended. Empty: false.
bool timestamps_usable(const std::vector<EventTimes>& in_order, uint64_t min_ns);

class Profiler {
 public:
  explicit Profiler(::cl::CommandQueue queue, Timing timing = Timing::kDevice)
      : queue_(std::move(queue)), timing_(timing) {}

  // Enqueues `kernel` on the queue; `local` may be ::cl::NullRange. Throws rp::cl::Error naming
  // the pass and kernel when the launch fails.
  void enqueue(const std::string& pass, const ::cl::Kernel& kernel, const ::cl::NDRange& global,
               const ::cl::NDRange& local = ::cl::NullRange);

  // Records an already enqueued command (a buffer write or copy) under `pass`. Host timing:
  // waits for it and counts the wait (a lower bound: an implementation that copies during the
  // enqueue shows ~0).
  void record(const std::string& pass, const ::cl::Event& event);

  // Waits for everything recorded since the last call and returns the per-pass times (device
  // execution time, CL_PROFILING_COMMAND_START..END, or host wall clock with Timing::kHost).
  // Clears the recorded events; the event list keeps its capacity, so steady-state frames
  // allocate nothing here.
  PassTimes collect();

  ::cl::CommandQueue& queue() { return queue_; }
  Timing timing() const { return timing_; }

 private:
  using Clock = std::chrono::steady_clock;
  ::cl::CommandQueue queue_;
  Timing timing_ = Timing::kDevice;
  std::vector<std::pair<std::string, ::cl::Event>> events_;
  PassTimes host_times_;  // Timing::kHost: accumulated since the last collect()
};

}  // namespace rp::cl
