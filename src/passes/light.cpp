#include "passes/light.h"

#include <string>

#include "cl/error.h"
#include "kernels/shared/voxel_layout.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 16;  // 16x16 work-groups (see gbuffer.cpp)

bool is_power_of_two(uint32_t v) { return v != 0 && (v & (v - 1)) == 0; }

uint32_t log2_exact(uint32_t v) {
  uint32_t l = 0;
  while ((1u << l) < v) ++l;
  return l;
}

// Binds the arguments shared by every variant up to and including the voxel chain; returns the
// next argument index.
cl_uint bind_common(::cl::Kernel& kernel, const render::GpuScene& scene,
                    const render::GBuffer& gbuffer, const render::ShadowMap& shadow,
                    const ::cl::Buffer& voxels, uint32_t resolution, uint32_t levels) {
  cl_uint arg = 0;
  kernel.setArg(arg++, scene.frame);
  kernel.setArg(arg++, gbuffer.albedo);
  kernel.setArg(arg++, gbuffer.normal_depth);
  kernel.setArg(arg++, gbuffer.position);
  kernel.setArg(arg++, gbuffer.emission);
  kernel.setArg(arg++, shadow.depth);
  kernel.setArg(arg++, voxels);
  kernel.setArg(arg++, cl_uint(resolution));
  kernel.setArg(arg++, cl_uint(levels));
  return arg;
}

void enqueue(rp::cl::Profiler& profiler, const ::cl::Kernel& kernel, uint32_t w, uint32_t h) {
  profiler.enqueue("light", kernel,
                   ::cl::NDRange(rp::cl::round_up(w, kGroup), rp::cl::round_up(h, kGroup)),
                   ::cl::NDRange(kGroup, kGroup));
}

}  // namespace

LightPass::LightPass(const rp::cl::Context& /*context*/, rp::cl::ProgramCache& programs,
                     ShadowFilter filter)
    : programs_(&programs),
      filter_options_(filter == ShadowFilter::kPcf5x5 ? "-DRP_SHADOW_PCF5=1" : ""),
      kernel_(programs.kernel("light.cl", "light_shade", filter_options_)) {}

void LightPass::check_sizes(const render::GpuScene& scene, const render::GBuffer& gbuffer,
                            const render::ShadowMap& shadow) const {
  const uint32_t w = scene.constants.width, h = scene.constants.height;
  if (gbuffer.width != w || gbuffer.height != h)
    throw rp::cl::Error("light pass: frame size " + std::to_string(w) + "x" + std::to_string(h) +
                        " does not match the GBuffer (" + std::to_string(gbuffer.width) + "x" +
                        std::to_string(gbuffer.height) + ")");
  if (shadow.size != scene.constants.shadow_size)
    throw rp::cl::Error("light pass: shadow map is " + std::to_string(shadow.size) +
                        " texels wide but the frame constants say " +
                        std::to_string(scene.constants.shadow_size));
}

void LightPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                    const render::GBuffer& gbuffer, const render::ShadowMap& shadow,
                    const ::cl::Buffer& voxels, uint32_t voxel_resolution,
                    uint32_t voxel_levels, ::cl::Buffer& hdr, LightComponents* components) {
  check_sizes(scene, gbuffer, shadow);
  if (!is_power_of_two(voxel_resolution) || voxel_resolution < 2 || voxel_resolution > 1024)
    throw rp::cl::Error("light pass: voxel resolution " + std::to_string(voxel_resolution) +
                        " is not a power of two between 2 and 1024");
  const uint32_t max_levels = log2_exact(voxel_resolution) + 1;
  if (voxel_levels < 1 || voxel_levels > max_levels)
    throw rp::cl::Error("light pass: " + std::to_string(voxel_levels) +
                        " voxel levels for resolution " + std::to_string(voxel_resolution) +
                        " (expected 1.." + std::to_string(max_levels) + ")");
  const size_t needed = size_t(gpu::rp_voxel_total(voxel_resolution, voxel_levels)) * 16;
  const size_t have = voxels.getInfo<CL_MEM_SIZE>();
  if (have < needed)
    throw rp::cl::Error("light pass: the voxel buffer holds " + std::to_string(have) +
                        " bytes but " + std::to_string(voxel_resolution) + "^3 with " +
                        std::to_string(voxel_levels) + " levels needs " + std::to_string(needed));
  const uint32_t w = scene.constants.width, h = scene.constants.height;
  if (w == 0 || h == 0) return;

  if (components == nullptr) {
    cl_uint arg = bind_common(kernel_, scene, gbuffer, shadow, voxels, voxel_resolution,
                              voxel_levels);
    kernel_.setArg(arg, hdr);
    enqueue(profiler, kernel_, w, h);
    return;
  }
  const size_t plane = size_t(w) * h * 16;
  if (components->direct.getInfo<CL_MEM_SIZE>() < plane ||
      components->indirect.getInfo<CL_MEM_SIZE>() < plane)
    throw rp::cl::Error("light pass: the direct/indirect buffers must hold " +
                        std::to_string(plane) + " bytes (" + std::to_string(w) + "x" +
                        std::to_string(h) + " float4)");
  if (!split_kernel_)
    split_kernel_ = programs_->kernel("light.cl", "light_shade",
                                      filter_options_ + " -DRP_LIGHT_SPLIT=1");
  ::cl::Kernel& k = *split_kernel_;
  cl_uint arg = bind_common(k, scene, gbuffer, shadow, voxels, voxel_resolution, voxel_levels);
  k.setArg(arg++, components->direct);
  k.setArg(arg++, components->indirect);
  k.setArg(arg, hdr);
  enqueue(profiler, k, w, h);
}

}  // namespace rp::passes
