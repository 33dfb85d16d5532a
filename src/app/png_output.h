// PNG and text output that never leaves a half-written file behind: the bytes are made in
// memory, then written by io::write_file (checked writes, temporary + rename; see
// src/io/atomic_file.h and src/io/output_path.h for devices, FIFOs and symlinks).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rp::app {

// "frame_0000.png", "frame_0001.png", ... (at least four digits).
std::string frame_file_name(uint32_t index);

// Encodes `rgba` (width * height * 4 bytes, top row first) as a PNG in memory and writes it with
// io::write_file: readers see either nothing (or the old file) or the whole new file.
// Throws std::runtime_error naming the file and the reason (e.g. "No space left on device").
void write_png_atomic(const std::filesystem::path& path, int width, int height,
                      const std::vector<uint8_t>& rgba);

// Creates `dir` (and parents) if needed and checks it accepts new files; throws
// std::runtime_error naming it on failure or when it exists but is not a directory.
void ensure_directory(const std::filesystem::path& dir);

// Writes `text` to `path` with io::write_file (same guarantee as write_png_atomic).
void write_text_atomic(const std::filesystem::path& path, const std::string& text);

}  // namespace rp::app
