// Shadow filter pass: the shadow map's mip chain of linear light depth (min, and for VSSM the
// depth moments; layout kernels/shared/shadow_mips.h, kernels/shadow_filter.cl), which the light
// pass's soft shadows read. One launch per level (7 for a 1024^2 map). Pass name
// "shadow_filter".
#pragma once

#include <optional>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"

namespace rp::passes {

class ShadowFilterPass {
 public:
  // Kernels build on first use.
  ShadowFilterPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs);

  // Builds shadow.mips from shadow.depth (size checked against the frame constants): the MIN
  // plane, and with `moments` also MEAN and MEAN2. Enqueues only; (re)allocates shadow.mips when
  // the size or plane count changes (a 1x1 map has no levels: one dummy float, nothing
  // enqueued).
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene, render::ShadowMap& shadow,
           bool moments);

  // Device memory of shadow.mips for a size x size map with `planes` planes (1 for pcss, 3
  // for vssm; passes/frame_memory.h). The buffer belongs to the ShadowMap.
  static uint64_t frame_bytes(uint32_t size, uint32_t planes);

 private:
  const rp::cl::Context* context_;
  rp::cl::ProgramCache* programs_;
  std::optional<::cl::Kernel> first_[2], next_[2];  // [moments]
  uint32_t allocated_size_ = 0;  // shadow.size the buffer was made for
};

}  // namespace rp::passes
