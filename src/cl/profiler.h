// The one place kernels are enqueued: each launch records a profiling event under its pass name,
// so the app, the tests and the bench all read the same per-pass times.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
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
// a frame's times cost no heap allocation (issue 8.6), as long as pass names stay within
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
  // execution time, CL_PROFILING_COMMAND_START..END). Clears the recorded events; the event
  // list keeps its capacity, so steady-state frames allocate nothing here.
  PassTimes collect();

  ::cl::CommandQueue& queue() { return queue_; }

 private:
  ::cl::CommandQueue queue_;
  std::vector<std::pair<std::string, ::cl::Event>> events_;
};

}  // namespace rp::cl
