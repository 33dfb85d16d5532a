// Where the frames the app renders come from (SimulationFrameSource: the simulated world).
#pragma once

#include <cstdint>

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

}  // namespace rp::app
