// Whether the GI volume of the last frame (the dense chain or the octree, and the bounce grid)
// still holds for this one, so that the renderer can keep it instead of building it again.
//
// What the volume is built from: the lamp and its shadow projection, the punctual lights and
// their shadow views, the shadow maps (drawn from those and the instances and spheres), every
// instance (transform, triangles, voxel proxy), every sphere, the sky the cones and the bounce
// grid gather (its record and texels), and the GI settings (volume kind, resolution, bounces,
// quality). update() hashes them each frame (64-bit FNV-1a, as the voxelizer's direct-light
// key) and counts the frames in a row that had the same inputs; it holds the shadow depth and
// sky buffers it compared, so their handles cannot come back as other buffers'.
//
// With one bounce the volume is a function of those inputs alone: a still frame's volume is
// the last one's, bit for bit. With several, every frame's gather changes the bounce grid a
// little (one cone per face, a running mean), so a kept volume freezes the grid where it
// stands: the renderer does so only once every face has gathered its whole cone set from a
// still scene (render/renderer.h: kStillFramesBeforeKeep).
#pragma once

#include <cstdint>

#include "render/frame_buffers.h"
#include "render/gpu_scene.h"
#include "render/render_settings.h"

namespace rp::render {

class StillVolume {
 public:
  // Records this frame's inputs; returns how many frames before this one in a row had the same
  // (0 after any change, and on the first frame).
  uint32_t update(const GpuScene& scene, const ShadowMap& shadow, const RenderSettings& settings);
  // Forgets the inputs (the next update returns 0).
  void reset() { valid_ = false; }

 private:
  uint64_t key_ = 0;
  bool valid_ = false;
  uint32_t still_frames_ = 0;
  ::cl::Buffer depth_, sky_;  // the buffers the key was taken with
};

}  // namespace rp::render
