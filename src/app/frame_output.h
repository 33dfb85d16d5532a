// What `render` writes per frame besides the PNG (png_output.h): the EXR of the frame's linear
// components, and the closing "wrote ..." line. Shared by the real-time and the path-traced loop.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rp::app {

// "frame_0000.exr", ...: the EXR beside frame_file_name(index).
std::string exr_file_name(uint32_t index);

// Writes the EXR of one frame (truth/exr_io.h): layers "" = combined, "direct", "indirect",
// "emission", "albedo"; each width * height * 3 floats, linear, top row first. Atomic like the
// PNGs; throws std::runtime_error naming the file.
void write_frame_exr(const std::filesystem::path& path, uint32_t width, uint32_t height,
                     const std::vector<float>& combined, const std::vector<float>& direct,
                     const std::vector<float>& indirect, const std::vector<float>& emission,
                     const std::vector<float>& albedo);

// "wrote out/frame_0000.png (WxH)" or "wrote N frames (WxH): out/frame_0000.png ...
// frame_NNNN.png", naming the .exr files too when `exr`.
void print_written(const std::filesystem::path& out_dir, uint32_t frames, uint32_t width,
                   uint32_t height, bool exr);

}  // namespace rp::app
