// The bench's scenes (see bench_scene.h).
#include "bench/src/bench_scene.h"

#include "app/simulation_source.h"
#include "bench/src/scene_file_facts.h"
#include "scene/particles.h"
#include "scene/world.h"

namespace rp::bench {

using app::CommonOptions;
using app::FileFrameSource;
using app::FileScene;
using app::FrameSource;
using app::RenderSession;
using app::SimulationFrameSource;
using app::make_simulation_options;
using app::open_scene_file;
using app::render_next_frame;

namespace {

// --scene busy: 30 marbles and a fireball (World with both on, seed --seed), settled for
// kSettleSteps fixed steps before the first frame; every frame then advances 1/60 s (4 steps)
// and tops the particle system up to its full budget (ParticleSystem::kMaxParticles = 2048)
// with ash clouds (ParticleSystem::emit_ash, 64 flakes each) at the marbles' centres in turn,
// drawing from the world's own particle stream. No input, no wall clock: every device gets the
// same frames, bit for bit.
class BusyFrameSource final : public FrameSource {
 public:
  static constexpr int kSettleSteps = 120;  // 0.5 s: marbles falling, fire trail formed
  static constexpr int kStepsPerFrame = 4;  // 1/60 s at 240 Hz

  explicit BusyFrameSource(uint64_t seed)
      : world_(scene::WorldConfig{seed, 1.0f / 240.0f, true, true}) {
    world_.advance(kSettleSteps);
    top_up();
  }

  scene::FrameScene next() override {
    world_.advance(kStepsPerFrame);
    top_up();
    scene::FrameScene frame;
    world_.fill_frame(frame);
    frame.frame_index = frames_++;
    return frame;
  }
  uint32_t frames_produced() const override { return frames_; }

 private:
  void top_up() {
    const auto& marbles = world_.marble_balls();
    const auto& fireballs = world_.fireball_balls();
    scene::ParticleSystem& particles = world_.particles();
    while (particles.live_count() < scene::ParticleSystem::kMaxParticles) {
      const scene::Ball* b = nullptr;
      if (!marbles.empty())
        b = &marbles[next_marble_++ % marbles.size()];
      else if (!fireballs.empty())
        b = &fireballs.front();
      glm::vec3 centre = b ? b->sphere.body.p : glm::vec3(0.0f);
      glm::vec3 velocity = b ? b->sphere.body.v : glm::vec3(0.0f);
      particles.emit_ash(centre, scene::world_constants::kMarbleRadius, velocity,
                         world_.particle_rng());
    }
  }

  scene::World world_;
  size_t next_marble_ = 0;
  uint32_t frames_ = 0;
};

// The demo as the command line sets it up (seed, marbles, fireball, replay): the app's frame
// loop, toggles and resets included.
class SimulationFrames final : public BenchFrames {
 public:
  SimulationFrames(const CommonOptions& common, const BenchOptions& options)
      : effects_(common.render.effects),
        source_(make_simulation_options(options.sim, common.render.effects)) {}
  rp::cl::PassTimes render(RenderSession& session, std::vector<uint8_t>& rgba,
                           double& frame_ms) override {
    return render_next_frame(session, source_, effects_, rgba, frame_ms);
  }
  scene::FrameScene last() const override {
    scene::FrameScene frame;
    source_.world().fill_frame(frame);  // the world's state is the last frame's
    return frame;
  }

 private:
  render::Effects effects_;
  SimulationFrameSource source_;
};

// Any other source: its frames with the command line's effects.
class SourceFrames final : public BenchFrames {
 public:
  SourceFrames(const render::Effects& effects, std::unique_ptr<FrameSource> source)
      : effects_(effects), source_(std::move(source)) {}
  rp::cl::PassTimes render(RenderSession& session, std::vector<uint8_t>& rgba,
                           double& frame_ms) override {
    last_ = source_->next();
    session.set_effects(effects_);
    return session.render(last_, rgba, frame_ms);
  }
  scene::FrameScene last() const override { return last_; }

 private:
  render::Effects effects_;
  std::unique_ptr<FrameSource> source_;
  scene::FrameScene last_;
};

}  // namespace

BenchScene::BenchScene(const CommonOptions& common, const BenchOptions& options)
    : common_(common), options_(options) {
  if (!is_bench_scene_file(options.scene)) return;
  file_ = std::make_unique<FileScene>(open_scene_file(options.scene));
  facts_ = scene_file_facts(*file_);
}

std::string BenchScene::kind() const {
  if (file_) return "file";
  return options_.scene == "busy" ? "busy" : "default";
}

std::unique_ptr<BenchFrames> BenchScene::frames() const {
  if (file_)
    return std::make_unique<SourceFrames>(common_.render.effects,
                                          std::make_unique<FileFrameSource>(*file_));
  if (options_.scene == "busy")
    return std::make_unique<SourceFrames>(
        common_.render.effects, std::make_unique<BusyFrameSource>(options_.sim.seed));
  return std::make_unique<SimulationFrames>(common_, options_);
}

}  // namespace rp::bench
