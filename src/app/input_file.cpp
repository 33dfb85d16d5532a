#include "app/input_file.h"

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/interrupt.h"
#include "app/replay_text.h"
#include "scene/gltf_loader.h"

namespace rp::app {
namespace {

// Closes the descriptor on every path out.
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

std::string cannot_read(const char* option, const std::string& path, const std::string& why) {
  return std::string(option) + ": cannot read " + path + ": " + why;
}

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return std::strerror(EISDIR);
  if (S_ISFIFO(mode)) return "it is a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "it is a character device";
  if (S_ISBLK(mode)) return "it is a block device";
  if (S_ISSOCK(mode)) return "it is a socket";
  return "it is not a regular file";
}

std::string mib(size_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

}  // namespace

std::string read_input_file(const std::string& path, const char* option, size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO without a writer would block here, out of reach of the signals'
  // flag; the reads below wait in poll() instead, a tenth of a second at a time.
  Fd in{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC)};
  if (in.fd < 0) throw std::runtime_error(cannot_read(option, path, std::strerror(errno)));
  struct stat st {};
  if (::fstat(in.fd, &st) != 0)
    throw std::runtime_error(cannot_read(option, path, std::strerror(errno)));
  if (S_ISDIR(st.st_mode)) throw std::runtime_error(cannot_read(option, path, kind_of(st.st_mode)));
  const bool regular = S_ISREG(st.st_mode);
  const std::string too_large = "larger than " + mib(max_bytes) + ", which no " +
                                std::string(option) + " file is";
  if (regular && uint64_t(st.st_size) > max_bytes)
    throw std::runtime_error(cannot_read(option, path, too_large));

  std::string bytes;
  const auto started = std::chrono::steady_clock::now();
  bool told = false;
  char buffer[65536];
  for (;;) {
    if (!regular) {
      // A FIFO without a writer, a terminal without input: wait, but never past a signal.
      pollfd p{in.fd, POLLIN, 0};
      const int ready = ::poll(&p, 1, 100);
      throw_if_interrupted(
          ("while waiting for " + std::string(option) + " " + path + "; nothing was written")
              .c_str());
      if (ready < 0 && errno != EINTR)
        throw std::runtime_error(cannot_read(option, path, std::strerror(errno)));
      if (ready <= 0) {
        if (!told && std::chrono::steady_clock::now() - started > std::chrono::seconds(2)) {
          told = true;
          std::fprintf(stderr, "rolypoly: %s %s: %s; waiting for data (Ctrl-C stops)\n", option,
                       path.c_str(), kind_of(st.st_mode));
        }
        continue;
      }
    }
    const ssize_t n = ::read(in.fd, buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      throw std::runtime_error(cannot_read(option, path, std::strerror(errno)));
    }
    if (bytes.size() + size_t(n) > max_bytes)
      throw std::runtime_error(cannot_read(option, path, too_large));
    bytes.append(buffer, size_t(n));
  }
  return bytes;
}

std::vector<scene::InputEvent> read_replay_log(const std::string& path) {
  return parse_replay_text(read_input_file(path, "--replay", kMaxInputLogBytes), path);
}

void require_regular_file(const std::string& path, const char* option) {
  struct stat st {};
  // A missing file is the loader's to report (it names what it looked for).
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    throw scene::SceneFileError(cannot_read(option, path, kind_of(st.st_mode)));
}

}  // namespace rp::app
