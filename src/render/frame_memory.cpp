#include "render/frame_memory.h"

#include "passes/bloom.h"
#include "passes/indirect.h"
#include "passes/light.h"
#include "passes/motion_blur.h"
#include "passes/pass_names.h"
#include "passes/prt_sky.h"
#include "passes/shadow_filter.h"
#include "passes/taa.h"
#include "passes/taa_upsample.h"
#include "passes/visibility.h"
#include "render/frame_buffers.h"

namespace rp::render {

void FrameMemory::add(std::string_view name, uint64_t bytes) {
  for (auto& [part, sum] : parts)
    if (part == name) {
      sum += bytes;
      return;
    }
  parts.emplace_back(name, bytes);
}

uint64_t FrameMemory::of(std::string_view name) const {
  for (const auto& [part, bytes] : parts)
    if (part == name) return bytes;
  return 0;
}

uint64_t FrameMemory::total() const {
  uint64_t sum = 0;
  for (const auto& part : parts) sum += part.second;
  return sum;
}

void FrameMemory::take_max(const FrameMemory& other) {
  for (const auto& [name, bytes] : other.parts) {
    const uint64_t mine = of(name);
    if (bytes > mine) add(name, bytes - mine);
  }
}

FrameMemory frame_memory(const RenderSettings& settings, const FrameMemoryOptions& options) {
  namespace pass_name = passes::pass_name;
  const uint32_t w = settings.width, h = settings.height, s = settings.shadow_size;
  const bool upsampling = settings.render_scale < 1.0f || settings.scale_follows_time;
  const float scale = settings.scale_follows_time ? 1.0f : settings.render_scale;
  const uint32_t rw = scaled_side(w, scale), rh = scaled_side(h, scale);
  const uint64_t render_pixels = passes::pixel_count(rw, rh);
  const uint64_t output_pixels = passes::pixel_count(w, h);
  const Effects& fx = settings.effects;

  FrameMemory m;
  m.add(pass_name::kVisibility, VisibilityBuffer::frame_bytes(rw, rh));
  if (settings.visibility == VisibilityBackend::kRaster)
    m.add(pass_name::kVisibility, passes::VisibilityPass::tile_list_bytes(rw, rh));
  m.add(pass_name::kShadowMap,
        ShadowMap::frame_bytes(s) + passes::VisibilityPass::tile_list_bytes(s, s));
  if (const uint32_t planes = shadow_mip_planes(settings.shadows); planes > 0)
    m.add(pass_name::kShadowFilter, passes::ShadowFilterPass::frame_bytes(s, planes));
  m.add(pass_name::kGBuffer, GBuffer::frame_bytes(rw, rh));
  if (settings.quality == Quality::kFast)
    m.add(pass_name::kIndirectTrace, passes::IndirectPass::frame_bytes(rw, rh));
  if (options.prt) m.add(pass_name::kPrt, passes::PrtSkyPass::frame_bytes(rw, rh));
  // The light pass's output, float4; the reference mode's copy of the previous frame's (its
  // screen-space reflections); the three component images.
  const uint64_t light_images = 1 + (settings.quality == Quality::kReference ? 1 : 0) +
                                (options.light_components ? 3 : 0);
  m.add(pass_name::kLight, light_images * render_pixels * 16 +
                               passes::LightPass::frame_bytes(rw, rh, settings.shadows));
  // Temporal upsampling runs with or without TAA (without: no history is used).
  if (upsampling)
    m.add(pass_name::kTaa, passes::TaaUpsamplePass::frame_bytes(w, h, rw, rh));
  else if (fx.taa)
    m.add(pass_name::kTaa, passes::TaaPass::frame_bytes(rw, rh));
  if (fx.bloom && fx.bloom_strength > 0.0f)
    m.add(pass_name::kBloom, passes::BloomPass::frame_bytes(w, h));
  if (fx.motion_blur && fx.shutter > 0.0f)
    // (temporal upsampling makes the depth/speed plane beside its velocity)
    m.add(pass_name::kMotionBlur, passes::MotionBlurPass::frame_bytes(w, h, !upsampling));
  m.add(kPostBuffers, 2 * output_pixels * 16);
  m.add(pass_name::kToneMap, output_pixels * 4);  // RGBA8, also the debug views' output
  return m;
}

}  // namespace rp::render
