// Files that are complete or absent: io::write_file (atomic_file.h) writes every output (PNG,
// EXR, JSON, logs) to a hidden temporary name next to the target and renames it over the target
// when complete; the output folder checks (output_path.h) probe with the same kind of name.
#pragma once

#include <filesystem>
#include <string>

#include <unistd.h>

namespace rp::io {

// ".<name>.tmp<pid>" in the target's folder: rename is atomic only within one file system,
// and the pid keeps two processes writing the same target apart.
inline std::filesystem::path temporary_for(const std::filesystem::path& path) {
  // Appending to one string (rather than "." + name + ...) also avoids a GCC 12 -Wrestrict
  // false positive on operator+(const char*, std::string&&).
  std::string name = ".";
  name += path.filename().string();
  name += ".tmp";
  name += std::to_string(getpid());
  std::filesystem::path tmp = path;
  tmp.replace_filename(name);
  return tmp;
}

}  // namespace rp::io
