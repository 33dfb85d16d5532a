// The renderer keeps its GI volume while the volume's inputs stay (render/still_volume.h):
// with one bounce from the second still frame, the kept volume being exactly what a voxelizer
// builds from the scene; with several bounces in the fast mode only after
// kStillFramesBeforeKeep still frames, and never in the reference mode. Any change of a light
// or an object, and a reset, builds it again.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "cl/profiler.h"
#include "passes/pass_names.h"
#include "passes/voxel_mips.h"
#include "passes/voxelize.h"
#include "render/renderer.h"
#include "scene/demo_scene.h"
#include "support/cl_fixture.h"

namespace {

namespace pass_name = rp::passes::pass_name;

constexpr uint32_t kSize = 32;
constexpr uint32_t kVoxels = 32;
// Renderer::kStillFramesBeforeKeep (private): every bounce face has blended its 16 cones, one
// face in 4 a frame.
constexpr uint32_t kKeepAfter = 64;

rp::render::RenderSettings settings(uint32_t bounces, rp::render::Quality quality) {
  rp::render::RenderSettings s;
  s.width = s.height = kSize;
  s.voxel_resolution = kVoxels;
  s.bounces = bounces;
  s.quality = quality;
  return s;
}

std::vector<float> read_floats(const ::cl::Buffer& buffer) {
  std::vector<float> out(buffer.getInfo<CL_MEM_SIZE>() / sizeof(float));
  rp::test::context().queue.enqueueReadBuffer(buffer, CL_TRUE, 0, out.size() * sizeof(float),
                                              out.data());
  return out;
}

// The renderer's current scene voxelized by a separate voxelizer and mip builder (no bounce
// grid): the chain a rebuild would give.
std::vector<float> voxelize_again(const rp::render::Renderer& r) {
  auto& ctx = rp::test::context();
  rp::render::VoxelVolume volume;
  volume.resize(ctx.context, kVoxels);
  rp::passes::VoxelizePass voxelize(ctx, rp::test::programs());
  rp::passes::VoxelMipsPass mips(ctx, rp::test::programs());
  rp::cl::Profiler profiler(ctx.queue);
  voxelize.run(profiler, r.gpu_scene(), r.shadow_map(), volume, nullptr, 0u);
  mips.run(profiler, volume);
  profiler.collect();
  return read_floats(volume.chain);
}

bool built(const rp::cl::PassTimes& times) {
  return times.count(pass_name::kVoxelize) != 0 && times.count(pass_name::kVoxelMips) != 0;
}

TEST(StillVolume, OneBounceKeepsTheVolumeFromTheSecondStillFrameBitForBit) {
  rp::scene::SceneAssets assets = rp::scene::make_demo_assets(rp::scene::default_asset_dir());
  rp::render::Renderer r(rp::test::context(), rp::test::programs(), assets,
                         settings(1, rp::render::Quality::kFast));
  EXPECT_TRUE(built(r.render(rp::scene::make_demo_frame(assets, 0))));
  const std::vector<float> first = read_floats(r.voxels().chain);
  for (uint32_t i = 1; i < 4; ++i) {
    // a new frame index (jitter, noise), the same scene
    EXPECT_FALSE(built(r.render(rp::scene::make_demo_frame(assets, i)))) << "frame " << i;
    ASSERT_EQ(read_floats(r.voxels().chain), first) << "frame " << i;
  }
  EXPECT_EQ(first, voxelize_again(r)) << "the kept volume is not the scene's";

  // A dimmer lamp: built again, and darker.
  rp::scene::FrameScene dim = rp::scene::make_demo_frame(assets, 4);
  dim.light.intensity *= 0.5f;
  EXPECT_TRUE(built(r.render(dim)));
  const std::vector<float> darker = read_floats(r.voxels().chain);
  EXPECT_NE(darker, first);
  EXPECT_EQ(darker, voxelize_again(r));
  EXPECT_FALSE(built(r.render(dim))) << "the dim lamp's second frame";

  // The lamp as it was: built again, the first frame's volume bit for bit.
  EXPECT_TRUE(built(r.render(rp::scene::make_demo_frame(assets, 6))));
  EXPECT_EQ(read_floats(r.voxels().chain), first);

  // An object moved: built again.
  rp::scene::FrameScene moved = rp::scene::make_demo_frame(assets, 7);
  ASSERT_FALSE(moved.instances.empty());
  for (rp::scene::MeshInstance& inst : moved.instances)
    if (inst.voxelize && inst.mesh != moved.instances.front().mesh) {
      inst.model[3].x += 0.05f;
      break;
    }
  EXPECT_TRUE(built(r.render(moved)));
  EXPECT_EQ(read_floats(r.voxels().chain), voxelize_again(r));
}

TEST(StillVolume, SeveralBouncesKeepTheVolumeAndGridOnlyAfterTheGridHasSettled) {
  rp::scene::SceneAssets assets = rp::scene::make_demo_assets(rp::scene::default_asset_dir());
  rp::render::Renderer r(rp::test::context(), rp::test::programs(), assets,
                         settings(rp::render::RenderSettings::kDefaultBounces,
                                  rp::render::Quality::kFast));
  uint32_t frame = 0;
  for (; frame <= kKeepAfter - 1; ++frame) {
    const rp::cl::PassTimes t = r.render(rp::scene::make_demo_frame(assets, frame));
    ASSERT_TRUE(built(t) && t.count(pass_name::kBounce)) << "frame " << frame;
  }
  // kKeepAfter still frames before this one: kept, grid and volume unchanged.
  const std::vector<float> chain = read_floats(r.voxels().chain);
  const std::vector<float> grid = read_floats(*r.bounce_grid());
  for (uint32_t k = 0; k < 3; ++k, ++frame) {
    const rp::cl::PassTimes t = r.render(rp::scene::make_demo_frame(assets, frame));
    EXPECT_FALSE(built(t) || t.count(pass_name::kBounce)) << "frame " << frame;
  }
  EXPECT_EQ(read_floats(r.voxels().chain), chain);
  EXPECT_EQ(read_floats(*r.bounce_grid()), grid);

  // A light change gathers again at once.
  rp::scene::FrameScene dim = rp::scene::make_demo_frame(assets, frame++);
  dim.light.intensity *= 0.5f;
  rp::cl::PassTimes t = r.render(dim);
  EXPECT_TRUE(built(t) && t.count(pass_name::kBounce)) << "after the light changed";
  dim.frame_index = frame++;
  t = r.render(dim);
  EXPECT_TRUE(built(t) && t.count(pass_name::kBounce)) << "the changed light's second frame";

  // A reset (R) starts the grid again: not kept on the next frames either.
  r.reset_history();
  for (uint32_t k = 0; k < 2; ++k) {
    t = r.render(rp::scene::make_demo_frame(assets, frame++));
    EXPECT_TRUE(built(t) && t.count(pass_name::kBounce)) << "frame " << k << " after a reset";
  }
}

TEST(StillVolume, TheReferenceModeGathersEveryFrame) {
  rp::scene::SceneAssets assets = rp::scene::make_demo_assets(rp::scene::default_asset_dir());
  rp::render::Renderer r(rp::test::context(), rp::test::programs(), assets,
                         settings(rp::render::RenderSettings::kDefaultBounces,
                                  rp::render::Quality::kReference));
  for (uint32_t frame = 0; frame < kKeepAfter + 2; ++frame) {
    const rp::cl::PassTimes t = r.render(rp::scene::make_demo_frame(assets, frame));
    ASSERT_TRUE(built(t) && t.count(pass_name::kBounce)) << "frame " << frame;
  }
}

}  // namespace
