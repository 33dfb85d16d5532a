// Cost of one World::step() with the full load of issue 3: 5 tumblers, 30 marbles, 1 fireball and
// a full particle budget (2048). Reports the median (and p10/p90) wall-clock microseconds of
// single steps. Marbles burned by the fireball are respawned and the particle budget is topped
// up with sparks between timed steps (untimed), so every timed step sees the full load.
//
//   bench_physics [--steps N] [--seed S]      (defaults: 4000 steps, seed 1)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "scene/world.h"

namespace {

using rp::scene::ParticleSystem;
using rp::scene::World;
using rp::scene::WorldConfig;

void top_up(World& world) {
  if (world.marble_balls().size() < rp::scene::world_constants::kMarbleCount) {
    world.set_marbles(false);
    world.set_marbles(true);
  }
  auto& rng = world.particle_rng();
  while (world.particles().live_count() < ParticleSystem::kMaxParticles) {
    const glm::vec3 at(rng.uniform(-0.9f, 0.9f), rng.uniform(-0.9f, 0.9f), rng.uniform(-0.9f, 0.9f));
    world.particles().emit_sparks(at, rng.unit_vector(), rng);
  }
}

}  // namespace

int main(int argc, char** argv) {
  int steps = 4000;
  uint64_t seed = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--steps") == 0) {
      steps = std::max(1, std::atoi(argv[i + 1]));
    } else if (std::strcmp(argv[i], "--seed") == 0) {
      seed = std::strtoull(argv[i + 1], nullptr, 10);
    } else {
      std::fprintf(stderr, "usage: bench_physics [--steps N] [--seed S]\n");
      return 2;
    }
  }
  World world(WorldConfig{seed, 1.0f / 240.0f, true, true});
  for (int i = 0; i < 240; ++i) world.step();  // 1 s: everything moving, fire burning

  std::vector<double> us;
  us.reserve(static_cast<size_t>(steps));
  size_t min_particles = ParticleSystem::kMaxParticles, min_marbles = 30;
  for (int i = 0; i < steps; ++i) {
    top_up(world);
    min_particles = std::min(min_particles, world.particles().live_count());
    min_marbles = std::min(min_marbles, world.marble_balls().size());
    const auto t0 = std::chrono::steady_clock::now();
    world.step();
    const auto t1 = std::chrono::steady_clock::now();
    us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
  }
  std::sort(us.begin(), us.end());
  auto pct = [&](double p) { return us[static_cast<size_t>(p * static_cast<double>(us.size() - 1))]; };
  std::printf("physics step: 5 tumblers, %zu+ marbles, %zu fireball, %zu+ particles (budget %zu), "
              "%d steps of %.4f s\n",
              min_marbles, world.fireball_balls().size(), min_particles,
              ParticleSystem::kMaxParticles, steps, static_cast<double>(world.config().dt));
  std::printf("median %.1f us  (p10 %.1f, p90 %.1f, max %.1f)\n", pct(0.5), pct(0.1), pct(0.9),
              us.back());
  return 0;
}
