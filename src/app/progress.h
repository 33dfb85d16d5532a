// A one-line progress bar on stderr, drawn only when stderr is a terminal (so logs and test
// captures stay clean).
#pragma once

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

 private:
  std::string label_;
  size_t total_;
  bool enabled_;
  std::FILE* stream_;
  bool drawn_ = false;
};

}  // namespace rp::app
