// No per-frame host allocations after warm-up. Runs the app's frame loop in process
// (SimulationFrameSource: input, World steps and fill_frame; RenderSession: Renderer::render and
// the RGBA8 read-back, exactly what `rolypoly render` does per frame before writing the PNG)
// and counts every C++ heap allocation (global operator new, all threads: alloc_counter.h) over
// steady-state frames of a busy scene: marbles, a fireball burning them, fire particles, TAA,
// bloom, motion blur.
//
// Not counted: malloc inside the C OpenCL runtime (ocl-icd, PoCL: command and event structures
// of every enqueue) and the PNG encoder (stb, after the frame). On failure the message lists the
// allocating call sites with their count per frame; ROLYPOLY_ALLOC_REPORT=1 prints that list
// even when the test passes.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "alloc_counter.h"
#include "app/commands.h"
#include "app/render_session.h"
#include "app/simulation_source.h"
#include "cl/context.h"

namespace rp::test {
namespace {

// The target: our code allocates nothing per frame once warm. (The OpenCL C++ bindings used on
// the frame path, enqueueNDRangeKernel / enqueueWriteBuffer / enqueueReadBuffer / cl::Event,
// allocate nothing either: they pass the caller's storage straight to the C API.)
constexpr uint64_t kAllowedPerFrame = 0;
constexpr int kWarmupFrames = 40;    // kernels built, history and particle counts up
constexpr int kMeasuredFrames = 30;  // 0.5 s of simulation: particles born and dying

TEST(SteadyStateAllocations, AppFrameLoopAllocatesNothingAfterWarmUp) {
  if (!AllocationCounter::enabled())
    GTEST_SKIP() << "operator new is AddressSanitizer's in this build; nothing to count";
  rp::cl::ensure_pocl_cache_dir();
  app::CommonOptions common;  // every effect on, the default (fast) quality
  common.render.voxel_resolution = 32;
  common.render.shadow_size = 128;
  app::RenderSession session(common, 48, 40);
  app::SimulationArgs args;
  args.marbles = true;
  args.fireball = true;
  args.seed = 3;
  app::SimulationFrameSource source(app::make_simulation_options(args, common.render.effects));
  std::vector<uint8_t> rgba;
  double frame_ms = 0.0;
  for (int i = 0; i < kWarmupFrames; ++i)
    app::render_next_frame(session, source, common.render.effects, rgba, frame_ms);

  AllocationCounter::start_recording();
  const uint64_t before = AllocationCounter::count();
  for (int i = 0; i < kMeasuredFrames; ++i)
    app::render_next_frame(session, source, common.render.effects, rgba, frame_ms);
  const uint64_t allocations = AllocationCounter::count() - before;
  AllocationCounter::stop_recording();

  // The scene really is busy and changing while measured.
  ASSERT_EQ(rgba.size(), size_t(48) * 40 * 4);
  // The counter sees allocations: a fresh FrameScene's vectors must grow (what every frame
  // cost when the source built a new FrameScene per frame).
  const uint64_t fresh_before = AllocationCounter::count();
  scene::FrameScene last;
  source.world().fill_frame(last);
  EXPECT_GE(AllocationCounter::count() - fresh_before, 2u) << "the counter counts nothing?";
  EXPECT_FALSE(source.world().marble_balls().empty());
  EXPECT_GT(last.spheres.size(), source.world().marble_balls().size() + 10) << "fire particles";
  const std::string sites = AllocationCounter::report(kMeasuredFrames);
  if (std::getenv("ROLYPOLY_ALLOC_REPORT")) std::printf("%s", sites.c_str());
  EXPECT_LE(allocations, kAllowedPerFrame * kMeasuredFrames)
      << allocations << " operator new calls in " << kMeasuredFrames << " steady-state frames ("
      << double(allocations) / kMeasuredFrames << " per frame); allowed "
      << kAllowedPerFrame << " per frame. Where they come from:\n"
      << sites;
}

}  // namespace
}  // namespace rp::test
