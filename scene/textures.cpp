#include "scene/textures.h"

#include <memory>
#include <vector>

#include <stb/stb_image.h>

#include "scene/asset_error.h"
#include "scene/regular_file.h"

namespace rp::scene {

namespace {
constexpr uint64_t kMaxTextureFileBytes = uint64_t(1) << 30;
}  // namespace

Texture load_texture(const std::string& path, const std::string& name) {
  // Read here, not by stb_image: a FIFO or device is refused before it is opened (it would
  // block or never end), and a file that does not open says why in the system's words (stb
  // knows only "can't fopen").
  std::vector<uint8_t> file;
  std::string why;
  if (!read_regular_file(path, kMaxTextureFileBytes, &file, &why))
    throw AssetError("cannot load texture '" + name + "' from " + path + ": " + why);
  int width = 0, height = 0, channels_in_file = 0;
  // The implementation lives in libstb (Debian's libstb-dev), so no STB_IMAGE_IMPLEMENTATION.
  std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> pixels(
      stbi_load_from_memory(file.data(), int(file.size()), &width, &height, &channels_in_file,
                            4),
      &stbi_image_free);
  if (!pixels) {
    const char* reason = stbi_failure_reason();
    throw AssetError("cannot load texture '" + name + "' from " + path + ": " +
                     (reason ? reason : "unknown error"));
  }
  Texture texture;
  texture.name = name;
  texture.width = width;
  texture.height = height;
  const size_t bytes = static_cast<size_t>(width) * static_cast<size_t>(height) * 4;
  texture.rgba.assign(pixels.get(), pixels.get() + bytes);
  return texture;
}

}  // namespace rp::scene
