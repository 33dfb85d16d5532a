// Frames from the simulated world (scene::World), driven by input events that come live from
// the window (recorded) or from a replayed input log, so a headless render reproduces an
// interactive session frame for frame.
//
// Step accounting: the "session step" counts fixed world steps actually taken since start; it
// never goes back (R resets the world, not the counter) and does not move while paused. Every
// event is stamped with the session step at which it was applied, and every displayed frame
// with a Frame event at the step it shows. Interactive frames take as many fixed steps as the
// wall clock says (capped); headless frames take 1/60 s worth of steps, or, when the replayed
// log has Frame marks, exactly the recorded number.
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "app/frame_source.h"
#include "scene/input.h"
#include "app/render_session.h"
#include "render/renderer.h"
#include "scene/world.h"

namespace rp::app {

// Render-side toggles that input can change (the world knows nothing of rendering); they start
// from the command line's choice and flip on key presses.
struct ViewToggles {
  bool taa = true;          // key T
  bool bloom = true;        // key B
  bool motion_blur = true;  // key M
};

struct SimulationArgs;

struct SimulationOptions {
  uint64_t seed = 1;
  bool marbles = false;
  bool fireball = false;
  double frame_seconds = 1.0 / 60.0;  // headless frame interval (without Frame marks)
  std::vector<scene::InputEvent> replay;  // events to replay (may hold Frame marks)
  ViewToggles toggles;                    // render toggles at the start
  // Keep every input event and frame mark in recording() (`run --record`). Off, a headless
  // render or bench keeps no per-frame log that grows with the frame count.
  bool record = false;
};

// From the command line's options; reads the --replay log (throws scene::InputLogError naming
// the file and line of a malformed log).
// `effects`: the command line's post-processing choice (the toggles start from it).
SimulationOptions make_simulation_options(const SimulationArgs& args,
                                          const render::Effects& effects);

// The command line's effects with the keys' toggles applied.
render::Effects effects_with(const render::Effects& base, const ViewToggles& toggles);


// Thrown by next_frame() when its step progress callback asked to stop.
class SimulationStopped : public std::runtime_error {
 public:
  SimulationStopped() : std::runtime_error("the simulation was stopped") {}
};

class SimulationFrameSource final : public FrameSource {
 public:
  // Steps per call of the step progress callback (about 10-20 ms of simulation here).
  static constexpr uint64_t kStepChunk = 4096;
  // (steps done, steps this frame takes); false stops the frame (next_frame throws
  // SimulationStopped).
  using StepProgress = std::function<bool(uint64_t done, uint64_t total)>;

  explicit SimulationFrameSource(SimulationOptions options);

  // A replayed frame mark may lie millions of steps ahead (minutes of simulation for one
  // frame): frames of more than kStepChunk steps advance in chunks and call `progress` after
  // each, so the caller can show progress and stop on Ctrl-C.
  void set_step_progress(StepProgress progress) { progress_ = std::move(progress); }

  // Interactive input: applied now (before the next frame's steps), stamped and recorded.
  void input(scene::InputEvent event);
  // Interactive frames: seconds of wall clock since the previous frame. Without a call, a frame
  // takes options.frame_seconds (headless).
  void set_elapsed_seconds(double seconds);

  // The next frame's scene, filled into a member whose vectors keep their capacity: after the
  // first frames no frame allocates (the capacity is reserved for the particle budget, the
  // marbles and a few fireballs). Valid until the next call.
  const scene::FrameScene& next_frame();
  // FrameSource: a copy of next_frame().
  scene::FrameScene next() override { return next_frame(); }
  uint32_t frames_produced() const override { return frames_; }

  // Frames the replay log asks for (its Frame marks; 0 when it has none).
  uint32_t replay_frames() const { return replay_frames_; }
  // Every input event and frame mark so far, stamped with its session step (empty unless
  // options.record).
  const scene::InputRecorder& recording() const { return recorder_; }
  const scene::World& world() const { return world_; }
  const ViewToggles& toggles() const { return toggles_; }
  // True once after the world was reset (key R): the renderer should drop its TAA history.
  bool take_reset() { return std::exchange(was_reset_, false); }
  bool paused() const { return paused_; }
  uint64_t session_step() const { return session_step_; }

 private:
  void apply(const scene::InputEvent& event);
  int steps_for_this_frame();
  void advance(uint64_t steps);

  SimulationOptions options_;
  StepProgress progress_;
  scene::World world_;
  scene::InputReplayer replayer_;
  scene::InputRecorder recorder_;
  scene::FrameScene frame_;  // next_frame()'s result, reused
  ViewToggles toggles_;
  uint32_t replay_frames_ = 0;
  uint32_t frames_ = 0;
  uint64_t session_step_ = 0;
  bool paused_ = false;
  bool single_step_ = false;
  bool dragging_ = false;
  bool was_reset_ = false;
  glm::vec2 last_cursor_{0.0f};
  double elapsed_seconds_ = -1.0;  // < 0: headless frame interval
  double time_debt_ = 0.0;         // wall-clock seconds not yet simulated
};

// One frame of the app loop: the source's next scene (input applied, world advanced), the
// toggles it ended with handed to the renderer (and its TAA history dropped after a reset),
// then rendered into `rgba`. Returns the per-pass times; frame_ms as RenderSession::render.
rp::cl::PassTimes render_next_frame(RenderSession& session, SimulationFrameSource& source,
                                    const render::Effects& base, std::vector<uint8_t>& rgba,
                                    double& frame_ms);

}  // namespace rp::app
