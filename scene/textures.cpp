#include "scene/textures.h"

#include <memory>

#include <stb/stb_image.h>

#include "scene/asset_error.h"

namespace rp::scene {

Texture load_texture(const std::string& path, const std::string& name) {
  int width = 0, height = 0, channels_in_file = 0;
  // The implementation lives in libstb (Debian's libstb-dev), so no STB_IMAGE_IMPLEMENTATION.
  // stb_image reports a missing file as "can't fopen"; that is all it knows.
  std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> pixels(
      stbi_load(path.c_str(), &width, &height, &channels_in_file, 4), &stbi_image_free);
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
