#include "passes/tone_map.h"

#include "cl/error.h"
#include "cl/kernel_args.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"

namespace rp::passes {
namespace {

// 1D, one work-item per 16 pixels (see kernels/tone_map.cl), 64 work-items per group.
constexpr size_t kPixelsPerItem = 16;
constexpr size_t kGroup = 64;

}  // namespace

ToneMapPass::ToneMapPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                         bool dither)
    : kernel_(programs.kernel("tone_map.cl", "tone_map_output")), dither_(dither) {
  // The kernel packs R into the low byte of each uint (RGBA8 in memory on little-endian).
  if (!context.info.device.getInfo<CL_DEVICE_ENDIAN_LITTLE>())
    throw rp::cl::Error("tone map: device '" + context.info.name +
                        "' is big-endian; the RGBA8 output assumes a little-endian device");
}

void ToneMapPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                      const ::cl::Buffer& hdr, uint32_t pixels, ::cl::Buffer& rgba8) {
  if (pixels == 0) return;
  gpu::ToneMapParams params{};
  params.pixel_count = pixels;
  params.dither = dither_ ? 1u : 0u;
  params.frame = scene.constants.frame_index;
  rp::cl::bind_args(kernel_, hdr, rgba8, params);
  const size_t items = (size_t(pixels) + kPixelsPerItem - 1) / kPixelsPerItem;
  profiler.enqueue(pass_name::kToneMap, kernel_, ::cl::NDRange(rp::cl::round_up(items, kGroup)),
                   ::cl::NDRange(kGroup));
}

}  // namespace rp::passes
