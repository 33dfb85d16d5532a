// Sparse voxel octree: the octree built from the demo scene's fragments against a
// straightforward C++ reference of its definition (kernels/shared/svo_layout.h) and against the
// dense volume built by the dense passes at the same resolution:
//   - structure: per depth, the nodes with a brick are exactly those whose 27 samples hold an
//     occupied voxel (brute force over every node coordinate), node counts = 8 x parents,
//     every fragment reaches an "own" leaf;
//   - values: every sample of every brick (own and border, every level and direction) equals
//     the dense chain's voxel at that place bit for bit (float samples) or to the packed
//     format's rounding (RGB9E5 + opacity byte),
//     so leaves = dense level 0, mips = dense mips, borders = neighbours' values;
//   - cone samples and whole cones through the octree equal the dense ones (RP_GI_SVO);
//   - determinism (two builds, identical pools);
//   - the build's measured device memory within a bound from its counts;
//   - the solid grid (closed objects' inside at the coarse levels) against a brute-force
//     count, and the cone samples it raises against a C++ reference of the rule.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "cl/error.h"
#include "kernels/shared/svo_layout.h"
#include "kernels/shared/voxel_layout.h"
#include "passes/svo.h"
#include "passes/svo_solid.h"
#include "passes/visibility.h"
#include "passes/voxel_mips.h"
#include "passes/voxelize.h"
#include "render/frame_buffers.h"
#include "render/renderer.h"
#include "render/gpu_scene.h"
#include "render/svo_volume.h"
#include "render/voxel_volume.h"
#include "scene/demo_scene.h"
#include "passes/svo_readback.h"
#include "support/cl_fixture.h"
#include "support/image_metrics.h"

namespace rp::test {
namespace {

constexpr uint32_t kShadow = 256;

struct Scene {
  scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  scene::FrameScene frame = scene::make_demo_frame(assets);
  std::unique_ptr<render::GpuScene> gpu;
  passes::VisibilityPass visibility{context(), programs()};
  rp::cl::Profiler profiler{context().queue};
  render::ShadowMap shadow;

  explicit Scene(uint32_t r) {
    // two marbles and a small particle so spheres take both sphere paths
    scene::Sphere s;
    s.center = s.prev_center = glm::vec3(0.3f, -0.8f, 0.1f);
    s.radius = 0.09f;
    s.albedo = glm::vec3(0.8f, 0.3f, 0.2f);
    frame.spheres.push_back(s);
    s.center = s.prev_center = glm::vec3(-0.4f, -0.5f, -0.3f);
    s.radius = 0.01f;
    s.albedo = glm::vec3(0.0f);
    s.emission = glm::vec3(5.0f, 2.0f, 0.5f);
    s.casts_shadow = false;
    frame.spheres.push_back(s);
    gpu = std::make_unique<render::GpuScene>(context().context, context().queue, assets);
    gpu->update(frame, 64, 64, kShadow, r);
    shadow.resize(context().context, kShadow);
    visibility.render_shadow(profiler, *gpu, shadow);
    profiler.collect();
  }
};

struct Dense {
  uint32_t r = 0, levels = 0;
  std::vector<float> chain;  // 4 floats per voxel, voxel_layout.h
  ::cl::Buffer buffer;
  float at(uint32_t level, uint32_t dir, uint32_t x, uint32_t y, uint32_t z, int c) const {
    const uint32_t n = r >> level;
    return chain[4 * (gpu::rp_voxel_offset(r, level, level == 0 ? 0 : dir) +
                      (size_t(z) * n + y) * n + x) + size_t(c)];
  }
};

Dense build_dense(Scene& s, uint32_t r) {
  passes::VoxelizePass voxelize(context(), programs());
  passes::VoxelMipsPass mips(context(), programs());
  render::VoxelVolume vol;
  vol.resize(context().context, r);
  voxelize.run(s.profiler, *s.gpu, s.shadow, vol);
  mips.run(s.profiler, vol);
  Dense d;
  d.r = r;
  d.levels = vol.levels;
  d.chain.resize(vol.chain_elements() * 4);
  context().queue.enqueueReadBuffer(vol.chain, CL_TRUE, 0, d.chain.size() * 4, d.chain.data());
  d.buffer = vol.chain;
  return d;
}

struct Octree : SvoReadback {
  // Own sample `own` of the sample pool, channel c.
  float own_sample(uint32_t own, int c) const {
    const size_t base = size_t(header(RP_SVO_HDR_BRICK_OFFSET)) * 4;
    if (vol.sample_bytes == 16) {
      float f;
      std::memcpy(&f, &words[base + 4 * size_t(own) + size_t(c)], 4);
      return f;
    }
    // packed: RGB9E5 (mantissa * 2^(e - 15 - 9)) and an opacity byte (svo_layout.h)
    if (c == 3) {
      const uint8_t* a = reinterpret_cast<const uint8_t*>(words.data()) +
                         header(RP_SVO_HDR_ALPHA_OFFSET);
      return float(a[own]) / 255.0f;
    }
    const uint32_t w = words[base + own];
    return std::ldexp(float((w >> (9 * c)) & 511u), int(w >> 27) - 24);
  }
  // Sample s (27 d + (k*3 + j)*3 + i) of the brick at address `brick`, as the cone tracer reads
  // it: the own sample of the node, or for a border sample of its neighbour a + e reached by
  // the face links (x, y, z); 0 where a link, the own samples or that voxel's are missing.
  float sample(uint32_t brick, uint32_t s, int c) const {
    const uint32_t slot = (brick & ((1u << RP_SVO_BRICK_SHIFT) - 1)) + s;
    const uint32_t d = slot / 27, t = slot % 27, i = t % 3, j = (t / 3) % 3, k = t / 9;
    const uint32_t e = (i >> 1) | ((j >> 1) << 1) | ((k >> 1) << 2);
    uint32_t b = brick >> RP_SVO_BRICK_SHIFT;
    for (uint32_t axis = 0; axis < 3 && b != RP_SVO_NO_LINK; ++axis)
      if ((e >> axis) & 1) b = table(b, 1 + axis) & RP_SVO_LINK_MASK;
    if (b == RP_SVO_NO_LINK || table(b, 0) == RP_SVO_NO_BRICK) return 0.0f;
    // occupied own voxels only, direction by direction (svo_layout.h)
    const uint32_t mask = table(b, 1) >> RP_SVO_MASK_SHIFT;
    const uint32_t o = (i & 1) + 2 * (j & 1) + 4 * (k & 1);
    if (((mask >> o) & 1) == 0) return 0.0f;
    const uint32_t n = uint32_t(__builtin_popcount(mask));
    const uint32_t index = d * n + uint32_t(__builtin_popcount(mask & ((1u << o) - 1)));
    return own_sample(table(b, 0) + index, c);
  }
};

// The tumbler mesh's first triangle in the scene (the renderer's rule for enable_solid).
uint32_t tumbler_first_triangle(const Scene& s) {
  for (size_t m = 0; m < s.assets.meshes.size(); ++m)
    if (s.assets.meshes[m].name == "tumbler") return s.gpu->meshes[m].first_triangle;
  ADD_FAILURE() << "no tumbler mesh";
  return 0;
}

Octree build_octree(Scene& s, uint32_t r, bool float_samples, bool solid = false) {
  passes::SvoPass pass(context(), programs(), float_samples);
  if (solid) pass.enable_solid(tumbler_first_triangle(s), scene::TumblerShape{});
  Octree o;
  pass.run(s.profiler, *s.gpu, s.shadow, r, o.vol);
  s.profiler.collect();
  o.read(pass);
  return o;
}

// Occupied level-l voxels from the fragments (a level-l voxel holds a fragment).
std::vector<uint8_t> occupancy(const Octree& o, uint32_t r, uint32_t level) {
  const uint32_t n = r >> level;
  std::vector<uint8_t> occ(size_t(n) * n * n, 0);
  for (size_t f = 0; f < o.fragments.size() / RP_SVO_FRAGMENT_WORDS; ++f) {
    const uint32_t key = o.fragments[RP_SVO_FRAGMENT_WORDS * f + RP_SVO_FRAGMENT_KEY];
    const uint32_t x = key % r, y = (key / r) % r, z = key / (r * r);
    occ[((size_t(z >> level) * n) + (y >> level)) * n + (x >> level)] = 1;
  }
  return occ;
}

void check_octree(const Octree& o, const Dense& d, bool exact) {
  const uint32_t r = d.r, D = o.vol.depths;
  ASSERT_EQ(o.header(RP_SVO_HDR_RESOLUTION), r);
  ASSERT_EQ(o.header(RP_SVO_HDR_DEPTHS), D);
  ASSERT_GT(o.vol.fragments, 1000u);
  size_t value_diff = 0, uncovered = 0, checked = 0;
  for (uint32_t k = 0; k < D; ++k) {
    const uint32_t level = D - 1 - k, n = r >> level, side = 1u << k;
    const std::vector<uint8_t> occ = occupancy(o, r, level);
    uint32_t expected = 0, missing = 0, extra = 0;
    for (uint32_t az = 0; az < side; ++az)
      for (uint32_t ay = 0; ay < side; ++ay)
        for (uint32_t ax = 0; ax < side; ++ax) {
          bool want = false;
          for (uint32_t s = 0; s < 27 && !want; ++s) {
            const uint32_t x = 2 * ax + s % 3, y = 2 * ay + (s / 3) % 3, z = 2 * az + s / 9;
            if (x < n && y < n && z < n) want = occ[(size_t(z) * n + y) * n + x] != 0;
          }
          const int64_t node = o.find(k, ax, ay, az);
          const bool got = node >= 0 && o.node_word(uint32_t(node), 1) != RP_SVO_NO_BRICK;
          expected += want;
          missing += want && !got;
          extra += got && !want;
          if (!got) continue;
          const uint32_t brick = o.node_word(uint32_t(node), 1);
          EXPECT_NE(o.node_word(uint32_t(node), 0) & RP_SVO_NODE_BRICK, 0u);
          const uint32_t dirs = level == 0 ? 1 : 6;
          for (uint32_t dir = 0; dir < dirs; ++dir)
            for (uint32_t s = 0; s < 27; ++s) {
              const uint32_t x = 2 * ax + s % 3, y = 2 * ay + (s / 3) % 3, z = 2 * az + s / 9;
              for (int c = 0; c < 4; ++c) {
                const float want_v = x < n && y < n && z < n ? d.at(level, dir, x, y, z, c) : 0.0f;
                const float got_v = o.sample(brick + 27 * dir, s, c);
                ++checked;
                // packed, level 0: the format's rounding: half a mantissa step (at most 2^-9 of
                // the largest channel), opacity half of 1/255. Levels >= 1 are composited from
                // rounded children and rounded again: the drift stays within 1/64 of the
                // largest channel + 1e-3 and 2/255 of opacity (measured up to about 1/200 and
                // 0.6/255 on this scene; the float build above checks the mips exactly).
                float largest = 0.0f;
                for (int cc = 0; cc < 3; ++cc)
                  largest = std::fmax(largest, x < n && y < n && z < n
                                                   ? d.at(level, dir, x, y, z, cc)
                                                   : 0.0f);
                const float tolerance =
                    level == 0 ? (c == 3 ? 0.5f / 255.0f + 1e-6f : largest / 512.0f + 1e-9f)
                               : (c == 3 ? 2.0f / 255.0f : largest / 64.0f + 1e-3f);
                const bool same = exact ? std::memcmp(&want_v, &got_v, 4) == 0
                                        : std::fabs(got_v - want_v) <= tolerance;
                value_diff += !same;
                if (!same && std::getenv("SVO_DEBUG"))
                  std::printf("level %u dir %u c %d want %g got %g largest %g\n", level, dir, c,
                              want_v, got_v, largest);
              }
            }
        }
    EXPECT_EQ(missing, 0u) << "depth " << k;
    EXPECT_EQ(extra, 0u) << "depth " << k;
    EXPECT_EQ(o.vol.bricks_per_depth[k], expected) << "depth " << k;
    if (k > 0) {
      EXPECT_EQ(o.vol.nodes_per_depth[k], 8 * o.vol.bricks_per_depth[k - 1]);
    }
    // Every non-empty dense voxel lies in a node with a brick (where the octree has no node the
    // dense volume is empty).
    const uint32_t dirs = level == 0 ? 1 : 6;
    for (uint32_t z = 0; z < n; ++z)
      for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x) {
          bool any = false;
          for (uint32_t dir = 0; dir < dirs; ++dir)
            for (int c = 0; c < 4; ++c) any |= d.at(level, dir, x, y, z, c) != 0.0f;
          if (!any) continue;
          const int64_t node = o.find(k, x / 2, y / 2, z / 2);
          uncovered += node < 0 || o.node_word(uint32_t(node), 1) == RP_SVO_NO_BRICK;
        }
  }
  EXPECT_EQ(value_diff, 0u) << "of " << checked << " sample channels";
  EXPECT_EQ(uncovered, 0u);
  // Every fragment reaches its own leaf.
  size_t unreachable = 0;
  for (size_t f = 0; f < o.fragments.size() / RP_SVO_FRAGMENT_WORDS; ++f) {
    const uint32_t key = o.fragments[RP_SVO_FRAGMENT_WORDS * f + RP_SVO_FRAGMENT_KEY];
    const uint32_t x = key % r, y = (key / r) % r, z = key / (r * r);
    const int64_t leaf = o.find(D - 1, x / 2, y / 2, z / 2);
    unreachable += leaf < 0 || (o.node_word(uint32_t(leaf), 0) & RP_SVO_NODE_OWN) == 0 ||
                   o.node_word(uint32_t(leaf), 1) == RP_SVO_NO_BRICK;
  }
  EXPECT_EQ(unreachable, 0u);
}

TEST(Svo, MatchesDenseVolumeFloatSamples) {
  const uint32_t r = 32;
  Scene s(r);
  const Dense d = build_dense(s, r);
  const Octree o = build_octree(s, r, true);
  check_octree(o, d, true);
  std::printf("[ stats    ] R = %u: %u fragments, %llu nodes, %llu samples\n", r,
              o.vol.fragments, (unsigned long long)o.vol.nodes(),
              (unsigned long long)o.vol.samples);
}

// The GPU layouts (one triangle / voxel per work-item: ROLYPOLY_VOXELIZE_SPAN=1,
// ROLYPOLY_VOXEL_MIPS_SPAN=1; a large triangle's columns over 4 work-items:
// ROLYPOLY_VOXELIZE_SLICES=4) and the voxelizer without its static cache give the same octree.
TEST(Svo, GpuLayoutsAndUncachedMatchDense) {
  const uint32_t r = 16;
  Scene s(r);
  for (const char* var : {"ROLYPOLY_VOXELIZE_SPAN", "ROLYPOLY_VOXEL_MIPS_SPAN"})
    setenv(var, "1", 1);
  setenv("ROLYPOLY_VOXELIZE_SLICES", "4", 1);
  setenv("ROLYPOLY_VOXELIZE_CACHE", "0", 1);
  const Dense d = build_dense(s, r);
  const Octree o = build_octree(s, r, true);
  for (const char* var : {"ROLYPOLY_VOXELIZE_SPAN", "ROLYPOLY_VOXEL_MIPS_SPAN",
                          "ROLYPOLY_VOXELIZE_SLICES", "ROLYPOLY_VOXELIZE_CACHE"})
    unsetenv(var);
  check_octree(o, d, true);
}

// A build that starts with pools far too small grows them (restarting the build) and ends with
// the same octree.
TEST(Svo, GrowsTooSmallPools) {
  const uint32_t r = 16;
  Scene s(r);
  const Dense d = build_dense(s, r);
  passes::SvoPass pass(context(), programs(), true);
  Octree o;
  o.vol.node_capacity = 9;
  o.vol.brick_capacity = 3;
  o.vol.sample_capacity = 10;
  o.vol.sample_bytes = 16;
  o.vol.buffer = ::cl::Buffer(context().context, CL_MEM_READ_WRITE, o.vol.buffer_bytes());
  pass.run(s.profiler, *s.gpu, s.shadow, r, o.vol);
  s.profiler.collect();
  EXPECT_GT(o.vol.node_capacity, 9u);
  EXPECT_GT(o.vol.brick_capacity, 3u);
  EXPECT_GT(o.vol.sample_capacity, 10u);
  o.read(pass);
  check_octree(o, d, true);
}

TEST(Svo, MatchesDenseVolumePackedSamples) {
  const uint32_t r = 16;
  Scene s(r);
  const Dense d = build_dense(s, r);
  const Octree o = build_octree(s, r, false);
  check_octree(o, d, false);
}

TEST(Svo, BitIdenticalRepeats) {
  const uint32_t r = 32;
  Scene s(r);
  const Octree a = build_octree(s, r, false);
  const Octree b = build_octree(s, r, false);
  ASSERT_EQ(a.vol.nodes(), b.vol.nodes());
  ASSERT_EQ(a.vol.samples, b.vol.samples);
  ASSERT_EQ(a.vol.bricks(), b.vol.bricks());
  const size_t used = (size_t(a.header(RP_SVO_HDR_BRICK_OFFSET)) * 16 + a.vol.samples * 4) / 4;
  const size_t nodes_end = 4 * RP_SVO_HEADER_FLOAT4S + 2 * a.vol.nodes();
  EXPECT_TRUE(std::equal(a.words.begin(), a.words.begin() + long(nodes_end), b.words.begin()));
  const size_t table = a.header(RP_SVO_HDR_TABLE_OFFSET);
  const size_t table_end = table + RP_SVO_TABLE_WORDS * a.vol.bricks();
  EXPECT_TRUE(std::equal(a.words.begin() + long(table), a.words.begin() + long(table_end),
                         b.words.begin() + long(table)));
  const size_t bricks = size_t(a.header(RP_SVO_HDR_BRICK_OFFSET)) * 4;
  EXPECT_TRUE(std::equal(a.words.begin() + long(bricks), a.words.begin() + long(used),
                         b.words.begin() + long(bricks)));
}

// The build's device memory, measured (CL_MEM_SIZE of every buffer the octree path holds),
// stays within what its counts allow: per fragment of the list's capacity (the count plus
// 1/16 slack, at least the first list of 65536) the fragment's 20 bytes and one 4-byte
// owner/link word; per node of the pool's capacity a flag word and a coordinate; the chunk
// sums (2 words per 256 nodes), the occupancy bits of levels >= 3 and two small fixed buffers.
// Nothing per leaf voxel (the
// accumulators this replaced took 256 bytes a leaf: 107 MiB of the 512^3 demo).
TEST(Svo, BuildScratchWithinBoundOfCounts) {
  const uint32_t r = 64;
  Scene s(r);
  const Octree o = build_octree(s, r, false);
  const uint64_t f = o.vol.fragments, nodes = o.vol.nodes(), cap = o.vol.node_capacity;
  ASSERT_GT(f, 10000u);
  const uint64_t list = std::max<uint64_t>(65536, f + f / 16);
  uint64_t occupancy = 0;  // the top levels' occupancy bits: levels 3 .. log2 R - 1, in words
  for (uint32_t n = r >> 3; n >= 2; n /= 2) occupancy += (uint64_t(n) * n * n + 31) / 32 * 4;
  const uint64_t bound = list * (RP_SVO_FRAGMENT_WORDS * 4 + 4) + cap * 8 + (cap / 256 + 1) * 8 +
                         (2 + 2 * RP_SVO_MAX_DEPTHS) * 4 + occupancy;
  EXPECT_LE(o.vol.scratch_bytes, bound);
  // the node pool's capacity: the first guess (4096 or fragments / 2) or the nodes + 1/16
  EXPECT_LE(cap, std::max<uint64_t>({4096, f / 2, nodes + nodes / 16}));
  // measured = pools + scratch, the peak so far at least that
  EXPECT_EQ(o.vol.device_bytes,
            uint64_t(o.vol.buffer.getInfo<CL_MEM_SIZE>()) + o.vol.scratch_bytes);
  EXPECT_GE(o.vol.peak_device_bytes, o.vol.device_bytes);
  EXPECT_GE(o.vol.buffer.getInfo<CL_MEM_SIZE>(), o.vol.node_bytes() + o.vol.brick_bytes());
  std::printf("[ stats    ] R = %u: %llu fragments, %llu nodes (capacity %llu), scratch %llu "
              "bytes (bound %llu), pools + scratch %llu\n",
              r, (unsigned long long)f, (unsigned long long)nodes, (unsigned long long)cap,
              (unsigned long long)o.vol.scratch_bytes, (unsigned long long)bound,
              (unsigned long long)o.vol.device_bytes);
}

// Fragment word 4 (shared/svo_layout.h) gives back every facing word one contribution adds:
// a plane's value (0 .. 128) in one half of an axis, a sphere's in both.
TEST(Svo, PackedFacingWordsRoundTrip) {
  for (uint32_t q = 0; q <= 128; ++q)
    for (uint32_t halves = 0; halves < 4; ++halves) {
      const uint32_t w = ((halves & 1) ? q : 0) | ((halves & 2) ? q << 16 : 0);
      const uint32_t packed = gpu::rp_svo_pack_facing(w, (q * 7) % 129, (q * 7) % 129 << 16);
      EXPECT_EQ(gpu::rp_svo_unpack_facing(packed, 0), w) << q << " " << halves;
      EXPECT_EQ(gpu::rp_svo_unpack_facing(packed, 1), (q * 7) % 129);
      EXPECT_EQ(gpu::rp_svo_unpack_facing(packed, 2), ((q * 7) % 129) << 16);
    }
}

// Fragment word 3 (shared/svo_layout.h) gives back the opacity and the facing words of both
// kinds of contribution the voxelizer adds: a plane's at opacity 1 (the fixed-point 2^16), each
// axis's value in one half and the largest axis at 128 (voxelize.cl vx_facing_words); a
// sphere's at any opacity up to 1 with round(128 a) in both halves of every axis
// (vx_facing_words_all), down to the tiny particles whose value rounds to 0.
TEST(Svo, PackedCoverWordsRoundTrip) {
  const uint32_t one = 1u << render::kVoxelFixedBits;
  for (uint32_t q = 0; q <= 128; ++q)
    for (uint32_t halves = 0; halves < 8; ++halves) {
      // axis x at 128, y at q, z at 128 - q; `halves` picks each axis's half
      const uint32_t v[3] = {128, q, 128 - q};
      uint32_t w[3];
      for (int i = 0; i < 3; ++i) w[i] = (halves >> i) & 1 ? v[i] << 16 : v[i];
      for (int rot = 0; rot < 3; ++rot) {  // the 128 on every axis in turn
        const uint32_t fx = w[rot], fy = w[(rot + 1) % 3], fz = w[(rot + 2) % 3];
        const uint32_t c = gpu::rp_svo_pack_cover(one, fx, fy, fz);
        EXPECT_EQ(gpu::rp_svo_cover_opacity(c, one), one) << q << " " << halves;
        EXPECT_EQ(gpu::rp_svo_cover_facing(c, 0), fx) << q << " " << halves;
        EXPECT_EQ(gpu::rp_svo_cover_facing(c, 1), fy) << q << " " << halves;
        EXPECT_EQ(gpu::rp_svo_cover_facing(c, 2), fz) << q << " " << halves;
      }
    }
  for (uint32_t a = 0; a <= one; a += 97) {
    for (uint32_t fixed : {a, one}) {  // the loop's values and opacity 1 itself
      const uint32_t q = uint32_t(float(fixed) / float(one) * 128.0f + 0.5f);
      const uint32_t f = q | q << 16;
      const uint32_t c = gpu::rp_svo_pack_cover(fixed, f, f, f);
      EXPECT_EQ(gpu::rp_svo_cover_opacity(c, one), fixed) << fixed;
      for (uint32_t axis = 0; axis < 3; ++axis)
        EXPECT_EQ(gpu::rp_svo_cover_facing(c, axis), f) << fixed;
    }
  }
}

// Cone-tracing functions of common/cone_trace.h built twice: on the dense chain and, with
// RP_GI_SVO, on the octree (float samples).
const char* kConeKernels = R"CLC(
__kernel void svo_cone_sample(__global const float4* voxels, uint resolution, uint levels,
                              __global const float4* queries, __global const float4* dirs,
                              __global float4* out) {
  const size_t i = get_global_id(0);
  const float3 d = dirs[i].xyz;
  out[2 * i] = rp_cone_sample(voxels, resolution, rp_cone_top_level(levels),
                              rp_voxel_cone_dirs(d), d * d, queries[i].xyz, queries[i].w,
                              queries[i].xyz - d * 0.05f);
  out[2 * i + 1] = rp_cone_trace_fine(voxels, resolution, levels, queries[i].xyz, d);
}
)CLC";

std::vector<float> run_cones(bool svo, const ::cl::Buffer& volume, uint32_t r, uint32_t levels,
                             const std::vector<float>& queries, const std::vector<float>& dirs) {
  rp::cl::Context& ctx = context();
  const std::string source =
      std::string(svo ? "#define RP_GI_SVO 1\n#define RP_SVO_FLOAT_SAMPLES 1\n" : "") +
                             rp::cl::kernel_source("common/cone_trace.h") + kConeKernels;
  ::cl::Program p(ctx.context, source);
  try {
    p.build(std::vector<::cl::Device>{ctx.info.device});
  } catch (const ::cl::Error&) {
    throw rp::cl::Error("svo cone kernels: " +
                        p.getBuildInfo<CL_PROGRAM_BUILD_LOG>(ctx.info.device));
  }
  ::cl::Kernel k(p, "svo_cone_sample");
  const size_t n = queries.size() / 4;
  ::cl::Buffer q(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, queries.size() * 4,
                 const_cast<float*>(queries.data()));
  ::cl::Buffer d(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, dirs.size() * 4,
                 const_cast<float*>(dirs.data()));
  ::cl::Buffer out(ctx.context, CL_MEM_WRITE_ONLY, n * 2 * 16);
  k.setArg(0, volume);
  k.setArg(1, cl_uint(r));
  k.setArg(2, cl_uint(levels));
  k.setArg(3, q);
  k.setArg(4, d);
  k.setArg(5, out);
  ctx.queue.enqueueNDRangeKernel(k, ::cl::NullRange, ::cl::NDRange(n));
  std::vector<float> result(n * 8);
  ctx.queue.enqueueReadBuffer(out, CL_TRUE, 0, result.size() * 4, result.data());
  return result;
}

TEST(Svo, ConeSamplesEqualDense) {
  const uint32_t r = 32;
  Scene s(r);
  const Dense d = build_dense(s, r);
  const Octree o = build_octree(s, r, true);
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> queries, dirs;
  for (int i = 0; i < 4096; ++i) {
    queries.insert(queries.end(), {0.98f * u(rng), 0.98f * u(rng), 0.98f * u(rng),
                                   2.5f + 2.5f * u(rng)});  // levels 0 .. 5 (clamped to top)
    float x = u(rng), y = u(rng), z = u(rng);
    const float len = std::sqrt(x * x + y * y + z * z) + 1e-6f;
    dirs.insert(dirs.end(), {x / len, y / len, z / len, 0.0f});
  }
  const std::vector<float> want = run_cones(false, d.buffer, r, d.levels, queries, dirs);
  const std::vector<float> got = run_cones(true, o.vol.buffer, r, o.vol.levels(), queries, dirs);
  size_t diff = 0, nonzero = 0;
  for (size_t i = 0; i < want.size(); ++i) {
    diff += std::memcmp(&want[i], &got[i], 4) != 0;
    nonzero += want[i] != 0.0f;
  }
  EXPECT_EQ(diff, 0u);
  EXPECT_GT(nonzero, want.size() / 4);
}

// The solid grid (passes/svo_solid.h) against a brute-force count of 12^3 points per cell
// inside a sphere and a tilted tumbler: level 2's cells that the surfaces cross within 0.15 of
// it (the distance ramp's error on curved, tilted surfaces; 0.04 on average), the others
// exact; level 3 the mean of level 2's cells (to the byte rounding).
TEST(Svo, SolidGridMatchesBruteForce) {
  const uint32_t r = 64;  // level 2: 16^3 cells of 0.125, level 3: 8^3, level 4: 4^3, level 5: 2^3
  passes::SolidObjects objects;
  const glm::mat4 model = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(-0.3f, -0.5f, 0.1f)),
                                      0.4f, glm::normalize(glm::vec3(1.0f, 0.2f, 0.3f)));
  objects.tumbler_world_to_local.push_back(glm::inverse(model));
  objects.spheres.emplace_back(0.45f, 0.3f, -0.2f, 0.3f);
  const std::vector<uint8_t> grid = passes::svo_solid_grid(r, objects);
  ASSERT_EQ(grid.size(), passes::svo_solid_bytes(r));
  ASSERT_EQ(grid.size(), size_t(16 * 16 * 16 + 8 * 8 * 8 + 4 * 4 * 4 + 2 * 2 * 2));
  const uint32_t n = 16;
  const float cell = 2.0f / float(n);
  constexpr int kFine = 12;
  std::vector<float> truth(size_t(n) * n * n);
  size_t full = 0, partial = 0;
  double partial_error = 0.0;
  for (uint32_t z = 0; z < n; ++z)
    for (uint32_t y = 0; y < n; ++y)
      for (uint32_t x = 0; x < n; ++x) {
        int inside = 0;
        for (int k = 0; k < kFine * kFine * kFine; ++k) {
          const glm::vec3 q = glm::vec3(-1.0f) +
                              cell * (glm::vec3(float(x), float(y), float(z)) +
                                      (glm::vec3(float(k % kFine), float((k / kFine) % kFine),
                                                 float(k / (kFine * kFine))) + 0.5f) /
                                          float(kFine));
          const glm::vec3 local(glm::inverse(model) * glm::vec4(q, 1.0f));
          inside += objects.tumbler.sdf(local) < 0.0f ||
                    glm::length(q - glm::vec3(0.45f, 0.3f, -0.2f)) < 0.3f;
        }
        const float want = float(inside) / float(kFine * kFine * kFine);
        truth[(size_t(z) * n + y) * n + x] = want;
        const float got = float(grid[(size_t(z) * n + y) * n + x]) / 255.0f;
        full += want == 1.0f;
        partial += want > 0.0f && want < 1.0f;
        if (want == 0.0f || want == 1.0f)
          EXPECT_NEAR(got, want, 0.5f / 255.0f + 0.02f) << x << " " << y << " " << z;
        else
          EXPECT_NEAR(got, want, 0.15f) << x << " " << y << " " << z;
        if (want > 0.0f && want < 1.0f) partial_error += std::fabs(got - want);
      }
  EXPECT_LT(partial_error / double(partial), 0.04);
  EXPECT_GT(full, 8u);
  EXPECT_GT(partial, 30u);
  const size_t l3 = passes::svo_solid_level_offset(r, 3);
  ASSERT_EQ(l3, size_t(16 * 16 * 16));
  for (uint32_t z = 0; z < 8; ++z)
    for (uint32_t y = 0; y < 8; ++y)
      for (uint32_t x = 0; x < 8; ++x) {
        float mean = 0.0f;
        for (uint32_t o = 0; o < 8; ++o)
          mean += float(grid[(size_t(2 * z + (o >> 2)) * n + 2 * y + ((o >> 1) & 1)) * n +
                             2 * x + (o & 1)]) / 255.0f;
        EXPECT_NEAR(float(grid[l3 + (size_t(z) * 8 + y) * 8 + x]) / 255.0f, mean / 8.0f,
                    1.0f / 255.0f);
      }
}

// Directional cone samples on the octree with the solid grid enabled = the dense chain's
// sample (no grid) with its opacity raised to RP_SVO_SOLID_WEIGHT x the grid's trilinear
// fraction at levels >= 2
// (C++ reference of common/svo.h rp_svo_solid_apply over the grid the pass uploaded), and
// unchanged below level 2.
const char* kDirectionalKernel = R"CLC(
__kernel void svo_directional(__global const float4* voxels, uint resolution,
                              __global const float4* queries, __global const float4* dirs,
                              __global float4* out) {
  const size_t i = get_global_id(0);
  const float3 d = dirs[i].xyz;
  out[i] = rp_cone_directional(voxels, resolution, (uint)queries[i].w, rp_voxel_cone_dirs(d),
                               d * d, queries[i].xyz, queries[i].xyz - d * 0.3f);
}
)CLC";

std::vector<float> run_directional(bool svo, const ::cl::Buffer& volume, uint32_t r,
                                   const std::vector<float>& queries,
                                   const std::vector<float>& dirs) {
  rp::cl::Context& ctx = context();
  const std::string source =
      std::string(svo ? "#define RP_GI_SVO 1\n#define RP_SVO_FLOAT_SAMPLES 1\n" : "") +
      rp::cl::kernel_source("common/cone_trace.h") + kDirectionalKernel;
  ::cl::Program p(ctx.context, source);
  try {
    p.build(std::vector<::cl::Device>{ctx.info.device});
  } catch (const ::cl::Error&) {
    throw rp::cl::Error("svo directional kernel: " +
                        p.getBuildInfo<CL_PROGRAM_BUILD_LOG>(ctx.info.device));
  }
  ::cl::Kernel k(p, "svo_directional");
  const size_t n = queries.size() / 4;
  ::cl::Buffer q(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, queries.size() * 4,
                 const_cast<float*>(queries.data()));
  ::cl::Buffer d(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, dirs.size() * 4,
                 const_cast<float*>(dirs.data()));
  ::cl::Buffer out(ctx.context, CL_MEM_WRITE_ONLY, n * 16);
  k.setArg(0, volume);
  k.setArg(1, cl_uint(r));
  k.setArg(2, q);
  k.setArg(3, d);
  k.setArg(4, out);
  ctx.queue.enqueueNDRangeKernel(k, ::cl::NullRange, ::cl::NDRange(n));
  std::vector<float> result(n * 4);
  ctx.queue.enqueueReadBuffer(out, CL_TRUE, 0, result.size() * 4, result.data());
  return result;
}

TEST(Svo, SolidGridRaisesCoarseOpacity) {
  const uint32_t r = 16;  // levels 2 and 3 have solid cells (4^3, 2^3); small for oclgrind
  Scene s(r);
  const Dense d = build_dense(s, r);
  const Octree o = build_octree(s, r, true, /*solid=*/true);
  const uint32_t offset = o.header(RP_SVO_HDR_SOLID_OFFSET);
  ASSERT_NE(offset, 0u);
  ASSERT_EQ(o.header(RP_SVO_HDR_SOLID_LEVEL), passes::kSvoSolidFirstLevel);
  const uint8_t* grid = reinterpret_cast<const uint8_t*>(o.words.data()) + offset;
  // queries around the tumblers and the marble (world y from the floor up)
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> queries, dirs;
  for (int i = 0; i < 4096; ++i) {
    queries.insert(queries.end(), {0.9f * u(rng), -0.95f + 0.6f * (u(rng) + 1.0f), 0.9f * u(rng),
                                   float(1 + i % 3)});  // levels 1 .. 3
    float x = u(rng), y = u(rng), z = u(rng);
    const float len = std::sqrt(x * x + y * y + z * z) + 1e-6f;
    dirs.insert(dirs.end(), {x / len, y / len, z / len, 0.0f});
  }
  const std::vector<float> dense = run_directional(false, d.buffer, r, queries, dirs);
  const std::vector<float> got = run_directional(true, o.vol.buffer, r, queries, dirs);
  size_t raised = 0, bad = 0;
  for (size_t i = 0; i < queries.size() / 4; ++i) {
    const uint32_t level = uint32_t(queries[4 * i + 3]);
    float want[4] = {dense[4 * i], dense[4 * i + 1], dense[4 * i + 2], dense[4 * i + 3]};
    if (level >= passes::kSvoSolidFirstLevel) {
      // trilinear over the level's cells, footprint as the dense sampler
      const uint32_t n = r >> level;
      const uint8_t* g = grid + passes::svo_solid_level_offset(r, level);
      float f[3];
      uint32_t x0[3], x1[3];
      for (int k = 0; k < 3; ++k) {
        const float uu = std::clamp((queries[4 * i + k] + 1.0f) * 0.5f * float(n) - 0.5f, 0.0f,
                                    float(n) - 1.0f);
        x0[k] = uint32_t(std::floor(uu));
        f[k] = uu - std::floor(uu);
        x1[k] = std::min(x0[k] + 1, n - 1);
      }
      float solid = 0.0f;
      for (int c = 0; c < 8; ++c) {
        const uint32_t x = (c & 1) ? x1[0] : x0[0], y = (c & 2) ? x1[1] : x0[1],
                       z = (c & 4) ? x1[2] : x0[2];
        const float w = ((c & 1) ? f[0] : 1.0f - f[0]) * ((c & 2) ? f[1] : 1.0f - f[1]) *
                        ((c & 4) ? f[2] : 1.0f - f[2]);
        solid += w * float(g[(size_t(z) * n + y) * n + x]) / 255.0f;
      }
      solid *= RP_SVO_SOLID_WEIGHT;
      if (solid > want[3]) {
        ++raised;
        for (int c = 0; c < 3; ++c) want[c] = want[3] > 0.0f ? want[c] * solid / want[3] : 0.0f;
        want[3] = solid;
      }
    }
    for (int c = 0; c < 4; ++c)
      bad += std::fabs(got[4 * i + c] - want[c]) > 1e-5f * (1.0f + std::fabs(want[c]));
  }
  EXPECT_EQ(bad, 0u);
  EXPECT_GT(raised, 100u);
}

// Measurement (printed, not a criterion): the octree's passes at 256^3 for the demo frame and
// for its static room alone (box walls: what a "static room built once" scheme would keep),
// third run of each (the voxelizer's static cache warm). Tells how much of the per-frame
// rebuild an incremental insertion of the dynamic objects could save.
TEST(Svo, DeviceTimesRoomOnlyVsFull) {
  const uint32_t r = 256;
  std::vector<std::pair<std::string, rp::cl::PassTimes>> rows;
  uint32_t fragments[2] = {0, 0};
  for (int room_only = 0; room_only < 2; ++room_only) {
    Scene s(r);
    if (room_only) {
      std::vector<scene::MeshInstance> room;
      for (const scene::MeshInstance& m : s.frame.instances)
        if (!m.casts_shadow) room.push_back(m);
      s.frame.instances = room;
      s.frame.spheres.clear();
      s.gpu->update(s.frame, 64, 64, kShadow, r);
    }
    passes::SvoPass pass(context(), programs());
    render::SvoVolume vol;
    rp::cl::PassTimes times;
    for (int i = 0; i < 3; ++i) {
      pass.run(s.profiler, *s.gpu, s.shadow, r, vol);
      times = s.profiler.collect();
    }
    fragments[room_only] = vol.fragments;
    rows.emplace_back(room_only ? "room only" : "demo frame", times);
  }
  for (const auto& [name, times] : rows) {
    std::printf("[ stats    ] %s at 256^3:", name.c_str());
    for (const auto& [pass, ms] : times) std::printf(" %s %.1f ms", pass.c_str(), ms);
    std::printf("\n");
  }
  std::printf("[ stats    ] fragments: demo %u, room only %u\n", fragments[0], fragments[1]);
  EXPECT_GT(fragments[0], fragments[1]);
}

// The whole renderer on either volume at the same resolution (16^3, 16x16 pixels: small enough
// for oclgrind): the octree's packed samples give the dense frame to rounding, in the fast mode
// (indirect, multi-bounce gathers) and the reference mode (16 cones per pixel). Packed samples.
std::vector<uint8_t> render_frames(render::GiVolume volume, render::Quality quality,
                                   uint32_t frames = 2, uint32_t bounces = 64) {
  scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  render::RenderSettings settings;
  settings.width = settings.height = 16;
  settings.shadow_size = 64;
  settings.voxel_resolution = 16;
  settings.gi_volume = volume;
  settings.quality = quality;
  settings.bounces = bounces;
  render::Renderer renderer(context(), programs(), assets, settings);
  for (uint32_t i = 0; i < frames; ++i) renderer.render(scene::make_demo_frame(assets, i));
  std::vector<uint8_t> pixels;
  renderer.read_rgba8(pixels);
  return pixels;
}

TEST(Svo, RendererMatchesDenseFrame) {
  for (render::Quality q : {render::Quality::kFast, render::Quality::kReference}) {
    const std::vector<uint8_t> dense = render_frames(render::GiVolume::kDense, q);
    const std::vector<uint8_t> svo = render_frames(render::GiVolume::kSvo, q);
    ASSERT_EQ(dense.size(), svo.size());
    const double psnr = psnr_rgb8(dense, svo);
    std::printf("[ stats    ] %s: octree vs dense frame %.1f dB\n",
                q == render::Quality::kFast ? "fast" : "reference", psnr);
    EXPECT_GE(psnr, 40.0);
    size_t lit = 0;
    for (size_t i = 0; i < svo.size(); i += 4) lit += svo[i] + svo[i + 1] + svo[i + 2] > 60;
    EXPECT_GT(lit, svo.size() / 8);  // not a blank frame
  }
}

// The octree's variants of the light, indirect and bounce kernels, once each (one frame per
// mode, two bounces: one warm-start gather): small enough for the oclgrind label, where the
// comparison above takes too long.
TEST(Svo, RendererRunsOnTheOctree) {
  for (render::Quality q : {render::Quality::kFast, render::Quality::kReference}) {
    const std::vector<uint8_t> svo = render_frames(render::GiVolume::kSvo, q, 1, 2);
    size_t lit = 0;
    for (size_t i = 0; i < svo.size(); i += 4) lit += svo[i] + svo[i + 1] + svo[i + 2] > 60;
    EXPECT_GT(lit, svo.size() / 8);
  }
}

}  // namespace
}  // namespace rp::test
