// Where the frames the app renders come from. Today: the static demo scene. Later a simulation
// (scene::World stepping at a fixed dt) implements the same interface, so render / run / bench
// loops stay unchanged.
#pragma once

#include <cstdint>

#include "scene/demo_scene.h"
#include "scene/frame_scene.h"

namespace rp::app {

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // The scene of the next frame (advances the simulation by one frame where there is one).
  virtual scene::FrameScene next() = 0;
  // Frames handed out so far.
  virtual uint32_t frames_produced() const = 0;
};

// scene::make_demo_frame(assets, 0), (assets, 1), ...
class DemoFrameSource final : public FrameSource {
 public:
  explicit DemoFrameSource(const scene::SceneAssets& assets) : assets_(&assets) {}
  scene::FrameScene next() override { return scene::make_demo_frame(*assets_, index_++); }
  uint32_t frames_produced() const override { return index_; }

 private:
  const scene::SceneAssets* assets_;
  uint32_t index_ = 0;
};

}  // namespace rp::app
