#include "app/render_session.h"

#include <cstdio>

#include "cl/error.h"
#include "passes/motion_blur.h"
#include "render/gpu_types.h"  // before raster_types.h, which builds on its types
#include "kernels/shared/raster_types.h"
#include "render/voxel_volume.h"
#include "scene/demo_scene.h"

namespace rp::app {
namespace {

// Meshes, textures, draw and sphere lists, frame constants: a few MiB for the demo scene.
constexpr uint64_t kSceneReserveBytes = uint64_t(64) << 20;

std::string gib(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(uint64_t(1) << 30));
  return text;
}

bool fits(const DeviceMemoryNeed& need, uint64_t global_bytes, uint64_t max_alloc_bytes) {
  return need.total_bytes <= global_bytes && need.largest_buffer_bytes <= max_alloc_bytes;
}

}  // namespace

DeviceMemoryNeed estimate_device_memory(uint32_t width, uint32_t height, uint32_t shadow_size,
                                        uint32_t voxel_resolution, bool light_components,
                                        bool octree, bool reference) {
  const uint64_t n = uint64_t(width) * height;
  uint64_t per_pixel_x3 = 3 * (20 + 72 + 16 + 32 + 4 + 32 + 4) + 32;  // bloom's 32/3 exactly
  if (light_components) per_pixel_x3 += 3 * 48;  // direct, indirect, specular float4
  if (reference) per_pixel_x3 += 3 * 16;         // the previous frame's output (its SSR)
  const auto tiles = [&](uint64_t side) {
    return ((width + side - 1) / side) * ((height + side - 1) / side);
  };
  const uint64_t blur_tiles = tiles(passes::MotionBlurPass::kTileSize);
  const uint64_t raster_tiles = tiles(RP_RASTER_TILE);
  const uint64_t r = voxel_resolution;
  // The octree's pools and build scratch grow with the surface area, about R^2 x 1 KiB on the
  // demo (the busy scene's fragments included).
  const uint64_t voxel_bytes =
      octree ? r * r * 1024
             : uint64_t(gpu::rp_voxel_total(voxel_resolution,
                                            render::VoxelVolume::levels_for(voxel_resolution))) *
                       16 +
                   r * r * r * (16 + 4);
  DeviceMemoryNeed need;
  need.total_bytes = (n * per_pixel_x3 + 2) / 3 + blur_tiles * 20 + raster_tiles * 2 * 12 +
                     uint64_t(shadow_size) * shadow_size * 4 + voxel_bytes + kSceneReserveBytes;
  need.largest_buffer_bytes = n * 16;
  return need;
}

uint32_t largest_square_that_fits(uint64_t global_bytes, uint64_t max_alloc_bytes,
                                  uint32_t shadow_size, uint32_t voxel_resolution,
                                  bool light_components, bool octree, bool reference) {
  uint32_t lo = 0, hi = 1u << 17;  // invariant: lo fits (0 trivially), hi does not
  while (hi - lo > 1) {
    const uint32_t mid = lo + (hi - lo) / 2;
    if (fits(estimate_device_memory(mid, mid, shadow_size, voxel_resolution, light_components,
                                    octree, reference),
             global_bytes, max_alloc_bytes))
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

void check_device_memory(const rp::cl::DeviceInfo& device, uint32_t width, uint32_t height,
                         uint32_t shadow_size, uint32_t voxel_resolution, bool light_components,
                         bool octree, bool reference) {
  const DeviceMemoryNeed need = estimate_device_memory(
      width, height, shadow_size, voxel_resolution, light_components, octree, reference);
  if (device.global_mem_bytes == 0 || fits(need, device.global_mem_bytes, device.max_alloc_bytes))
    return;  // 0: the driver did not say; buffer creation failures are still reported
  std::string size = std::to_string(width) + "x" + std::to_string(height);
  std::string message;
  if (need.total_bytes > device.global_mem_bytes)
    message = size + " needs " + gib(need.total_bytes) + " of device memory, the device has " +
              gib(device.global_mem_bytes);
  else
    message = size + " needs one buffer of " + gib(need.largest_buffer_bytes) +
              " (a float4 per pixel), the device allows at most " +
              gib(device.max_alloc_bytes) + " per buffer";
  const uint32_t side = largest_square_that_fits(device.global_mem_bytes, device.max_alloc_bytes,
                                                 shadow_size, voxel_resolution, light_components,
                                                 octree, reference);
  if (side == 0)
    message += "; not even a 1x1 image fits (a smaller --voxels or --shadow-size may help)";
  else
    message += "; the largest square size that fits is about " + std::to_string(side) +
               " (--size " + std::to_string(side) + ")";
  throw rp::cl::Error(message);
}
RenderSession::RenderSession(const CommonOptions& options, uint32_t width, uint32_t height,
                             bool keep_components, const scene::SceneAssets* assets)
    : assets_(assets ? *assets
                     : scene::make_demo_assets(options.asset_dir.empty()
                                                   ? scene::default_asset_dir()
                                                   : options.asset_dir)),
      context_(rp::cl::Context::create(options.device)),
      programs_(context_) {
  render::RenderSettings settings;
  settings.width = width;
  settings.height = height;
  if (options.shadow_size != 0) settings.shadow_size = options.shadow_size;
  settings.gi_volume = options.gi_volume;
  if (options.voxels != 0)
    settings.voxel_resolution = options.voxels;
  else if (options.gi_volume == render::GiVolume::kSvo)
    settings.voxel_resolution = CommonOptions::kDefaultSvoVoxels;
  settings.effects = options.effects;
  settings.visibility = options.visibility;
  settings.quality = options.quality;
  settings.bounces = options.bounces;
  settings.shadows = options.shadows;
  settings.texture_filter = options.texture_filter;
  // Before any allocation or kernel build: a size the device cannot hold fails at once, with
  // what would fit.
  check_device_memory(context_.info, width, height, settings.shadow_size,
                      settings.voxel_resolution,
                      passes::needs_light_components(options.view.view) || keep_components,
                      settings.gi_volume == render::GiVolume::kSvo,
                      settings.quality == render::Quality::kReference);
  device_memory_estimate_ =
      estimate_device_memory(width, height, settings.shadow_size, settings.voxel_resolution,
                             passes::needs_light_components(options.view.view) || keep_components,
                             settings.gi_volume == render::GiVolume::kSvo,
                             settings.quality == render::Quality::kReference)
          .total_bytes;
  renderer_ = std::make_unique<render::Renderer>(context_, programs_, assets_, settings);
  set_view(options.view);
  if (keep_components) renderer_->set_keep_light_components(true);
}

void RenderSession::set_keep_components(bool keep) {
  if (keep)
    check_device_memory(context_.info, width(), height(), renderer_->settings().shadow_size,
                        renderer_->settings().voxel_resolution, true,
                        renderer_->settings().gi_volume == render::GiVolume::kSvo,
                        renderer_->settings().quality == render::Quality::kReference);
  renderer_->set_keep_light_components(keep);
}

void RenderSession::set_view(const passes::DebugViewSettings& view) {
  renderer_->set_debug_view(view);
  view_ = view;
}

rp::cl::PassTimes RenderSession::render(const scene::FrameScene& frame,
                                        std::vector<uint8_t>& rgba, double& frame_ms) {
  auto start = std::chrono::steady_clock::now();
  rp::cl::PassTimes times = renderer_->render(frame);
  frame_ms = ms_since(start);
  renderer_->read_rgba8(rgba);
  return times;
}

std::string describe_device(const rp::cl::DeviceInfo& info) {
  std::string text = "[";  // appends, not operator+ chains: GCC 12 -Wrestrict false positive
  text += std::to_string(info.index);
  text += "] ";
  text += info.name;
  text += " (";
  text += info.type;
  text += ", ";
  text += info.platform_name;
  text += ")";
  return text;
}

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace rp::app
