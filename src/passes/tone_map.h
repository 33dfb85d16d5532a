// Tone map + sRGB encode + dithered 8-bit quantise: HDR float4 -> RGBA8 (uint per pixel, R in
// the low byte, A = 255). Pass name "tone_map".
#pragma once

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "render/gpu_scene.h"

namespace rp::passes {

class ToneMapPass {
 public:
  // dither: add per-pixel, per-frame noise of one code before quantising (no banding); false
  // rounds to nearest (exact comparisons in tests).
  ToneMapPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs, bool dither = true);
  // hdr and rgba8 hold `pixels` pixels (the output size, which the render scale may make
  // larger than scene.constants' render size).
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene, const ::cl::Buffer& hdr,
           uint32_t pixels, ::cl::Buffer& rgba8);

 private:
  ::cl::Kernel kernel_;
  bool dither_;
};

}  // namespace rp::passes
