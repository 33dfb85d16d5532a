#include "passes/light.h"

#include <string>

#include "cl/error.h"
#include "cl/kernel_args.h"
#include "kernels/shared/svo_layout.h"
#include "kernels/shared/voxel_layout.h"
#include "passes/pass_names.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 16;        // 16x16 work-groups (see gbuffer.cpp)
// light_compose: work-groups of 16 x 4 chunks of 8 pixels (128 x 4 pixels; measured at 720x720
// a little faster than 8x8, 4x16 or 32x4 chunks)
constexpr size_t kComposeGroupX = 16, kComposeGroupY = 4;
// shadow_visibility's `pass` (kernels/shadow_visibility.cl, RP_SHADOW_PASS_*)
constexpr cl_uint kShadowPassAll = 0, kShadowPassBlack = 1, kShadowPassWhite = 2;

bool is_power_of_two(uint32_t v) { return v != 0 && (v & (v - 1)) == 0; }

uint32_t log2_exact(uint32_t v) {
  uint32_t l = 0;
  while ((1u << l) < v) ++l;
  return l;
}

void enqueue(rp::cl::Profiler& profiler, const ::cl::Kernel& kernel, uint32_t w, uint32_t h) {
  profiler.enqueue(pass_name::kLight, kernel,
                   ::cl::NDRange(rp::cl::round_up(w, kGroup), rp::cl::round_up(h, kGroup)),
                   ::cl::NDRange(kGroup, kGroup));
}

}  // namespace

void check_voxel_chain(const char* pass, const ::cl::Buffer& voxels, uint32_t voxel_resolution,
                       uint32_t voxel_levels, bool octree) {
  const std::string name(pass);
  if (!is_power_of_two(voxel_resolution) || voxel_resolution < 2 || voxel_resolution > 1024)
    throw rp::cl::Error(name + ": voxel resolution " + std::to_string(voxel_resolution) +
                        " is not a power of two between 2 and 1024");
  const uint32_t max_levels = log2_exact(voxel_resolution) + 1;
  if (voxel_levels < 1 || voxel_levels > max_levels)
    throw rp::cl::Error(name + ": " + std::to_string(voxel_levels) +
                        " voxel levels for resolution " + std::to_string(voxel_resolution) +
                        " (expected 1.." + std::to_string(max_levels) + ")");
  const size_t needed = octree ? size_t(RP_SVO_HEADER_FLOAT4S) * 16
                              : size_t(gpu::rp_voxel_total(voxel_resolution, voxel_levels)) * 16;
  const size_t have = voxels.getInfo<CL_MEM_SIZE>();
  if (have < needed)
    throw rp::cl::Error(name + ": the voxel buffer holds " + std::to_string(have) +
                        " bytes but " + std::to_string(voxel_resolution) + "^3 with " +
                        std::to_string(voxel_levels) + " levels needs " + std::to_string(needed));
}

LightPass::LightPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                     render::ShadowMode filter, std::string gi_options)
    : context_(&context), programs_(&programs), filter_(filter),
      gi_options_(std::move(gi_options)) {}

::cl::Kernel& LightPass::variant(bool upsample, bool split, bool prt) {
  std::optional<::cl::Kernel>& k = kernels_[upsample][split][prt];
  if (!k) {
    std::string options = split ? "-DRP_LIGHT_SPLIT=1" : "";
    if (prt) options += std::string(options.empty() ? "" : " ") + "-DRP_LIGHT_PRT=1";
    if (!gi_options_.empty()) options += (options.empty() ? "" : " ") + gi_options_;
    k = programs_->kernel("light.cl", upsample ? "light_compose" : "light_shade", options);
  }
  return *k;
}

::cl::Kernel& LightPass::shadow_kernel() {
  // Only pcss samples its penumbrae stochastically: the other filters have one variant.
  const bool more_taps = without_history_ && filter_ == render::ShadowMode::kPcss;
  std::optional<::cl::Kernel>& k = shadow_kernels_[int(filter_)][more_taps ? 1 : 0];
  if (!k)
    k = programs_->kernel(
        "shadow_visibility.cl", "shadow_visibility",
        "-DRP_SHADOW_MODE=" + std::to_string(int(filter_)) +
            (more_taps ? " -DRP_PCSS_FILTER_TAPS=" + std::to_string(kPcssTapsWithoutHistory)
                       : std::string()));
  return *k;
}

uint64_t LightPass::frame_bytes(uint32_t w, uint32_t h, render::ShadowMode filter) {
  const uint64_t chunks = uint64_t((w + 3) / 4) * ((h + 1) / 2);  // 4x2 pixels, one uchar
  return pixel_count(w, h) * sizeof(float) + (filter == render::ShadowMode::kPcss ? chunks : 0);
}

void LightPass::run_visibility(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                               const render::GBuffer& gbuffer, const render::ShadowMap& shadow) {
  const uint32_t w = scene.constants.width, h = scene.constants.height;
  const size_t bytes = size_t(w) * h * sizeof(float);
  if (visibility_bytes_ < bytes) {
    visibility_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, bytes);
    visibility_bytes_ = bytes;
  }
  // Without the lamp (a file scene) the light kernels read no visibility (light.cl rp_lamp_on).
  const gpu::rp_float4 lamp = scene.constants.light_intensity;
  if (lamp.x == 0.0f && lamp.y == 0.0f && lamp.z == 0.0f) return;
  ::cl::Kernel& k = shadow_kernel();
  // hard and pcf never read the mips: any buffer will do
  const ::cl::Buffer& mips = shadow.mip_planes > 0 ? shadow.mips : shadow.depth;
  const auto bind = [&](cl_uint pass, const ::cl::Buffer& consensus) {
    rp::cl::bind_args(k, scene.frame, gbuffer.normal_depth, gbuffer.position, shadow.depth, mips,
                      visibility_, pass, consensus);
  };
  // 4x2 pixels per work-item; timed as part of the light pass
  const size_t chunks_x = (w + 3) / 4, chunks_y = (h + 1) / 2;
  const ::cl::NDRange local(kComposeGroupX, kComposeGroupY);
  const size_t rows = rp::cl::round_up(chunks_y, kComposeGroupY);
  if (!checkerboard_ || filter_ != render::ShadowMode::kPcss) {
    bind(kShadowPassAll, visibility_);  // the consensus is not read in this pass
    profiler.enqueue(pass_name::kLight, k,
                     ::cl::NDRange(rp::cl::round_up(chunks_x, kComposeGroupX), rows),
                     local);
    return;
  }
  if (consensus_bytes_ < chunks_x * chunks_y) {
    consensus_bytes_ = chunks_x * chunks_y;
    consensus_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, consensus_bytes_);
  }
  const ::cl::NDRange half(rp::cl::round_up((chunks_x + 1) / 2, kComposeGroupX), rows);
  for (cl_uint pass : {kShadowPassBlack, kShadowPassWhite}) {
    bind(pass, consensus_);
    profiler.enqueue(pass_name::kLight, k, half, local);
  }
}

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
  if (shadow_mip_planes(filter_) > 0 &&
      (shadow.mip_planes < shadow_mip_planes(filter_) || shadow.mips() == nullptr))
    throw rp::cl::Error("light pass: the soft shadows need the shadow map's mips (run the "
                          "shadow filter pass first)");
}

void LightPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                    const render::GBuffer& gbuffer, const render::ShadowMap& shadow,
                    const ::cl::Buffer& voxels, uint32_t voxel_resolution,
                    uint32_t voxel_levels, ::cl::Buffer& hdr, LightComponents* components,
                    const LowResIndirect* indirect, const SsrInputs* ssr,
                    const ::cl::Buffer* prt) {
  check_sizes(scene, gbuffer, shadow);
  check_voxel_chain("light pass", voxels, voxel_resolution, voxel_levels, !gi_options_.empty());
  const uint32_t w = scene.constants.width, h = scene.constants.height;
  if (w == 0 || h == 0) return;
  if (indirect != nullptr &&
      (indirect->irradiance == nullptr || indirect->geometry == nullptr ||
       indirect->specular == nullptr ||
       indirect->width != IndirectPass::low_res(w) || indirect->height != IndirectPass::low_res(h) ||
       indirect->stride != IndirectPass::plane_stride(indirect->width) ||
       indirect->plane != IndirectPass::plane_size(indirect->width, indirect->height)))
    throw rp::cl::Error("light pass: the low-resolution indirect light (" +
                        std::to_string(indirect->width) + "x" + std::to_string(indirect->height) +
                        ") does not belong to a " + std::to_string(w) + "x" + std::to_string(h) +
                        " frame");
  if (components != nullptr) {
    const size_t plane = size_t(w) * h * 16;
    if (components->direct() == nullptr || components->indirect() == nullptr ||
        components->specular() == nullptr ||
        components->direct.getInfo<CL_MEM_SIZE>() < plane ||
        components->indirect.getInfo<CL_MEM_SIZE>() < plane ||
        components->specular.getInfo<CL_MEM_SIZE>() < plane)
      throw rp::cl::Error("light pass: the direct/indirect/specular buffers must hold " +
                          std::to_string(plane) + " bytes (" + std::to_string(w) + "x" +
                          std::to_string(h) + " float4)");
  }
  run_visibility(profiler, scene, gbuffer, shadow);
  if (prt != nullptr && prt->getInfo<CL_MEM_SIZE>() < size_t(w) * h * 16)
    throw rp::cl::Error("light pass: the PRT sky light must hold " +
                        std::to_string(size_t(w) * h * 16) + " bytes (" + std::to_string(w) +
                        "x" + std::to_string(h) + " float4)");
  ::cl::Kernel& k = variant(indirect != nullptr, components != nullptr, prt != nullptr);
  // What a variant does not read: any buffer will do (the lamp visibility, small).
  const ::cl::Buffer& unused = visibility_;
  const ::cl::Buffer& prt_in = prt != nullptr ? *prt : unused;
  const ::cl::Buffer& direct_out = components != nullptr ? components->direct : unused;
  const ::cl::Buffer& indirect_out = components != nullptr ? components->indirect : unused;
  const ::cl::Buffer& specular_out = components != nullptr ? components->specular : unused;
  if (indirect != nullptr) {
    gpu::LowResPlanes lr{};
    lr.width = indirect->width;
    lr.height = indirect->height;
    lr.stride = indirect->stride;
    lr.plane = indirect->plane;
    lr.pixel_scale = indirect->pixel_scale;
    rp::cl::bind_args(k, scene.frame, gbuffer.albedo, gbuffer.normal_depth, gbuffer.position,
                      gbuffer.emission, visibility_, scene.brdf_table, *indirect->irradiance,
                      *indirect->geometry, *indirect->specular, prt_in, direct_out,
                      indirect_out, specular_out, hdr, lr);
  } else {
    // the screen-space reflections (light_shade reads none of these when ssr_history is 0)
    if (ssr != nullptr && ssr->prev_hdr == &hdr)
      throw rp::cl::Error("light pass: the reflections' previous frame must not be the output");
    gpu::LightShadeParams params{};
    params.voxel_resolution = voxel_resolution;
    params.voxel_levels = voxel_levels;
    params.ssr_history = ssr != nullptr ? 1u : 0u;
    rp::cl::bind_args(k, scene.frame, gbuffer.albedo, gbuffer.normal_depth, gbuffer.position,
                      gbuffer.emission, visibility_, scene.brdf_table, voxels, scene.sky,
                      ssr != nullptr ? *ssr->depth : visibility_,
                      ssr != nullptr ? *ssr->prev_hdr : gbuffer.position,
                      ssr != nullptr ? *ssr->velocity : gbuffer.velocity, prt_in, direct_out,
                      indirect_out, specular_out, hdr, params);
  }
  if (indirect != nullptr) {
    // light_compose: 8 pixels of a row per work-item.
    profiler.enqueue(pass_name::kLight, k,
                     ::cl::NDRange(rp::cl::round_up((w + 7) / 8, kComposeGroupX),
                                   rp::cl::round_up(h, kComposeGroupY)),
                     ::cl::NDRange(kComposeGroupX, kComposeGroupY));
    return;
  }
  enqueue(profiler, k, w, h);
}

}  // namespace rp::passes
