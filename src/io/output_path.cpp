#include "io/output_path.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/temporary_file.h"

namespace rp::io {
namespace {

// Linux gives up after 40 links in one path; so do we (a loop would never end).
constexpr int kMaxLinks = 40;

// The files of /proc/<pid>/fd are "magic" links: they name an open file description (a pipe,
// a terminal, a file opened by the shell's redirection) rather than a path, so they are opened,
// never resolved and replaced. Returns whether `p` is one, and sets `own_fd` to N when it is
// this process's descriptor N.
bool is_open_file_link(const std::filesystem::path& p, int& own_fd) {
  std::error_code ec;
  const std::filesystem::path dir = std::filesystem::canonical(p.parent_path(), ec);
  if (ec || dir.filename() != "fd" || dir.string().rfind("/proc/", 0) != 0) return false;
  const std::string ours = "/proc/" + std::to_string(::getpid()) + "/";
  const std::string name = p.filename().string();
  own_fd = -1;
  if (dir.string().rfind(ours, 0) == 0 && !name.empty() && name.size() < 10 &&
      name.find_first_not_of("0123456789") == std::string::npos)
    own_fd = std::stoi(name);
  return true;
}

const char* kind_name(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISBLK(mode)) return "a block device";
  return "neither a file nor a device";
}

}  // namespace

OutputTarget resolve_output(const std::filesystem::path& path) {
  if (path.empty()) throw std::runtime_error("cannot write a file with an empty name");
  std::filesystem::path p = path;
  for (int links = 0;; ++links) {
    if (int fd = -1; is_open_file_link(p, fd))
      return {OutputTarget::Kind::kInPlace, path, true, fd};
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0) {
      const int err = errno;
      // Nothing there (also at the end of a dangling link): the file will be created, and a
      // missing folder (or a file where a folder should be) is reported by whoever creates it.
      if (err == ENOENT || err == ENOTDIR)
        return {OutputTarget::Kind::kReplace, p, false, -1, links > 0};
      throw WriteError(path, std::strerror(err));
    }
    if (S_ISREG(st.st_mode)) return {OutputTarget::Kind::kReplace, p, true, -1, links > 0};
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode))
      return {OutputTarget::Kind::kInPlace, p, true};
    if (!S_ISLNK(st.st_mode)) throw WriteError(path, std::string("it is ") + kind_name(st.st_mode));
    if (links == kMaxLinks) throw WriteError(path, std::strerror(ELOOP));
    std::error_code ec;
    const std::filesystem::path target = std::filesystem::read_symlink(p, ec);
    if (ec) throw WriteError(path, ec.message());
    // A relative link is relative to the folder holding the link, not to ours.
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
}

void ensure_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw std::runtime_error("cannot create output folder " + dir.string() +
                             (ec ? ": " + ec.message() : ": a file of that name exists"));
  // An existing folder may still refuse new files (read-only mount, /proc, no permission):
  // find out now by creating and removing an empty probe file, not after the first frame.
  const std::filesystem::path probe = temporary_for(dir / ".rolypoly-write-test");
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    const int err = errno;
    throw std::runtime_error("cannot write into output folder " + dir.string() + ": " +
                             std::strerror(err));
  }
  ::close(fd);
  std::filesystem::remove(probe, ec);
}

void check_output_file(const std::filesystem::path& path, const std::string& what) {
  const std::string prefix = what.empty() ? "" : what + ": ";
  try {
    const OutputTarget target = resolve_output(path);
    if (target.kind == OutputTarget::Kind::kInPlace) {
      if (target.fd >= 0) {
        const int flags = ::fcntl(target.fd, F_GETFL);
        if (flags < 0) throw WriteError(path, std::strerror(errno));
        if ((flags & O_ACCMODE) == O_RDONLY) throw WriteError(path, "it is open for reading only");
      } else if (::access(target.path.c_str(), W_OK) != 0) {
        throw WriteError(path, std::strerror(errno));
      }
      return;
    }
    const std::filesystem::path dir = target.path.parent_path();
    std::error_code ec;
    if (target.via_link && !dir.empty() && !std::filesystem::is_directory(dir, ec))
      throw WriteError(path, "it is a symbolic link to " + target.path.string() +
                                 ", whose folder does not exist (it is not created for a link)");
    // A bare "out.json" goes to the current folder, named in full should it refuse files.
    ensure_directory(dir.empty() ? std::filesystem::current_path() : dir);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(prefix + e.what());
  }
}

}  // namespace rp::io
