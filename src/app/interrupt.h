// Ctrl-C (SIGINT) and SIGTERM during `render`, `run` and `bench --accuracy`: the loops check a
// flag between frames (the path tracer while it runs, a long replay between chunks of steps), so
// every file written is complete, and report how far they got. The exit code is the shells'
// 128 + signal: 130 for SIGINT, 143 for SIGTERM.
//
// A signal during start-up can also make the work fail: LLVM (inside PoCL) removes its temporary
// files on SIGINT / SIGTERM before passing the signal on, so the kernel build being compiled
// fails. Callers that catch an error while interrupted() is true report the interruption
// instead of that consequence (report_interrupted, or cli.cpp for every command).
#pragma once

#include <csignal>
#include <cstdint>
#include <filesystem>
#include <string>

namespace rp::app {

// Exit code of a process ended by SIGINT, as shells report it (128 + 2).
inline constexpr int kInterruptedExitCode = 130;

// 128 + the signal that interrupted (SIGINT 130, SIGTERM 143); kInterruptedExitCode if none.
int interrupted_exit_code();
// "SIGINT", "SIGTERM" (the signal that interrupted; "a signal" if none).
const char* interrupt_signal_name();

// Installs the handler for one render and restores the previous ones afterwards. The handler
// only sets a flag; SA_RESETHAND makes a second Ctrl-C kill at once (e.g. while kernels build).
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  // Safe from any thread (it reads a sig_atomic_t the handler set).
  static bool interrupted();
  // The signal number that interrupted, 0 if none.
  static int signal_number();

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

// Prints "rolypoly: error: interrupted after N frames (frame_0000.png ... frame_NNNN.png in DIR
// are complete<also>)" on stderr and returns interrupted_exit_code(). `also`: e.g. " with their
// .exr files" ("" = nothing more).
int report_interrupted(uint32_t frames_written, const std::filesystem::path& out_dir,
                       const std::string& also = "");

}  // namespace rp::app
