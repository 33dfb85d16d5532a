// Pipes RGBA8 frames into ffmpeg to encode a video (`rolypoly render --video FILE.mp4`).
//
// ffmpeg is started with an argument vector (posix_spawn, no shell: any file name works), in its
// own process group (a Ctrl-C in the terminal reaches rolypoly alone, which then ends the video
// itself), with its stderr going to an unlinked temporary file that failure messages quote.
// ffmpeg writes a temporary name beside FILE (same extension: ffmpeg picks the container from
// it); only a successful encode is synced and renamed to FILE, so a failed or interrupted
// encode never leaves a file behind. Writes into the pipe are checked; while a VideoPipe exists
// SIGPIPE is ignored, so ffmpeg quitting early is an error message (naming its exit status and
// its own last words), not a silent death by SIGPIPE (exit 141).
#pragma once

#include <sys/types.h>

#include <csignal>
#include <cstdint>
#include <string>
#include <vector>

namespace rp::app {

class VideoPipe {
 public:
  // Throws std::runtime_error with a clear message when ffmpeg is not installed (checked on
  // PATH before any frame is rendered), when FILE's folder cannot take the temporary file, or
  // when ffmpeg cannot be started.
  VideoPipe(const std::string& path, uint32_t width, uint32_t height, uint32_t fps);
  ~VideoPipe();  // abandons an unfinished video: ends ffmpeg, removes the temporary file
  VideoPipe(const VideoPipe&) = delete;
  VideoPipe& operator=(const VideoPipe&) = delete;

  void write(const std::vector<uint8_t>& rgba);  // width * height * 4 bytes, top row first
  // Closes ffmpeg's input and waits for it; throws if it failed (the message quotes its
  // stderr), else syncs the video and renames it into place.
  void finish();

  const std::string& temp_path() const { return temp_path_; }

 private:
  // Waits for ffmpeg (once) and returns "" when it exited with 0, else how it ended and what
  // it printed.
  std::string wait_for_ffmpeg();
  void abandon() noexcept;

  std::string path_, temp_path_;
  size_t frame_bytes_ = 0;
  pid_t pid_ = -1;
  int input_fd_ = -1;  // ffmpeg's stdin
  int log_fd_ = -1;    // ffmpeg's stderr (an unlinked temporary file)
  bool temp_created_ = false;
  bool sigpipe_ignored_ = false;  // old_pipe_ holds what to restore
  struct sigaction old_pipe_ {};
};

// True when an executable named `name` is on PATH.
bool on_path(const std::string& name);

}  // namespace rp::app
