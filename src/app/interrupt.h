// Ctrl-C (SIGINT) and SIGTERM during `render`: the render loops check a flag between frames (and
// the path tracer while it runs), so every file written is complete, and report how far they got.
#pragma once

#include <csignal>
#include <cstdint>
#include <filesystem>
#include <string>

namespace rp::app {

// Exit code of a process ended by SIGINT, as shells report it (128 + 2).
inline constexpr int kInterruptedExitCode = 130;

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

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

// Prints "rolypoly: error: interrupted after N frames (frame_0000.png ... frame_NNNN.png in DIR
// are complete<also>)" on stderr and returns kInterruptedExitCode. `also`: e.g. " with their
// .exr files" ("" = nothing more).
int report_interrupted(uint32_t frames_written, const std::filesystem::path& out_dir,
                       const std::string& also = "");

}  // namespace rp::app
