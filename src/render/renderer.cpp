#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cl/error.h"
#include "passes/bloom.h"
#include "passes/bounce.h"
#include "passes/debug_view.h"
#include "passes/embree_visibility.h"
#include "passes/gbuffer.h"
#include "passes/indirect.h"
#include "passes/light.h"
#include "passes/motion_blur.h"
#include "passes/pass_names.h"
#include "passes/prt_sky.h"
#include "passes/punctual_light.h"
#include "passes/shadow_filter.h"
#include "passes/sky_background.h"
#include "passes/svo.h"
#include "passes/taa.h"
#include "passes/taa_upsample.h"
#include "passes/tone_map.h"
#include "passes/visibility.h"
#include "passes/voxel_mips.h"
#include "passes/voxelize.h"

namespace rp::render {
namespace {

// Errors a driver gives when a buffer does not fit (CL_INVALID_BUFFER_SIZE: above
// CL_DEVICE_MAX_MEM_ALLOC_SIZE).
bool out_of_device_memory(cl_int err) {
  return err == CL_MEM_OBJECT_ALLOCATION_FAILURE || err == CL_OUT_OF_RESOURCES ||
         err == CL_OUT_OF_HOST_MEMORY || err == CL_INVALID_BUFFER_SIZE;
}

// The app checks an estimate first (app/render_session.h); this catches what it missed.
[[noreturn]] void throw_out_of_memory(const ::cl::Error& e, uint32_t width, uint32_t height) {
  throw rp::cl::Error("the device ran out of memory for a " + std::to_string(width) + "x" +
                      std::to_string(height) + " image (" + e.what() + ": " +
                      rp::cl::error_name(e.err()) +
                      "); choose a smaller --size (or --width / --height); `rolypoly devices` "
                      "shows each device's memory");
}

// The gbuffer kernel's code for a texture filter (kernels/shared/types.h).
uint32_t texture_filter_code(TextureFilter filter) {
  switch (filter) {
    case TextureFilter::kBilinear: return RP_TEXTURE_FILTER_BILINEAR;
    case TextureFilter::kTrilinear: return RP_TEXTURE_FILTER_TRILINEAR;
    case TextureFilter::kAnisotropic: return RP_TEXTURE_FILTER_ANISOTROPIC;
  }
  return RP_TEXTURE_FILTER_TRILINEAR;
}

}  // namespace

Renderer::Renderer(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                   const scene::SceneAssets& assets, RenderSettings settings)
    : context_(context), programs_(programs), settings_(settings),
      profiler_(context.queue, context.timing) {
  if (settings_.width == 0 || settings_.height == 0 || settings_.shadow_size == 0)
    throw rp::cl::Error("render size must be at least 1x1 pixels");
  if (!(settings_.render_scale >= RenderSettings::kMinRenderScale &&
        settings_.render_scale <= 1.0f))
    throw rp::cl::Error("render scale " + std::to_string(settings_.render_scale) +
                        " is outside [0.5, 1]");
  const auto start = std::chrono::steady_clock::now();
  const auto ms_since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t)
        .count();
  };
  scene_ = std::make_unique<GpuScene>(context.context, context.queue, assets);
  setup_times_.scene_ms = ms_since(start);
  setup_times_.mips_ms = scene_->mips_ms;
  const auto kernels_start = std::chrono::steady_clock::now();
  visibility_ = std::make_unique<passes::VisibilityPass>(context, programs);
  if (settings_.visibility == VisibilityBackend::kEmbree) {
    const auto bvh_start = std::chrono::steady_clock::now();
    embree_ = std::make_unique<passes::EmbreeVisibilityPass>(context, assets);
    setup_times_.bvh_ms = ms_since(bvh_start);
  }
  gbuffer_pass_ = std::make_unique<passes::GBufferPass>(context, programs);
  const bool svo = settings_.gi_volume == GiVolume::kSvo;
  if (!gi_resolution_supported(settings_.gi_volume, settings_.voxel_resolution))
    throw rp::cl::Error("the " + std::string(name_of(settings_.gi_volume)) +
                        " GI volume does not take " + std::to_string(settings_.voxel_resolution) +
                        " voxels per side (dense: 32, 64 or 128; svo: 256 or 512)");
  const std::string gi_options = svo ? "-DRP_GI_SVO" : "";
  if (svo) {
    svo_pass_ = std::make_unique<passes::SvoPass>(context, programs);
    // The tumblers (the mesh named "tumbler", made from scene::TumblerShape{}) and the spheres
    // are made solid at the octree's coarse levels (passes/svo_solid.h).
    for (size_t m = 0; m < assets.meshes.size() && m < scene_->meshes.size(); ++m)
      if (assets.meshes[m].name == "tumbler")
        svo_pass_->enable_solid(scene_->meshes[m].first_triangle, scene::TumblerShape{});
  } else {
    voxelize_ = std::make_unique<passes::VoxelizePass>(context, programs);
    voxel_mips_ = std::make_unique<passes::VoxelMipsPass>(context, programs);
  }
  if (settings_.bounces >= 2)
    bounce_ = std::make_unique<passes::BouncePass>(context, programs, gi_options);
  if (settings_.quality == Quality::kFast)
    indirect_ = std::make_unique<passes::IndirectPass>(context, programs, gi_options);
  light_ = std::make_unique<passes::LightPass>(context, programs,
                                               settings_.shadows, gi_options);
  light_->prepare(indirect_ != nullptr);
  punctual_ = std::make_unique<passes::PunctualLightPass>(programs);
  sky_background_ = std::make_unique<passes::SkyBackgroundPass>(programs);
  shadow_filter_ = std::make_unique<passes::ShadowFilterPass>(context, programs);
  tone_map_ = std::make_unique<passes::ToneMapPass>(context, programs);
  taa_ = std::make_unique<passes::TaaPass>(context, programs);
  taa_upsample_ = std::make_unique<passes::TaaUpsamplePass>(context, programs);
  bloom_ = std::make_unique<passes::BloomPass>(context, programs);
  motion_blur_ = std::make_unique<passes::MotionBlurPass>(context, programs);
  debug_view_pass_ =
      std::make_unique<passes::DebugViewPass>(context, programs, gi_options);  // builds lazily
  setup_times_.kernels_ms = ms_since(kernels_start) - setup_times_.bvh_ms;
  shadow_.resize(context.context, settings_.shadow_size);
  if (!svo) voxels_.resize(context.context, settings_.voxel_resolution);
  resize(settings_.width, settings_.height);
}

Renderer::~Renderer() = default;

void Renderer::resize(uint32_t width, uint32_t height) {
  if (width == 0 || height == 0) throw rp::cl::Error("render size must be at least 1x1 pixels");
  settings_.width = width;
  settings_.height = height;
  size_t n = size_t(width) * height;
  try {
    for (::cl::Buffer& b : post_) b = ::cl::Buffer(context_.context, CL_MEM_READ_WRITE, n * 16);
    rgba8_ = ::cl::Buffer(context_.context, CL_MEM_READ_WRITE, n * 4);
  } catch (const ::cl::Error& e) {
    if (out_of_device_memory(e.err())) throw_out_of_memory(e, width, height);
    throw;
  }
  const bool scaled = view_.view == passes::DebugView::kFinal;
  const float scale = scaled ? settings_.render_scale : 1.0f;
  resize_render(scaled_side(width, scale), scaled_side(height, scale));
}

void Renderer::resize_render(uint32_t width, uint32_t height) {
  if (width == render_width_ && height == render_height_) return;
  size_t n = size_t(width) * height;
  try {
    vis_.resize(context_.context, width, height);
    gbuffer_.resize(context_.context, width, height);
    hdr_ = ::cl::Buffer(context_.context, CL_MEM_READ_WRITE, n * 16);
    if (!indirect_) hdr_prev_ = ::cl::Buffer(context_.context, CL_MEM_READ_WRITE, n * 16);
  } catch (const ::cl::Error& e) {
    if (out_of_device_memory(e.err())) throw_out_of_memory(e, width, height);
    throw;
  }
  render_width_ = width;
  render_height_ = height;
  components_written_ = false;  // what they hold is of the old size
  hdr_prev_valid_ = false;
  update_light_components();    // reallocate at the new size (when they are needed)
}

void Renderer::set_render_scale(float scale) {
  settings_.render_scale = std::clamp(scale, RenderSettings::kMinRenderScale, 1.0f);
}

bool Renderer::upsampling() const {
  return view_.view == passes::DebugView::kFinal &&
         (settings_.render_scale < 1.0f || settings_.scale_follows_time);
}

void Renderer::set_debug_view(const passes::DebugViewSettings& view) {
  // The octree holds levels 0 .. log2 R - 1 (the dense chain's 1^3 top level is never traced).
  const uint32_t view_levels =
      settings_.gi_volume == GiVolume::kSvo ? gi_levels() - 1 : gi_levels();
  if (view.view == passes::DebugView::kVoxels && (view.level >= view_levels || view.dir >= 6))
    throw rp::cl::Error("voxel view: level " + std::to_string(view.level) + " direction " +
                        std::to_string(view.dir) + " does not exist (levels 0.." +
                        std::to_string(view_levels - 1) + ", directions 0..5)");
  view_ = view;
  update_light_components();
}

void Renderer::set_keep_light_components(bool keep) {
  keep_components_ = keep;
  update_light_components();
}

void Renderer::set_prt(const passes::PrtShading& prt) {
  prt_ = std::make_unique<passes::PrtSkyPass>(context_, programs_, *scene_, prt);
  scene_->set_sky_diffuse_cones(false);
  scene_->set_suns_in_voxels(!prt_->carries_suns_bounce());
}

void Renderer::update_light_components() {
  if (!passes::needs_light_components(view_.view) && !keep_components_) {
    light_components_ = {};
    components_pixels_ = 0;
    components_written_ = false;
    return;
  }
  const size_t n = size_t(render_width_) * render_height_;
  if (light_components_.direct() != nullptr && components_pixels_ == n) return;  // still fits
  components_written_ = false;
  try {
    light_components_.direct = ::cl::Buffer(context_.context, CL_MEM_READ_WRITE, n * 16);
    light_components_.indirect = ::cl::Buffer(context_.context, CL_MEM_READ_WRITE, n * 16);
    light_components_.specular = ::cl::Buffer(context_.context, CL_MEM_READ_WRITE, n * 16);
    components_pixels_ = n;
  } catch (const ::cl::Error& e) {
    light_components_ = {};
    components_pixels_ = 0;
    if (out_of_device_memory(e.err())) throw_out_of_memory(e, render_width_, render_height_);
    throw;
  }
}

rp::cl::PassTimes Renderer::render(const scene::FrameScene& frame) {
  try {
    const Effects& fx = settings_.effects;
    // A camera cut (this frame's previous camera is not what the last frame showed) makes the
    // TAA history meaningless.
    const glm::mat4 prev_view = frame.prev_camera.view();
    if (last_view_ && *last_view_ != prev_view) reset_view_history();
    last_view_ = frame.camera.view();
    const bool final_view = view_.view == passes::DebugView::kFinal;
    const bool upsample = upsampling();
    {
      const float scale = final_view ? settings_.render_scale : 1.0f;
      const uint32_t rw = scaled_side(settings_.width, scale);
      const uint32_t rh = scaled_side(settings_.height, scale);
      // the indirect pass resamples its history to the new size itself (passes/indirect.h)
      if (rw != render_width_ || rh != render_height_) resize_render(rw, rh);
    }
    const uint32_t jitter_frames =
        fx.taa && final_view
            ? (upsample ? passes::upsample_jitter_frames(settings_.render_scale) : 16u)
            : 0u;
    scene_->update(frame, render_width_, render_height_, settings_.shadow_size, gi_resolution(),
                   jitter_frames);
    double host_visibility_ms = 0.0;
    if (embree_)
      host_visibility_ms = embree_->render(profiler_, *scene_, vis_);
    else
      visibility_->render(profiler_, *scene_, vis_);
    // The punctual lights' views first: they may grow the depth buffer (a new one). Then the
    // lamp's map: a file scene without the demo's lamp (intensity 0) draws it once into each
    // depth buffer, so the lamp's shadow lookups read defined depths, and then leaves it.
    const ::cl::Buffer depth_before = shadow_.depth;
    visibility_->render_light_shadows(profiler_, *scene_, shadow_);
    if (shadow_.depth() != depth_before()) lamp_map_drawn_ = false;
    const gpu::rp_float4 lamp = scene_->constants.light_intensity;
    if (lamp.x != 0.0f || lamp.y != 0.0f || lamp.z != 0.0f || !lamp_map_drawn_) {
      visibility_->render_shadow(profiler_, *scene_, shadow_);
      lamp_map_drawn_ = true;
    }
    if (const uint32_t planes = shadow_mip_planes(light_->filter()); planes > 0)
      shadow_filter_->run(profiler_, *scene_, shadow_, planes > 1);
    // Texture detail for the output size: a render pixel covers 1 / scale output pixels per
    // axis, so the levels are log2(scale) finer than the render size alone would pick.
    const float lod_bias =
        (settings_.effects.taa ? passes::GBufferPass::kTaaTextureLodBias : 0.0f) +
        std::log2(float(render_width_) / float(settings_.width));
    gbuffer_pass_->run(profiler_, *scene_, vis_, gbuffer_,
                       texture_filter_code(settings_.texture_filter), lod_bias,
                       settings_.effects.taa);
    build_voxels();
    const bool split = passes::needs_light_components(view_.view) || keep_components_;
    passes::LowResIndirect low_res;
    if (indirect_) {
      // screen-space reflections: hdr_ still holds the previous frame's light pass output
      const passes::SsrInputs ssr{&vis_.depth, &hdr_, &gbuffer_.velocity};
      low_res = indirect_->run(profiler_, *scene_, gbuffer_, gi_buffer(), gi_resolution(),
                               gi_levels(), &ssr);
    }
    // the reference mode's screen-space reflections read the previous frame's light output
    const passes::SsrInputs ssr_reference{&vis_.depth, &hdr_prev_, &gbuffer_.velocity};
    const bool ssr_history = !indirect_ && hdr_prev_valid_;
    if (ssr_history)
      profiler_.queue().enqueueCopyBuffer(hdr_, hdr_prev_, 0, 0,
                                          size_t(render_width_) * render_height_ * 16);
    if (prt_) prt_->run(profiler_, *scene_, vis_, frame.environment, frame.lights);
    // a frame no history will average gets smooth penumbrae of its own
    light_->set_without_history(
        !(fx.taa && final_view &&
          (upsample ? taa_upsample_->history_valid() : taa_->history_valid())));
    light_->run(profiler_, *scene_, gbuffer_, shadow_, gi_buffer(), gi_resolution(),
                gi_levels(), hdr_, split ? &light_components_ : nullptr,
                indirect_ ? &low_res : nullptr, ssr_history ? &ssr_reference : nullptr,
                prt_ ? &prt_->output() : nullptr);
    punctual_->run(profiler_, *scene_, gbuffer_, shadow_, hdr_,
                   split ? &light_components_ : nullptr);
    sky_background_->run(profiler_, *scene_, gbuffer_, hdr_);
    hdr_prev_valid_ = !indirect_;
    if (final_view) {
      const uint32_t w = settings_.width, h = settings_.height;
      const ::cl::Buffer* colour = &hdr_;
      passes::MotionInputs motion = gbuffer_;  // velocity and depth at the output size
      const bool bloom_on = fx.bloom && fx.bloom_strength > 0.0f;
      const bool blur_on = fx.motion_blur && fx.shutter > 0.0f;
      int next = 0;
      if (upsample) {
        // without TAA: the current frame's reconstruction alone (no jitter, no history)
        if (!fx.taa) taa_upsample_->reset_history();
        taa_upsample_->set_motion_blur_shutter(blur_on ? fx.shutter : 0.0f);
        taa_upsample_->run(profiler_, *scene_, *colour, gbuffer_, w, h, post_[next]);
        colour = &post_[next];
        motion = taa_upsample_->motion();
        next ^= 1;
      } else if (fx.taa) {
        taa_->run(profiler_, *scene_, *colour, gbuffer_, vis_.depth, post_[next]);
        colour = &post_[next];
        next ^= 1;
      }
      if (bloom_on && blur_on) {  // the bloom's full-resolution mix fused into motion blur
        bloom_->run_chain(profiler_, *colour, w, h);
        motion_blur_->run(profiler_, *colour, motion, w, h, fx.shutter,
                          bloom_->composite(fx.bloom_strength), post_[next]);
        colour = &post_[next];
      } else {
        if (bloom_on) {
          bloom_->run(profiler_, *colour, w, h, fx.bloom_strength, post_[next]);
          colour = &post_[next];
          next ^= 1;
        }
        if (blur_on) {
          motion_blur_->run(profiler_, *colour, motion, w, h, fx.shutter, post_[next]);
          colour = &post_[next];
        }
      }
      tone_map_->run(profiler_, *scene_, *colour, w * h, rgba8_);
    } else {
      passes::DebugViewInputs in;
      in.gbuffer = &gbuffer_;
      in.shadow = &shadow_;
      in.light = split ? &light_components_ : nullptr;
      in.voxels = &gi_buffer();
      in.voxel_resolution = gi_resolution();
      in.voxel_levels = gi_levels();
      debug_view_pass_->run(profiler_, *scene_, view_, in, rgba8_);
    }
    components_written_ = split;
    rp::cl::PassTimes times = profiler_.collect();
    if (embree_) times[passes::pass_name::kVisibilityHost] = host_visibility_ms;
    return times;
  } catch (const ::cl::Error& e) {
    // The passes allocate their own per-size buffers (TAA history, bloom chain, motion blur
    // tiles) on the first frame.
    if (out_of_device_memory(e.err())) throw_out_of_memory(e, settings_.width, settings_.height);
    throw rp::cl::Error(std::string("OpenCL call failed while rendering: ") + e.what() + " (" +
                        rp::cl::error_name(e.err()) + ")");
  }
}

FrameMemory Renderer::frame_device_memory() const {
  namespace pass_name = passes::pass_name;
  using passes::buffer_bytes;
  FrameMemory m;
  m.add(pass_name::kVisibility, vis_.device_bytes() + visibility_->camera_tile_bytes());
  m.add(pass_name::kShadowMap, buffer_bytes({&shadow_.depth}) + visibility_->lamp_tile_bytes());
  m.add(pass_name::kShadowFilter, buffer_bytes({&shadow_.mips}));
  m.add(pass_name::kGBuffer, gbuffer_.device_bytes());
  if (indirect_) m.add(pass_name::kIndirectTrace, indirect_->frame_device_bytes());
  if (prt_) m.add(pass_name::kPrt, prt_->frame_device_bytes());
  m.add(pass_name::kLight,
        buffer_bytes({&hdr_, &hdr_prev_, &light_components_.direct, &light_components_.indirect,
                      &light_components_.specular}) +
            light_->frame_device_bytes());
  m.add(pass_name::kTaa, taa_->frame_device_bytes() + taa_upsample_->frame_device_bytes());
  m.add(pass_name::kBloom, bloom_->frame_device_bytes());
  m.add(pass_name::kMotionBlur, motion_blur_->frame_device_bytes());
  m.add(kPostBuffers, buffer_bytes({&post_[0], &post_[1]}));
  m.add(pass_name::kToneMap, buffer_bytes({&rgba8_}));
  return m;
}

void Renderer::set_effects(const Effects& effects) {
  if (effects.taa && !settings_.effects.taa) {
    taa_->reset_history();
    taa_upsample_->reset_history();
  }
  settings_.effects = effects;
}

void Renderer::set_shadows(ShadowMode mode) {
  settings_.shadows = mode;
  light_->set_filter(mode);
}

void Renderer::reset_view_history() {
  taa_->reset_history();
  taa_upsample_->reset_history();
  hdr_prev_valid_ = false;
  if (indirect_) indirect_->reset_history();
}

void Renderer::reset_history() {
  reset_view_history();
  if (bounce_) bounce_->reset();
  still_volume_.reset();  // the grid gathers again from its warm start before it is kept
}

const ::cl::Buffer* Renderer::bounce_grid() const {
  return bounce_ && bounce_->valid() ? &bounce_->grid() : nullptr;
}

const ::cl::Buffer& Renderer::gi_buffer() const {
  return settings_.gi_volume == GiVolume::kSvo ? svo_.buffer : voxels_.chain;
}

uint32_t Renderer::gi_resolution() const {
  return settings_.gi_volume == GiVolume::kSvo ? settings_.voxel_resolution : voxels_.resolution;
}

uint32_t Renderer::gi_levels() const {
  return settings_.gi_volume == GiVolume::kSvo
             ? gpu::rp_svo_log2(settings_.voxel_resolution) + 1
             : voxels_.levels;
}

void Renderer::build_voxels() {
  const uint32_t still = still_volume_.update(*scene_, shadow_, settings_);
  // (still >= 1 means the last frame saw these inputs and built or kept a volume from them)
  const bool keep = bounce_ ? settings_.quality == Quality::kFast && bounce_->valid() &&
                                  still >= kStillFramesBeforeKeep
                            : still >= 1;
  if (keep) return;
  // bounce_refresh: the static surface cache's bounce-light refresh stride (VoxelizePass).
  const auto voxelize = [&](bool with_bounce, uint32_t bounce_refresh = 1) {
    const ::cl::Buffer* grid = with_bounce ? &bounce_->grid() : nullptr;
    const uint32_t cells = passes::BouncePass::cells(gi_resolution());
    if (svo_pass_) {
      // The octree is rebuilt every frame from the frame's fragments (the static room's
      // surface samples come from the voxelizer's cache): see passes/svo.h.
      svo_pass_->run(profiler_, *scene_, shadow_, settings_.voxel_resolution, svo_, grid, cells);
      return;
    }
    voxelize_->set_bounce_refresh_stride(bounce_refresh);
    voxelize_->run(profiler_, *scene_, shadow_, voxels_, grid, cells);
    voxel_mips_->run(profiler_, voxels_);
  };
  if (!bounce_) {
    voxelize(false);
    return;
  }
  const bool reference = settings_.quality == Quality::kReference;
  const uint32_t frame = scene_->constants.frame_index;
  if (!bounce_->valid()) {
    // Warm start: every gather adds a bounce; iterate so that the first frame already shows
    // several (the fast mode then converges over the next frames).
    voxelize(false);
    const uint32_t iterations =
        std::min(settings_.bounces - 1, reference ? kWarmGathersReference : kWarmGathersFast);
    for (uint32_t i = 0; i < iterations; ++i) {
      bounce_->run(profiler_, *scene_, gi_buffer(), gi_resolution(), gi_levels(), frame,
                   passes::BouncePass::Cones::kAll);
      voxelize(true);
    }
  } else {
    // The fast mode refreshes the static samples' bounce light over several frames (the grid
    // itself lags 32); the reference mode every frame.
    voxelize(true, reference ? 1u : kBounceRefreshFast);
  }
  // This frame's gather, for the next frame's voxels.
  bounce_->run(profiler_, *scene_, gi_buffer(), gi_resolution(), gi_levels(), frame,
               reference ? passes::BouncePass::Cones::kAll : passes::BouncePass::Cones::kOne);
}

void Renderer::read_components(LinearComponents& out) {
  if (!components_written_)
    throw rp::cl::Error("the light components were not written: keep them "
                        "(set_keep_light_components) before rendering a frame");
  const uint32_t w = render_width_, h = render_height_;
  const size_t n = size_t(w) * h;
  std::vector<float> rgba(n * 4), albedo(n * 4);
  // float4 per pixel -> 3 floats; where the GBuffer's albedo.a says background (1 covered,
  // 0 background) the value of `background` (the sky seen directly: the combined image's), or
  // 0 without one, whatever the buffer holds there. The path tracer's layers hold the sky the
  // same way: in the combined image and in the emission (what the camera sees emitted).
  const auto read_rgb = [&](const ::cl::Buffer& buffer, std::vector<float>& rgb,
                            const std::vector<float>* background = nullptr) {
    context_.queue.enqueueReadBuffer(buffer, CL_TRUE, 0, n * 16, rgba.data());
    rgb.resize(n * 3);
    for (size_t i = 0; i < n; ++i)
      for (size_t c = 0; c < 3; ++c)
        rgb[3 * i + c] = albedo[4 * i + 3] != 0.0f ? rgba[4 * i + c]
                         : background            ? (*background)[3 * i + c]
                                                 : 0.0f;
  };
  try {
    context_.queue.enqueueReadBuffer(gbuffer_.albedo, CL_TRUE, 0, n * 16, albedo.data());
    out.width = w;
    out.height = h;
    // the light pass writes the sky (or 0) into background pixels: its own background
    context_.queue.enqueueReadBuffer(hdr_, CL_TRUE, 0, n * 16, rgba.data());
    out.combined.resize(n * 3);
    for (size_t i = 0; i < n; ++i)
      for (size_t c = 0; c < 3; ++c) out.combined[3 * i + c] = rgba[4 * i + c];
    read_rgb(light_components_.direct, out.direct);
    read_rgb(light_components_.indirect, out.indirect);
    read_rgb(light_components_.specular, out.specular);
    read_rgb(gbuffer_.emission, out.emission, &out.combined);
    read_rgb(gbuffer_.albedo, out.albedo);
  } catch (const ::cl::Error& e) {
    throw rp::cl::Error(std::string("OpenCL call failed while reading the light components: ") +
                        e.what() + " (" + rp::cl::error_name(e.err()) + ")");
  }
}

void Renderer::read_rgba8(std::vector<uint8_t>& out) {
  out.resize(size_t(settings_.width) * settings_.height * 4);
  context_.queue.enqueueReadBuffer(rgba8_, CL_TRUE, 0, out.size(), out.data());
}

}  // namespace rp::render
