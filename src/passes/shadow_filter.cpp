#include "passes/shadow_filter.h"

#include <algorithm>
#include <string>

#include "cl/error.h"
#include "cl/kernel_args.h"
#include "kernels/shared/shadow_mips.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 8;  // 8x8 work-groups

::cl::NDRange square(uint32_t n) {
  const size_t g = rp::cl::round_up(n, kGroup);
  return ::cl::NDRange(g, g);
}

}  // namespace

ShadowFilterPass::ShadowFilterPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs)
    : context_(&context), programs_(&programs) {}

uint64_t ShadowFilterPass::frame_bytes(uint32_t size, uint32_t planes) {
  return std::max<uint64_t>(uint64_t(gpu::rp_shadow_mip_total(size)) * planes, 1) * sizeof(float);
}

void ShadowFilterPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                           render::ShadowMap& shadow, bool moments) {
  if (shadow.size != scene.constants.shadow_size)
    throw rp::cl::Error("shadow filter pass: shadow map is " + std::to_string(shadow.size) +
                        " texels wide but the frame constants say " +
                        std::to_string(scene.constants.shadow_size));
  const uint32_t size = shadow.size, levels = gpu::rp_shadow_mip_levels(size);
  const uint32_t planes = moments ? 3u : 1u;
  const uint32_t plane = gpu::rp_shadow_mip_total(size);
  if (allocated_size_ != size || shadow.mip_planes != planes || shadow.mips() == nullptr) {
    shadow.mips =
        ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, size_t(frame_bytes(size, planes)));
    shadow.mip_planes = planes;
    allocated_size_ = size;
  }
  if (levels == 0) return;
  std::optional<::cl::Kernel>& first = first_[moments];
  std::optional<::cl::Kernel>& next = next_[moments];
  if (!first) {
    const std::string options = moments ? "-DRP_SHADOW_MOMENTS=1" : "";
    first = programs_->kernel("shadow_filter.cl", "shadow_filter_first", options);
    next = programs_->kernel("shadow_filter.cl", "shadow_filter_next", options);
  }
  const uint32_t n1 = gpu::rp_shadow_mip_size(size, 1);
  gpu::ShadowMipStep step{};
  step.src_size = size;
  step.dst_size = n1;
  step.plane = plane;
  rp::cl::bind_args(*first, scene.frame, shadow.depth, shadow.mips, step);
  profiler.enqueue(pass_name::kShadowFilter, *first, square(n1), ::cl::NDRange(kGroup, kGroup));
  for (uint32_t l = 2; l <= levels; ++l) {
    const uint32_t m = gpu::rp_shadow_mip_size(size, l - 1), n = gpu::rp_shadow_mip_size(size, l);
    gpu::ShadowMipStep level{};
    level.src_offset = gpu::rp_shadow_mip_offset(size, l - 1);
    level.src_size = m;
    level.dst_offset = gpu::rp_shadow_mip_offset(size, l);
    level.dst_size = n;
    level.plane = plane;
    rp::cl::bind_args(*next, shadow.mips, level);
    profiler.enqueue(pass_name::kShadowFilter, *next, square(n), ::cl::NDRange(kGroup, kGroup));
  }
}

}  // namespace rp::passes
