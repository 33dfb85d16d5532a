// Voxel mips pass: the anisotropic chain against a C++ reference of the compositing rule
// (kernels/voxel_mips.cl) and of level 1's facing rule (mips_facing: each level-0 voxel as a
// cone along a direction sees it, from the voxelizer's facing coverage words) on a random
// level 0 with random coverage, hand-computed volumes where an opaque voxel hides what is
// behind it for one direction and not for the opposite one (also through two levels), one-sided
// and partly covered voxels, determinism, the layout's offsets and the pass name.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "cl/error.h"
#include "passes/pass_names.h"
#include "passes/voxel_mips.h"
#include "render/voxel_volume.h"
#include "support/cl_fixture.h"

namespace {

using rp::render::VoxelVolume;
using V4 = std::array<float, 4>;

V4 add(const V4& a, const V4& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3] + b[3]}; }
V4 scale(const V4& a, float s) { return {a[0] * s, a[1] * s, a[2] * s, a[3] * s}; }

// The documented rule, written independently of the kernel's loop structure: direction d on
// axis A with sign; front child = low-A child for +, high-A child for -; columns by ascending
// child index of their low-A child; ((c0 + c1) + (c2 + c3)) * 0.25.
V4 composite_ref(const std::array<V4, 8>& c, int dir) {
  const int axis = dir / 2;
  const bool positive = dir % 2 == 0;
  std::vector<V4> cols;
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x) {
        const int xyz[3] = {x, y, z};
        if (xyz[axis] != 0) continue;
        const int lo = x + 2 * y + 4 * z, hi = lo + (1 << axis);
        const V4& f = positive ? c[lo] : c[hi];
        const V4& b = positive ? c[hi] : c[lo];
        cols.push_back(add(f, scale(b, 1.0f - f[3])));
      }
  // Sorted by the low child's index already (x fastest loop over z, y, x matches ascending).
  return scale(add(add(cols[0], cols[1]), add(cols[2], cols[3])), 0.25f);
}

// The voxelizer's scratch words per level-0 voxel (kernels/shared/voxel_layout.h): the mip
// builder reads words 4, 5, 6 (facing coverage along x, y, z; low 16 bits: what faces +, high
// 16 bits: what faces -).
constexpr size_t kWords = RP_VOXEL_ACCUM_WORDS;
using Accum = std::vector<uint32_t>;  // kWords per level-0 voxel

// Full coverage in all six halves for every voxel (each voxel seen as it is from everywhere,
// the rule before facing coverage); words 0-3 and 7 garbage the builder must not read.
Accum all_facing(uint32_t r) {
  Accum a(size_t(r) * r * r * kWords, 0xDEADBEEFu);
  for (size_t v = 0; v < a.size() / kWords; ++v)
    for (size_t w = 4; w < 7; ++w) a[kWords * v + w] = 128u | (128u << 16);
  return a;
}

// mips_facing: level-0 voxel `iso` as a cone travelling along `dir` sees it. A cone along +axis
// sees what faces -axis (the high half), along -axis the low half; coverage c = min(half / 128,
// 1, iso.a), radiance iso.rgb * (c / iso.a); nothing where iso.a = 0.
V4 facing_ref(const V4& iso, const uint32_t* words, int dir) {
  const uint32_t w = words[4 + dir / 2];
  const uint32_t half = dir % 2 == 0 ? w >> 16 : w & 0xFFFFu;
  const float c = std::fmin(std::fmin(float(half) * (1.0f / RP_VOXEL_FACING_UNIT), 1.0f), iso[3]);
  if (!(iso[3] > 0.0f)) return V4{};
  const float k = c / iso[3];
  return {iso[0] * k, iso[1] * k, iso[2] * k, c};
}

// Reference chain (float4 elements, layout of kernels/shared/voxel_layout.h): level 1 from
// level 0 through facing_ref, higher levels from the same direction's volume below.
std::vector<V4> mips_ref(const std::vector<V4>& level0, const Accum& accum, uint32_t r) {
  const uint32_t levels = VoxelVolume::levels_for(r);
  std::vector<V4> chain(rp::gpu::rp_voxel_total(r, levels), V4{});
  std::copy(level0.begin(), level0.end(), chain.begin());
  for (uint32_t l = 1; l < levels; ++l) {
    const uint32_t n = r >> l, cn = 2 * n;
    for (int dir = 0; dir < 6; ++dir) {
      const uint32_t src = rp::gpu::rp_voxel_offset(r, l - 1, l == 1 ? 0 : dir);
      const uint32_t dst = rp::gpu::rp_voxel_offset(r, l, dir);
      for (uint32_t z = 0; z < n; ++z)
        for (uint32_t y = 0; y < n; ++y)
          for (uint32_t x = 0; x < n; ++x) {
            std::array<V4, 8> c;
            for (uint32_t i = 0; i < 8; ++i) {
              uint32_t cx = 2 * x + (i & 1), cy = 2 * y + ((i >> 1) & 1), cz = 2 * z + (i >> 2);
              const uint32_t child = (cz * cn + cy) * cn + cx;
              c[i] = l == 1 ? facing_ref(chain[child], &accum[kWords * child], dir)
                            : chain[src + child];
            }
            chain[dst + (z * n + y) * n + x] = composite_ref(c, dir);
          }
    }
  }
  return chain;
}

// Runs the pass on `level0` with the voxelizer's scratch `accum` and returns the whole chain.
std::vector<V4> mips_gpu(const std::vector<V4>& level0, const Accum& accum, uint32_t r,
                         rp::cl::PassTimes* times = nullptr) {
  auto& ctx = rp::test::context();
  VoxelVolume vol;
  vol.resize(ctx.context, r);
  ctx.queue.enqueueWriteBuffer(vol.chain, CL_TRUE, 0, level0.size() * sizeof(V4), level0.data());
  EXPECT_EQ(accum.size(), level0.size() * kWords);
  ctx.queue.enqueueWriteBuffer(vol.accum, CL_TRUE, 0, accum.size() * sizeof(uint32_t),
                               accum.data());
  rp::passes::VoxelMipsPass pass(ctx, rp::test::programs());
  rp::cl::Profiler profiler(ctx.queue);
  pass.run(profiler, vol);
  rp::cl::PassTimes t = profiler.collect();
  if (times) *times = t;
  std::vector<V4> chain(vol.chain_elements());
  ctx.queue.enqueueReadBuffer(vol.chain, CL_TRUE, 0, chain.size() * sizeof(V4), chain.data());
  return chain;
}

uint32_t at(uint32_t r, uint32_t level, uint32_t dir, uint32_t x, uint32_t y, uint32_t z) {
  const uint32_t n = r >> level;
  return rp::gpu::rp_voxel_offset(r, level, dir) + (z * n + y) * n + x;
}

void expect_v4(const V4& got, const V4& want, const char* what) {
  for (int c = 0; c < 4; ++c) EXPECT_FLOAT_EQ(got[c], want[c]) << what << " channel " << c;
}

TEST(VoxelMips, LayoutAndLevels) {
  EXPECT_EQ(VoxelVolume::levels_for(64), 7u);
  EXPECT_EQ(VoxelVolume::levels_for(2), 2u);
  EXPECT_EQ(rp::gpu::rp_voxel_offset(4, 1, 0), 64u);
  EXPECT_EQ(rp::gpu::rp_voxel_offset(4, 1, 5), 64u + 5 * 8);
  EXPECT_EQ(rp::gpu::rp_voxel_offset(4, 2, 0), 64u + 6 * 8);
  EXPECT_EQ(rp::gpu::rp_voxel_total(4, 3), 64u + 6 * 8 + 6);
  EXPECT_FALSE(VoxelVolume::valid_resolution(48));
  EXPECT_FALSE(VoxelVolume::valid_resolution(512));
  VoxelVolume vol;
  EXPECT_THROW(vol.resize(rp::test::context().context, 48), rp::cl::Error);
  rp::passes::VoxelMipsPass pass(rp::test::context(), rp::test::programs());
  rp::cl::Profiler profiler(rp::test::context().queue);
  EXPECT_THROW(pass.run(profiler, vol), rp::cl::Error);  // never allocated
}

// A random level 0 of r^3 voxels through the pass, against the reference chain; voxel 0 of
// `check_level` (+x) must be neither empty nor opaque (the values are not trivial).
void check_random_volume(uint32_t r, uint32_t check_level) {
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::vector<V4> level0(size_t(r) * r * r);
  for (V4& v : level0) {
    const float pick = u01(rng);
    // A third empty, a third opaque, a third partly transparent; rgb premultiplied (<= a * 4).
    const float a = pick < 0.33f ? 0.0f : pick < 0.66f ? 1.0f : u01(rng);
    v = {a * 4.0f * u01(rng), a * u01(rng), a * 0.5f * u01(rng), a};
  }
  // Facing coverage: per half none, partial, exactly full, beyond full (several surfaces), or
  // large (up to 511 full contributions); the unused words random.
  std::uniform_int_distribution<uint32_t> any(0u, 0xFFFFFFFFu), count(0u, 511u * 128u);
  auto half = [&]() -> uint32_t {
    const float pick = u01(rng);
    return pick < 0.3f ? 0u : pick < 0.5f ? uint32_t(u01(rng) * 128.0f) : pick < 0.7f ? 128u
           : pick < 0.9f ? 128u + uint32_t(u01(rng) * 300.0f) : count(rng);
  };
  Accum accum(level0.size() * kWords);
  for (size_t v = 0; v < level0.size(); ++v)
    for (size_t w = 0; w < kWords; ++w)
      accum[kWords * v + w] = w >= 4 && w < 7 ? half() | (half() << 16) : any(rng);
  rp::cl::PassTimes times;
  const std::vector<V4> got = mips_gpu(level0, accum, r, &times);
  const std::vector<V4> want = mips_ref(level0, accum, r);
  ASSERT_EQ(got.size(), want.size());
  size_t bad = 0;
  for (size_t i = 0; i < got.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      const float tol = 1e-6f * std::fabs(want[i][c]) + 1e-12f;
      if (!(std::fabs(got[i][c] - want[i][c]) <= tol) && bad++ < 5)
        ADD_FAILURE() << "element " << i << " channel " << c << ": " << got[i][c] << " vs "
                      << want[i][c];
    }
  EXPECT_EQ(bad, 0u);
  EXPECT_EQ(times.count(rp::passes::pass_name::kVoxelMips), 1u);
  const V4 top = got[at(r, check_level, 0, 0, 0, 0)];
  EXPECT_GT(top[3], 0.1f);
  EXPECT_LT(top[3], 1.0f);
}

TEST(VoxelMips, MatchesReferenceOnRandomVolume) { check_random_volume(16, 4); }  // top level

// 64^3: levels 1 and 2 have 32 and 16 voxels per side, where CPUs compute 16 parents per
// work-item; both layouts (ROLYPOLY_VOXEL_MIPS_SPAN: 1 = GPU, 16) match the reference.
class VoxelMipsSpans : public ::testing::TestWithParam<const char*> {};

TEST_P(VoxelMipsSpans, MatchesReferenceOnRandomVolume) {
  setenv("ROLYPOLY_VOXEL_MIPS_SPAN", GetParam(), 1);
  try {
    check_random_volume(64, 2);
  } catch (...) {
    unsetenv("ROLYPOLY_VOXEL_MIPS_SPAN");
    throw;
  }
  unsetenv("ROLYPOLY_VOXEL_MIPS_SPAN");
}

INSTANTIATE_TEST_SUITE_P(Spans, VoxelMipsSpans, ::testing::Values("1", "16"));

TEST(VoxelMips, OpaqueVoxelHidesWhatIsBehindInOneDirectionOnly) {
  // R = 2: black opaque voxel at x = 0, green opaque voxel behind it at x = 1 (same y, z).
  const uint32_t r = 2;
  std::vector<V4> level0(8, V4{});
  level0[0] = {0.0f, 0.0f, 0.0f, 1.0f};  // (0,0,0)
  level0[1] = {0.0f, 1.0f, 0.0f, 1.0f};  // (1,0,0)
  level0[6] = {0.5f, 0.0f, 0.0f, 0.5f};  // (0,1,1): half-transparent red over ...
  level0[7] = {0.0f, 0.0f, 1.0f, 1.0f};  // (1,1,1): ... opaque blue
  const std::vector<V4> got = mips_gpu(level0, all_facing(r), r);
  // +x travels from x = 0 to x = 1: sees the black voxel (green hidden), and red over blue.
  expect_v4(got[at(r, 1, RP_DIR_POS_X, 0, 0, 0)], {0.125f, 0.0f, 0.125f, 0.5f}, "+x");
  // -x travels from x = 1 to x = 0: sees green (black hidden), and blue (red hidden).
  expect_v4(got[at(r, 1, RP_DIR_NEG_X, 0, 0, 0)], {0.0f, 0.25f, 0.25f, 0.5f}, "-x");
  // Along y and z every non-empty voxel is its column's only one: plain mean.
  const V4 mean = {0.125f, 0.25f, 0.25f, 0.875f};
  for (uint32_t dir : {RP_DIR_POS_Y, RP_DIR_NEG_Y, RP_DIR_POS_Z, RP_DIR_NEG_Z})
    expect_v4(got[at(r, 1, dir, 0, 0, 0)], mean, "y/z");
}

TEST(VoxelMips, HigherLevelsComposeTheSameDirection) {
  // R = 4: an opaque black slab at x = 0 and an opaque green slab at x = 3. Level 1 +x sees
  // black in its x = 0 half and green in its x = 1 half; level 2 +x must take black (its front),
  // level 2 -x green: only right if each level reads the same direction's volume below.
  const uint32_t r = 4;
  std::vector<V4> level0(64, V4{});
  for (uint32_t z = 0; z < 4; ++z)
    for (uint32_t y = 0; y < 4; ++y) {
      level0[(z * 4 + y) * 4 + 0] = {0.0f, 0.0f, 0.0f, 1.0f};
      level0[(z * 4 + y) * 4 + 3] = {0.0f, 1.0f, 0.0f, 1.0f};
    }
  const std::vector<V4> got = mips_gpu(level0, all_facing(r), r);
  expect_v4(got[at(r, 1, RP_DIR_POS_X, 0, 1, 1)], {0.0f, 0.0f, 0.0f, 1.0f}, "L1 +x x=0");
  expect_v4(got[at(r, 1, RP_DIR_POS_X, 1, 1, 1)], {0.0f, 1.0f, 0.0f, 1.0f}, "L1 +x x=1");
  expect_v4(got[at(r, 2, RP_DIR_POS_X, 0, 0, 0)], {0.0f, 0.0f, 0.0f, 1.0f}, "L2 +x");
  expect_v4(got[at(r, 2, RP_DIR_NEG_X, 0, 0, 0)], {0.0f, 1.0f, 0.0f, 1.0f}, "L2 -x");
  // Across x (+y): level 1 sees each slab in half of its columns, (0,0,0,.5) and (0,.5,0,.5);
  // level 2 composites two such voxels per column: .5 + .5 * .5 = .75, half of them green.
  expect_v4(got[at(r, 2, RP_DIR_POS_Y, 0, 0, 0)], {0.0f, 0.375f, 0.0f, 0.75f}, "L2 +y");
}

TEST(VoxelMips, Level1SeesOnlyWhatFacesTheCone) {
  // R = 2. Voxel (0,0,0): opaque red, covered only by surfaces facing +x (a wall whose front
  // is +x): cones travelling -x (towards its front) see it, cones travelling +x (leaving its
  // front) and along y or z do not. Voxel (1,1,1): half-opaque (premultiplied (0.4, 0.2, 0)),
  // y coverage 32 from what faces +y (a quarter) and 300 from what faces -y (more than full,
  // so the voxel's own opacity 0.5 bounds it); no x or z coverage.
  const uint32_t r = 2;
  std::vector<V4> level0(8, V4{});
  level0[0] = {1.0f, 0.0f, 0.0f, 1.0f};
  level0[7] = {0.4f, 0.2f, 0.0f, 0.5f};
  Accum accum(8 * kWords, 0xDEADBEEFu);
  for (size_t v = 0; v < 8; ++v)
    for (size_t w = 4; w < 7; ++w) accum[kWords * v + w] = 0u;
  accum[kWords * 0 + 4] = 128u;               // x: faces +x, full
  accum[kWords * 7 + 5] = 32u | (300u << 16);  // y: faces +y a quarter, -y beyond full
  accum[kWords * 2 + 6] = 128u | (128u << 16);  // coverage of an empty voxel counts nothing
  const std::vector<V4> got = mips_gpu(level0, accum, r);
  // -x: the front slab is x = 1 (empty there), the red voxel behind: one column of four.
  expect_v4(got[at(r, 1, RP_DIR_NEG_X, 0, 0, 0)], {0.25f, 0.0f, 0.0f, 0.25f}, "-x");
  expect_v4(got[at(r, 1, RP_DIR_POS_X, 0, 0, 0)], {0.0f, 0.0f, 0.0f, 0.0f}, "+x");
  // +y sees what faces -y: c = min(300 / 128, 1, 0.5) = 0.5, the voxel as it is.
  expect_v4(got[at(r, 1, RP_DIR_POS_Y, 0, 0, 0)], {0.1f, 0.05f, 0.0f, 0.125f}, "+y");
  // -y sees what faces +y: c = 0.25, radiance scaled by c / a = 0.5.
  expect_v4(got[at(r, 1, RP_DIR_NEG_Y, 0, 0, 0)], {0.05f, 0.025f, 0.0f, 0.0625f}, "-y");
  for (uint32_t dir : {RP_DIR_POS_Z, RP_DIR_NEG_Z})
    expect_v4(got[at(r, 1, dir, 0, 0, 0)], {0.0f, 0.0f, 0.0f, 0.0f}, "z");
  // Level 1 is what the higher levels build on: the same through the reference.
  const std::vector<V4> want = mips_ref(level0, accum, r);
  for (size_t i = 0; i < got.size(); ++i)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(got[i][c], want[i][c]) << i << " " << c;
}

TEST(VoxelMips, Deterministic) {
  const uint32_t r = 32;
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::vector<V4> level0(size_t(r) * r * r);
  for (V4& v : level0) {
    const float a = u01(rng) < 0.7f ? 0.0f : u01(rng);
    v = {a * u01(rng), a * u01(rng), a * u01(rng), a};
  }
  Accum accum = all_facing(r);
  for (size_t v = 0; v < level0.size(); ++v)  // some one-sided voxels
    if (v % 3 == 0) accum[kWords * v + 4 + v % 7 % 3] = 64u + uint32_t(v % 200);
  const std::vector<V4> first = mips_gpu(level0, accum, r),
                        second = mips_gpu(level0, accum, r);
  ASSERT_EQ(first.size(), second.size());
  EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(V4)), 0);
}

}  // namespace
