#include "render/renderer.h"

#include "cl/error.h"
#include "passes/debug_view.h"
#include "passes/embree_visibility.h"
#include "passes/gbuffer.h"
#include "passes/bloom.h"
#include "passes/indirect.h"
#include "passes/light.h"
#include "passes/motion_blur.h"
#include "passes/taa.h"
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

}  // namespace

Renderer::Renderer(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                   const scene::SceneAssets& assets, RenderSettings settings)
    : context_(context), settings_(settings), profiler_(context.queue) {
  if (settings_.width == 0 || settings_.height == 0 || settings_.shadow_size == 0)
    throw rp::cl::Error("render size must be at least 1x1 pixels");
  scene_ = std::make_unique<GpuScene>(context.context, context.queue, assets);
  visibility_ = std::make_unique<passes::VisibilityPass>(context, programs);
  if (settings_.visibility == VisibilityBackend::kEmbree)
    embree_ = std::make_unique<passes::EmbreeVisibilityPass>(context, assets);
  gbuffer_pass_ = std::make_unique<passes::GBufferPass>(context, programs);
  voxelize_ = std::make_unique<passes::VoxelizePass>(context, programs);
  voxel_mips_ = std::make_unique<passes::VoxelMipsPass>(context, programs);
  if (settings_.quality == Quality::kFast)
    indirect_ = std::make_unique<passes::IndirectPass>(context, programs);
  light_ = std::make_unique<passes::LightPass>(context, programs);
  light_->prepare(indirect_ != nullptr);
  tone_map_ = std::make_unique<passes::ToneMapPass>(context, programs);
  taa_ = std::make_unique<passes::TaaPass>(context, programs);
  bloom_ = std::make_unique<passes::BloomPass>(context, programs);
  motion_blur_ = std::make_unique<passes::MotionBlurPass>(context, programs);
  debug_view_pass_ = std::make_unique<passes::DebugViewPass>(context, programs);  // builds lazily
  shadow_.resize(context.context, settings_.shadow_size);
  voxels_.resize(context.context, settings_.voxel_resolution);
  resize(settings_.width, settings_.height);
}

Renderer::~Renderer() = default;

void Renderer::resize(uint32_t width, uint32_t height) {
  if (width == 0 || height == 0) throw rp::cl::Error("render size must be at least 1x1 pixels");
  settings_.width = width;
  settings_.height = height;
  size_t n = size_t(width) * height;
  try {
    vis_.resize(context_.context, width, height);
    gbuffer_.resize(context_.context, width, height);
    hdr_ = ::cl::Buffer(context_.context, CL_MEM_READ_WRITE, n * 16);
    for (::cl::Buffer& b : post_) b = ::cl::Buffer(context_.context, CL_MEM_READ_WRITE, n * 16);
    rgba8_ = ::cl::Buffer(context_.context, CL_MEM_READ_WRITE, n * 4);
  } catch (const ::cl::Error& e) {
    if (out_of_device_memory(e.err())) throw_out_of_memory(e, width, height);
    throw;
  }
  if (light_components_.direct() != nullptr) set_debug_view(view_);  // reallocate at the new size
}

void Renderer::set_debug_view(const passes::DebugViewSettings& view) {
  if (view.view == passes::DebugView::kVoxels && (view.level >= voxels_.levels || view.dir >= 6))
    throw rp::cl::Error("voxel view: level " + std::to_string(view.level) + " direction " +
                        std::to_string(view.dir) + " does not exist (levels 0.." +
                        std::to_string(voxels_.levels - 1) + ", directions 0..5)");
  view_ = view;
  if (passes::needs_light_components(view.view)) {
    const size_t bytes = size_t(settings_.width) * settings_.height * 16;
    try {
      light_components_.direct = ::cl::Buffer(context_.context, CL_MEM_READ_WRITE, bytes);
      light_components_.indirect = ::cl::Buffer(context_.context, CL_MEM_READ_WRITE, bytes);
    } catch (const ::cl::Error& e) {
      light_components_ = {};
      if (out_of_device_memory(e.err())) throw_out_of_memory(e, settings_.width, settings_.height);
      throw;
    }
  } else {
    light_components_ = {};
  }
}

rp::cl::PassTimes Renderer::render(const scene::FrameScene& frame) {
  try {
    const Effects& fx = settings_.effects;
    // A camera cut (this frame's previous camera is not what the last frame showed) makes the
    // TAA history meaningless.
    const glm::mat4 prev_view = frame.prev_camera.view();
    if (last_view_ && *last_view_ != prev_view) reset_history();
    last_view_ = frame.camera.view();
    scene_->update(frame, settings_.width, settings_.height, settings_.shadow_size,
                   voxels_.resolution,
                   fx.taa && view_.view == passes::DebugView::kFinal ? 16u : 0u);
    double host_visibility_ms = 0.0;
    if (embree_)
      host_visibility_ms = embree_->render(profiler_, *scene_, vis_);
    else
      visibility_->render(profiler_, *scene_, vis_);
    visibility_->render_shadow(profiler_, *scene_, shadow_);
    gbuffer_pass_->run(profiler_, *scene_, vis_, gbuffer_);
    voxelize_->run(profiler_, *scene_, shadow_, voxels_);
    voxel_mips_->run(profiler_, voxels_);
    const bool split = passes::needs_light_components(view_.view);
    passes::LowResIndirect low_res;
    if (indirect_)
      low_res = indirect_->run(profiler_, *scene_, gbuffer_, voxels_.chain, voxels_.resolution,
                               voxels_.levels);
    light_->run(profiler_, *scene_, gbuffer_, shadow_, voxels_.chain, voxels_.resolution,
                voxels_.levels, hdr_, split ? &light_components_ : nullptr,
                indirect_ ? &low_res : nullptr);
    if (view_.view == passes::DebugView::kFinal) {
      const uint32_t w = settings_.width, h = settings_.height;
      const ::cl::Buffer* colour = &hdr_;
      int next = 0;
      if (fx.taa) {
        taa_->run(profiler_, *scene_, *colour, gbuffer_, post_[next]);
        colour = &post_[next];
        next ^= 1;
      }
      const bool bloom_on = fx.bloom && fx.bloom_strength > 0.0f;
      const bool blur_on = fx.motion_blur && fx.shutter > 0.0f;
      if (bloom_on && blur_on) {  // the bloom's full-resolution mix fused into motion blur
        bloom_->run_chain(profiler_, *colour, w, h);
        motion_blur_->run(profiler_, *colour, gbuffer_, w, h, fx.shutter,
                          bloom_->composite(fx.bloom_strength), post_[next]);
        colour = &post_[next];
      } else {
        if (bloom_on) {
          bloom_->run(profiler_, *colour, w, h, fx.bloom_strength, post_[next]);
          colour = &post_[next];
          next ^= 1;
        }
        if (blur_on) {
          motion_blur_->run(profiler_, *colour, gbuffer_, w, h, fx.shutter, post_[next]);
          colour = &post_[next];
        }
      }
      tone_map_->run(profiler_, *scene_, *colour, rgba8_);
    } else {
      passes::DebugViewInputs in;
      in.gbuffer = &gbuffer_;
      in.shadow = &shadow_;
      in.light = split ? &light_components_ : nullptr;
      in.voxels = &voxels_.chain;
      in.voxel_resolution = voxels_.resolution;
      in.voxel_levels = voxels_.levels;
      debug_view_pass_->run(profiler_, *scene_, view_, in, rgba8_);
    }
    rp::cl::PassTimes times = profiler_.collect();
    if (embree_) times["visibility_host"] = host_visibility_ms;
    return times;
  } catch (const ::cl::Error& e) {
    // The passes allocate their own per-size buffers (TAA history, bloom chain, motion blur
    // tiles) on the first frame.
    if (out_of_device_memory(e.err())) throw_out_of_memory(e, settings_.width, settings_.height);
    throw rp::cl::Error(std::string("OpenCL call failed while rendering: ") + e.what() + " (" +
                        rp::cl::error_name(e.err()) + ")");
  }
}

void Renderer::set_effects(const Effects& effects) {
  if (effects.taa && !settings_.effects.taa) taa_->reset_history();
  settings_.effects = effects;
}

void Renderer::reset_history() {
  taa_->reset_history();
  if (indirect_) indirect_->reset_history();
}

void Renderer::read_rgba8(std::vector<uint8_t>& out) {
  out.resize(size_t(settings_.width) * settings_.height * 4);
  context_.queue.enqueueReadBuffer(rgba8_, CL_TRUE, 0, out.size(), out.data());
}

}  // namespace rp::render
