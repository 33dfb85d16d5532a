// The bounce grid (several bounces, passes/bounce.h) in the full renderer on the
// demo: with one bounce the voxels are exactly the no-bounce voxelizer's, a gathered but dark
// grid adds nothing; with several bounces the gathered light converges and stays below the
// geometric-series bound that albedos < 1 give. And the renderer keeps its GI volume while the
// volume's inputs stay (render/still_volume.h): with one bounce from the second still frame,
// the kept volume being exactly what a voxelizer builds from the scene; with several bounces in
// the fast mode only after kStillFramesBeforeKeep still frames, never in the reference mode. Any
// change of a light or an object, and a reset, builds it again.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "cl/profiler.h"
#include "passes/bounce.h"
#include "passes/pass_names.h"
#include "passes/voxel_mips.h"
#include "passes/voxelize.h"
#include "render/renderer.h"
#include "scene/demo_scene.h"
#include "support/cl_fixture.h"

namespace {

constexpr uint32_t kSize = 32;
constexpr uint32_t kVoxels = 32;
// Renderer::kStillFramesBeforeKeep (private): every bounce face has blended its 16 cones, one
// face in 4 a frame.
constexpr uint32_t kKeepAfter = 64;

namespace pass_name = rp::passes::pass_name;

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

// The renderer's current scene voxelized again by a separate voxelizer (bounce grid `grid`, or
// none) and mip builder: the whole chain.
std::vector<float> voxelize_again(const rp::render::Renderer& r, const ::cl::Buffer* grid) {
  auto& ctx = rp::test::context();
  rp::render::VoxelVolume volume;
  volume.resize(ctx.context, kVoxels);
  rp::passes::VoxelizePass voxelize(ctx, rp::test::programs());
  rp::passes::VoxelMipsPass mips(ctx, rp::test::programs());
  rp::cl::Profiler profiler(ctx.queue);
  voxelize.run(profiler, r.gpu_scene(), r.shadow_map(), volume, grid,
               grid ? rp::passes::BouncePass::cells(kVoxels) : 0u);
  mips.run(profiler, volume);
  profiler.collect();
  return read_floats(volume.chain);
}

// bounces = 1: no bounce pass at all, and the chain is the voxelizer's without a grid, bit for
// bit. A grid whose faces were all gathered (age 1) but hold no light adds exactly nothing; one
// that holds light brightens the voxels (the voxelizer does read it).
TEST(Bounce, OneBounceLeavesTheVoxelsOfTheNoBouncePath) {
  rp::scene::SceneAssets assets = rp::scene::make_demo_assets(rp::scene::default_asset_dir());
  rp::render::Renderer r(rp::test::context(), rp::test::programs(), assets,
                         settings(1, rp::render::Quality::kFast));
  r.render(rp::scene::make_demo_frame(assets, 0));
  EXPECT_EQ(r.bounce_grid(), nullptr);
  const std::vector<float> chain = read_floats(r.voxels().chain);
  EXPECT_EQ(chain, voxelize_again(r, nullptr));

  const size_t g = rp::passes::BouncePass::cells(kVoxels);
  auto& ctx = rp::test::context();
  std::vector<float> faces(6 * g * g * g * 4, 0.0f);
  for (size_t i = 3; i < faces.size(); i += 4) faces[i] = 1.0f;  // gathered, dark
  ::cl::Buffer grid(ctx.context, CL_MEM_READ_WRITE, faces.size() * sizeof(float));
  ctx.queue.enqueueWriteBuffer(grid, CL_TRUE, 0, faces.size() * sizeof(float), faces.data());
  EXPECT_EQ(chain, voxelize_again(r, &grid)) << "a dark grid changed the voxels";
  for (size_t i = 0; i < faces.size(); i += 4) faces[i] = faces[i + 1] = faces[i + 2] = 0.5f;
  ctx.queue.enqueueWriteBuffer(grid, CL_TRUE, 0, faces.size() * sizeof(float), faces.data());
  const std::vector<float> lit = voxelize_again(r, &grid);
  double before = 0.0, after = 0.0;
  for (size_t i = 0; i < size_t(kVoxels) * kVoxels * kVoxels * 4; i += 4) {
    before += chain[i];
    after += lit[i];
  }
  EXPECT_GT(after, 1.1 * before) << "the voxelizer ignores the bounce light";
}

// Largest linear albedo per channel over the materials (textured ones: the material albedo
// times the brightest texel decoded from sRGB, as the voxelizer multiplies them).
glm::dvec3 max_albedo(const rp::scene::SceneAssets& assets) {
  auto linear = [](double s) {
    return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
  };
  glm::dvec3 a(0.0);
  for (const rp::scene::Material& m : assets.materials) {
    glm::dvec3 albedo(m.albedo);
    if (m.texture >= 0) {
      const rp::scene::Texture& t = assets.textures[size_t(m.texture)];
      glm::dvec3 texel(0.0);
      for (size_t i = 0; i < t.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c) texel[c] = std::max(texel[c], linear(t.rgba[i + c] / 255.0));
      albedo *= texel;
    }
    a = glm::max(a, albedo);
  }
  return a;
}

// Per channel, the largest radiance of a level-0 voxel (premultiplied rgb / opacity).
glm::dvec3 max_voxel_radiance(const std::vector<float>& chain) {
  glm::dvec3 m(0.0);
  for (size_t i = 0; i < size_t(kVoxels) * kVoxels * kVoxels * 4; i += 4)
    if (chain[i + 3] > 0.0f)
      for (int c = 0; c < 3; ++c) m[c] = std::max(m[c], double(chain[i + c]) / chain[i + 3]);
  return m;
}

struct GridStats {
  glm::dvec3 total{0.0}, max{0.0};
};

GridStats grid_stats(const std::vector<float>& grid) {
  GridStats s;
  for (size_t i = 0; i < grid.size(); i += 4) {
    if (grid[i + 3] <= 0.0f) continue;  // not gathered
    for (int c = 0; c < 3; ++c) {
      s.total[c] += grid[i + c];
      s.max[c] = std::max(s.max[c], double(grid[i + c]));
    }
  }
  return s;
}

// Every gather adds a bounce: with albedo a < 1 the light is a geometric series. A face holds
// irradiance / pi, a mean of what its cones see, and a cone's radiance per unit opacity never
// exceeds the largest voxel radiance; a voxel reflects its direct light plus albedo times a
// mean of faces. So every face stays below E / (1 - a) per channel, E the largest radiance of
// the one-bounce voxels (direct light and emission), a the largest albedo. In the reference
// mode (the whole cone set every frame: one more bounce per frame) the total converges: its
// frame-to-frame change falls to the jitter's noise. In the fast mode (one cone per face every
// other frame, a running mean) it stays bounded too.
TEST(Bounce, SeveralBouncesConvergeBelowTheGeometricSeriesBound) {
  rp::scene::SceneAssets assets = rp::scene::make_demo_assets(rp::scene::default_asset_dir());
  // The tumblers' painted texture has white texels under albedo 1: scale it to 0.9 so that
  // every albedo is below 1 (the bound needs it; the walls are already).
  for (rp::scene::Material& m : assets.materials)
    if (m.name == "tumbler") m.albedo = glm::vec3(0.9f);
  const glm::dvec3 albedo = max_albedo(assets);
  std::printf("[ stats    ] largest albedo %.3f %.3f %.3f\n", albedo.x, albedo.y, albedo.z);
  for (int c = 0; c < 3; ++c) ASSERT_LT(albedo[c], 1.0);
  rp::render::Renderer one(rp::test::context(), rp::test::programs(), assets,
                           settings(1, rp::render::Quality::kFast));
  one.render(rp::scene::make_demo_frame(assets, 0));
  const glm::dvec3 e = max_voxel_radiance(read_floats(one.voxels().chain));
  const glm::dvec3 bound = e / (1.0 - albedo);

  for (rp::render::Quality quality : {rp::render::Quality::kReference, rp::render::Quality::kFast}) {
    const bool reference = quality == rp::render::Quality::kReference;
    rp::render::Renderer r(rp::test::context(), rp::test::programs(), assets,
                           settings(rp::render::RenderSettings::kDefaultBounces, quality));
    constexpr uint32_t kFrames = 64;
    std::vector<double> totals;
    glm::dvec3 largest(0.0);
    for (uint32_t i = 0; i < kFrames; ++i) {
      r.render(rp::scene::make_demo_frame(assets, i));
      ASSERT_NE(r.bounce_grid(), nullptr);
      const GridStats s = grid_stats(read_floats(*r.bounce_grid()));
      for (int c = 0; c < 3; ++c)
        ASSERT_LE(s.max[c], bound[c] * (1.0 + 1e-4))
            << (reference ? "reference" : "fast") << " frame " << i << " channel " << c;
      totals.push_back(s.total.x + s.total.y + s.total.z);
      largest = glm::max(largest, s.max);
    }
    double last_change = 0.0;
    for (uint32_t i = kFrames - 16; i < kFrames; ++i)
      last_change = std::max(last_change, std::abs(totals[i] - totals[i - 1]) / totals[i]);
    std::printf("[ stats    ] %s: grid total frame 1 %.1f, 32 %.1f, 64 %.1f; largest relative "
                "change over the last 16 frames %.5f; largest face %.3f %.3f %.3f, bound %.3f %.3f "
                "%.3f\n",
                reference ? "reference" : "fast", totals[0], totals[31], totals[kFrames - 1],
                last_change, largest.x, largest.y, largest.z, bound.x, bound.y, bound.z);
    EXPECT_LT(last_change, reference ? 0.002 : 0.005) << "the bounce light keeps changing";
    EXPECT_LT(std::abs(totals[kFrames - 1] - totals[kFrames - 17]) / totals[kFrames - 1], 0.01)
        << "the bounce light keeps growing";
  }
}

// Whether the frame built its GI volume (voxelized and made the mips) rather than kept it.
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
  EXPECT_EQ(first, voxelize_again(r, nullptr)) << "the kept volume is not the scene's";

  // A dimmer lamp: built again, and darker.
  rp::scene::FrameScene dim = rp::scene::make_demo_frame(assets, 4);
  dim.light.intensity *= 0.5f;
  EXPECT_TRUE(built(r.render(dim)));
  const std::vector<float> darker = read_floats(r.voxels().chain);
  EXPECT_NE(darker, first);
  EXPECT_EQ(darker, voxelize_again(r, nullptr));
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
  EXPECT_EQ(read_floats(r.voxels().chain), voxelize_again(r, nullptr));
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
