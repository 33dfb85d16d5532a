// What a scene puts on the device (render/gpu_scene.cpp's buffers), counted from its assets
// before anything is uploaded, so that the device memory check (render_session.h) can name a
// loaded scene that is too large by its sizes instead of failing in clCreateBuffer.
#pragma once

#include <cstdint>
#include <string>

#include "scene/frame_scene.h"

namespace rp::app {

struct SceneMemory {
  uint64_t vertices = 0, triangles = 0, textures = 0;
  uint64_t texels = 0;  // every texture's mip chain, 4 bytes a texel on the device
  uint64_t sky_texels = 0;  // the environment map's chain (render/sky_texture.h), float4 each
  // --sky-light prt: the transfer's floats (passes/prt_sky.h), counted as one transfer per
  // mesh vertex (a file's meshes are mostly placed once)
  uint64_t prt_floats = 0;
  // The punctual lights' shadow views (render/punctual_shadows.h) at the session's shadow
  // size: they follow the lamp's two planes in its one depth buffer. Counted from the first
  // frame (the lights are the frame's, not the assets').
  uint64_t light_shadow_bytes = 0;
  // Bytes per element on the device: gpu::Vertex (2 float4) + its tangent (float4), one
  // gpu::Triangle (4 uint).
  static constexpr uint64_t kVertexBytes = 32 + 16, kTriangleBytes = 16, kTexelBytes = 4;
  static constexpr uint64_t kSkyTexelBytes = 16;
  uint64_t bytes() const {
    return vertices * kVertexBytes + triangles * kTriangleBytes + texels * kTexelBytes +
           sky_texels * kSkyTexelBytes + prt_floats * 4;
  }
  // The largest of the scene's buffers: vertices (32 bytes each), triangles, texels, sky or
  // PRT transfer.
  uint64_t largest_buffer_bytes() const;
  // "1200000 vertices, 2400000 triangles, 3 textures (1.3 GiB of texels with their mipmaps)"
  std::string describe() const;
};

SceneMemory count_scene_memory(const scene::SceneAssets& assets);

}  // namespace rp::app
