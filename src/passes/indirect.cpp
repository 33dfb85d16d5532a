#include "passes/indirect.h"

#include <cstring>

#include <algorithm>
#include <string>

#include <glm/glm.hpp>

#include "cl/error.h"
#include "cl/kernel_args.h"
#include "passes/light.h"
#include "passes/pass_names.h"
#include "render/sky_texture.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 8;  // 8x8 work-groups over the low-resolution grid

glm::mat4 to_glm(const gpu::rp_mat4& m) {
  glm::mat4 out;
  for (int c = 0; c < 4; ++c) out[c] = glm::vec4(m.c[c].x, m.c[c].y, m.c[c].z, m.c[c].w);
  return out;  // both column-major
}

}  // namespace

float pixel_scale(const render::GpuScene& scene) {
  const glm::mat4 projection =
      to_glm(scene.constants.view_proj_unjittered) * glm::inverse(to_glm(scene.constants.view));
  const float p11 = projection[1][1];
  const uint32_t height = scene.constants.height;
  if (height == 0 || !(p11 > 0.0f)) return 0.0f;
  return 2.0f / (float(height) * p11);
}

IndirectPass::IndirectPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                           const std::string& gi_options)
    : context_(&context),
      programs_(&programs),
      gi_options_(gi_options),
      octree_(!gi_options.empty()),
      filter_(programs.kernel("indirect.cl", "indirect_filter",
                              rp::cl::join_options({render::kNoDiffuseSkyOption, gi_options}))),
      min_z_(programs.kernel("ssr.cl", "ssr_min_z")) {
  trace_kernel(false, false);
  trace_kernel(true, false);
}

::cl::Kernel& IndirectPass::trace_kernel(bool warm, bool sky) {
  std::optional<::cl::Kernel>& k = traces_[warm][sky];
  if (!k)
    k = programs_->kernel("indirect.cl", "indirect_trace",
                          rp::cl::join_options({warm ? "-DRP_INDIRECT_WARM_START=1" : "",
                                        sky ? "" : render::kNoDiffuseSkyOption, gi_options_}));
  return *k;
}

uint32_t IndirectPass::ssr_top_level(uint32_t w, uint32_t h) {
  uint32_t top = 0;
  while (top < 6 && (std::max(w, h) >> (top + 1)) >= 2) ++top;
  return top;
}

uint64_t IndirectPass::hiz_floats(uint32_t w, uint32_t h) {
  uint64_t floats = 1;
  for (uint32_t k = 1, lw = w, lh = h; k <= ssr_top_level(w, h); ++k) {
    lw = (lw + 1) / 2;
    lh = (lh + 1) / 2;
    floats += uint64_t(lw) * lh;
  }
  return floats;
}

// Planes per resize(): radiance 3, specular 3, specular_filled 2 x 3, position 4, geometry
// 2 x 4, history 2 x 5.
uint64_t IndirectPass::frame_bytes(uint32_t w, uint32_t h) {
  const uint64_t plane = uint64_t(plane_size(low_res(w), low_res(h))) * sizeof(float);
  return (3 + 3 + 2 * 3 + 4 + 2 * 4 + 2 * 5) * plane + hiz_floats(w, h) * sizeof(float) + 16;
}

uint64_t IndirectPass::frame_device_bytes() const {
  return buffer_bytes({&radiance_, &specular_, &specular_filled_[0], &specular_filled_[1],
                       &position_, &geometry_[0], &geometry_[1], &history_[0], &history_[1],
                       &hiz_, &dummy_});
}

void IndirectPass::resize(uint32_t width, uint32_t height) {
  width_ = width;
  height_ = height;
  const size_t plane = size_t(plane_size(low_res(width), low_res(height))) * sizeof(float);
  radiance_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, 3 * plane);
  specular_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, 3 * plane);
  for (::cl::Buffer& b : specular_filled_) b = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, 3 * plane);
  const size_t bytes = 4 * plane;
  position_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, bytes);
  for (int slot = 0; slot < 2; ++slot) reallocate_slot(slot);
  // Defined contents from the start (the filter ignores the previous frame's planes until
  // history_valid_, but they are read).
  // The padding must stay zero (kernels/common/indirect.h); the kernels write only samples.
  // Except in the traced reflections, which only indirect_filter reads: -3 there marks "no
  // surface", like the background's samples, so that every value >= 0 is a traced coat.
  for (::cl::Buffer* b : {&radiance_, &specular_filled_[0], &specular_filled_[1], &position_})
    context_->queue.enqueueFillBuffer(*b, 0.0f, 0, b->getInfo<CL_MEM_SIZE>());
  context_->queue.enqueueFillBuffer(specular_, -3.0f, 0, specular_.getInfo<CL_MEM_SIZE>());
  hiz_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE,
                      size_t(hiz_floats(width, height)) * sizeof(float));
  dummy_ = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, 16);
  context_->queue.enqueueFillBuffer(dummy_, 0.0f, 0, 16);
  prev_width_ = width;
  prev_height_ = height;
  stale_slot_ = false;
  history_valid_ = false;
}

void IndirectPass::reallocate_slot(int slot) {
  const size_t plane = size_t(plane_size(low_res(width_), low_res(height_))) * sizeof(float);
  geometry_[slot] = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, 4 * plane);
  history_[slot] = ::cl::Buffer(context_->context, CL_MEM_READ_WRITE, 5 * plane);
  for (::cl::Buffer* b : {&geometry_[slot], &history_[slot]})
    context_->queue.enqueueFillBuffer(*b, 0.0f, 0, b->getInfo<CL_MEM_SIZE>());
}

LowResIndirect IndirectPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                                 const render::GBuffer& gbuffer, const ::cl::Buffer& voxels,
                                 uint32_t voxel_resolution, uint32_t voxel_levels,
                                 const SsrInputs* ssr) {
  const uint32_t w = scene.constants.width, h = scene.constants.height;
  if (gbuffer.width != w || gbuffer.height != h)
    throw rp::cl::Error("indirect pass: frame size " + std::to_string(w) + "x" +
                        std::to_string(h) + " does not match the GBuffer (" +
                        std::to_string(gbuffer.width) + "x" + std::to_string(gbuffer.height) +
                        ")");
  check_voxel_chain("indirect pass", voxels, voxel_resolution, voxel_levels, octree_);
  if (w == 0 || h == 0) return {};
  const int cur = current_, prev = current_ ^ 1;
  if (w != width_ || h != height_) {
    // A new render size (the render scale moved): the previous frame's geometry and history
    // planes are kept in their old layout and resampled by this frame's filter, so the blocks
    // keep their light instead of starting over (a start traces all 16 cones: a frame many
    // times slower, which a held frame rate would feel at every change of scale).
    const bool carry = history_valid_ && width_ != 0;
    const ::cl::Buffer old_geometry = geometry_[prev], old_history = history_[prev];
    const uint32_t old_w = width_, old_h = height_;
    resize(w, h);
    if (carry) {
      geometry_[prev] = old_geometry;
      history_[prev] = old_history;
      prev_width_ = old_w;
      prev_height_ = old_h;
      history_valid_ = true;
    }
  } else if (stale_slot_) {
    reallocate_slot(cur);  // the old size's planes, read last frame: this frame writes here
    stale_slot_ = false;
  }
  const bool resampled = prev_width_ != w || prev_height_ != h;
  const uint32_t lw = low_res(w), lh = low_res(h);
  const uint32_t stride = plane_stride(lw), plane = plane_size(lw, lh);
  const float scale = pixel_scale(scene);
  const ::cl::NDRange local(kGroup, kGroup);

  // The min-Z pyramid for the screen-space reflections, finest level first.
  const uint32_t top = ssr ? ssr_top_level(w, h) : 0u;
  for (uint32_t k = 1, sw = w, sh = h, src_off = 0, dst_off = 0; k <= top; ++k) {
    const uint32_t dw = (sw + 1) / 2, dh = (sh + 1) / 2;
    const gpu::MinZLevel level{src_off, sw, sh, dst_off, dw, dh, 0u, 0u};
    rp::cl::bind_args(min_z_, k == 1 ? *ssr->depth : hiz_, hiz_, level);
    profiler.enqueue(pass_name::kSsrMinZ, min_z_,
                     ::cl::NDRange(rp::cl::round_up(dw, kGroup), rp::cl::round_up(dh, kGroup)),
                     ::cl::NDRange(kGroup, kGroup));
    src_off = dst_off;  // level k is the next level's source
    dst_off += dw * dh;
    sw = dw;
    sh = dh;
  }

  // Without history the block traces the whole cone set (a converged-looking first frame after
  // a start, reset or camera cut, at 16x the trace cost for that one frame).
  ::cl::Kernel& trace = trace_kernel(!history_valid_, scene.constants.sky.diffuse_cones != 0);
  gpu::LowResPlanes planes{};
  planes.width = lw;
  planes.height = lh;
  planes.stride = stride;
  planes.plane = plane;
  planes.pixel_scale = scale;
  gpu::IndirectTraceParams trace_params{};
  trace_params.planes = planes;
  trace_params.voxel_resolution = voxel_resolution;
  trace_params.voxel_levels = voxel_levels;
  trace_params.ssr_top = top;
  // after a change of size the previous light output is not of this size (Renderer: a new
  // buffer)
  trace_params.ssr_history = ssr && history_valid_ && !resampled ? 1u : 0u;
  rp::cl::bind_args(trace, scene.frame, gbuffer.normal_depth, gbuffer.position, gbuffer.emission,
                    voxels, scene.sky, radiance_, position_, geometry_[cur], specular_,
                    ssr ? *ssr->depth : dummy_, ssr ? hiz_ : dummy_,
                    ssr ? *ssr->prev_hdr : dummy_, ssr ? *ssr->velocity : dummy_, trace_params);
  profiler.enqueue(pass_name::kIndirectTrace, trace,
                   ::cl::NDRange(rp::cl::round_up(lw, kGroup), rp::cl::round_up(lh, kGroup)),
                   local);

  // reflections move with the view: their history is used only while the camera stands still
  const bool still = std::memcmp(&scene.constants.view_proj_unjittered,
                                 &scene.constants.prev_view_proj_unjittered,
                                 sizeof(scene.constants.view_proj_unjittered)) == 0;
  gpu::IndirectFilterParams filter_params{};
  filter_params.planes = planes;
  filter_params.history_valid = history_valid_ ? 1u : 0u;
  filter_params.alpha_min = kAlphaMin;
  filter_params.specular_history = history_valid_ && still && !resampled ? 1u : 0u;
  const uint32_t plw = low_res(prev_width_), plh = low_res(prev_height_);
  filter_params.prev_planes = planes;
  filter_params.prev_planes.width = plw;
  filter_params.prev_planes.height = plh;
  filter_params.prev_planes.stride = plane_stride(plw);
  filter_params.prev_planes.plane = plane_size(plw, plh);
  filter_params.prev_width = prev_width_;
  filter_params.prev_height = prev_height_;
  // 8 samples of a row per work-item (kernels/common/indirect_simd.h).
  rp::cl::bind_args(filter_, scene.frame, radiance_, position_, geometry_[cur], geometry_[prev],
                    history_[prev], history_[cur], specular_, specular_filled_[prev],
                    specular_filled_[cur], filter_params);
  profiler.enqueue(pass_name::kIndirectFilter, filter_,
                   ::cl::NDRange(rp::cl::round_up((lw + 7) / 8, kGroup), rp::cl::round_up(lh, kGroup)),
                   local);

  history_valid_ = true;
  current_ = prev;  // this frame's planes become the previous ones
  if (resampled) {  // the old size's slot is written next frame: reallocated then
    prev_width_ = w;
    prev_height_ = h;
    stale_slot_ = true;
  }
  LowResIndirect out;
  out.width = lw;
  out.height = lh;
  out.stride = stride;
  out.plane = plane;
  out.irradiance = &history_[cur];
  out.geometry = &geometry_[cur];
  out.specular = &specular_filled_[cur];
  out.pixel_scale = scale;
  return out;
}

}  // namespace rp::passes
