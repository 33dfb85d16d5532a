#include "io/atomic_file.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include <fcntl.h>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/output_path.h"
#include "io/temporary_file.h"

namespace rp::io {
namespace {

constexpr uint64_t kNoLimit = std::numeric_limits<uint64_t>::max();

// Bytes written by write_file in this process, for ROLYPOLY_FAIL_WRITE_AFTER.
std::atomic<uint64_t> g_written{0};

uint64_t injected_limit() {
  const char* value = std::getenv("ROLYPOLY_FAIL_WRITE_AFTER");
  if (value == nullptr || *value == '\0') return kNoLimit;
  char* end = nullptr;
  errno = 0;
  const unsigned long long n = std::strtoull(value, &end, 10);
  // A hook for tests: a malformed value fails every write rather than being ignored, so a
  // typo in a test cannot turn it into a test of nothing.
  if (*end != '\0' || errno != 0) return 0;
  return n;
}

WriteError failure(const std::filesystem::path& path, int err) {
  return WriteError(path, std::strerror(err));
}

// write(2) until every byte is out: a short write is not an error (a signal, a pipe's
// buffer), only a -1 is. Returns 0 or the errno.
int write_all(int fd, std::string_view bytes) {
  const uint64_t limit = injected_limit();
  size_t done = 0;
  while (done < bytes.size()) {
    size_t chunk = std::min<size_t>(bytes.size() - done, size_t(1) << 30);
    if (limit != kNoLimit) {
      const uint64_t used = g_written.load();
      if (used >= limit) return ENOSPC;
      chunk = size_t(std::min<uint64_t>(chunk, limit - used));
    }
    const ssize_t n = ::write(fd, bytes.data() + done, chunk);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    if (n == 0) return EIO;  // no progress and no reason: do not loop forever
    done += size_t(n);
    g_written += uint64_t(n);
  }
  return 0;
}

// A FIFO whose reader went away raises SIGPIPE, which would end the process without a word.
// Blocked for one write, the write fails with EPIPE instead and is reported like any error;
// the SIGPIPE it left pending is taken before the old mask returns.
class SigpipeBlock {
 public:
  SigpipeBlock() {
    sigemptyset(&pipe_);
    sigaddset(&pipe_, SIGPIPE);
    sigset_t pending;
    sigemptyset(&pending);
    sigpending(&pending);
    was_pending_ = sigismember(&pending, SIGPIPE) == 1;
    pthread_sigmask(SIG_BLOCK, &pipe_, &old_);
  }
  ~SigpipeBlock() {
    if (!was_pending_) {
      const timespec now{};
      while (sigtimedwait(&pipe_, nullptr, &now) > 0) {
      }
    }
    pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  SigpipeBlock(const SigpipeBlock&) = delete;
  SigpipeBlock& operator=(const SigpipeBlock&) = delete;

 private:
  sigset_t pipe_{}, old_{};
  bool was_pending_ = false;
};

// Makes the rename itself durable. Best effort: the file is already complete under its name,
// and some file systems refuse fsync on a folder (EINVAL), which is no reason to fail.
void sync_directory(const std::filesystem::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

void replace_file(const std::filesystem::path& shown, const OutputTarget& target,
                  std::string_view bytes) {
  const std::filesystem::path tmp = temporary_for(target.path);
  // O_NOFOLLOW: a link planted at the temporary's name must not redirect the write.
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd < 0) throw failure(shown, errno);
  int err = 0;
  struct stat old {};
  if (target.exists && ::stat(target.path.c_str(), &old) == 0 &&
      ::fchmod(fd, old.st_mode & 0777) != 0)
    err = errno;
  if (err == 0) err = write_all(fd, bytes);
  // fsync before rename: otherwise a crash can leave the new name on an empty file.
  if (err == 0 && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && err == 0) err = errno;  // NFS and friends report write errors here
  if (err == 0 && ::rename(tmp.c_str(), target.path.c_str()) != 0) err = errno;
  if (err != 0) {
    ::unlink(tmp.c_str());
    throw failure(shown, err);
  }
  sync_directory(target.path.parent_path());
}

void write_in_place(const std::filesystem::path& shown, const OutputTarget& target,
                    std::string_view bytes) {
  // Our own buffered stdout first, in case the target is our stdout (/dev/stdout).
  std::fflush(nullptr);
  const int fd = target.fd >= 0
                     ? ::fcntl(target.fd, F_DUPFD_CLOEXEC, 0)
                     : ::open(target.path.c_str(), O_WRONLY | O_APPEND | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) throw failure(shown, errno);
  int err = 0;
  {
    SigpipeBlock block;
    err = write_all(fd, bytes);
  }
  // Devices and pipes cannot be synced (EINVAL); a regular file behind /dev/stdout can.
  if (err == 0 && ::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) err = errno;
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err != 0) throw failure(shown, err);
}

}  // namespace

void write_file(const std::filesystem::path& path, std::string_view bytes) {
  const OutputTarget target = resolve_output(path);
  if (target.kind == OutputTarget::Kind::kInPlace)
    write_in_place(path, target, bytes);
  else
    replace_file(path, target, bytes);
}

}  // namespace rp::io
