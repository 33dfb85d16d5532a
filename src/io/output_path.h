// What an output path given by the user is, and so how it may be written, decided from
// lstat/stat alone (never opening it: opening a FIFO would block, opening a tape would rewind).
//
//   regular file, or nothing yet   replaced atomically: a temporary beside it, renamed over it
//   symlink                        followed to its final target, which is then replaced (the
//                                  link stays a link); a dangling link creates its target
//                                  file, but never the folders the target names
//   character device, FIFO         written in place (/dev/null, /dev/full, /dev/tty, a pipe
//                                  whose reader waits): renaming over it would destroy it
//   /dev/stdout, /dev/fd/N, ...    a link in /proc/<pid>/fd names a file already open (a
//                                  pipe, a terminal, the shell's `> file`): written in place,
//                                  whatever it is; our own descriptors through a dup of them
//   directory, socket, block dev   refused: "cannot write PATH: it is a directory"
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace rp::io {

// "cannot write PATH: REASON"; reason() alone for callers that word their own message.
class WriteError : public std::runtime_error {
 public:
  WriteError(const std::filesystem::path& path, const std::string& reason)
      : std::runtime_error("cannot write " + path.string() + ": " + reason), reason_(reason) {}
  const std::string& reason() const { return reason_; }

 private:
  std::string reason_;
};

struct OutputTarget {
  enum class Kind { kReplace, kInPlace };
  Kind kind = Kind::kReplace;
  // kReplace: the file to create or replace (symlinks resolved, so the temporary lands beside
  // the real file); kInPlace: the path to open for writing.
  std::filesystem::path path;
  bool exists = false;  // kReplace: a regular file is there now
  // kInPlace through /proc/self/fd/N (/dev/stdout, /dev/fd/N): our own descriptor N, written
  // through a dup so the write continues at its offset (reopening would start elsewhere, and
  // our later stdout lines would overwrite the file's); -1 otherwise.
  int fd = -1;
  bool via_link = false;  // kReplace: `path` was reached by following a symlink
};

// Classifies `path` (see the table above). Throws WriteError "cannot write PATH: it is
// a directory" (socket, block device, a symlink loop, lstat's error) for paths that cannot be
// written as a file.
OutputTarget resolve_output(const std::filesystem::path& path);

// Creates `dir` (and parents) if needed and proves it accepts a new file by creating and
// removing an empty probe file. Throws std::runtime_error naming `dir` and the system's reason.
void ensure_directory(const std::filesystem::path& dir);

// Before any work: resolve_output(path), then for kReplace ensure_directory on the folder the
// file goes to (a folder named by a symlink's target must exist: a dangling link is no reason
// to create folders elsewhere), for kInPlace access(W_OK) (or, for our own descriptor, that it
// is open for writing). Throws std::runtime_error naming `path` and why.
// `what` names the option in the message ("--json"); empty for none.
void check_output_file(const std::filesystem::path& path, const std::string& what = "");

}  // namespace rp::io
