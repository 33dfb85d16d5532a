// PNG output that never leaves a half-written file behind.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rp::app {

// "frame_0000.png", "frame_0001.png", ... (at least four digits).
std::string frame_file_name(uint32_t index);

// Writes `rgba` (width * height * 4 bytes, top row first) as a PNG: first to a temporary file
// next to `path`, then renamed over it, so readers see either nothing or the whole file.
// Throws std::runtime_error naming the file on failure.
void write_png_atomic(const std::filesystem::path& path, int width, int height,
                      const std::vector<uint8_t>& rgba);

// Creates `dir` (and parents) if needed; throws std::runtime_error naming it on failure or when
// it exists but is not a directory.
void ensure_directory(const std::filesystem::path& dir);

// Writes `text` to `path` via a temporary file + rename (same guarantee as write_png_atomic).
void write_text_atomic(const std::filesystem::path& path, const std::string& text);

}  // namespace rp::app
