#include "app/video_output.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>

namespace rp::app {
namespace {

// Single-quoted for /bin/sh.
std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

bool on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    std::filesystem::path candidate = std::filesystem::path(dir) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return true;
  }
  return false;
}

VideoPipe::VideoPipe(const std::string& path, uint32_t width, uint32_t height, uint32_t fps)
    : path_(path), frame_bytes_(size_t(width) * height * 4) {
  if (!on_path("ffmpeg"))
    throw std::runtime_error("--video needs ffmpeg, which is not installed (apt-get install "
                             "ffmpeg), or leave out --video: the PNG frames are written anyway");
  std::filesystem::path p(path);
  temp_path_ = (p.parent_path() / (p.stem().string() + ".partial" + p.extension().string())).string();
  // yuv420p needs even sizes: pad by one pixel where necessary.
  std::string cmd = "ffmpeg -y -loglevel error -f rawvideo -pix_fmt rgba -s " +
                    std::to_string(width) + "x" + std::to_string(height) + " -r " +
                    std::to_string(fps) + " -i - -vf pad=ceil(iw/2)*2:ceil(ih/2)*2 " +
                    "-pix_fmt yuv420p " + shell_quote(temp_path_);
  pipe_ = ::popen(cmd.c_str(), "w");
  if (!pipe_) throw std::runtime_error("cannot start ffmpeg for --video " + path);
}

VideoPipe::~VideoPipe() {
  if (pipe_) {
    ::pclose(pipe_);
    std::error_code ec;
    std::filesystem::remove(temp_path_, ec);
  }
}

void VideoPipe::write(const std::vector<uint8_t>& rgba) {
  if (!pipe_) throw std::runtime_error("--video: the video is already finished");
  if (rgba.size() != frame_bytes_) throw std::runtime_error("--video: frame size changed");
  if (std::fwrite(rgba.data(), 1, rgba.size(), pipe_) != rgba.size())
    throw std::runtime_error("--video: ffmpeg stopped accepting frames (see its messages above)");
}

void VideoPipe::finish() {
  if (!pipe_) return;
  int status = ::pclose(pipe_);
  pipe_ = nullptr;
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::error_code ec;
    std::filesystem::remove(temp_path_, ec);
    throw std::runtime_error("ffmpeg failed to encode " + path_ + " (see its messages above)");
  }
  std::filesystem::rename(temp_path_, path_);
}

}  // namespace rp::app
