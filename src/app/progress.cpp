#include "app/progress.h"

#include <algorithm>

#include <unistd.h>

namespace rp::app {

ProgressBar::ProgressBar(std::string label, size_t total)
    : ProgressBar(std::move(label), total, isatty(fileno(stderr)) != 0, stderr) {}

ProgressBar::ProgressBar(std::string label, size_t total, bool enabled, std::FILE* stream)
    : label_(std::move(label)), total_(total), enabled_(enabled), stream_(stream) {}

ProgressBar::~ProgressBar() { finish(); }

std::string ProgressBar::render_line(const std::string& label, size_t done, size_t total,
                                     size_t bar_width) {
  done = std::min(done, total);
  size_t filled = total == 0 ? bar_width : done * bar_width / total;
  std::string line = label + " [";
  line.append(filled, '#');
  line.append(bar_width - filled, '.');
  line += "] " + std::to_string(done) + "/" + std::to_string(total);
  return line;
}

void ProgressBar::update(size_t done) {
  if (!enabled_) return;
  std::fprintf(stream_, "\r%s", render_line(label_, done, total_).c_str());
  std::fflush(stream_);
  drawn_ = true;
}

void ProgressBar::finish() {
  if (enabled_ && drawn_) {
    std::fputc('\n', stream_);
    std::fflush(stream_);
  }
  drawn_ = false;
}

}  // namespace rp::app
