// The one way rolypoly writes a file: the bytes are produced in memory first (PNG, EXR, JSON,
// SVG, Markdown, input logs), then handed to write_file, which checks every system call, so a
// full disk or an I/O error is an error naming the file and the system's reason, never a
// silently short file.
#pragma once

#include <filesystem>
#include <string_view>

namespace rp::io {

// Writes `bytes` as the whole content of `path`, as output_path.h decides for that path:
//  - a regular file (or none yet, or a symlink to one): a temporary beside the real file,
//    write loop, fsync, close, rename over it (then the folder is fsynced); readers see the old
//    file or the whole new one, and an existing file keeps its permission bits;
//  - a character device or FIFO: opened and written in place (appending); /dev/stdout,
//    /dev/fd/N: written through a dup of our descriptor N, at its offset (our stdout is flushed
//    first). SIGPIPE is turned into an EPIPE error for this write.
// On failure no temporary remains and the target is untouched (replace) or holds what was
// written before the error (in place). Throws io::WriteError "cannot write PATH: REASON"
// with the system's reason (strerror), or resolve_output's refusal for a directory, socket or
// block device.
//
// Test hook, read on every call in all builds: with ROLYPOLY_FAIL_WRITE_AFTER=N in the
// environment, writes fail with ENOSPC ("No space left on device") once N bytes in all have
// been written by this process, as on a disk that fills up.
void write_file(const std::filesystem::path& path, std::string_view bytes);

}  // namespace rp::io
