#include "app/scene_memory.h"

#include <algorithm>
#include <cstdio>

#include "render/texture_mips.h"

namespace rp::app {

uint64_t SceneMemory::largest_buffer_bytes() const {
  return std::max({vertices * 32, triangles * kTriangleBytes, texels * kTexelBytes,
                   sky_texels * kSkyTexelBytes, prt_floats * 4});
}

std::string SceneMemory::describe() const {
  char text[160];
  std::snprintf(text, sizeof text,
                "%llu vertices, %llu triangles, %llu textures (%.0f MiB of texels with their "
                "mipmaps)",
                static_cast<unsigned long long>(vertices),
                static_cast<unsigned long long>(triangles),
                static_cast<unsigned long long>(textures),
                double(texels * kTexelBytes) / double(1 << 20));
  std::string out = text;
  if (sky_texels > 0)
    out += ", the sky's map (" +
           std::to_string((sky_texels * kSkyTexelBytes + (1u << 20) - 1) >> 20) +
           " MiB with its mipmaps)";
  if (prt_floats > 0)
    out += ", the PRT transfer (" + std::to_string((prt_floats * 4 + (1u << 20) - 1) >> 20) +
           " MiB)";
  return out;
}

SceneMemory count_scene_memory(const scene::SceneAssets& assets) {
  SceneMemory m;
  for (const scene::Mesh& mesh : assets.meshes) {
    m.vertices += mesh.vertices.size();
    m.triangles += mesh.triangles.size();
  }
  m.textures = assets.textures.size();
  for (const scene::Texture& t : assets.textures) {
    const uint32_t w = uint32_t(std::max(t.width, 1)), h = uint32_t(std::max(t.height, 1));
    for (uint32_t k = 0; k < render::mip_level_count(w, h); ++k)
      m.texels += uint64_t(std::max(1u, w >> k)) * std::max(1u, h >> k);
  }
  return m;
}

}  // namespace rp::app
