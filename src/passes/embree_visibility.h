// Second visibility backend: Embree primary rays traced on the host, written into the same
// render::VisibilityBuffer the compute rasterizer fills (kernels/visibility.cl), then uploaded.
// Everything after the visibility pass is shared between the two backends.
//
// Conventions matched with the rasterizer (kernels/visibility.cl, kernels/shared/types.h):
//   rays     one per pixel centre (x + 0.5, y + 0.5), pixel y down, from the near plane
//            (z_ndc = -1) towards the far plane (z_ndc = +1) through FrameConstants.inv_view_proj
//            (the jittered matrix, the same rays the rasterizer uses for analytic spheres);
//            t in [0, |far - near|], so hits in front of the near plane or behind the far plane
//            are rejected as the rasterizer's z_ndc >= -1 test and depth clear to 1 do.
//   depth    z_ndc * 0.5 + 0.5 with z_ndc = (z_o + t z_d) / (w_o + t w_d), clip z and w being
//            linear along the ray; for spheres t is recomputed with the rasterizer's float
//            formula, so sphere depths match it to rounding.
//   ids      (instance, triangle index in its mesh); spheres RP_ID_SPHERE_BIT | index, 0;
//            background RP_ID_NONE twice, depth 1.
//   bary     Embree's (u, v) = weights of the triangle's 2nd and 3rd vertex (the vertex order
//            is the mesh's), (0, 0) for spheres and background.
// Exact ties (two surfaces at the same depth) and pixel centres exactly on an edge may resolve
// differently from the rasterizer's (z, instance, primitive) order and top-left rule.
//
// Scene layout (Embree 3, one instance level):
//   one RTCScene per mesh (RTC_BUILD_QUALITY_HIGH, built once);
//   a static scene (HIGH) holding every instance whose model is exactly the identity (the box
//   and the lamp), one triangle geometry each, rebuilt only when that set changes;
//   the top-level scene (LOW, dynamic): the static scene instanced once, one instance geometry
//   per moving instance (transform updated per frame), and all spheres as one native
//   RTC_GEOMETRY_TYPE_SPHERE_POINT geometry (float4 centre + radius, rewritten per frame).
// Steady frames allocate nothing: host vectors and Embree geometries only grow.
//
// Threads: 4x4 pixel tiles traced with rtcIntersect16 by a pool of hardware_concurrency()
// threads (the caller included) that take rows of tiles from an atomic counter. Each pixel is
// written by exactly one ray, so the output does not depend on the schedule.
//
// The shadow map stays on the rasterizer (VisibilityPass::render_shadow) with either backend.
#pragma once

#include <memory>

#include "cl/context.h"
#include "cl/profiler.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"
#include "scene/frame_scene.h"

namespace rp::passes {

class EmbreeVisibilityPass {
 public:
  // Copies the meshes of `assets` (the same assets, in the same order, the GpuScene was built
  // from) and builds one BVH per mesh. threads = 0: std::thread::hardware_concurrency().
  // Throws rp::cl::Error when Embree cannot create a device or a geometry.
  EmbreeVisibilityPass(const rp::cl::Context& context, const scene::SceneAssets& assets,
                       unsigned threads = 0);
  ~EmbreeVisibilityPass();
  EmbreeVisibilityPass(const EmbreeVisibilityPass&) = delete;
  EmbreeVisibilityPass& operator=(const EmbreeVisibilityPass&) = delete;

  // Updates the Embree scene from `scene` (instances, spheres, constants of the last
  // GpuScene::update), traces every pixel of `out` on the host and uploads the three planes
  // (non-blocking writes recorded under pass name "visibility"). Returns the host time in ms
  // (scene update + BVH commit + tracing), which no profiling event covers.
  double render(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                render::VisibilityBuffer& out);

  unsigned threads() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rp::passes
