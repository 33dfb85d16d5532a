#include "app/simulation_source.h"

#include <algorithm>
#include <cmath>

#include "app/commands.h"
#include "app/input_file.h"
#include "scene/particles.h"
#include "scene/picking.h"

namespace rp::app {
namespace {

// Interactive frames simulate at most this many steps (1/30 s at 240 Hz): after a stall the
// simulation slows down instead of spiralling into ever longer frames.
constexpr int kMaxStepsPerFrame = 8;

}  // namespace

SimulationOptions make_simulation_options(const SimulationArgs& args,
                                          const render::Effects& effects) {
  SimulationOptions o;
  o.seed = args.seed;
  o.marbles = args.marbles;
  o.fireball = args.fireball;
  o.toggles = {effects.taa, effects.bloom, effects.motion_blur};
  if (!args.replay.empty()) o.replay = read_replay_log(args.replay);
  return o;
}

render::Effects effects_with(const render::Effects& base, const ViewToggles& toggles) {
  render::Effects e = base;
  e.taa = toggles.taa;
  e.bloom = toggles.bloom;
  e.motion_blur = toggles.motion_blur;
  return e;
}

SimulationFrameSource::SimulationFrameSource(SimulationOptions options)
    : options_(std::move(options)),
      world_(scene::WorldConfig{options_.seed, 1.0f / 240.0f, options_.marbles,
                                options_.fireball}),
      replayer_(options_.replay),
      toggles_(options_.toggles) {
  // Room (box, lamp) + 5 tumblers; spheres: marbles, a fireball or a few, the particle budget.
  frame_.instances.reserve(16);
  frame_.spheres.reserve(scene::ParticleSystem::kMaxParticles + 64);
  replay_frames_ = static_cast<uint32_t>(
      std::count_if(options_.replay.begin(), options_.replay.end(), [](const auto& e) {
        return e.type == scene::InputEventType::Frame;
      }));
}

void SimulationFrameSource::input(scene::InputEvent event) {
  event.step = session_step_;
  if (options_.record) recorder_.record(event);
  apply(event);
}

void SimulationFrameSource::set_elapsed_seconds(double seconds) {
  elapsed_seconds_ = std::max(0.0, seconds);
}

void SimulationFrameSource::apply(const scene::InputEvent& e) {
  using scene::InputEventType;
  namespace keys = scene::keys;
  switch (e.type) {
    case InputEventType::Key:
      switch (e.key) {
        case keys::kMarbles: world_.set_marbles(!world_.marbles()); break;
        case keys::kFireball: world_.set_fireball(!world_.fireball()); break;
        case keys::kMotionBlur: toggles_.motion_blur = !toggles_.motion_blur; break;
        case keys::kTaa: toggles_.taa = !toggles_.taa; break;
        case keys::kBloom: toggles_.bloom = !toggles_.bloom; break;
        case keys::kPause: paused_ = !paused_; break;
        case keys::kReset:
          world_.reset();
          was_reset_ = true;
          break;
        case keys::kSingleStep: single_step_ = paused_; break;
        default: break;  // other keys belong to the view (debug views), not the world
      }
      break;
    case InputEventType::MouseDown: {
      glm::vec2 viewport = e.viewport;
      glm::mat4 vp = world_.camera().projection(viewport.x / viewport.y) * world_.camera().view();
      scene::Ray ray = scene::camera_ray(glm::inverse(vp), e.cursor, viewport);
      dragging_ = world_.begin_drag(ray.origin, ray.direction);
      last_cursor_ = e.cursor;
      break;
    }
    case InputEventType::MouseMove:
      if (dragging_) {
        glm::vec2 viewport = e.viewport;
        glm::mat4 vp =
            world_.camera().projection(viewport.x / viewport.y) * world_.camera().view();
        scene::Ray ray = scene::camera_ray(glm::inverse(vp), e.cursor, viewport);
        world_.drag(ray.origin, ray.direction, e.cursor - last_cursor_);
      }
      last_cursor_ = e.cursor;
      break;
    case InputEventType::MouseUp:
      if (dragging_) world_.end_drag();
      dragging_ = false;
      break;
    case InputEventType::Frame:
      break;
  }
}

int SimulationFrameSource::steps_for_this_frame() {
  const double dt = world_.config().dt;
  if (paused_) {
    int n = single_step_ ? 1 : 0;
    single_step_ = false;
    return n;
  }
  double seconds = elapsed_seconds_ >= 0.0 ? elapsed_seconds_ : options_.frame_seconds;
  time_debt_ += seconds;
  int n = static_cast<int>(std::floor(time_debt_ / dt + 1e-9));
  if (n > kMaxStepsPerFrame) {
    n = kMaxStepsPerFrame;
    time_debt_ = 0.0;  // drop what cannot be caught up
  } else {
    time_debt_ -= n * dt;
  }
  return n;
}

void SimulationFrameSource::advance(uint64_t steps) {
  // World::advance takes an int: chunks keep every count in range (replay steps are below 2^31
  // too, scene/input.h) and give the progress callback its chances to run.
  for (uint64_t done = 0; done < steps;) {
    const uint64_t chunk = std::min(steps - done, kStepChunk);
    world_.advance(static_cast<int>(chunk));
    session_step_ += chunk;
    done += chunk;
    if (steps > kStepChunk && progress_ && !progress_(done, steps)) throw SimulationStopped();
  }
}

const scene::FrameScene& SimulationFrameSource::next_frame() {
  // Replayed events due now (stamped at or before the current session step) come first, as
  // live input does in the interactive loop.
  for (const scene::InputEvent& e : replayer_.due(session_step_))
    if (e.type != scene::InputEventType::Frame) apply(e);

  if (frames_ < replay_frames_) {
    // Follow the recorded frame schedule: advance to the step the next Frame mark shows.
    const std::vector<scene::InputEvent>& events = replayer_.events();
    uint32_t seen = 0;
    uint64_t target = session_step_;
    for (const scene::InputEvent& e : events)
      if (e.type == scene::InputEventType::Frame && seen++ == frames_) {
        target = e.step;
        break;
      }
    advance(target - std::min(target, session_step_));
  } else {
    advance(static_cast<uint64_t>(steps_for_this_frame()));
  }
  if (options_.record) recorder_.record(scene::InputEvent::frame(session_step_));

  world_.fill_frame(frame_);  // clears and refills; the vectors keep their capacity
  frame_.frame_index = frames_++;
  return frame_;
}

rp::cl::PassTimes render_next_frame(RenderSession& session, SimulationFrameSource& source,
                                    const render::Effects& base, std::vector<uint8_t>& rgba,
                                    double& frame_ms) {
  const scene::FrameScene& frame = source.next_frame();
  session.set_effects(effects_with(base, source.toggles()));
  if (source.take_reset()) session.reset_history();
  return session.render(frame, rgba, frame_ms);
}

}  // namespace rp::app
