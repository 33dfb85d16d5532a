#include "app/video_output.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "io/output_path.h"

extern char** environ;

namespace rp::app {
namespace {

std::string errno_text(int err) { return std::strerror(err); }

// The last few non-empty lines of ffmpeg's stderr, joined: enough to say why it failed
// without flooding the one-line error message.
std::string tail_lines(const std::string& text, size_t count) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
  std::string out;
  for (size_t i = lines.size() > count ? lines.size() - count : 0; i < lines.size(); ++i) {
    if (!out.empty()) out += " / ";
    out += lines[i];
  }
  return out;
}

// Everything in `fd` from its start (ffmpeg's stderr file).
std::string read_all(int fd) {
  std::string text;
  if (fd < 0 || ::lseek(fd, 0, SEEK_SET) < 0) return text;
  char buffer[4096];
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) != 0;) {
    if (n < 0) {
      if (errno == EINTR) continue;
      break;
    }
    text.append(buffer, size_t(n));
  }
  return text;
}

// Makes the spawn fail-safe: every resource below is released on every path.
struct SpawnSetup {
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attr;
  SpawnSetup() {
    posix_spawn_file_actions_init(&actions);
    posix_spawnattr_init(&attr);
  }
  ~SpawnSetup() {
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
  }
  SpawnSetup(const SpawnSetup&) = delete;
  SpawnSetup& operator=(const SpawnSetup&) = delete;
};

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
  // The output path rules of io/output_path.h: a symlink is followed (the file it points to is
  // replaced, the link stays); a device or FIFO is refused: ffmpeg finishes a video with seeks
  // back to its header, which a pipe cannot take.
  const io::OutputTarget target = io::resolve_output(path);
  if (target.kind != io::OutputTarget::Kind::kReplace)
    throw std::runtime_error("--video: cannot write " + path +
                             ": a video is finished with seeks back to its start, so it must "
                             "go to a regular file (not a device, FIFO or pipe)");
  path_ = target.path.string();
  const std::filesystem::path p(path_);
  // Unique per process (two renders may encode into one folder); the extension stays last.
  temp_path_ = (p.parent_path() / (p.stem().string() + ".partial-" + std::to_string(::getpid()) +
                                   p.extension().string()))
                   .string();
  // Claim the temporary name now: an unwritable folder fails before any frame is rendered,
  // with the system's reason (ffmpeg would open its output only after the first frame).
  const int probe = ::open(temp_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (probe < 0)
    throw std::runtime_error("--video: cannot write " + temp_path_ + " (beside " + path +
                             "): " + errno_text(errno));
  ::close(probe);
  temp_created_ = true;

  try {
    std::string log_template =
        (std::filesystem::temp_directory_path() / "rolypoly-ffmpeg-XXXXXX").string();
    log_fd_ = ::mkostemp(log_template.data(), O_CLOEXEC);
    if (log_fd_ < 0)
      throw std::runtime_error("--video: cannot create a file for ffmpeg's messages in " +
                               log_template + ": " + errno_text(errno));
    ::unlink(log_template.c_str());  // nothing to clean up later

    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0)
      throw std::runtime_error("--video: cannot create a pipe to ffmpeg: " + errno_text(errno));
    input_fd_ = fds[1];

    // yuv420p needs even sizes: pad by one pixel where necessary.
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    const std::string rate = std::to_string(fps);
    // -xerror: ffmpeg 5 exits 0 after "Error writing trailer ...: No space left on device"
    // (a truncated video) unless told to treat errors as fatal.
    std::vector<std::string> args = {"ffmpeg", "-hide_banner", "-loglevel", "error",
                                     "-xerror", "-y", "-f", "rawvideo", "-pix_fmt", "rgba",
                                     "-s", size, "-r", rate, "-i", "-", "-vf",
                                     "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p",
                                     temp_path_};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    SpawnSetup setup;
    posix_spawn_file_actions_adddup2(&setup.actions, fds[0], STDIN_FILENO);
    posix_spawn_file_actions_addopen(&setup.actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&setup.actions, log_fd_, STDERR_FILENO);
    // Its own process group: a terminal's Ctrl-C reaches rolypoly only, which then abandons
    // the video (ffmpeg would otherwise die first and the last frame's write fail). SIGPIPE
    // (ignored here while the pipe exists), SIGINT and SIGTERM get their default action back.
    sigset_t defaults, none;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGPIPE);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    sigemptyset(&none);
    posix_spawnattr_setsigdefault(&setup.attr, &defaults);
    posix_spawnattr_setsigmask(&setup.attr, &none);
    posix_spawnattr_setpgroup(&setup.attr, 0);
    posix_spawnattr_setflags(&setup.attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF |
                                              POSIX_SPAWN_SETSIGMASK);

    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    sigpipe_ignored_ = ::sigaction(SIGPIPE, &ignore, &old_pipe_) == 0;

    const int err = ::posix_spawnp(&pid_, "ffmpeg", &setup.actions, &setup.attr, argv.data(),
                                   environ);
    ::close(fds[0]);
    if (err != 0) {
      pid_ = -1;
      throw std::runtime_error("--video: cannot start ffmpeg: " + errno_text(err));
    }
  } catch (...) {
    abandon();
    throw;
  }
}

VideoPipe::~VideoPipe() { abandon(); }

void VideoPipe::abandon() noexcept {
  if (input_fd_ >= 0) {
    ::close(input_fd_);
    input_fd_ = -1;
  }
  if (pid_ > 0) {  // unfinished: the video is unwanted, do not wait for ffmpeg to finish it
    ::kill(pid_, SIGKILL);
    while (::waitpid(pid_, nullptr, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
  }
  if (temp_created_) {
    ::unlink(temp_path_.c_str());
    temp_created_ = false;
  }
  if (log_fd_ >= 0) {
    ::close(log_fd_);
    log_fd_ = -1;
  }
  if (sigpipe_ignored_) {
    ::sigaction(SIGPIPE, &old_pipe_, nullptr);
    sigpipe_ignored_ = false;
  }
}

std::string VideoPipe::wait_for_ffmpeg() {
  if (pid_ <= 0) return "ffmpeg is not running";
  int status = 0;
  pid_t done;
  while ((done = ::waitpid(pid_, &status, 0)) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  if (done < 0) return "waiting for ffmpeg failed: " + errno_text(errno);
  const std::string said = tail_lines(read_all(log_fd_), 3);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    // At -loglevel error anything it printed is an error, even with exit status 0.
    return said.empty() ? "" : "ffmpeg exited with status 0 but reported: " + said;
  }
  std::string how = WIFEXITED(status)
                        ? "ffmpeg exited with status " + std::to_string(WEXITSTATUS(status))
                        : "ffmpeg was killed by signal " + std::to_string(WTERMSIG(status)) +
                              " (" + strsignal(WTERMSIG(status)) + ")";
  return said.empty() ? how : how + ": " + said;
}

void VideoPipe::write(const std::vector<uint8_t>& rgba) {
  if (input_fd_ < 0) throw std::runtime_error("--video: the video is already finished");
  if (rgba.size() != frame_bytes_) throw std::runtime_error("--video: frame size changed");
  size_t done = 0;
  while (done < rgba.size()) {
    const ssize_t n = ::write(input_fd_, rgba.data() + done, rgba.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = errno;
      const std::string why = wait_for_ffmpeg();
      abandon();
      throw std::runtime_error("--video " + path_ + ": ffmpeg stopped reading frames (" +
                               (why.empty() ? errno_text(err) : why) + "); no video was written");
    }
    done += size_t(n);
  }
}

void VideoPipe::finish() {
  if (input_fd_ < 0) return;
  ::close(input_fd_);
  input_fd_ = -1;
  const std::string why = wait_for_ffmpeg();
  if (!why.empty()) {
    abandon();
    throw std::runtime_error("--video: ffmpeg failed to encode " + path_ + " (" + why +
                             "); no video was written");
  }
  // ffmpeg does not sync: the rename must not make a name point at data still in flight.
  const int fd = ::open(temp_path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int err = errno;
    if (fd >= 0) ::close(fd);
    abandon();
    throw std::runtime_error("--video: cannot sync " + temp_path_ + ": " + errno_text(err));
  }
  ::close(fd);
  if (::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    abandon();
    throw std::runtime_error("--video: cannot rename " + temp_path_ + " to " + path_ + ": " +
                             errno_text(err));
  }
  temp_created_ = false;
  abandon();  // closes the log, restores SIGPIPE
}

}  // namespace rp::app
