// The particle system allocates once (its ring buffer) and never while emitting or stepping, even
// when full. Global operator new/delete are replaced in this test binary by versions that forward
// to malloc/free and count allocations on the calling thread while a probe is armed; everything
// else in the binary is unaffected.
#include <cstdlib>
#include <new>

#include <gtest/gtest.h>

#include "scene/particles.h"

namespace {
thread_local bool g_counting = false;
thread_local size_t g_allocations = 0;
}  // namespace

void* operator new(std::size_t size) {
  if (g_counting) ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return ::operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace {

using rp::scene::ParticleSystem;
using rp::scene::Rng;

TEST(ParticlesAllocation, NoHeapAllocationWhenEmittingOrStepping) {
  ParticleSystem ps;  // the one allocation happens here
  Rng rng(3);
  g_counting = true;
  g_allocations = 0;
  for (int step = 0; step < 240; ++step) {
    ps.emit_fire(glm::vec3(0.0f), 0.1f, glm::vec3(0.3f, 0.0f, 0.0f), 1.0f / 120.0f, rng);
    for (int k = 0; k < 10; ++k) ps.emit_sparks(glm::vec3(0.0f, -0.9f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), rng);
    ps.emit_ash(glm::vec3(0.2f, 0.0f, 0.0f), 0.05f, glm::vec3(0.5f, 0.0f, 0.0f), rng);
    ps.step(1.0f / 120.0f, rng);
    (void)ps.hash();
  }
  const size_t allocations = g_allocations;
  const size_t live = ps.live_count();
  g_counting = false;
  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(live, ParticleSystem::kMaxParticles);  // it was full, so recycling was exercised
}

TEST(ParticlesAllocation, ProbeSeesAnAllocation) {  // the probe itself works
  g_counting = true;
  g_allocations = 0;
  void* volatile p = ::operator new(16);  // volatile: the call cannot be optimised away
  const size_t allocations = g_allocations;
  g_counting = false;
  ::operator delete(p);
  EXPECT_EQ(allocations, 1u);
}

}  // namespace
