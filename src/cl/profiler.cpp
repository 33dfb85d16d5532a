#include "cl/profiler.h"

#include <stdexcept>
#include <thread>

#include "cl/error.h"
#include "cl/kernel_args.h"
#include "cl/launch_log.h"

namespace rp::cl {

PassTimes::iterator PassTimes::find(std::string_view pass) {
  iterator it = std::lower_bound(begin(), end(), pass,
                                 [](const value_type& e, std::string_view p) { return e.first < p; });
  return it != end() && it->first == pass ? it : end();
}

PassTimes::const_iterator PassTimes::find(std::string_view pass) const {
  return const_cast<PassTimes*>(this)->find(pass);
}

double& PassTimes::operator[](std::string_view pass) {
  iterator it = std::lower_bound(begin(), end(), pass,
                                 [](const value_type& e, std::string_view p) { return e.first < p; });
  if (it != end() && it->first == pass) return it->second;
  if (size_ == kCapacity)
    throw std::length_error("PassTimes: more than " + std::to_string(kCapacity) +
                            " passes in one frame (adding '" + std::string(pass) + "')");
  // Shift the tail one slot up (moves: the slot past the end is reused, its string storage too).
  std::move_backward(it, end(), end() + 1);
  ++size_;
  it->first.assign(pass.data(), pass.size());
  it->second = 0.0;
  return it->second;
}

double& PassTimes::at(std::string_view pass) {
  iterator it = find(pass);
  if (it == end()) throw std::out_of_range("PassTimes: no pass '" + std::string(pass) + "'");
  return it->second;
}

double PassTimes::at(std::string_view pass) const { return const_cast<PassTimes*>(this)->at(pass); }

namespace {

// Waits until every command enqueued so far on `queue` has finished, sleeping between polls of
// a marker's status (host timing is therefore good to about 1 ms on long passes) instead of
// clFinish, so the waiting thread stays idle whatever the implementation's wait does. (Under
// rusticl, gdb caught the waiting thread in clFinish's timed condition-variable loop while
// top showed it near a full core; perf later showed most of that thread's CPU was its own
// clBuildProgram work, so how much clFinish itself costs there is not established.)
void wait_idle(::cl::CommandQueue& queue) {
  ::cl::Event marker;
  queue.enqueueMarkerWithWaitList(nullptr, &marker);
  queue.flush();
  for (int polls = 0;; ++polls) {
    const cl_int status = marker.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>();
    if (status == CL_COMPLETE) return;
    if (status < 0) {  // the marker (or a command before it) failed: let finish report it
      queue.finish();
      return;
    }
    // A few immediate polls (a pass that just finished), then naps growing from 20 us to 1 ms
    // (a status query is not free on every implementation: rusticl's takes its queue's lock).
    if (polls >= 8)
      std::this_thread::sleep_for(std::chrono::microseconds(std::min(1000, 20 << std::min(polls - 8, 6))));
  }
}

}  // namespace

const char* timing_name(Timing timing) { return timing == Timing::kHost ? "host" : "device"; }

bool timestamps_usable(const std::vector<EventTimes>& in_order, uint64_t min_ns) {
  if (in_order.empty()) return false;
  uint64_t previous_end = 0;
  for (const EventTimes& t : in_order) {
    if (t.start == 0 || t.end == 0 || t.end < t.start || t.end - t.start < min_ns) return false;
    if (t.start < previous_end) return false;
    previous_end = t.end;
  }
  return true;
}

void Profiler::enqueue(const std::string& pass, const ::cl::Kernel& kernel,
                       const ::cl::NDRange& global, const ::cl::NDRange& local) {
  note_kernel_launch(kernel);
  ::cl::Event event;
  const bool host = timing_ == Timing::kHost;
  Clock::time_point t0;
  if (host) {
    wait_idle(queue_);  // earlier work (uploads not recorded) is not this pass's
    t0 = Clock::now();
  }
  try {
    queue_.enqueueNDRangeKernel(kernel, ::cl::NullRange, global, local, nullptr,
                                host ? nullptr : &event);
  } catch (const ::cl::Error& e) {
    throw Error("pass '" + pass + "': launching kernel '" + kernel_name(kernel) + "' failed: " +
                error_name(e.err()));
  }
  if (host) {
    wait_idle(queue_);
    host_times_[pass] += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    return;
  }
  events_.emplace_back(pass, std::move(event));
}

void Profiler::record(const std::string& pass, const ::cl::Event& event) {
  if (timing_ == Timing::kHost) {
    const Clock::time_point t0 = Clock::now();
    wait_idle(queue_);  // in order: the recorded command is done when the queue is
    host_times_[pass] += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    return;
  }
  events_.emplace_back(pass, event);
}

PassTimes Profiler::collect() {
  if (timing_ == Timing::kHost) {
    wait_idle(queue_);
    PassTimes times = host_times_;
    host_times_.clear();
    return times;
  }
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
