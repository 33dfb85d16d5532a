// OpenEXR files of the path tracer's (and the renderer's) linear components: one file per frame,
// 32-bit float channels, uncompressed-friendly ZIP compression. Layout: the combined image as the
// default layer (channels R, G, B, so any viewer shows it), then one layer per further component
// ("direct.R", "direct.G", "direct.B", "indirect.*", "emission.*", "albedo.*").
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rp::truth {

// A named linear RGB layer: 3 floats per pixel, row-major, top row first.
struct ExrLayer {
  std::string name;                 // "" = the default layer (R, G, B)
  const std::vector<float>* rgb = nullptr;
};

// Encodes the layers (each width * height * 3 floats) in memory, reads them back to check, and
// writes the file with io::write_file (src/io/atomic_file.h: checked writes, temporary + rename):
// readers see the whole file or none. Throws std::runtime_error "cannot write EXR PATH: REASON"
// (the library's or the system's reason, e.g. "No space left on device"); no temporary remains.
void write_exr_atomic(const std::filesystem::path& path, uint32_t width, uint32_t height,
                      const std::vector<ExrLayer>& layers);

// Reads one layer ("" = R, G, B) of an EXR file into 3 floats per pixel. Throws
// std::runtime_error naming the file when it cannot be read or lacks the layer.
std::vector<float> read_exr_layer(const std::filesystem::path& path, const std::string& layer,
                                  uint32_t& width, uint32_t& height);

}  // namespace rp::truth
