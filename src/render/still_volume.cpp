#include "render/still_volume.h"

#include <algorithm>

#include "io/fnv1a.h"

namespace rp::render {

uint32_t StillVolume::update(const GpuScene& scene, const ShadowMap& shadow,
                             const RenderSettings& settings) {
  io::Fnv1a h;
  const gpu::FrameConstants& c = scene.constants;
  h.value(c.light_view_proj);
  h.value(c.light_pos);
  h.value(c.light_intensity);
  h.value(c.clip.z);
  h.value(c.clip.w);
  h.value(c.shadow_size);
  h.value(c.voxel_resolution);
  h.value(c.voxel_levels);
  h.value(c.punctual_count);
  h.bytes(c.punctual, std::min<size_t>(c.punctual_count, RP_MAX_PUNCTUAL_LIGHTS) *
                          sizeof(c.punctual[0]));
  h.value(c.shadow_view_count);
  h.bytes(c.shadow_views, std::min<size_t>(c.shadow_view_count, RP_MAX_SHADOW_VIEWS) *
                              sizeof(c.shadow_views[0]));
  h.value(c.sky);
  h.value(uint64_t(scene.host_instances.size()));
  h.bytes(scene.host_instances.data(), scene.host_instances.size() * sizeof(gpu::Instance));
  h.value(uint64_t(scene.host_spheres.size()));
  h.bytes(scene.host_spheres.data(), scene.host_spheres.size() * sizeof(gpu::Sphere));
  h.value(settings.gi_volume);
  h.value(settings.voxel_resolution);
  h.value(settings.bounces);
  h.value(settings.quality);
  const bool same = valid_ && h.get() == key_ && depth_() == shadow.depth() &&
                    sky_() == scene.sky();
  still_frames_ = same ? still_frames_ + 1 : 0;
  key_ = h.get();
  valid_ = true;
  depth_ = shadow.depth;
  sky_ = scene.sky;
  return still_frames_;
}

}  // namespace rp::render
