#include "app/frame_output.h"

#include <cstdio>

#include "app/png_output.h"
#include "truth/exr_io.h"

namespace rp::app {

std::string exr_file_name(uint32_t index) {
  std::filesystem::path name = frame_file_name(index);
  name.replace_extension(".exr");
  return name.string();
}

void write_frame_exr(const std::filesystem::path& path, uint32_t width, uint32_t height,
                     const std::vector<float>& combined, const std::vector<float>& direct,
                     const std::vector<float>& indirect, const std::vector<float>& emission,
                     const std::vector<float>& albedo) {
  rp::truth::write_exr_atomic(path, width, height,
                              {{"", &combined},
                               {"direct", &direct},
                               {"indirect", &indirect},
                               {"emission", &emission},
                               {"albedo", &albedo}});
}

void print_written(const std::filesystem::path& out_dir, uint32_t frames, uint32_t width,
                   uint32_t height, bool exr) {
  const std::string first = (out_dir / frame_file_name(0)).string();
  if (frames == 1 && exr)
    std::printf("wrote %s and %s (%ux%u)\n", first.c_str(),
                (out_dir / exr_file_name(0)).string().c_str(), width, height);
  else if (frames == 1)
    std::printf("wrote %s (%ux%u)\n", first.c_str(), width, height);
  else
    std::printf("wrote %u frames (%ux%u): %s ... %s%s\n", frames, width, height, first.c_str(),
                frame_file_name(frames - 1).c_str(), exr ? ", each with its .exr" : "");
}

}  // namespace rp::app
