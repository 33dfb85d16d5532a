#include "app/png_output.h"

#include <cstdio>
#include <stdexcept>
#include <string_view>

#include <stb/stb_image_write.h>

#include "io/atomic_file.h"
#include "io/output_path.h"

namespace rp::app {
namespace {

// stbi_write_png_to_func's sink: appends each encoded piece to a std::string.
void append_to_string(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

}  // namespace

std::string frame_file_name(uint32_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04u.png", index);
  return name;
}

void write_png_atomic(const std::filesystem::path& path, int width, int height,
                      const std::vector<uint8_t>& rgba) {
  if (width <= 0 || height <= 0 || rgba.size() != size_t(width) * size_t(height) * 4)
    throw std::runtime_error("cannot write " + path.string() + ": image size mismatch");
  // Encoding to memory, not to the file: stbi_write_png reports only a failed open, so a full
  // disk would pass unnoticed; io::write_file checks every write.
  std::string png;
  if (!stbi_write_png_to_func(append_to_string, &png, width, height, 4, rgba.data(), width * 4))
    throw std::runtime_error("cannot write " + path.string() + ": PNG encoding failed");
  io::write_file(path, png);
}

void write_text_atomic(const std::filesystem::path& path, const std::string& text) {
  io::write_file(path, text);
}

void ensure_directory(const std::filesystem::path& dir) { io::ensure_directory(dir); }

}  // namespace rp::app
