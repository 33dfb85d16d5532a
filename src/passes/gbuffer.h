// GBuffer resolve: visibility buffer -> albedo, normal + linear depth, position, emission,
// velocity. Pass name "gbuffer".
#pragma once

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"

namespace rp::passes {

class GBufferPass {
 public:
  GBufferPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs);
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
           const render::VisibilityBuffer& vis, render::GBuffer& out);

 private:
  ::cl::Kernel kernel_;
};

}  // namespace rp::passes
