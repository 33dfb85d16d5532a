// Pipes RGBA8 frames into ffmpeg to encode a video (`rolypoly render --video FILE.mp4`).
// The video is written under a temporary name next to FILE and renamed when ffmpeg finished
// successfully, so an interrupted or failed encode never leaves a half-written FILE.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace rp::app {

class VideoPipe {
 public:
  // Throws std::runtime_error with a clear message when ffmpeg is not installed (checked on
  // PATH before any frame is rendered) or cannot be started.
  VideoPipe(const std::string& path, uint32_t width, uint32_t height, uint32_t fps);
  ~VideoPipe();  // abandons an unfinished video (removes the temporary file)
  VideoPipe(const VideoPipe&) = delete;
  VideoPipe& operator=(const VideoPipe&) = delete;

  void write(const std::vector<uint8_t>& rgba);  // width * height * 4 bytes, top row first
  // Waits for ffmpeg; throws if it failed (its messages went to stderr); renames into place.
  void finish();

 private:
  std::string path_, temp_path_;
  size_t frame_bytes_ = 0;
  FILE* pipe_ = nullptr;
};

// True when an executable named `name` is on PATH.
bool on_path(const std::string& name);

}  // namespace rp::app
