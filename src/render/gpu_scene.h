// The scene on the device: static assets uploaded once, per-frame instances, spheres and
// constants rewritten each frame into buffers that only grow (no per-frame allocation).
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <CL/opencl.hpp>
#include <glm/glm.hpp>

#include "io/fnv1a.h"
#include "render/gpu_types.h"
#include "render/punctual_shadows.h"
#include "scene/frame_scene.h"

namespace rp::render {

// Radical inverse of `index` in `base` (the Halton sequence): index 1, 2, 3, ... in base 2 gives
// 1/2, 1/4, 3/4, 1/8, ...; in base 3: 1/3, 2/3, 1/9, ... Index 0 gives 0.
float halton(uint32_t index, uint32_t base);

// TAA sub-pixel jitter of a frame, in pixels (+x right, +y down, types.h): the Halton(2,3)
// point number (frame_index % jitter_frames) + 1 minus 0.5, so each offset lies in (-0.5, 0.5).
// jitter_frames = 0 turns jitter off (returns 0). The jittered view_proj moves every projected
// point by exactly this many pixels.
glm::vec2 taa_jitter_px(uint32_t frame_index, uint32_t jitter_frames);

// `view_proj` followed by a clip-space translation that moves projected points by `jitter_px`
// pixels on a width x height screen (pixel y grows downwards, NDC y upwards).
glm::mat4 jittered_view_proj(const glm::mat4& view_proj, glm::vec2 jitter_px, uint32_t width,
                             uint32_t height);

struct MeshRange {
  uint32_t first_triangle = 0;
  uint32_t triangle_count = 0;
  int proxy = -1;  // scene::Mesh::proxy, proxy_max_voxels and proxy_max_shadow_texels
  uint32_t proxy_max_voxels = 0;
  uint32_t proxy_max_shadow_texels = 0;
  uint32_t first_vertex = 0;  // the mesh's first vertex in the shared vertex buffer
  uint32_t vertex_count = 0;
  glm::vec3 lo{1.0f}, hi{-1.0f};  // the vertices' bounds in the mesh's space (none: lo > hi)
};

// Throws rp::cl::Error naming the largest texture, the need and the limit when the textures
// with their mip chains do not fit the device: 4 bytes per texel (packed sRGB, in one buffer,
// so all of them must fit `max_alloc_bytes`).
// GpuScene checks this before building the chains; 0 = the driver did not say.
void check_texture_memory(const std::vector<scene::Texture>& textures, uint64_t max_alloc_bytes,
                          uint64_t global_mem_bytes);

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
  // jitter_frames: length of the TAA jitter cycle (16 with TAA on, SPEC 6.7); 0 = no jitter.
  // With jitter, view_proj and inv_view_proj carry taa_jitter_px(frame.frame_index,
  // jitter_frames); view_proj_unjittered / prev_view_proj_unjittered never do.
  // FrameConstants.jitter = (this update's jitter, the previous update's jitter) in pixels.
  void update(const scene::FrameScene& frame, uint32_t width, uint32_t height,
              uint32_t shadow_size, uint32_t voxel_resolution = 64, uint32_t jitter_frames = 0);

  // Static data.
  ::cl::Buffer vertices;   // gpu::Vertex[vertex_count]
  ::cl::Buffer triangles;  // gpu::Triangle[triangle_count], vertex indices are global
  // float4 per vertex, parallel to `vertices`: a file's tangent frame (scene::Mesh::tangents;
  // zero where none); one element only when no material has per-texel maps.
  ::cl::Buffer tangents;
  // Some material has a normal, metallic-roughness or emission map: the GBuffer's material
  // pass (kernels/gbuffer_material.cl) runs.
  bool has_material_maps = false;
  // Some material cuts holes (alpha mask): the rasterizer, shadow maps and voxelizer test
  // texture alpha (kernels/common/alpha_mask.h).
  bool has_alpha_masks = false;
  // Wall-clock milliseconds the constructor spent on the textures' mip chains (set-up times).
  double mips_ms = 0.0;
  ::cl::Buffer materials;  // gpu::Material[]
  // uint RGBA8 (R in the low byte, sRGB rgb), all textures back to back, each followed by its
  // mip levels (render/texture_mips.h; 4/3 of the level-0 texels for square textures).
  ::cl::Buffer texels;
  ::cl::Buffer textures;   // gpu::TextureInfo[]: size, level count and level offsets
  // float4[RP_BRDF_TABLE_SIZE^2]: the surface model's Kulla-Conty tables
  // (kernels/shared/brdf_layout.h, shading::BrdfTables), read by the light pass.
  ::cl::Buffer brdf_table;
  uint32_t vertex_count = 0, triangle_count = 0;
  std::vector<MeshRange> meshes;
  // The mesh whose triangles the voxelizer takes for `mesh` at `voxel_resolution`, and the one
  // a shadow map of `shadow_size` texels draws: its proxy up to the proxy's resolutions, else
  // the mesh itself (scene::voxel_mesh, scene::shadow_mesh).
  uint32_t voxel_mesh(uint32_t mesh, uint32_t voxel_resolution) const;
  uint32_t shadow_mesh(uint32_t mesh, uint32_t shadow_size) const;

  // The region `frame`'s instances and spheres occupy (unsnapped, unclipped; empty without
  // either): where the directional lights' shadow views look.
  ShadowBounds frame_bounds(const scene::FrameScene& frame) const;

  // Per frame.
  ::cl::Buffer frame;      // gpu::FrameConstants (one)
  ::cl::Buffer instances;  // gpu::Instance[instance_count] (capacity may be larger)
  ::cl::Buffer spheres;    // gpu::Sphere[sphere_count] (capacity may be larger)
  // The frame's environment map and its mip chain (render/sky_texture.h; one unused texel
  // without one), uploaded when the frame's map changes; FrameConstants.sky places its levels.
  ::cl::Buffer sky;
  // The map seen directly (kernels/sky.cl): `sky` itself, or where suns were taken out of
  // what the cones gather (scene::Environment::residual), the whole map's level 0 alone, laid
  // out as `sky`'s.
  ::cl::Buffer sky_seen;
  // Whether the diffuse cones add the sky (FrameConstants.sky.diffuse_cones; on by default):
  // off where precomputed radiance transfer carries the diffuse sky (passes/prt_sky.h).
  void set_sky_diffuse_cones(bool on) { sky_diffuse_cones_ = on; }
  // Whether the GI volume takes the suns' light: off, it leaves the environment's suns
  // (scene::PunctualLight::in_environment) and the directional lights out
  // (RP_LIGHT_NOT_IN_VOXELS), where PRT gathers their bounces (passes/prt_sky.h).
  void set_suns_in_voxels(bool on) { suns_in_voxels_ = on; }
  uint32_t instance_count = 0, sphere_count = 0;
  uint32_t instance_triangle_count = 0;  // sum of triangle_count over instances
  uint32_t voxel_triangle_count = 0;     // sum of voxel_triangle_count over instances
  gpu::FrameConstants constants{};
  // This frame's punctual lights and shadow views (also in `constants`), for the shadow pass.
  PunctualSetup punctual;
  std::vector<gpu::Instance> host_instances;
  // Per instance, its mesh's bounds in world space (8 corners transformed; lo > hi: an empty
  // mesh): what the camera's rasterizer tests against its frustum.
  std::vector<std::pair<glm::vec3, glm::vec3>> host_instance_bounds;
  std::vector<gpu::Sphere> host_spheres;

  // Adds to `h` what light reaches the scene's surfaces from and what is lit: the lamp (position,
  // intensity, shadow projection and planes), the punctual lights and their shadow views, every
  // instance and sphere (the shadow maps are drawn from these). The voxelizer's cached direct
  // light and the kept GI volume (render/still_volume.h) are keyed by it.
  void hash_lights_and_objects(io::Fnv1a& h) const;

 private:
  ::cl::Context context_;
  ::cl::CommandQueue queue_;
  size_t instance_capacity_ = 0, sphere_capacity_ = 0;
  void update_sky(const scene::Environment& environment);
  bool sky_diffuse_cones_ = true;
  bool suns_in_voxels_ = true;
  std::shared_ptr<const scene::EnvironmentMap> sky_map_;  // the map `sky` holds (nullptr: none)
  std::shared_ptr<const scene::EnvironmentMap> sky_seen_map_;  // the one `sky_seen` shows
  gpu::SkyGpu sky_info_{};
  glm::vec2 last_jitter_px_{0.0f};  // the jitter the previous update() used (0 before the first)
};

}  // namespace rp::render
