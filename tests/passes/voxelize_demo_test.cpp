// The voxelize and voxel_mips passes on the demo scene (Cornell box, lamp, five tumblers) plus
// marbles, two fireballs and ~2100 fire particles, with the real shadow map: opacity sums
// identical to the C++ reference and radiance within rounding, the coloured walls in the
// volume, bit-identical repeats, and the device times at R = 32, 64, 128 (printed and recorded
// as test properties; measurements, not pass/fail criteria).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "passes/pass_names.h"
#include "passes/visibility.h"
#include "passes/voxel_mips.h"
#include "passes/voxelize.h"
#include "passes/voxelize_reference.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"
#include "render/voxel_volume.h"
#include "scene/demo_scene.h"
#include "support/cl_fixture.h"

namespace rp::test {
namespace {

namespace pass_name = rp::passes::pass_name;

// Six marbles (cast shadows; every other one coated like the demo's, so the voxelizer's coat
// weight Sphere.albedo.w is exercised), two fireballs and `particles` fire particles around them (emit,
// no shadow), from a fixed seed.
void add_spheres(scene::FrameScene& frame, int particles) {
  const glm::vec3 marbles[6] = {{-0.2f, -0.94f, 0.65f}, {0.75f, -0.6f, -0.3f}, {-0.7f, 0.1f, -0.6f},
                                {0.1f, 0.5f, 0.2f},     {0.3f, -0.94f, -0.8f}, {-0.85f, -0.9f, 0.0f}};
  const glm::vec3 colours[3] = {{0.9f, 0.2f, 0.2f}, {0.2f, 0.8f, 0.3f}, {0.9f, 0.9f, 0.9f}};
  for (int i = 0; i < 6; ++i) {
    scene::Sphere s;
    s.center = s.prev_center = marbles[i];
    s.radius = 0.06f;
    s.albedo = colours[i % 3];
    s.emission = glm::vec3(0.0f);
    s.casts_shadow = true;
    if (i % 2 == 0) s.specular = scene::demo::kMarbleSpecular;
    frame.spheres.push_back(s);
  }
  const glm::vec3 fireballs[2] = {{-0.3f, 0.2f, 0.1f}, {0.45f, -0.1f, 0.35f}};
  for (const glm::vec3& c : fireballs) {
    scene::Sphere s;
    s.center = s.prev_center = c;
    s.radius = 0.08f;
    s.albedo = glm::vec3(0.0f);
    s.emission = glm::vec3(9.0f, 3.5f, 0.8f);
    s.casts_shadow = false;
    frame.spheres.push_back(s);
  }
  std::mt19937 rng(2024);
  std::normal_distribution<float> offset(0.0f, 0.05f);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (int i = 0; i < particles; ++i) {
    scene::Sphere s;
    s.center = fireballs[i % 2] + glm::vec3(offset(rng), offset(rng) + 0.05f, offset(rng));
    s.prev_center = s.center;
    s.radius = 0.004f + 0.008f * u01(rng);
    s.albedo = glm::vec3(0.0f);
    s.emission = glm::vec3(6.0f, 2.0f, 0.4f) * (0.5f + u01(rng));
    s.casts_shadow = false;
    frame.spheres.push_back(s);
  }
}

struct Demo {
  scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  scene::FrameScene frame = scene::make_demo_frame(assets);
  std::unique_ptr<render::GpuScene> gpu;
  passes::VisibilityPass visibility{context(), programs()};
  rp::cl::Profiler profiler{context().queue};
  render::ShadowMap shadow;
  std::vector<float> shadow_depth;

  Demo(int particles, uint32_t shadow_size) {
    add_spheres(frame, particles);
    gpu = std::make_unique<render::GpuScene>(context().context, context().queue, assets);
    gpu->update(frame, 256, 256, shadow_size);
    shadow.resize(context().context, shadow_size);
    visibility.render_shadow(profiler, *gpu, shadow);
    profiler.collect();
    shadow_depth.resize(size_t(shadow_size) * shadow_size);
    context().queue.enqueueReadBuffer(shadow.depth, CL_TRUE, 0, shadow_depth.size() * sizeof(float),
                                      shadow_depth.data());
  }
};

TEST(VoxelizeDemo, MatchesReferenceAndHoldsTheWalls) {
  const uint32_t R = 32;
  Demo d(2100, 256);
  const VoxelGpuOutput got = run_voxelize(*d.gpu, d.shadow_depth, R);
  const VoxelSums want =
      reference_voxelize(reference_input(d.assets, d.frame, *d.gpu, d.shadow_depth), R);
  const std::vector<float> want0 = reference_resolve(want);
  const size_t voxels = size_t(R) * R * R;
  size_t alpha_diff = 0, radiance_diff = 0, occupied = 0, facing_diff = 0, slack = 0,
         slack_used = 0;
  for (size_t v = 0; v < voxels; ++v) {
    alpha_diff += got.sums.accum[kAccumWords * v + 3] != want.accum[kAccumWords * v + 3];
    occupied += want.accum[kAccumWords * v + 3] != 0;
    // The facing coverage does not depend on the light: exact up to the reference's slack.
    for (int h = 0; h < 6; ++h) {
      const int64_t g = facing_half(got.sums, v, h / 2, h % 2),
                    r = facing_half(want, v, h / 2, h % 2);
      const int64_t allowed = want.facing_slack[6 * v + size_t(h)];
      slack += allowed != 0;
      slack_used += g != r;
      facing_diff += g > r + allowed || g < r - allowed;
    }
    facing_diff += got.sums.accum[kAccumWords * v + 7] != 0;
    bool differs = false;
    for (int c = 0; c < 3; ++c) {
      const float g = got.level0[4 * v + c], r = want0[4 * v + c];
      differs |= !(std::fabs(g - r) <= 2e-4f + 2e-4f * std::fabs(r));
    }
    radiance_diff += differs;
  }
  std::printf("[ stats    ] demo R = %u: %zu occupied voxels, %zu with radiance beyond rounding, "
              "%zu facing halves with rounding slack (%zu of them differ)\n",
              R, occupied, radiance_diff, slack, slack_used);
  // Coverage is exact where the device rounds as the reference does (PoCL); a compiler that
  // fuses a * b + c (OpenCL allows it; NVIDIA's does) may move a fragment lying on a voxel
  // face into its neighbour: at most 1 voxel in 1000.
  EXPECT_LE(alpha_diff, occupied / 1000) << alpha_diff << " of " << occupied;
  EXPECT_EQ(facing_diff, 0u);
  // Lighting agrees to rounding; a shadow-map lookup right at a depth edge may decide the
  // other way, which can flip a handful of voxels.
  EXPECT_LE(radiance_diff, occupied / 200) << radiance_diff << " of " << occupied;
  EXPECT_GT(occupied, 5000u);

  // The walls are in the volume: the layer x = 0 is the orange wall (red > blue where lit),
  // x = R - 1 the blue one; both opaque over their whole interior.
  auto at = [&](uint32_t x, uint32_t y, uint32_t z, int c) {
    return got.level0[4 * ((size_t(z) * R + y) * R + x) + c];
  };
  size_t left_red = 0, right_blue = 0, opaque = 0, cells = 0;
  for (uint32_t z = 2; z < R - 2; ++z)
    for (uint32_t y = 2; y < R - 4; ++y) {
      ++cells;
      left_red += at(0, y, z, 0) > 2.0f * at(0, y, z, 2);
      right_blue += at(R - 1, y, z, 2) > 2.0f * at(R - 1, y, z, 0);
      opaque += at(0, y, z, 3) == 1.0f && at(R - 1, y, z, 3) == 1.0f;
    }
  EXPECT_EQ(opaque, cells);
  EXPECT_GT(left_red, cells * 9 / 10);
  EXPECT_GT(right_blue, cells * 9 / 10);

  // The walls face the room: the x = 0 wall's voxels are covered in the +x half of their x
  // word only, the x = R - 1 wall's in the -x half only (corners also hold floor / ceiling /
  // back wall triangles, hence the interior cells).
  auto word = [&](uint32_t x, uint32_t y, uint32_t z, size_t w) {
    return got.sums.accum[kAccumWords * ((size_t(z) * R + y) * R + x) + w];
  };
  size_t one_sided = 0;
  for (uint32_t z = 2; z < R - 2; ++z)
    for (uint32_t y = 2; y < R - 4; ++y) {
      const uint32_t l = word(0, y, z, 4), r = word(R - 1, y, z, 4);
      one_sided += (l & 0xFFFFu) >= 128u && (l >> 16) == 0u && (r >> 16) >= 128u &&
                   (r & 0xFFFFu) == 0u;
    }
  EXPECT_EQ(one_sided, cells);
}

TEST(VoxelizeDemo, LampCapIsNotVoxelized) {
  // The lamp's light enters through the analytic point light; its emissive cap in the volume
  // would count it twice. The sums with the lamp instance equal those without it.
  const uint32_t R = 32;
  Demo d(0, 256);
  ASSERT_FALSE(d.frame.instances.at(1).voxelize);
  const VoxelGpuOutput with_lamp = run_voxelize(*d.gpu, d.shadow_depth, R);
  scene::FrameScene no_lamp = d.frame;
  no_lamp.instances.erase(no_lamp.instances.begin() + 1);
  d.gpu->update(no_lamp, 256, 256, d.shadow.size);
  const VoxelGpuOutput without = run_voxelize(*d.gpu, d.shadow_depth, R);
  EXPECT_TRUE(with_lamp.sums.accum == without.sums.accum);
  // And marking the lamp voxelized does add its emission (the flag is what keeps it out).
  scene::FrameScene lamp_in = d.frame;
  lamp_in.instances[1].voxelize = true;
  d.gpu->update(lamp_in, 256, 256, d.shadow.size);
  const VoxelGpuOutput lit = run_voxelize(*d.gpu, d.shadow_depth, R);
  EXPECT_FALSE(lit.sums.accum == with_lamp.sums.accum);
}

// The tumbler's proxy (scene::Mesh::proxy, a third of its triangles) stands in for
// it up to 64^3 (and in shadow maps up to 512^2): GpuScene gives the instances the proxy's
// triangles there and the mesh's above,
// and at 64^3 voxelizing the proxy gives nearly the voxels the mesh gives (C++ reference, both
// ways, the five tumblers alone): the same opaque voxels but for a thin rim (bound 5 % of the
// tumblers' voxels), and the same light in the volume (bound 1 %).
TEST(VoxelizeDemo, TumblerProxyVoxelizesLikeTheMesh) {
  Demo d(0, 1024);
  const render::MeshRange& mesh = d.gpu->meshes.at(scene::demo::kTumblerMesh);
  const render::MeshRange& proxy = d.gpu->meshes.at(scene::demo::kTumblerProxyMesh);
  ASSERT_LT(proxy.triangle_count * 3, mesh.triangle_count + 3);
  for (uint32_t r : {32u, 64u, 128u, 256u, 512u}) {
    d.gpu->update(d.frame, 256, 256, d.shadow.size, r);
    const render::MeshRange& want = r <= scene::demo::kTumblerProxyMaxVoxels ? proxy : mesh;
    for (size_t i = 0; i < d.frame.instances.size(); ++i) {
      if (d.frame.instances[i].mesh != scene::demo::kTumblerMesh) continue;
      EXPECT_EQ(d.gpu->host_instances[i].voxel_first_triangle, want.first_triangle) << r;
      EXPECT_EQ(d.gpu->host_instances[i].voxel_triangle_count, want.triangle_count) << r;
      EXPECT_EQ(d.gpu->host_instances[i].triangle_count, mesh.triangle_count) << r;
    }
  }
  // and the shadow map draws the proxy up to 512^2 texels, the mesh above
  for (uint32_t size : {256u, 512u, 1024u, 2048u}) {
    d.gpu->update(d.frame, 256, 256, size);
    const render::MeshRange& want =
        size <= scene::demo::kTumblerProxyMaxShadowTexels ? proxy : mesh;
    for (size_t i = 0; i < d.frame.instances.size(); ++i) {
      if (d.frame.instances[i].mesh != scene::demo::kTumblerMesh) continue;
      EXPECT_EQ(d.gpu->host_instances[i].shadow_first_triangle, want.first_triangle) << size;
      EXPECT_EQ(d.gpu->host_instances[i].shadow_triangle_count, want.triangle_count) << size;
    }
  }
  // the tumblers alone (the room's large triangles are most of the reference's time), lit and
  // shadowed as in the demo
  scene::FrameScene tumblers = d.frame;
  std::erase_if(tumblers.instances, [](const scene::MeshInstance& i) {
    return i.mesh != scene::demo::kTumblerMesh;
  });
  d.gpu->update(tumblers, 256, 256, d.shadow.size);
  scene::SceneAssets no_proxy = d.assets;
  no_proxy.meshes[scene::demo::kTumblerMesh].proxy = -1;
  for (uint32_t R : {64u}) {
    const std::vector<float> with = reference_resolve(
        reference_voxelize(reference_input(d.assets, tumblers, *d.gpu, d.shadow_depth), R));
    const std::vector<float> full = reference_resolve(
        reference_voxelize(reference_input(no_proxy, tumblers, *d.gpu, d.shadow_depth), R));
    size_t occupied = 0, differ = 0;
    double light_with = 0.0, light_full = 0.0;
    for (size_t v = 0; v < with.size() / 4; ++v) {
      const bool a = with[4 * v + 3] > 0.0f, b = full[4 * v + 3] > 0.0f;
      occupied += b;
      differ += a != b;
      for (int c = 0; c < 3; ++c) {
        light_with += with[4 * v + size_t(c)];
        light_full += full[4 * v + size_t(c)];
      }
    }
    std::printf("[ stats    ] tumbler proxy at %u^3: %zu of %zu occupied voxels differ, light "
                "%.4f x the mesh's\n", R, differ, occupied, light_with / light_full);
    EXPECT_GT(occupied, 2000u);
    EXPECT_LE(differ, occupied / 20) << R;  // of the tumblers' opaque voxels
    EXPECT_NEAR(light_with / light_full, 1.0, 0.01) << R;
  }
}

TEST(VoxelizeDemo, BitIdenticalRepeats) {
  const uint32_t R = 32;
  Demo d(2100, 256);
  const VoxelGpuOutput a = run_voxelize(*d.gpu, d.shadow_depth, R);
  const VoxelGpuOutput b = run_voxelize(*d.gpu, d.shadow_depth, R);
  EXPECT_EQ(a.sums.accum, b.sums.accum);
  EXPECT_EQ(a.sums.overflow, b.sums.overflow);
  EXPECT_EQ(std::memcmp(a.level0.data(), b.level0.data(), a.level0.size() * sizeof(float)), 0);
}

TEST(VoxelizeDemo, DeviceTimes) {
  for (int particles : {0, 2100}) {
    Demo d(particles, 1024);
    passes::VoxelizePass voxelize(context(), programs());
    passes::VoxelMipsPass mips(context(), programs());
    for (uint32_t R : {32u, 64u, 128u}) {
      render::VoxelVolume vol;
      vol.resize(context().context, R);
      d.gpu->constants.voxel_resolution = vol.resolution;
      d.gpu->constants.voxel_levels = vol.levels;
      context().queue.enqueueWriteBuffer(d.gpu->frame, CL_TRUE, 0, sizeof(d.gpu->constants),
                                         &d.gpu->constants);
      double best_vox = 1e30, best_mips = 1e30;
      for (int frame = 0; frame < 4; ++frame) {  // the first one builds and warms up
        voxelize.run(d.profiler, *d.gpu, d.shadow, vol);
        mips.run(d.profiler, vol);
        rp::cl::PassTimes t = d.profiler.collect();
        ASSERT_TRUE(t.count(pass_name::kVoxelize) && t.count(pass_name::kVoxelMips));
        if (frame > 0) {
          best_vox = std::min(best_vox, t[pass_name::kVoxelize]);
          best_mips = std::min(best_mips, t[pass_name::kVoxelMips]);
        }
      }
      std::printf("[ timing   ] demo + %zu spheres, R = %u: voxelize %.2f ms, voxel_mips %.2f ms on %s\n",
                  d.frame.spheres.size(), R, best_vox, best_mips, context().info.name.c_str());
      const std::string suffix = std::to_string(R) + (particles ? "_spheres" : "");
      RecordProperty("voxelize_ms_" + suffix, std::to_string(best_vox));
      RecordProperty("voxel_mips_ms_" + suffix, std::to_string(best_mips));
      EXPECT_GT(best_vox, 0.0);
    }
  }
}

}  // namespace
}  // namespace rp::test
