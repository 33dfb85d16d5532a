// A private X server (Xvfb) for the window tests, and small process helpers they share.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <string>

namespace rp::test {

// Xvfb with a 24-bit screen (GLFW needs an RGBA8 visual). -displayfd lets Xvfb pick a free
// display and say which once it accepts connections. Stopped (SIGTERM) on destruction.
class XvfbServer {
 public:
  XvfbServer();
  ~XvfbServer();
  XvfbServer(const XvfbServer&) = delete;
  XvfbServer& operator=(const XvfbServer&) = delete;
  const std::string& display() const { return display_; }  // "" when it did not start
  // Kills the server now (SIGKILL): its clients lose their connection.
  void kill_now();

 private:
  pid_t pid_ = -1;
  std::string display_;
};

// `command` through /bin/sh in the background; returns its pid.
pid_t spawn_shell(const std::string& command);

// The exit status of `pid`, waiting at most `limit`; -1 if it was killed by a signal, or if it
// outlived `limit` (then it is killed).
int wait_exit(pid_t pid, std::chrono::seconds limit);

// stdout of a short shell command.
std::string output_of(const std::string& command);

std::string read_text(const std::filesystem::path& path);

// The id of the window titled "rolypoly..." on `display`, once its title shows a frame rate
// (it has shown frames for >= 0.5 s); 0 when none appeared within two minutes.
unsigned long wait_for_rolypoly_window(const std::string& display);

}  // namespace rp::test
