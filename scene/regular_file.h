// Reading input files safely: only regular files, checked with stat() before they are opened
// (opening a FIFO for reading blocks until a writer appears; a device may never end), read with
// the size known beforehand. Used by the glTF loader and the texture loader.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rp::scene {

// A regular file's size, and its bytes (at most `max_bytes` of them). Directories, FIFOs,
// devices and sockets are refused after stat() and before open(). On failure these return
// false and say why (the system's reason, "is a directory", ...).
bool regular_file_size(const std::string& path, uint64_t* size, std::string* why);
bool read_regular_file(const std::string& path, uint64_t max_bytes, std::vector<uint8_t>* out,
                       std::string* why);
// The first `want` bytes of a regular file (whose size was checked to be at least that).
bool read_file_start(const std::string& path, uint64_t want, std::vector<uint8_t>* out,
                     std::string* why);

}  // namespace rp::scene
