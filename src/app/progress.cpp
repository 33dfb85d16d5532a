#include "app/progress.h"

#include <algorithm>
#include <cmath>

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

std::string ProgressBar::eta_text(double elapsed_s, size_t done, size_t total) {
  if (done == 0 || done >= total || !(elapsed_s >= 1.0)) return "";
  const double left = elapsed_s * double(total - done) / double(done);
  char text[48];
  if (left >= 3600.0)
    std::snprintf(text, sizeof text, ", ETA %dh%02dm", int(left / 3600.0),
                  int(std::fmod(left, 3600.0) / 60.0));
  else if (left >= 60.0)
    std::snprintf(text, sizeof text, ", ETA %dm%02ds", int(left / 60.0), int(std::fmod(left, 60.0)));
  else
    std::snprintf(text, sizeof text, ", ETA %ds", int(std::ceil(left)));
  return text;
}

void ProgressBar::update(size_t done) {
  if (!enabled_) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string line = render_line(label_, done, total_) + eta_text(elapsed, done, total_);
  const size_t length = line.size();
  if (length < drawn_length_) line.append(drawn_length_ - length, ' ');
  drawn_length_ = length;
  std::fprintf(stream_, "\r%s", line.c_str());
  std::fflush(stream_);
  drawn_ = true;
}

void ProgressBar::finish() {
  if (enabled_ && drawn_) {
    std::fputc('\n', stream_);
    std::fflush(stream_);
  }
  drawn_ = false;
  drawn_length_ = 0;
}

}  // namespace rp::app
