#include "app/png_output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

#include <stb/stb_image_write.h>

#include "io/temporary_file.h"

namespace rp::app {
namespace {

void commit(const std::filesystem::path& tmp, const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error("cannot write " + path.string() + ": rename failed");
  }
}

}  // namespace

std::string frame_file_name(uint32_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04u.png", index);
  return name;
}

void write_png_atomic(const std::filesystem::path& path, int width, int height,
                      const std::vector<uint8_t>& rgba) {
  if (width <= 0 || height <= 0 || rgba.size() != size_t(width) * size_t(height) * 4)
    throw std::runtime_error("cannot write " + path.string() + ": image size mismatch");
  std::filesystem::path tmp = io::temporary_for(path);
  if (!stbi_write_png(tmp.c_str(), width, height, 4, rgba.data(), width * 4)) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error("cannot write " + path.string() +
                             " (is the folder writable and the disk not full?)");
  }
  commit(tmp, path);
}

void write_text_atomic(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::path tmp = io::temporary_for(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) {
      out.close();
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw std::runtime_error("cannot write " + path.string());
    }
  }
  commit(tmp, path);
}

void ensure_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw std::runtime_error("cannot create output folder " + dir.string() +
                             (ec ? ": " + ec.message() : ": a file of that name exists"));
  // An existing folder may still refuse new files (read-only mount, /proc, no permission):
  // find out now by creating and removing an empty probe file, not after the first frame.
  std::filesystem::path probe = io::temporary_for(dir / ".rolypoly-write-test");
  int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) {
    const int err = errno;
    throw std::runtime_error("cannot write into output folder " + dir.string() + ": " +
                             std::strerror(err));
  }
  ::close(fd);
  std::filesystem::remove(probe, ec);
}

}  // namespace rp::app
