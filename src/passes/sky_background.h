// The environment seen directly: the real-time modes' background (kernels/sky.cl) written into
// the light pass's HDR output where the GBuffer is uncovered. Runs only for frames with an
// environment (GpuScene::constants.sky.levels > 0); its kernel is built on first use, so scenes
// without a sky compile nothing for it. Pass name "sky".
#pragma once

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"

namespace rp::passes {

class SkyBackgroundPass {
 public:
  explicit SkyBackgroundPass(rp::cl::ProgramCache& programs) : programs_(&programs) {}
  // hdr: float4 per pixel of the render size (scene.constants.width x height), the light pass's
  // output. Enqueues only; nothing when the frame has no environment.
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
           const render::GBuffer& gbuffer, ::cl::Buffer& hdr);

 private:
  rp::cl::ProgramCache* programs_;
  ::cl::Kernel kernel_;
};

}  // namespace rp::passes
