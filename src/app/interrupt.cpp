#include "app/interrupt.h"

#include <cstdio>
#include <thread>

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include "app/png_output.h"

namespace rp::app {
namespace {

// The first signal that interrupted. A signal handler can only talk to the program through a
// variable like this, hence the one file-local global; the handler does nothing else.
volatile std::sig_atomic_t g_interrupted = 0;

// How each signal reaches the flag.
//  kHandler: a handler sets it. LLVM (inside PoCL, while it compiles) puts its own handler in
//    front, deletes its temporary files and raises the signal again for ours: the kernel build
//    fails, and is reported as the interruption (fast: the build stops).
//  kWatched: blocked in every thread and taken by a watcher thread (sigwaitinfo). LLVM's handler
//    for these ends in its crash handlers without raising them again, after failing the build:
//    the signal was lost. Blocked, it never reaches LLVM. SIGXFSZ raised by the kernel for our
//    own write is directed at the writing thread, stays pending there, and the write fails with
//    EFBIG: a write error naming the file, not an interruption.
enum class Route { kHandler, kWatched };

struct Handled {
  int signal;
  const char* name;
  Route route;
  // Whether a second one ends the process at once: the way out of a stuck wait. Not for
  // SIGPIPE, which every further write to a broken pipe raises again, nor for SIGXCPU and
  // SIGXFSZ, which the kernel repeats.
  bool second_kills;
};

constexpr Handled kHandled[] = {
    {SIGHUP, "SIGHUP", Route::kHandler, true},     {SIGINT, "SIGINT", Route::kHandler, true},
    {SIGTERM, "SIGTERM", Route::kHandler, true},   {SIGUSR2, "SIGUSR2", Route::kHandler, true},
    {SIGALRM, "SIGALRM", Route::kHandler, true},   {SIGPIPE, "SIGPIPE", Route::kHandler, false},
    {SIGQUIT, "SIGQUIT", Route::kWatched, true},   {SIGUSR1, "SIGUSR1", Route::kWatched, true},
    {SIGXCPU, "SIGXCPU", Route::kWatched, false},  {SIGXFSZ, "SIGXFSZ", Route::kWatched, false},
};

const Handled* find(int signal) {
  for (const Handled& h : kHandled)
    if (h.signal == signal) return &h;
  return nullptr;
}

// The kernel's SIGXFSZ for our own write past the size limit (sent as SI_USER from our pid).
bool own_file_size_signal(int signal, const siginfo_t* info) {
  return signal == SIGXFSZ && info != nullptr && info->si_code == SI_USER &&
         info->si_pid == ::getpid();
}

extern "C" void on_signal(int signal, siginfo_t* info, void*) {
  // A watched signal reaches a handler only in a thread that unblocked it (LLVM's handler
  // unblocks everything in the thread it ran on); the same rules apply.
  if (own_file_size_signal(signal, info)) return;
  if (g_interrupted == 0) g_interrupted = signal;
}

// The watcher thread: sets the flag on the first watched signal, ends the process with the
// default action on a second one of a kind that allows it.
void watch(sigset_t watched) {
  for (;;) {
    siginfo_t info{};
    const int signal = ::sigwaitinfo(&watched, &info);
    if (signal <= 0 || own_file_size_signal(signal, &info)) continue;
    if (g_interrupted == 0) {
      g_interrupted = signal;
      continue;
    }
    const Handled* h = find(signal);
    if (h == nullptr || !h->second_kills) continue;
    ::signal(signal, SIG_DFL);
    sigset_t one;
    sigemptyset(&one);
    sigaddset(&one, signal);
    pthread_sigmask(SIG_UNBLOCK, &one, nullptr);
    ::raise(signal);
  }
}

}  // namespace

void install_signal_handlers() {
  static bool installed = false;
  if (installed) return;
  installed = true;
  sigset_t unblock, block, watched;
  sigemptyset(&unblock);
  sigemptyset(&block);
  sigemptyset(&watched);
  for (const Handled& h : kHandled) {
    struct sigaction old {};
    sigaction(h.signal, nullptr, &old);
    if (h.signal == SIGHUP && old.sa_handler == SIG_IGN) {
      // nohup: the user asked for the run to survive the terminal. Blocked as well, because
      // LLVM installs its own handler over an ignored signal, deletes its temporary files and
      // so fails the kernel build in progress.
      sigaddset(&block, SIGHUP);
      continue;
    }
    struct sigaction action {};
    action.sa_sigaction = on_signal;
    sigemptyset(&action.sa_mask);
    // SA_RESTART: a write interrupted by the signal goes on, so the file it writes is whole.
    action.sa_flags = SA_SIGINFO | SA_RESTART | (h.second_kills ? SA_RESETHAND : 0);
    sigaction(h.signal, &action, nullptr);
    sigaddset(h.route == Route::kWatched ? &block : &unblock, h.signal);
    if (h.route == Route::kWatched) sigaddset(&watched, h.signal);
  }
  // A mask inherited from the launcher would hold the handled signals back until the end.
  // Every thread started later (PoCL's, Embree's, the watcher) inherits this mask.
  pthread_sigmask(SIG_UNBLOCK, &unblock, nullptr);
  pthread_sigmask(SIG_BLOCK, &block, nullptr);
  std::thread(watch, watched).detach();
}

bool InterruptGuard::interrupted() { return g_interrupted != 0; }

int InterruptGuard::signal_number() { return g_interrupted; }

void throw_if_interrupted(const char* while_doing) {
  if (InterruptGuard::interrupted()) throw Interrupted(while_doing);
}

int interrupted_exit_code() {
  const int signal = InterruptGuard::signal_number();
  return signal > 0 ? 128 + signal : kInterruptedExitCode;
}

const char* signal_name(int signal) {
  const Handled* h = find(signal);
  return h ? h->name : "a signal";
}

const char* interrupt_signal_name() { return signal_name(InterruptGuard::signal_number()); }

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
