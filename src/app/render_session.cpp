#include "app/render_session.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <new>
#include <utility>

#include "app/interrupt.h"
#include "app/pathtrace_settings.h"
#include "app/progress.h"
#include "app/sky_input.h"
#include "cl/error.h"
#include "passes/pass_names.h"
#include "passes/prt_sky.h"
#include "render/frame_memory.h"
#include "render/gpu_scene.h"
#include "render/punctual_shadows.h"
#include "render/sky_texture.h"
#include "render/voxel_volume.h"
#include "scene/demo_scene.h"
#include "truth/prt_cache.h"

namespace rp::app {
namespace {

// Meshes, textures, draw and sphere lists, frame constants: a few MiB for the demo scene. A
// loaded scene counts its own buffers (scene_memory.h) plus kSceneListsBytes for the lists.
constexpr uint64_t kSceneReserveBytes = uint64_t(64) << 20;
constexpr uint64_t kSceneListsBytes = uint64_t(16) << 20;

std::string gib(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(uint64_t(1) << 30));
  return text;
}

std::string mib(uint64_t bytes) {
  return std::to_string((bytes + (uint64_t(1) << 20) - 1) >> 20) + " MiB";
}

bool fits(const DeviceMemoryNeed& need, uint64_t global_bytes, uint64_t max_alloc_bytes) {
  return need.total_bytes <= global_bytes && need.largest_buffer_bytes <= max_alloc_bytes;
}

// The --voxels the app offers for a volume (app/cli_options.cpp), largest first.
std::vector<uint32_t> voxel_choices(bool octree) {
  return octree ? std::vector<uint32_t>{512, 256} : std::vector<uint32_t>{128, 64, 32};
}

}  // namespace

render::FrameMemory frame_memory_worst_case(render::RenderSettings settings,
                                            const render::FrameMemoryOptions& frame) {
  settings.effects.taa = settings.effects.bloom = settings.effects.motion_blur = true;
  render::FrameMemory m = render::frame_memory(settings, frame);
  for (render::ShadowMode mode : {render::ShadowMode::kPcss, render::ShadowMode::kVssm}) {
    settings.shadows = mode;
    m.take_max(render::frame_memory(settings, frame));
  }
  return m;
}

DeviceMemoryNeed estimate_device_memory(const render::RenderSettings& settings,
                                        const render::FrameMemoryOptions& frame,
                                        const SceneMemory* scene) {
  namespace pass_name = passes::pass_name;
  const render::FrameMemory parts = frame_memory_worst_case(settings, frame);
  const uint64_t r = settings.voxel_resolution;
  DeviceMemoryNeed need;
  need.shadow_bytes = parts.of(pass_name::kShadowMap) + parts.of(pass_name::kShadowFilter);
  need.image_bytes = parts.total() - need.shadow_bytes;
  const uint64_t light_views = scene ? scene->light_shadow_bytes : 0;  // follow the scene
  need.shadow_bytes += light_views;
  if (settings.gi_volume == render::GiVolume::kSvo) {
    // The octree's pools, fragment list and build scratch grow with the surface area: at
    // peak 502-567 bytes per R^2 measured on the demo, the busy scene and the atrium at 512^3
    // (141.9 MiB on the atrium), 508 on the atrium at 1024^3; the largest buffer, the fragment
    // list, 209-268 bytes per R^2 (bench/results/zen3-2core-pocl-svo-memory.md). Counted high.
    need.volume_bytes = r * r * 640;
    need.volume_buffer_bytes = r * r * 320;
  } else {
    // The chain (one float4 buffer) and the voxelizer's sums (8 words) and overflow bits (one
    // word) per voxel (render/voxel_volume.h).
    need.volume_buffer_bytes =
        uint64_t(gpu::rp_voxel_total(settings.voxel_resolution,
                                     render::VoxelVolume::levels_for(settings.voxel_resolution))) *
        16;
    need.volume_bytes = need.volume_buffer_bytes + r * r * r * (RP_VOXEL_ACCUM_WORDS * 4 + 4);
  }
  need.scene_bytes = scene ? std::max(kSceneReserveBytes, scene->bytes() + kSceneListsBytes)
                           : kSceneReserveBytes;
  need.total_bytes = need.image_bytes + need.shadow_bytes + need.volume_bytes + need.scene_bytes;
  const uint64_t pixels = uint64_t(settings.width) * settings.height;
  need.largest_buffer_bytes = std::max(pixels * 16, need.volume_buffer_bytes);
  // The shadow depth buffer: the lamp's two planes, then the lights' views.
  const uint64_t s = settings.shadow_size;
  need.largest_buffer_bytes = std::max(need.largest_buffer_bytes, 2 * s * s * 4 + light_views);
  if (scene) need.largest_buffer_bytes = std::max(need.largest_buffer_bytes,
                                                  scene->largest_buffer_bytes());
  return need;
}

uint32_t largest_square_that_fits(uint64_t global_bytes, uint64_t max_alloc_bytes,
                                  render::RenderSettings settings,
                                  const render::FrameMemoryOptions& frame,
                                  const SceneMemory* scene) {
  uint32_t lo = 0, hi = 1u << 17;  // invariant: lo fits (0 trivially), hi does not
  while (hi - lo > 1) {
    const uint32_t mid = lo + (hi - lo) / 2;
    settings.width = settings.height = mid;
    if (fits(estimate_device_memory(settings, frame, scene), global_bytes, max_alloc_bytes))
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

uint32_t largest_voxels_that_fit(uint64_t global_bytes, uint64_t max_alloc_bytes,
                                 render::RenderSettings settings,
                                 const render::FrameMemoryOptions& frame,
                                 const SceneMemory* scene) {
  for (uint32_t v : voxel_choices(settings.gi_volume == render::GiVolume::kSvo)) {
    settings.voxel_resolution = v;
    if (fits(estimate_device_memory(settings, frame, scene), global_bytes, max_alloc_bytes))
      return v;
  }
  return 0;
}

void check_device_memory(const rp::cl::DeviceInfo& device, const render::RenderSettings& settings,
                         const render::FrameMemoryOptions& frame, const SceneMemory* scene,
                         const std::string& scene_name) {
  const DeviceMemoryNeed need = estimate_device_memory(settings, frame, scene);
  if (device.global_mem_bytes == 0 || fits(need, device.global_mem_bytes, device.max_alloc_bytes))
    return;  // 0: the driver did not say; buffer creation failures are still reported
  const uint64_t global = device.global_mem_bytes, max_alloc = device.max_alloc_bytes;
  const bool octree = settings.gi_volume == render::GiVolume::kSvo;
  const uint32_t voxel_resolution = settings.voxel_resolution;
  const std::string size = std::to_string(settings.width) + "x" + std::to_string(settings.height);
  const std::string volume = std::string("--gi-volume ") + (octree ? "svo" : "dense") +
                             " --voxels " + std::to_string(voxel_resolution);
  const std::string parts = " (the image's buffers " + mib(need.image_bytes) + ", " +
                            (octree ? "the octree " : "the dense GI volume ") +
                            mib(need.volume_bytes) + ", the shadow maps " +
                            mib(need.shadow_bytes) + ", the scene " + mib(need.scene_bytes) + ")";

  // A loaded scene that does not fit even with a 1x1 image and the smallest volume: no
  // setting helps, the scene is the cause.
  if (scene != nullptr) {
    render::RenderSettings least_settings = settings;
    least_settings.width = least_settings.height = least_settings.shadow_size = 1;
    least_settings.voxel_resolution = voxel_choices(octree).back();
    const DeviceMemoryNeed least = estimate_device_memory(least_settings, {}, scene);
    if (!fits(least, global, max_alloc)) {
      std::string message = "the scene " + scene_name + " needs " + mib(need.scene_bytes) +
                            " of device memory (" + scene->describe() + ")";
      if (scene->largest_buffer_bytes() > max_alloc)
        message += ", one buffer of " + mib(scene->largest_buffer_bytes()) +
                   ", but the device allows at most " + mib(max_alloc) + " per buffer";
      else
        message += ", but the device has " + mib(global);
      throw rp::cl::Error(message + "; use a smaller scene (fewer triangles, smaller textures)");
    }
  }

  // The GI volume decides when a smaller --voxels fits at this image size.
  const uint32_t voxels = largest_voxels_that_fit(global, max_alloc, settings, frame, scene);
  const uint32_t side = largest_square_that_fits(global, max_alloc, settings, frame, scene);
  if (voxels != 0 && voxels < voxel_resolution) {
    std::string message = volume + " at " + size + " needs ";
    if (need.total_bytes > global)
      message += mib(need.total_bytes) + " of device memory" + parts + ", the device has " +
                 mib(global);
    else
      message += "one buffer of " + mib(need.volume_buffer_bytes) + " for the " +
                 (octree ? "octree's fragment list" : "dense volume's mip chain") +
                 ", the device allows at most " + mib(max_alloc) + " per buffer";
    message += "; the largest --voxels that fits at this size is " + std::to_string(voxels) +
               " (--voxels " + std::to_string(voxels) + ")";
    if (side != 0)
      message += ", or at --voxels " + std::to_string(voxel_resolution) +
                 " the largest square size is about " + std::to_string(side) + " (--size " +
                 std::to_string(side) + ")";
    throw rp::cl::Error(message);
  }

  std::string message;
  if (need.total_bytes > global)
    message = size + " needs " + gib(need.total_bytes) + " of device memory, the device has " +
              gib(global);
  else if (need.volume_buffer_bytes > max_alloc)
    message = volume + " needs one buffer of " + mib(need.volume_buffer_bytes) +
              ", the device allows at most " + mib(max_alloc) + " per buffer";
  else
    message = size + " needs one buffer of " + gib(need.largest_buffer_bytes) +
              " (a float4 per pixel), the device allows at most " + gib(max_alloc) +
              " per buffer";
  if (side == 0)
    message += "; not even a 1x1 image fits" + parts + " (a smaller --voxels or --shadow-size "
               "may help)";
  else
    message += "; the largest square size that fits is about " + std::to_string(side) +
               " (--size " + std::to_string(side) + ")";
  throw rp::cl::Error(message);
}

RenderSession::RenderSession(const CommonOptions& options, uint32_t width, uint32_t height,
                             bool keep_components, const scene::SceneAssets* assets)
    : assets_(assets ? *assets : load_demo_assets(options)),
      context_(rp::cl::Context::create(options.device)),
      programs_(context_) {
  if (options.sky.given()) {
    sky_ = std::make_unique<SkyLight>(load_sky(options.sky));
    sky_description_ = describe_sky(options.sky, *sky_);
  }
  if (sky_ && options.sky.prt) prt_ = options.sky.prt_settings;
  render::RenderSettings settings = options.render;
  settings.width = width;
  settings.height = height;
  settings.scale_follows_time = options.target_ms > 0.0;
  // Before any allocation or kernel build: a size, volume or scene the device cannot hold
  // fails at once, with what would fit. The textures first: their own message names the
  // largest one.
  render::check_texture_memory(assets_.textures, context_.info.max_alloc_bytes,
                               context_.info.global_mem_bytes);
  const SceneMemory scene = scene_memory();
  render::FrameMemoryOptions frame;
  frame.light_components =
      passes::needs_light_components(options.view.view) || keep_components;
  frame.prt = prt_.has_value();
  scene_name_ = "--scene " + options.scene;
  check_device_memory(context_.info, settings, frame, &scene, scene_name_);
  device_memory_estimate_ = estimate_device_memory(settings, frame, &scene).total_bytes;
  try {
    renderer_ = std::make_unique<render::Renderer>(context_, programs_, assets_, settings);
  } catch (const std::bad_alloc&) {
    // The host copies of the scene's buffers (vertices, triangles, mip chains) are the large
    // allocations of the set-up.
    throw rp::cl::Error("setting up the renderer ran out of host memory (the scene: " +
                        scene.describe() + ")");
  }
  set_view(options.view);
  if (keep_components) renderer_->set_keep_light_components(true);
  if (options.target_ms > 0.0)
    frame_scale_.emplace(options.target_ms, options.render.render_scale);
}

void RenderSession::set_keep_components(bool keep) {
  if (keep) {
    const SceneMemory scene = scene_memory();
    render::FrameMemoryOptions frame;
    frame.light_components = true;
    frame.prt = prt_.has_value();
    check_device_memory(context_.info, renderer_->settings(), frame, &scene, scene_name_);
  }
  renderer_->set_keep_light_components(keep);
}

void RenderSession::set_view(const passes::DebugViewSettings& view) {
  renderer_->set_debug_view(view);
  view_ = view;
}

RenderSession::~RenderSession() = default;

std::optional<float> RenderSession::turn_sky(float degrees) {
  if (!sky_) return std::nullopt;
  app::turn_sky(*sky_, degrees);
  return sky_->environment.rotate_deg;
}

SceneMemory RenderSession::scene_memory() const {
  SceneMemory memory = count_scene_memory(assets_);
  if (sky_ && sky_->environment.enabled())
    memory.sky_texels = render::sky_texel_count(sky_->environment.map->width,
                                                sky_->environment.map->height) +
                        (sky_->environment.residual ? render::sky_level0_texel_count(
                                                          sky_->environment.map->width,
                                                          sky_->environment.map->height)
                                                    : 0);
  if (prt_) {
    // interreflected: RGB, and the grey shadowed transfer beside it where it bounces, with
    // the directional lights' traced bounces (RGB per light; the most there can be, as the
    // lights are not known before the first frame)
    const bool bouncing = prt_->kind == truth::PrtKind::kInterreflected && prt_->bounces > 0;
    const uint64_t per_vertex =
        uint64_t(prt_->bands * prt_->bands) *
            (prt_->kind == truth::PrtKind::kInterreflected ? (bouncing ? 4u : 3u) : 1u) +
        (bouncing ? 3u * truth::kPrtMaxSuns : 0u);
    memory.prt_floats = memory.vertices * per_vertex;
  }
  memory.light_shadow_bytes = light_shadow_bytes_;
  return memory;
}

void RenderSession::check_light_views(const scene::FrameScene& frame) {
  light_views_checked_ = true;
  if (frame.lights.empty()) return;
  light_shadow_bytes_ =
      4 * render::punctual_shadow_floats(frame.lights, renderer_->settings().shadow_size);
  const SceneMemory scene = scene_memory();
  render::FrameMemoryOptions options;
  options.light_components =
      passes::needs_light_components(view_.view) || renderer_->keeps_light_components();
  options.prt = prt_.has_value();
  check_device_memory(context_.info, renderer_->settings(), options, &scene, scene_name_);
  device_memory_estimate_ =
      estimate_device_memory(renderer_->settings(), options, &scene).total_bytes;
}

rp::cl::PassTimes RenderSession::render(const scene::FrameScene& frame,
                                        std::vector<uint8_t>& rgba, double& frame_ms) {
  auto start = std::chrono::steady_clock::now();
  rp::cl::PassTimes times;
  if (sky_) {
    lit_frame_ = frame;  // copy assignment keeps the vectors' capacity: no per-frame allocation
    add_sky(*sky_, lit_frame_);
    if (!light_views_checked_) check_light_views(lit_frame_);
    if (prt_ && !prt_ready_) {
      prepare_prt(lit_frame_);
      start = std::chrono::steady_clock::now();  // the frame's time, not the transfer's
    }
    times = renderer_->render(lit_frame_);
  } else {
    if (!light_views_checked_) check_light_views(frame);
    times = renderer_->render(frame);
  }
  frame_ms = ms_since(start);
  renderer_->read_rgba8(rgba);
  if (frame_scale_) renderer_->set_render_scale(frame_scale_->update(frame_ms));
  return times;
}

void RenderSession::prepare_prt(const scene::FrameScene& frame) {
  truth::PrtSettings settings = *prt_;
  // The directional lights of this frame (the map's suns, the clear sky's, a scene's): their
  // bounces are traced per vertex for these directions (the pass falls back to the SH transfer
  // once the lights turn away from them).
  for (const scene::PunctualLight& l : frame.lights)
    if (l.type == scene::LightType::kDirectional &&
        settings.sun_directions.size() < truth::kPrtMaxSuns)
      settings.sun_directions.push_back(-l.direction);
  // The glow around the map's suns, turned as the map is now: traced per vertex (the pass takes
  // it back into the SH sky once the map turns).
  const scene::Environment& environment = frame.environment;
  if (environment.glow)
    for (const scene::GlowCell& c : environment.glow->cells)
      settings.glow_cells.push_back(
          {scene::environment_to_world(c.direction, environment.rotate_deg), c.irradiance});
  const size_t kSteps = 1000;
  std::atomic<bool> cancel{false};
  truth::CachedPrt cached;
  {
    ProgressBar bar("PRT transfer", kSteps);
    try {
      cached = truth::cached_prt_transfer(
          assets_, frame, settings, truth::default_prt_cache_dir(),
          [&](double fraction) {
            bar.update(size_t(fraction * double(kSteps)));
            if (InterruptGuard::interrupted()) cancel = true;
          },
          &cancel);
    } catch (const truth::PrtCancelled&) {
      throw Interrupted("while computing the PRT transfer; nothing was cached");
    }
  }
  truth::PrtTransfer& t = cached.transfer;
  passes::PrtShading shading;
  shading.bands = t.bands;
  shading.channels = t.channels;
  shading.coefficients = std::move(t.coefficients);  // tens of MB on a large scene
  shading.shadowed = std::move(t.shadowed);
  shading.sun_directions = t.sun_directions;
  shading.sun_bounce = std::move(t.sun_bounce);
  if (!t.glow.empty()) {
    shading.glow = std::move(t.glow);
    shading.glow_source = environment.glow;
    shading.glow_turn_deg = environment.rotate_deg;
  }
  for (size_t i = 0; i < frame.instances.size(); ++i) {
    const bool has = i < t.instances.size() && t.instances[i].count > 0;
    shading.instances.push_back(
        {frame.instances[i].mesh, has ? t.instances[i].first : passes::PrtShading::kNoTransfer});
  }
  renderer_->set_prt(shading);
  std::string bounces;
  if (t.kind == truth::PrtKind::kInterreflected) {
    bounces = ", " + std::to_string(t.bounces) + " bounces";
    if (!t.sun_directions.empty())
      bounces += " (" + std::to_string(t.sun_directions.size()) + " directional light" +
                 (t.sun_directions.size() == 1 ? "'s" : "s'") + " traced)";
  }
  if (!t.glow_cells.empty())
    bounces += ", the glow around the map's suns traced (" +
               std::to_string(t.glow_cells.size()) + " cells)";
  std::fprintf(stderr, "rolypoly: PRT sky light: %d coefficients, %s%s, %u vertices (%s %s)\n",
               t.count(), name_of(t.kind).data(), bounces.c_str(),
               t.vertex_count(), cached.from_cache ? "cached in" : "written to",
               cached.file.string().c_str());
  prt_ready_ = true;
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
