#include "render/still_volume.h"

#include "io/fnv1a.h"

namespace rp::render {

uint32_t StillVolume::update(const GpuScene& scene, const ShadowMap& shadow,
                             const RenderSettings& settings) {
  io::Fnv1a h;
  scene.hash_lights_and_objects(h);
  const gpu::FrameConstants& c = scene.constants;
  h.value(c.voxel_resolution);
  h.value(c.voxel_levels);
  h.value(c.sky);
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
