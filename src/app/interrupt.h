// Signals that end a run: SIGHUP (a closed terminal or ssh session), SIGINT (Ctrl-C), SIGQUIT,
// SIGTERM, SIGPIPE (a reader that went away), SIGALRM, SIGUSR1/2, SIGXCPU and a SIGXFSZ sent by
// someone else. Installed once for the whole process, a handler (or, for the signals LLVM would
// swallow, a watcher thread: interrupt.cpp) only sets a flag; the commands check it between
// frames (the path tracer while it runs, a long replay between chunks of steps, the bench
// between frames, input reads while they wait), so every file written is complete, no temporary
// remains and exit() still runs (it removes the private PoCL cache). The exit code is the
// shells' 128 + signal: 129 SIGHUP, 130 SIGINT, 131 SIGQUIT, 141 SIGPIPE, 143 SIGTERM.
//
// SIGXFSZ raised by the kernel for our own write beyond the file size limit (ulimit -f) is not an
// interruption: that write fails with EFBIG and is reported as "cannot write FILE: File too
// large" by the writer.
//
// A signal during start-up can also make the work fail: LLVM (inside PoCL) removes its temporary
// files on SIGHUP / SIGINT / SIGTERM before passing the signal on, so the kernel build being
// compiled fails. Callers that catch an error while interrupted() is true report the
// interruption instead of that consequence (report_interrupted, or cli.cpp for every command).
#pragma once

#include <csignal>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace rp::app {

// Exit code of a process ended by SIGINT, as shells report it (128 + 2).
inline constexpr int kInterruptedExitCode = 130;

// Installs the flag handler for every signal above, once per process (later calls do nothing).
// What the process inherited does not matter: a signal inherited as ignored (SIGINT and SIGQUIT
// in a script's background job) or blocked is handled like any other, with one exception: a
// SIGHUP inherited as ignored (nohup) stays ignored, and is also blocked so that LLVM's handler
// cannot see it and break a kernel build. A second SIGHUP / SIGINT / SIGQUIT / SIGTERM ends the
// process at once (the default action): the way out of a stuck wait.
void install_signal_handlers();

// Kept by the commands as a reminder that they check interrupted(): installs the handlers (see
// above) if they are not already.
class InterruptGuard {
 public:
  InterruptGuard() { install_signal_handlers(); }
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  // Safe from any thread (it reads a sig_atomic_t the handler set).
  static bool interrupted();
  // The first signal that interrupted, 0 if none.
  static int signal_number();
};

// Thrown by waits and loops that stop on a signal (input reads, the bench's frames); cli.cpp
// reports it as "interrupted by SIGNAL <what()>" with interrupted_exit_code(). what(): "while
// benchmarking; no file was written".
struct Interrupted : std::runtime_error {
  explicit Interrupted(const std::string& while_doing)
      : std::runtime_error(while_doing) {}
};
// Throws Interrupted("while_doing") when a signal arrived.
void throw_if_interrupted(const char* while_doing);

// 128 + the signal that interrupted (SIGINT 130, SIGTERM 143); kInterruptedExitCode if none.
int interrupted_exit_code();
// "SIGINT", "SIGHUP", ... (the signal that interrupted; "a signal" if none).
const char* interrupt_signal_name();
// The name of `signal` ("SIGQUIT"), "a signal" for one not handled here.
const char* signal_name(int signal);

// Prints "rolypoly: error: interrupted after N frames (frame_0000.png ... frame_NNNN.png in DIR
// are complete<also>)" on stderr and returns interrupted_exit_code(). `also`: e.g. " with their
// .exr files" ("" = nothing more).
int report_interrupted(uint32_t frames_written, const std::filesystem::path& out_dir,
                       const std::string& also = "");

}  // namespace rp::app
