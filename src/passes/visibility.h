// Compute rasterizer: triangles of all instances plus analytic spheres -> visibility buffer,
// and the same rasterizer depth-only from the lamp -> shadow map.
#pragma once

#include <memory>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"

namespace rp::passes {

class VisibilityPass {
 public:
  VisibilityPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs);

  // Camera view (FrameConstants.view_proj, width x height of `out`). Instances whose world
  // bounds (GpuScene::host_instance_bounds) lie outside FrameConstants.view_proj_unjittered's
  // frustum, widened by two pixels, are not set up. Pass name "visibility".
  void render(rp::cl::Profiler& profiler, const render::GpuScene& scene,
              render::VisibilityBuffer& out);

  // Lamp view (FrameConstants.light_view_proj), only instances and spheres that cast shadows,
  // depth only. Pass name "shadow_map".
  void render_shadow(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                     render::ShadowMap& out);

  // The punctual lights' shadow views (FrameConstants.shadow_views, render/punctual_shadows.h)
  // into `out`'s depth buffer after the lamp's planes, which it grows to hold them. Depth only,
  // the shadow casters. Pass name "shadow_map_lights". Nothing when the frame has no views, or
  // when its views, instances and spheres are those the maps were last drawn with (a static
  // scene under fixed lights draws them once).
  void render_light_shadows(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                            render::ShadowMap& out);

  // The raster's tile lists for a width x height view (counts, start, cursor: a uint per tile
  // for triangles and one for spheres; passes/frame_memory.h), and what the camera's and the
  // lamp's views hold now (they only grow). The triangle lists follow the scene.
  static uint64_t tile_list_bytes(uint32_t width, uint32_t height);
  // Triangles the camera view set up in its last render (its draw list, after the culling).
  uint32_t camera_triangles() const;
  uint64_t camera_tile_bytes() const;
  uint64_t lamp_tile_bytes() const;

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace rp::passes
