// A one-line progress bar on stderr, drawn only when stderr is a terminal (so logs and test
// captures stay clean), with the estimated time left once there is progress to go by.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace rp::app {

class ProgressBar {
 public:
  // `enabled` defaults to isatty(stderr).
  ProgressBar(std::string label, size_t total);
  ProgressBar(std::string label, size_t total, bool enabled, std::FILE* stream);
  ~ProgressBar();  // ends the line if one was drawn

  void update(size_t done);
  void finish();
  bool enabled() const { return enabled_; }

  // The text drawn for `done` of `total` (without the leading carriage return); for tests.
  static std::string render_line(const std::string& label, size_t done, size_t total,
                                 size_t bar_width = 30);
  // ", ETA 2m05s" after `elapsed_s` seconds for `done` of `total` at the same rate; "" before
  // any progress, when finished, or before a second has passed (too early to tell).
  static std::string eta_text(double elapsed_s, size_t done, size_t total);

 private:
  std::string label_;
  size_t total_;
  bool enabled_;
  std::FILE* stream_;
  bool drawn_ = false;
  size_t drawn_length_ = 0;  // characters of the last line drawn (a shorter one pads over it)
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace rp::app
