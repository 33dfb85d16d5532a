#include "passes/debug_view.h"

#include <array>
#include <string>

#include "cl/error.h"
#include "cl/kernel_args.h"
#include "kernels/shared/voxel_layout.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 16;  // 16x16 work-groups, like the other per-pixel passes

constexpr std::array<const char*, 6> kDirNames = {"+x", "-x", "+y", "-y", "+z", "-z"};

std::string frame_size(uint32_t w, uint32_t h) { return std::to_string(w) + "x" + std::to_string(h); }

void require(bool ok, const std::string& message) {
  if (!ok) throw rp::cl::Error("debug view: " + message);
}

// True when `buffer` is set and holds at least `bytes`.
bool holds(const ::cl::Buffer& buffer, size_t bytes) {
  return buffer() != nullptr && buffer.getInfo<CL_MEM_SIZE>() >= bytes;
}

}  // namespace

const char* voxel_dir_name(uint32_t dir) { return dir < kDirNames.size() ? kDirNames[dir] : "?"; }

std::optional<uint32_t> parse_voxel_dir(std::string_view name) {
  for (uint32_t i = 0; i < kDirNames.size(); ++i)
    if (name == kDirNames[i]) return i;
  return std::nullopt;
}

std::optional<DebugView> debug_view_for_key(char key) {
  if (key == '0') return DebugView::kSpecular;
  if (key < '1' || key > '9') return std::nullopt;
  return DebugView(key - '1');
}

DebugViewPass::DebugViewPass(const rp::cl::Context& /*context*/, rp::cl::ProgramCache& programs,
                             std::string gi_options)
    : programs_(&programs), gi_options_(std::move(gi_options)) {}

::cl::Kernel& DebugViewPass::kernel(const std::string& name) {
  auto it = kernels_.find(name);
  if (it == kernels_.end())
    it = kernels_
             .emplace(name, programs_->kernel("debug_view.cl", "debug_view_" + name, gi_options_))
             .first;
  return it->second;
}

void DebugViewPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                        const DebugViewSettings& settings, const DebugViewInputs& in,
                        ::cl::Buffer& rgba8) {
  const uint32_t w = scene.constants.width, h = scene.constants.height;
  const size_t pixels = size_t(w) * h;
  const std::string view(name_of(settings.view));
  require(settings.view != DebugView::kFinal, "'final' is the normal image, not a debug view");
  require(holds(rgba8, pixels * 4), "the output buffer is smaller than " + frame_size(w, h) +
                                        " RGBA8 pixels");
  if (pixels == 0) return;

  auto gbuffer = [&]() -> const render::GBuffer& {
    require(in.gbuffer != nullptr, "view '" + view + "' needs the GBuffer");
    require(in.gbuffer->width == w && in.gbuffer->height == h,
            "the GBuffer is " + frame_size(in.gbuffer->width, in.gbuffer->height) +
                " but the frame is " + frame_size(w, h));
    return *in.gbuffer;
  };

  ::cl::Kernel* k = nullptr;
  switch (settings.view) {
    case DebugView::kFinal:
      break;
    case DebugView::kAlbedo:
      k = &kernel("albedo");
      rp::cl::bind_args(*k, scene.frame, gbuffer().albedo, rgba8);
      break;
    case DebugView::kNormal:
      k = &kernel("normal");
      rp::cl::bind_args(*k, scene.frame, gbuffer().normal_depth, gbuffer().position, rgba8);
      break;
    case DebugView::kDepth:
      k = &kernel("depth");
      rp::cl::bind_args(*k, scene.frame, gbuffer().normal_depth, rgba8);
      break;
    case DebugView::kVelocity:
      k = &kernel("velocity");
      rp::cl::bind_args(*k, scene.frame, gbuffer().velocity, rgba8);
      break;
    case DebugView::kShadowMap:
      require(in.shadow != nullptr, "view 'shadow-map' needs the shadow map");
      require(in.shadow->size == scene.constants.shadow_size && in.shadow->size > 0,
              "the shadow map is " + std::to_string(in.shadow->size) +
                  " texels wide but the frame constants say " +
                  std::to_string(scene.constants.shadow_size));
      k = &kernel("shadow_map");
      rp::cl::bind_args(*k, scene.frame, in.shadow->depth, rgba8);
      break;
    case DebugView::kDirect:
    case DebugView::kIndirect:
    case DebugView::kSpecular: {
      require(in.light != nullptr, "view '" + view + "' needs the light pass's components");
      const ::cl::Buffer& buffer = settings.view == DebugView::kDirect     ? in.light->direct
                                   : settings.view == DebugView::kIndirect ? in.light->indirect
                                                                           : in.light->specular;
      require(holds(buffer, pixels * 16),
              "the " + view + " buffer is smaller than " + frame_size(w, h) + " float4 pixels");
      k = &kernel("radiance");
      rp::cl::bind_args(*k, scene.frame, buffer, rgba8);
      break;
    }
    case DebugView::kVoxels: {
      const uint32_t r = in.voxel_resolution, levels = in.voxel_levels;
      require(in.voxels != nullptr && r > 0 && levels > 0, "view 'voxels' needs the voxel chain");
      require(settings.level < levels,
              "voxel level " + std::to_string(settings.level) + " does not exist (the chain has " +
                  std::to_string(levels) + " levels, 0.." + std::to_string(levels - 1) + ")");
      require(settings.dir < 6, "voxel direction " + std::to_string(settings.dir) +
                                    " is not one of +x, -x, +y, -y, +z, -z");
      require(levels <= 31 && (r >> (levels - 1)) >= 1, "voxel resolution " + std::to_string(r) +
                                            " has fewer than " + std::to_string(levels) +
                                            " levels");
      // (the octree's buffer is checked by its builder)
      require(!gi_options_.empty() ||
                  holds(*in.voxels, size_t(gpu::rp_voxel_total(r, levels)) * 16),
              "the voxel buffer is smaller than a " + std::to_string(r) + "^3 chain of " +
                  std::to_string(levels) + " levels");
      k = &kernel("voxels");
      rp::cl::bind_args(*k, scene.frame, *in.voxels, rgba8,
                        gpu::VoxelViewParams{r, settings.level,
                                             settings.level == 0 ? 0u : settings.dir, 0u});
      break;
    }
  }
  profiler.enqueue(pass_name::kDebugView, *k,
                   ::cl::NDRange(rp::cl::round_up(w, kGroup), rp::cl::round_up(h, kGroup)),
                   ::cl::NDRange(kGroup, kGroup));
}

}  // namespace rp::passes
