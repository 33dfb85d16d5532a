#include "app/interrupt.h"

#include <cstdio>

#include "app/png_output.h"

namespace rp::app {
namespace {

// The signal number, set by SIGINT / SIGTERM. A signal handler can only talk to the program
// through a variable like this, hence the one file-local global; the handler does nothing else.
volatile std::sig_atomic_t g_interrupted = 0;

extern "C" void on_interrupt(int signal) { g_interrupted = signal; }

}  // namespace

InterruptGuard::InterruptGuard() {
  g_interrupted = 0;
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART | SA_RESETHAND;  // restart interrupted writes
  sigaction(SIGINT, &action, &old_int_);
  sigaction(SIGTERM, &action, &old_term_);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &old_int_, nullptr);
  sigaction(SIGTERM, &old_term_, nullptr);
}

bool InterruptGuard::interrupted() { return g_interrupted != 0; }

int InterruptGuard::signal_number() { return g_interrupted; }

int interrupted_exit_code() {
  const int signal = InterruptGuard::signal_number();
  return signal > 0 ? 128 + signal : kInterruptedExitCode;
}

const char* interrupt_signal_name() {
  switch (InterruptGuard::signal_number()) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "a signal";
  }
}

int report_interrupted(uint32_t frames_written, const std::filesystem::path& out_dir,
                       const std::string& also) {
  std::fflush(stdout);
  const uint32_t i = frames_written;
  std::string done;  // appends, not operator+ chains: GCC 12 -Wrestrict false positive
  if (i == 0) {
    done = "no frame was written";
  } else {
    if (i > 1) {
      done += frame_file_name(0);
      done += " ... ";
    }
    done += frame_file_name(i - 1);
    done += " in ";
    done += out_dir.string();
    done += i == 1 ? " is complete" : " are complete";
    done += also;
  }
  std::fprintf(stderr, "rolypoly: error: interrupted after %u frame%s (%s)\n", i,
               i == 1 ? "" : "s", done.c_str());
  return interrupted_exit_code();
}

}  // namespace rp::app
