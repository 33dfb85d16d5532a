// The scene on the device: static assets uploaded once, per-frame instances, spheres and
// constants rewritten each frame into buffers that only grow (no per-frame allocation).
#pragma once

#include <cstdint>
#include <vector>

#include <CL/opencl.hpp>

#include "render/gpu_types.h"
#include "scene/frame_scene.h"

namespace rp::render {

struct MeshRange {
  uint32_t first_triangle = 0;
  uint32_t triangle_count = 0;
};

class GpuScene {
 public:
  // Converts and uploads meshes (all into one vertex and one triangle buffer), materials and
  // textures (one texel buffer, TextureInfo table).
  GpuScene(const ::cl::Context& context, const ::cl::CommandQueue& queue,
           const scene::SceneAssets& assets);

  // Fills FrameConstants, Instance and Sphere arrays from `frame` and writes them (non-blocking
  // writes on `queue`; the host copies stay alive until the next update, so the queue must
  // have finished the previous frame before update() is called again).
  // voxel_resolution: level-0 voxels per side of the GI volume (FrameConstants.voxel_*).
  void update(const scene::FrameScene& frame, uint32_t width, uint32_t height,
              uint32_t shadow_size, uint32_t voxel_resolution = 64);

  // Static data.
  ::cl::Buffer vertices;   // gpu::Vertex[vertex_count]
  ::cl::Buffer triangles;  // gpu::Triangle[triangle_count], vertex indices are global
  ::cl::Buffer materials;  // gpu::Material[]
  ::cl::Buffer texels;     // uint RGBA8 (R in the low byte), all textures back to back
  ::cl::Buffer textures;   // gpu::TextureInfo[]
  uint32_t vertex_count = 0, triangle_count = 0;
  std::vector<MeshRange> meshes;

  // Per frame.
  ::cl::Buffer frame;      // gpu::FrameConstants (one)
  ::cl::Buffer instances;  // gpu::Instance[instance_count] (capacity may be larger)
  ::cl::Buffer spheres;    // gpu::Sphere[sphere_count] (capacity may be larger)
  uint32_t instance_count = 0, sphere_count = 0;
  uint32_t instance_triangle_count = 0;  // sum of triangle_count over instances
  gpu::FrameConstants constants{};
  std::vector<gpu::Instance> host_instances;
  std::vector<gpu::Sphere> host_spheres;

 private:
  ::cl::Context context_;
  ::cl::CommandQueue queue_;
  size_t instance_capacity_ = 0, sphere_capacity_ = 0;
};

}  // namespace rp::render
