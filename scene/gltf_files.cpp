// Files the glTF loader reads: only regular files, checked with stat() before they are opened,
// read with a size known beforehand; and the paths relative URIs name.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "scene/gltf_internal.h"

namespace rp::scene {

bool read_file_start(const std::string& path, uint64_t want, std::vector<uint8_t>* out,
                     std::string* why) {
  // O_NONBLOCK: should the path have been swapped for a FIFO since stat(), open() still
  // returns at once, and fstat() below refuses it.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    *why = std::strerror(errno);
    return false;
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || static_cast<uint64_t>(st.st_size) < want) {
    ::close(fd);
    *why = "changed while being opened";
    return false;
  }
  out->resize(static_cast<size_t>(want));
  size_t done = 0;
  while (done < want) {
    const ssize_t n = ::read(fd, out->data() + done, static_cast<size_t>(want) - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      *why = n < 0 ? std::strerror(errno) : "shorter than expected (changed while being read)";
      ::close(fd);
      out->clear();
      return false;
    }
    done += static_cast<size_t>(n);
  }
  ::close(fd);
  return true;
}

// stat() before open(): opening a FIFO for reading blocks until a writer appears.
bool regular_file_size(const std::string& path, uint64_t* size, std::string* why) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    *why = std::strerror(errno);  // the system's reason: "No such file or directory", ...
    return false;
  }
  if (S_ISDIR(st.st_mode)) {
    *why = "is a directory";
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    *why = "is not a regular file (a FIFO, device or socket)";
    return false;
  }
  *size = static_cast<uint64_t>(st.st_size);
  return true;
}

bool read_regular_file(const std::string& path, uint64_t max_bytes, std::vector<uint8_t>* out,
                       std::string* why) {
  uint64_t size = 0;
  if (!regular_file_size(path, &size, why)) return false;
  if (size > max_bytes) {
    *why = "is " + std::to_string(size) + " bytes, more than the limit of " +
           std::to_string(max_bytes);
    return false;
  }
  return read_file_start(path, size, out, why);
}

}  // namespace rp::scene

namespace rp::scene::gltf {

std::string base_dir_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

// The same decoding as tinygltf's (dlib's urldecode, '+' as a space), so the paths checked here
// are the paths tinygltf then opens.
std::string uri_decode(const std::string& uri) {
  auto hex = [](char ch) -> unsigned {
    if (ch >= '0' && ch <= '9') return unsigned(ch - '0');
    if (ch >= 'a' && ch <= 'f') return unsigned(ch - 'a' + 10);
    if (ch >= 'A' && ch <= 'F') return unsigned(ch - 'A' + 10);
    return 0;
  };
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+') {
      out += ' ';
    } else if (uri[i] == '%' && uri.size() > i + 2) {
      out += static_cast<char>((hex(uri[i + 1]) << 4) | hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

std::string join_path(const std::string& dir, const std::string& name) {
  if (dir.empty()) return name;
  return dir.back() == '/' ? dir + name : dir + "/" + name;
}

}  // namespace rp::scene::gltf
