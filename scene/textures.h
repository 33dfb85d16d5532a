// Loading textures from image files (PNG, via stb_image).
#pragma once

#include <string>

#include "scene/frame_scene.h"

namespace rp::scene {

// Loads an image as RGBA8 (sRGB bytes as stored, rows top to bottom; images without alpha get
// alpha 255). Throws AssetError naming `path` and stb_image's reason when the file is missing or
// cannot be decoded.
Texture load_texture(const std::string& path, const std::string& name);

}  // namespace rp::scene
