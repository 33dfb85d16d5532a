#include "passes/gbuffer.h"

#include <cstdlib>
#include <string>

#include "cl/error.h"
#include "cl/kernel_args.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"

namespace rp::passes {
namespace {

// Work-items per work-group (1D). With 16-pixel spans on PoCL (busy 720, CPU ms a frame): 4
// and 16 cost the same (9.2), 64 twice as much (17.8: PoCL keeps every work-item's private
// arrays side by side, and 64 of them no longer stay in cache).
constexpr size_t kGroup = 16;

// Pixels per work-item: the CPU's native float vector width (rp::cl::cpu_span_lanes: spans map
// onto PoCL's SIMD code), 1 on GPUs. Measured on the 2-core AVX-512 EPYC, busy 720: before the
// texture footprint 8 was best (3.6 ms against 4.2 ms with 16, 6.5 ms with 4); the
// footprint's per-primitive set-up (gb_uv_derivatives) and the trilinear taps made 16 the better
// choice there: 8.9 against 11.0 CPU ms a frame (perf cpu-clock samples, both threads; 15.0
// with 4). On the 2-core AVX2 EPYC 8 is: 32.1 against 42.3 CPU ms.
// ROLYPOLY_GBUFFER_SPAN (1, 4, 8 or 16) overrides the choice (tests compare the variants).
int choose_span(const rp::cl::Context& context) {
  if (const char* env = std::getenv("ROLYPOLY_GBUFFER_SPAN"); env && *env) {
    const std::string s = env;
    if (s == "1" || s == "4" || s == "8" || s == "16") return std::stoi(s);
    throw rp::cl::Error("ROLYPOLY_GBUFFER_SPAN must be 1, 4, 8 or 16, not '" + s + "'");
  }
  return context.info.is_cpu ? rp::cl::cpu_span_lanes(context.info) : 1;
}

}  // namespace

GBufferPass::GBufferPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                         const std::string& extra_options)
    : context_(&context), span_(choose_span(context)), programs_(&programs) {
  options_ = "-DRP_SPAN=" + std::to_string(span_);
  if (!extra_options.empty()) options_ += " " + extra_options;
}

void GBufferPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                      const render::VisibilityBuffer& vis, render::GBuffer& out,
                      uint32_t texture_filter, float lod_bias, bool stochastic_levels) {
  if (texture_filter > RP_TEXTURE_FILTER_ANISOTROPIC)
    throw rp::cl::Error("gbuffer pass: unknown texture filter " + std::to_string(texture_filter));
  const uint32_t w = scene.constants.width, h = scene.constants.height;
  if (vis.width != w || vis.height != h || out.width != w || out.height != h)
    throw rp::cl::Error("gbuffer pass: frame size " + std::to_string(w) + "x" + std::to_string(h) +
                        " does not match the visibility buffer (" + std::to_string(vis.width) +
                        "x" + std::to_string(vis.height) + ") or the GBuffer (" +
                        std::to_string(out.width) + "x" + std::to_string(out.height) + ")");
  if (w == 0 || h == 0) return;
  if (!scene.texels() && !no_texels_())
    no_texels_ = ::cl::Buffer(context_->context, CL_MEM_READ_ONLY, sizeof(cl_uint));
  ::cl::Kernel& resolve = resolve_[texture_filter];
  if (!resolve())
    resolve = programs_->kernel("gbuffer.cl", "gbuffer_resolve",
                                options_ + " -DRP_TEXTURE_FILTER_FIXED=" +
                                    std::to_string(texture_filter) + "u");
  gpu::GBufferParams params{};
  params.texture_filter = texture_filter;
  params.lod_bias = lod_bias;
  params.stochastic_levels = stochastic_levels ? 1u : 0u;
  // The packed RGBA8 sRGB texels, decoded per tap (kernels/common/span_texture.h).
  const ::cl::Buffer& texels = scene.texels() ? scene.texels : no_texels_;
  rp::cl::bind_args(resolve, scene.frame, vis.ids, vis.bary, scene.instances, scene.spheres,
                    scene.vertices, scene.triangles, scene.materials, scene.textures, texels,
                    out.albedo, out.normal_depth, out.position, out.emission, out.velocity,
                    params);
  // One work-item per span of span_ pixels of a row, a 1D range in row-major order.
  const size_t span = static_cast<size_t>(span_);
  const size_t spans = (w + span - 1) / span * h;
  profiler.enqueue(pass_name::kGBuffer, resolve, ::cl::NDRange(rp::cl::round_up(spans, kGroup)),
                   ::cl::NDRange(kGroup));
  if (scene.has_material_maps) run_material(profiler, scene, vis, out);
}

void GBufferPass::run_material(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                               const render::VisibilityBuffer& vis, render::GBuffer& out) {
  if (!material_())
    material_ = programs_->kernel("gbuffer_material.cl", "gbuffer_material", options_);
  rp::cl::bind_args(material_, scene.frame, vis.ids, vis.bary, scene.instances, scene.vertices,
                    scene.tangents, scene.triangles, scene.materials, scene.textures,
                    scene.texels() ? scene.texels : no_texels_, out.normal_depth, out.emission);
  // One work-item per span of span_ pixels of a row, a 1D range in row-major order.
  const uint32_t w = scene.constants.width, h = scene.constants.height;
  const size_t span = static_cast<size_t>(span_);
  const size_t spans = (w + span - 1) / span * h;
  profiler.enqueue(pass_name::kGBuffer, material_,
                   ::cl::NDRange(rp::cl::round_up(spans, kGroup)), ::cl::NDRange(kGroup));
}

}  // namespace rp::passes
