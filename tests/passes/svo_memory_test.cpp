// The octree's memory: the pools sized from the build's counts, the bytes it reports
// within the limits, and its invariants on the atrium (a Sponza-class courtyard, 250k
// triangles) at 256^3:
//   - every fragment reaches a leaf that has its own samples;
//   - per depth, the nodes are 8 per existing parent, a node stores own samples iff its own
//     voxels hold a fragment, and its own-voxel mask is the set of own voxels that do;
//   - the brick table's face links (svo_layout.h) name the face neighbours found by an
//     independent descent;
//   - "brick borders equal": every border sample of every brick, read as the cone tracer reads
//     it (face links x, y, z: an edge or corner neighbour through the face neighbours), equals
//     the own sample of the neighbour found by descent (stored bytes, every direction), 0 where
//     that neighbour stores none;
//   - the reported pool bytes equal what the counts give, and the allocated pools exceed them
//     by at most the growth slack (1/16) plus alignment.
// Limits: the 512^3 octree's pools (nodes + brick table + samples, every level) within 64 MiB
// on the demo and the atrium (seed 001: "under 70 MB" for Sponza). The pools grow
// with the surface, so at 256^3 a quarter of that: 16 MiB.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <unordered_set>
#include <vector>

#include "app/scene_input.h"
#include "kernels/shared/svo_layout.h"
#include "passes/svo.h"
#include "passes/visibility.h"
#include "render/gpu_scene.h"
#include "render/svo_volume.h"
#include "scene/demo_scene.h"
#include "passes/svo_readback.h"
#include "support/cl_fixture.h"

namespace rp::test {
namespace {

constexpr uint32_t kShadow = 256;
constexpr uint64_t kMiB = 1024 * 1024;
// The pools (node pool + brick table + sample pool) at 512^3, demo and atrium.
constexpr uint64_t kPoolLimit512 = 64 * kMiB;

struct Built : SvoReadback {
  double build_ms = 0.0;  // voxelize + build, wall clock (the last frame)
  std::string passes;     // the last frame's device time per pass

  // Own sample s of the sample pool as stored: the rgb word and the opacity byte (packed).
  uint64_t stored(uint32_t s) const {
    const size_t base = size_t(header(RP_SVO_HDR_BRICK_OFFSET)) * 4;
    const uint8_t* a =
        reinterpret_cast<const uint8_t*>(words.data()) + header(RP_SVO_HDR_ALPHA_OFFSET);
    return uint64_t(words[base + s]) | uint64_t(a[s]) << 32;
  }
  // Own sample `own` (8 d + o) of brick index b as stored, 0 where it is not stored.
  uint64_t own_stored(uint32_t b, uint32_t own) const {
    if (b == RP_SVO_NO_LINK || table(b, 0) == RP_SVO_NO_BRICK) return 0;
    const uint32_t mask = table(b, 1) >> RP_SVO_MASK_SHIFT, o = own & 7;
    if (((mask >> o) & 1) == 0) return 0;
    const uint32_t slot = (own >> 3) * uint32_t(__builtin_popcount(mask)) +
                          uint32_t(__builtin_popcount(mask & ((1u << o) - 1)));
    return stored(table(b, 0) + slot);
  }
  // Brick index b's neighbour a + e through the face links (x, then y, then z), as the cone
  // tracer reaches a border sample (RP_SVO_NO_LINK: none, the sample reads 0).
  uint32_t linked(uint32_t b, uint32_t e) const {
    for (uint32_t axis = 0; axis < 3 && b != RP_SVO_NO_LINK; ++axis)
      if ((e >> axis) & 1) b = table(b, 1 + axis) & RP_SVO_LINK_MASK;
    return b;
  }
};

// `frames` builds of the same frame (the first grows the pools from their first guess; a static
// scene's later frames rebuild in place).
Built build(const render::GpuScene& gpu, const render::ShadowMap& shadow,
            rp::cl::Profiler& profiler, uint32_t r, int frames = 1) {
  passes::SvoPass pass(context(), programs());
  Built b;
  profiler.collect();
  for (int f = 0; f < frames; ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    pass.run(profiler, gpu, shadow, r, b.vol);
    context().queue.finish();
    b.build_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    b.passes.clear();
    for (const auto& [name, ms] : profiler.collect()) {
      char buf[64];
      std::snprintf(buf, sizeof buf, " %s %.1f ms", name.c_str(), ms);
      b.passes += buf;
    }
  }
  b.read(pass);
  return b;
}

// The octree of `frame` (its lamp's shadow map drawn first), built `frames` times.
Built build_frame(const scene::SceneAssets& assets, const scene::FrameScene& frame, uint32_t r,
                  int frames) {
  render::GpuScene gpu(context().context, context().queue, assets);
  gpu.update(frame, 64, 64, kShadow, r);
  rp::cl::Profiler profiler(context().queue);
  passes::VisibilityPass visibility(context(), programs());
  render::ShadowMap shadow;
  shadow.resize(context().context, kShadow);
  visibility.render_shadow(profiler, gpu, shadow);
  return build(gpu, shadow, profiler, r, frames);
}

Built build_demo(uint32_t r, int frames = 1) {
  const scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  return build_frame(assets, scene::make_demo_frame(assets), r, frames);
}

Built build_atrium(uint32_t r, int frames = 1) {
  const app::FileScene file = app::open_scene_file("atrium");
  app::FileFrameSource source(file);
  return build_frame(file.loaded.assets, source.next(), r, frames);
}

void print(const char* what, const Built& b) {
  const double mb = 1.0 / double(kMiB);
  std::printf("[ memory   ] %s %u^3: %u fragments, %llu nodes (%.2f MiB), %llu bricks (table "
              "%.2f MiB), %llu own samples (%.2f MiB); pools in use %.2f MiB, allocated %.2f "
              "MiB; scratch %.2f MiB (fragment list %.2f MiB); peak %.2f MiB; voxelize + build "
              "%.0f ms:%s\n",
              what, b.vol.resolution, b.vol.fragments, (unsigned long long)b.vol.nodes(),
              double(b.vol.node_bytes()) * mb, (unsigned long long)b.vol.bricks(),
              double(b.vol.table_bytes()) * mb, (unsigned long long)b.vol.samples,
              double(b.vol.sample_pool_bytes()) * mb,
              double(b.vol.node_bytes() + b.vol.brick_bytes()) * mb,
              double(b.vol.buffer_bytes()) * mb, double(b.vol.scratch_bytes) * mb,
              double(b.vol.fragment_bytes) * mb, double(b.vol.peak_device_bytes) * mb, b.build_ms,
              b.passes.c_str());
}

// The reported figures follow from the counts, and the allocation from the figures.
void check_memory(const Built& b, uint64_t pool_limit) {
  const render::SvoVolume& v = b.vol;
  const uint32_t D = v.depths;
  ASSERT_EQ(v.nodes_per_depth.size(), D);
  ASSERT_EQ(v.own_per_depth.size(), D);
  uint64_t samples = 0;
  for (uint32_t k = 0; k < D; ++k) {
    samples += uint64_t(v.own_per_depth[k]) * gpu::rp_svo_directions(D - 1 - k);
    EXPECT_LE(v.own_per_depth[k], 8 * uint64_t(v.bricks_per_depth[k]));
  }
  EXPECT_EQ(v.samples, samples);
  EXPECT_EQ(v.node_bytes(), v.nodes() * 8);
  EXPECT_EQ(v.brick_bytes(), v.bricks() * RP_SVO_TABLE_WORDS * 4 + samples * v.sample_bytes);
  // allocated: what is used plus at most 1/16 (the growth slack) of each pool, plus the header
  // and alignment; at least what is used
  const uint64_t used = v.node_bytes() + v.brick_bytes();
  const uint64_t header = RP_SVO_HEADER_FLOAT4S * 16;
  EXPECT_GE(uint64_t(v.buffer.getInfo<CL_MEM_SIZE>()), header + used);
  EXPECT_LE(uint64_t(v.buffer.getInfo<CL_MEM_SIZE>()),
            header + used + used / 16 + 64 + v.solid_capacity);
  // the minimum first guesses (4096 nodes, 512 bricks, 4096 samples) aside
  if (v.nodes() > 4096 && v.bricks() > 512 && v.samples > 4096) {
    EXPECT_LE(v.node_capacity, v.nodes() + v.nodes() / 16 + 1);
    EXPECT_LE(v.brick_capacity, v.bricks() + v.bricks() / 16 + 1);
    EXPECT_LE(v.sample_capacity, v.samples + v.samples / 16 + 1);
  }
  EXPECT_LE(used, pool_limit);
  EXPECT_LE(uint64_t(v.buffer.getInfo<CL_MEM_SIZE>()), pool_limit + pool_limit / 16);
  // the device memory the build reports: pools + scratch, the peak at least that
  EXPECT_EQ(v.device_bytes, uint64_t(v.buffer.getInfo<CL_MEM_SIZE>()) + v.scratch_bytes);
  EXPECT_GE(v.peak_device_bytes, v.device_bytes);
}

// Structure of the octree from the buffer (see the file's header).
void check_invariants(const Built& b) {
  const uint32_t D = b.vol.depths, R = b.vol.resolution;
  ASSERT_EQ(b.header(RP_SVO_HDR_RESOLUTION), R);
  ASSERT_GT(b.vol.fragments, 1000u);
  // every fragment's leaf: in the tree, "own", with own samples
  size_t unreachable = 0;
  for (size_t f = 0; f < b.fragments.size() / RP_SVO_FRAGMENT_WORDS; ++f) {
    const uint32_t key = b.fragments[RP_SVO_FRAGMENT_WORDS * f + RP_SVO_FRAGMENT_KEY];
    const uint32_t x = key % R, y = (key / R) % R, z = key / (R * R);
    const int64_t leaf = b.find(D - 1, x / 2, y / 2, z / 2);
    unreachable += leaf < 0 || (b.node_word(uint32_t(leaf), 0) & RP_SVO_NODE_OWN) == 0 ||
                   b.node_word(uint32_t(leaf), 1) == RP_SVO_NO_BRICK ||
                   b.table(b.node_word(uint32_t(leaf), 1) >> RP_SVO_BRICK_SHIFT, 0) ==
                       RP_SVO_NO_BRICK;
  }
  EXPECT_EQ(unreachable, 0u);
  // occupied voxels per level (x | y << 21 | z << 42), from the fragments
  std::vector<std::unordered_set<uint64_t>> occupied(D);
  for (size_t f = 0; f < b.fragments.size() / RP_SVO_FRAGMENT_WORDS; ++f) {
    const uint32_t key = b.fragments[RP_SVO_FRAGMENT_WORDS * f + RP_SVO_FRAGMENT_KEY];
    const uint32_t x = key % R, y = (key / R) % R, z = key / (R * R);
    for (uint32_t l = 0; l < D; ++l)
      occupied[l].insert((uint64_t(z >> l) << 42) | (uint64_t(y >> l) << 21) | (x >> l));
  }
  // walk the tree depth by depth with coordinates
  struct Node {
    uint32_t index, x, y, z;
  };
  std::vector<Node> level{{0, 0, 0, 0}};
  size_t bad_links = 0, bad_own = 0, bad_mask = 0, links = 0, bad_borders = 0, borders = 0;
  for (uint32_t k = 0; k < D; ++k) {
    EXPECT_EQ(level.size(), b.vol.nodes_per_depth[k]) << "depth " << k;
    uint32_t bricks = 0, owns = 0;
    std::vector<Node> next;
    const uint32_t side = 1u << k;
    for (const Node& n : level) {
      const uint32_t w0 = b.node_word(n.index, 0), brick = b.node_word(n.index, 1);
      if (brick == RP_SVO_NO_BRICK) {
        EXPECT_EQ(w0, 0u);
        continue;
      }
      ++bricks;
      const uint32_t bi = brick >> RP_SVO_BRICK_SHIFT;
      const bool own = (w0 & RP_SVO_NODE_OWN) != 0;
      const uint32_t mask = b.table(bi, 1) >> RP_SVO_MASK_SHIFT;
      owns += uint32_t(__builtin_popcount(mask));
      bad_own += own != (b.table(bi, 0) != RP_SVO_NO_BRICK) || own != (mask != 0);
      // the mask: own voxel o holds a fragment (the occupancy from the fragment list)
      const uint32_t brick_level = D - 1 - k;
      for (uint32_t o = 0; o < 8; ++o) {
        const uint64_t v = (uint64_t(2 * n.z + (o >> 2)) << 42) |
                           (uint64_t(2 * n.y + ((o >> 1) & 1)) << 21) | (2 * n.x + (o & 1));
        bad_mask += ((mask >> o) & 1) != (occupied[brick_level].count(v) ? 1u : 0u);
      }
      const uint32_t dirs = k + 1 == D ? 1 : 6;
      for (uint32_t e = 1; e < 8; ++e) {
        const uint32_t x = n.x + (e & 1), y = n.y + ((e >> 1) & 1), z = n.z + (e >> 2);
        uint32_t want = RP_SVO_NO_BRICK;  // the neighbour's brick index
        if (x < side && y < side && z < side) {
          const int64_t m = b.find(k, x, y, z);
          if (m >= 0 && b.node_word(uint32_t(m), 1) != RP_SVO_NO_BRICK)
            want = b.node_word(uint32_t(m), 1) >> RP_SVO_BRICK_SHIFT;
        }
        if (want == RP_SVO_NO_BRICK) want = RP_SVO_NO_LINK;
        if (e == 1 || e == 2 || e == 4) {  // face: the link itself
          bad_links += (b.table(bi, e == 1 ? 1 : e == 2 ? 2 : 3) & RP_SVO_LINK_MASK) != want;
          links += want != RP_SVO_NO_LINK;
        }
        // the border samples of offset e: own index 0 along e's axes, 0..1 along the others
        const uint32_t got = b.linked(bi, e);
        for (uint32_t o = 0; o < 8; ++o) {
          if ((o & e) != 0) continue;
          for (uint32_t d = 0; d < dirs; ++d) {
            bad_borders += b.own_stored(got, 8 * d + o) != b.own_stored(want, 8 * d + o);
            ++borders;
          }
        }
      }
      const uint32_t child = w0 & RP_SVO_NODE_CHILD_MASK;
      if (k + 1 < D) {
        EXPECT_NE(child, 0u);
        for (uint32_t o = 0; o < 8; ++o)
          next.push_back({child + o, 2 * n.x + (o & 1), 2 * n.y + ((o >> 1) & 1),
                          2 * n.z + (o >> 2)});
      }
    }
    EXPECT_EQ(bricks, b.vol.bricks_per_depth[k]) << "depth " << k;
    EXPECT_EQ(owns, b.vol.own_per_depth[k]) << "depth " << k;
    level.swap(next);
  }
  EXPECT_EQ(bad_own, 0u);
  EXPECT_EQ(bad_mask, 0u);
  EXPECT_EQ(bad_links, 0u) << "of " << links << " face links";
  EXPECT_EQ(bad_borders, 0u) << "of " << borders << " border samples";
}

TEST(SvoMemory, DemoPoolsFromCounts256) {
  const Built b = build_demo(256);
  print("demo", b);
  check_memory(b, kPoolLimit512 / 4);
  check_invariants(b);
}

TEST(SvoMemory, AtriumInvariantsAndPools256) {
  const Built b = build_atrium(256);
  print("atrium", b);
  check_memory(b, kPoolLimit512 / 4);
  check_invariants(b);
}

// The limit itself at 512^3 (the demo: about 20 s on the project's 2-core CPU).
TEST(SvoMemory, DemoPoolsWithin64MiB512) {
  const Built b = build_demo(512);
  print("demo", b);
  check_memory(b, kPoolLimit512);
}

TEST(SvoMemory, AtriumPoolsWithin64MiB512) {
  const Built b = build_atrium(512);
  print("atrium", b);
  check_memory(b, kPoolLimit512);
}

// 1024^3 (the atrium's pools within 256 MiB where feasible). Not run by default
// (minutes and over 1 GiB of device memory on the project's 2-core CPU); run with
// --gtest_also_run_disabled_tests --gtest_filter='SvoMemory.DISABLED_*'. Two frames: the second
// one's pass times are the static rebuild's.
TEST(SvoMemory, DISABLED_Demo1024) {
  const Built b = build_demo(1024, 2);
  print("demo", b);
  check_memory(b, 4 * kPoolLimit512);
}

TEST(SvoMemory, DISABLED_Atrium1024) {
  const Built b = build_atrium(1024, 2);
  print("atrium", b);
  check_memory(b, 4 * kPoolLimit512);
}

// The same two-frame measurement at 256^3 and 512^3 (pass times of a static rebuild).
TEST(SvoMemory, DISABLED_PassTimes) {
  for (uint32_t r : {256u, 512u}) {
    print("demo", build_demo(r, 2));
    print("atrium", build_atrium(r, 2));
  }
}

}  // namespace
}  // namespace rp::test
