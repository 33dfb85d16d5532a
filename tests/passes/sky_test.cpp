// The environment light in the real-time modes: the mip chain (render/sky_texture.h) keeps the
// map's solid-angle weighted mean level by level, and the kernels' lookup (kernels/common/
// sky.h) reads the same texel as the path tracer's sampler (truth/environment.h) for the same
// direction, turn and strength, picks the level whose texels are as tall as the cone is wide,
// and is black without an environment.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "cl/error.h"
#include "cl/program_cache.h"
#include "render/gpu_types.h"
#include "render/sky_cells.h"
#include "render/sky_texture.h"
#include "support/cl_fixture.h"
#include "truth/environment.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

const char* kTestKernels = R"CLC(
/* dirs: xyz unit world direction, w tan of the cone's half-angle */
__kernel void sky_test_radiance(__global const FrameConstants* frame,
                                __global const float4* sky, __global const float4* dirs,
                                __global float4* out) {
  const size_t i = get_global_id(0);
  out[i] = (float4)(rp_sky_radiance(frame, sky, dirs[i].xyz, dirs[i].w), 0.0f);
}
/* rows[i], weights[i]: the cones' table rows rp_sky_cells interpolates for normals[i] */
__kernel void sky_test_cells(__global const FrameConstants* frame,
                             __global const float4* normals, __global uint4* rows,
                             __global float4* weights) {
  const size_t i = get_global_id(0);
  const RpSkyCells c = rp_sky_cells(frame, normals[i].xyz);
  rows[i] = c.rows;
  weights[i] = c.weight;
}
)CLC";

const ::cl::Program& test_program() {
  static ::cl::Program program = [] {
    auto& ctx = rp::test::context();
    ::cl::Program p(ctx.context, rp::cl::kernel_source("common/sky.h") + kTestKernels);
    try {
      p.build(std::vector<::cl::Device>{ctx.info.device});
    } catch (const ::cl::Error&) {
      throw rp::cl::Error("sky test kernels: " +
                          p.getBuildInfo<CL_PROGRAM_BUILD_LOG>(ctx.info.device));
    }
    return p;
  }();
  return program;
}

// The kernel's radiance for each (direction, tan_half) with FrameConstants.sky = `info`.
std::vector<glm::vec3> lookup(const rp::gpu::SkyGpu& info,
                              const std::vector<rp::gpu::rp_float4>& texels,
                              const std::vector<glm::vec4>& dirs) {
  auto& ctx = rp::test::context();
  rp::gpu::FrameConstants frame{};
  frame.sky = info;
  ::cl::Buffer frame_buf(ctx.context, CL_MEM_READ_ONLY, sizeof frame);
  ctx.queue.enqueueWriteBuffer(frame_buf, CL_TRUE, 0, sizeof frame, &frame);
  const size_t tn = std::max<size_t>(texels.size(), 1);
  ::cl::Buffer sky(ctx.context, CL_MEM_READ_ONLY, tn * 16);
  if (!texels.empty()) ctx.queue.enqueueWriteBuffer(sky, CL_TRUE, 0, tn * 16, texels.data());
  ::cl::Buffer in(ctx.context, CL_MEM_READ_ONLY, dirs.size() * 16);
  ctx.queue.enqueueWriteBuffer(in, CL_TRUE, 0, dirs.size() * 16, dirs.data());
  ::cl::Buffer out(ctx.context, CL_MEM_WRITE_ONLY, dirs.size() * 16);
  ::cl::Kernel k(test_program(), "sky_test_radiance");
  k.setArg(0, frame_buf);
  k.setArg(1, sky);
  k.setArg(2, in);
  k.setArg(3, out);
  ctx.queue.enqueueNDRangeKernel(k, ::cl::NullRange, ::cl::NDRange(dirs.size()));
  std::vector<glm::vec4> result(dirs.size());
  ctx.queue.enqueueReadBuffer(out, CL_TRUE, 0, dirs.size() * 16, result.data());
  std::vector<glm::vec3> rgb;
  for (const glm::vec4& v : result) rgb.emplace_back(v);
  return rgb;
}

std::shared_ptr<rp::scene::EnvironmentMap> random_map(int w, int h, uint32_t seed) {
  auto map = std::make_shared<rp::scene::EnvironmentMap>();
  map->width = w;
  map->height = h;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 4.0f);
  for (int i = 0; i < w * h * 3; ++i) map->rgb.push_back(u(rng));
  return map;
}

// Sum over a level's texels of radiance x solid angle, (2 pi / w)(cos theta0 - cos theta1).
glm::dvec3 integral(const rp::render::SkyTexture& t, uint32_t level) {
  const uint32_t w = std::max(t.info.width >> level, 1u), h = std::max(t.info.height >> level, 1u);
  glm::dvec3 sum(0.0);
  for (uint32_t y = 0; y < h; ++y) {
    const double omega = 2.0 * kPi / w * (std::cos(kPi * y / h) - std::cos(kPi * (y + 1) / h));
    for (uint32_t x = 0; x < w; ++x) {
      const rp::gpu::rp_float4& c = t.texels[t.info.level_offset[level] + y * w + x];
      sum += omega * glm::dvec3(c.x, c.y, c.z);
    }
  }
  return sum;
}

TEST(SkyTexture, EveryLevelKeepsTheMapsIntegralOverTheSphere) {
  const auto map = random_map(64, 32, 3);
  const rp::render::SkyTexture t = rp::render::build_sky_texture(*map);
  ASSERT_EQ(t.info.levels, 6u);  // 64x32 .. 2x1
  EXPECT_EQ(t.info.width, 64u);
  EXPECT_EQ(t.info.height, 32u);
  const size_t chain = 64 * 32 + 32 * 16 + 16 * 8 + 8 * 4 + 4 * 2 + 2 * 1;
  EXPECT_EQ(t.info.cell_offset, chain);  // the cones' table follows the chain
  EXPECT_EQ(t.texels.size(), chain + RP_SKY_CELL_SIDE * RP_SKY_CELL_SIDE * 16);
  const glm::dvec3 base = integral(t, 0);
  for (uint32_t l = 1; l < t.info.levels; ++l)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(integral(t, l)[c], base[c], 1e-5 * base[c]) << "level " << l;
}

TEST(SkyTexture, MapsWiderThanTheCapAreHalvedFirst) {
  const auto map = random_map(2 * rp::render::kSkyMaxWidth, rp::render::kSkyMaxWidth, 4);
  const rp::render::SkyTexture t = rp::render::build_sky_texture(*map);
  EXPECT_EQ(t.info.width, uint32_t(rp::render::kSkyMaxWidth));
  EXPECT_EQ(t.info.height, uint32_t(rp::render::kSkyMaxWidth / 2));
  EXPECT_EQ(rp::render::sky_texel_count(map->width, map->height), t.texels.size());
}

// Level 0 alone (the map seen beside a chain without its suns) is the chain's first level.
TEST(SkyTexture, LevelZeroAloneIsTheChainsFirstLevel) {
  const auto map = random_map(2 * rp::render::kSkyMaxWidth, rp::render::kSkyMaxWidth / 2, 6);
  const rp::render::SkyTexture t = rp::render::build_sky_texture(*map);
  const std::vector<rp::gpu::rp_float4> level0 = rp::render::build_sky_level0(*map);
  ASSERT_EQ(level0.size(), rp::render::sky_level0_texel_count(map->width, map->height));
  ASSERT_EQ(level0.size(), size_t(t.info.width) * t.info.height);
  EXPECT_EQ(std::memcmp(level0.data(), t.texels.data(), level0.size() * 16), 0);
}

// The memory estimate counts what the chain holds, odd sizes included.
TEST(SkyTexture, TexelCountIsTheChainsSize) {
  for (const auto& [w, h] : {std::pair{64, 32}, {100, 50}, {6, 3}, {2, 1}}) {
    const auto map = random_map(w, h, 5);
    EXPECT_EQ(rp::render::sky_texel_count(w, h), rp::render::build_sky_texture(*map).texels.size())
        << w << "x" << h;
  }
}

// At texel centres the bilinear lookup is the texel itself, which is what the path tracer's
// sampler returns (nearest texel) for the same world direction: the two agree on the map's
// orientation, the turn's sense and the strength.
TEST(SkyLookup, ReadsThePathTracersTexelForEveryTurn) {
  const auto map = random_map(32, 16, 7);
  const rp::render::SkyTexture t = rp::render::build_sky_texture(*map);
  for (float turn : {0.0f, 90.0f, 217.0f, -45.0f}) {
    rp::scene::Environment env;
    env.map = map;
    env.rotate_deg = turn;
    env.strength = 2.0f;
    const rp::truth::EnvironmentSampler truth(env);
    const float c = std::cos(turn * float(kPi / 180.0)), s = std::sin(turn * float(kPi / 180.0));
    std::vector<glm::vec4> dirs;
    for (int y = 0; y < map->height; ++y)
      for (int x = 0; x < map->width; ++x) {
        const glm::vec3 m = rp::scene::environment_direction(
            (float(x) + 0.5f) / float(map->width), (float(y) + 0.5f) / float(map->height));
        // world direction whose map direction is m (the inverse of the turn)
        dirs.emplace_back(c * m.x + s * m.z, m.y, -s * m.x + c * m.z, 0.0f);
      }
    const std::vector<glm::vec3> got = lookup(rp::render::sky_record(t.info, env), t.texels, dirs);
    for (size_t i = 0; i < dirs.size(); ++i) {
      const glm::vec3 want = truth.radiance(glm::vec3(dirs[i]));
      for (int k = 0; k < 3; ++k)
        ASSERT_NEAR(got[i][k], want[k], 2e-3f * (1.0f + want[k]))
            << "turn " << turn << ", texel " << i;
    }
  }
}

// Levels filled with the constants 1, 2, 3, ...: a cone exactly as wide as level l's texels are
// tall reads l + 1, one halfway between two levels the mean of theirs, a needle level 0, and
// the widest cone the last level.
TEST(SkyLookup, ConeWidthPicksTheLevel) {
  const uint32_t w = 64, h = 32;
  rp::render::SkyTexture t;
  t.info.width = w;
  t.info.height = h;
  t.info.levels = 6;
  for (uint32_t l = 0; l < t.info.levels; ++l) {
    t.info.level_offset[l] = uint32_t(t.texels.size());
    const float v = float(l + 1);
    t.texels.insert(t.texels.end(), size_t(std::max(w >> l, 1u)) * std::max(h >> l, 1u),
                    rp::gpu::rp_float4{v, v, v, 0.0f});
  }
  rp::scene::Environment env;
  env.map = random_map(2, 1, 1);  // enabled; its texels are not read (t's are)
  // tan of the half-angle for a cone 2^L level-0 texels (pi / h each) wide
  const auto tan_for = [&](double level) {
    return float(std::tan(0.5 * std::exp2(level) * kPi / h));
  };
  const glm::vec3 d = glm::normalize(glm::vec3(0.3f, 0.5f, -0.8f));
  const std::vector<glm::vec4> dirs = {glm::vec4(d, 0.0f), glm::vec4(d, tan_for(2.0)),
                                       glm::vec4(d, tan_for(2.5)), glm::vec4(d, tan_for(4.0)),
                                       glm::vec4(d, 100.0f)};
  const std::vector<glm::vec3> got = lookup(rp::render::sky_record(t.info, env), t.texels, dirs);
  EXPECT_NEAR(got[0].x, 1.0f, 1e-5f);
  EXPECT_NEAR(got[1].x, 3.0f, 1e-3f);
  EXPECT_NEAR(got[2].x, 3.5f, 1e-3f);
  EXPECT_NEAR(got[3].x, 5.0f, 1e-3f);
  EXPECT_NEAR(got[4].x, 6.0f, 0.01f);  // atan(100) h / pi: 31.8 texels, level 4.99
  // a chain of 5 levels (64x32 .. 4x2) clamps the widest cone to its last level
  t.info.levels = 5;
  EXPECT_NEAR(lookup(rp::render::sky_record(t.info, env), t.texels, {dirs[4]})[0].x, 5.0f, 1e-5f);
}

TEST(SkyLookup, NoEnvironmentIsBlack) {
  const auto map = random_map(16, 8, 9);
  const rp::render::SkyTexture t = rp::render::build_sky_texture(*map);
  const rp::scene::Environment none;
  const std::vector<glm::vec3> got =
      lookup(rp::render::sky_record(t.info, none), t.texels, {glm::vec4(0, 1, 0, 0.5f)});
  EXPECT_EQ(got[0], glm::vec3(0.0f));
}

// The cones' cells (render/sky_cells.h): in the disk of r = sin theta, where the cosine-weighted
// measure is uniform, each cell holds 1/16, and each cone's axis lies in its own cell.
TEST(SkyCells, EachConeOwnsASixteenthOfTheCosineWeightedHemisphere) {
  constexpr int kSteps = 400;  // midpoints of a kSteps^2 grid in (r^2, azimuth)
  std::vector<int> count(16, 0);
  for (int a = 0; a < kSteps; ++a)
    for (int r = 0; r < kSteps; ++r) {
      const double r2 = (r + 0.5) / kSteps, phi = 2.0 * kPi * (a + 0.5) / kSteps;
      const int k = rp::render::sky_cone_cell(
          {std::sqrt(r2) * std::cos(phi), std::sqrt(r2) * std::sin(phi), std::sqrt(1.0 - r2)});
      ASSERT_GE(k, 0);
      ++count[size_t(k)];
    }
  for (int k = 0; k < 16; ++k) EXPECT_NEAR(count[size_t(k)], kSteps * kSteps / 16, kSteps) << k;
  EXPECT_EQ(rp::render::sky_cone_cell({0.6, 0.0, -0.8}), -1);  // below the horizon
  // the axes of kernels/common/cone_trace.h's RP_CONE_SET16
  EXPECT_EQ(rp::render::sky_cone_cell({0.0, 0.0, 1.0}), 0);
  for (int k = 1; k < 16; ++k) {
    const bool inner = k <= 5;
    const double s2 = inner ? 3.5 / 16.0 : 11.0 / 16.0;
    const double az = (inner ? 72.0 * (k - 1) : 18.0 + 36.0 * (k - 6)) * kPi / 180.0;
    EXPECT_EQ(rp::render::sky_cone_cell({std::sqrt(s2) * std::cos(az), std::sqrt(s2) * std::sin(az),
                                         std::sqrt(1.0 - s2)}),
              k);
  }
}

// The grid's normals are unit, the six axes among them, and its basis is right-handed.
TEST(SkyCells, GridHoldsTheAxes) {
  const int side = int(RP_SKY_CELL_SIDE), mid = side / 2;
  EXPECT_EQ(rp::render::sky_cell_normal(mid, mid), glm::dvec3(0, 0, 1));
  EXPECT_EQ(rp::render::sky_cell_normal(side - 1, mid), glm::dvec3(1, 0, 0));
  EXPECT_EQ(rp::render::sky_cell_normal(0, mid), glm::dvec3(-1, 0, 0));
  EXPECT_EQ(rp::render::sky_cell_normal(mid, side - 1), glm::dvec3(0, 1, 0));
  EXPECT_EQ(rp::render::sky_cell_normal(mid, 0), glm::dvec3(0, -1, 0));
  EXPECT_EQ(rp::render::sky_cell_normal(0, 0), glm::dvec3(0, 0, -1));
  for (int j = 0; j < side; j += 5)
    for (int i = 0; i < side; i += 3) {
      const glm::dvec3 n = rp::render::sky_cell_normal(i, j);
      glm::dvec3 t, b;
      rp::render::sky_cell_basis(n, t, b);
      EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
      EXPECT_NEAR(glm::dot(glm::cross(t, b), n), 1.0, 1e-12) << i << " " << j;
    }
}

// A constant map gives its radiance in every cell of every normal.
TEST(SkyCells, ConstantMapIsConstant) {
  std::vector<double> rgb;
  for (int i = 0; i < 64 * 32; ++i) rgb.insert(rgb.end(), {0.5, 1.0, 2.0});
  for (const rp::gpu::rp_float4& c : rp::render::sky_cell_table({64, 32, rgb.data()})) {
    EXPECT_FLOAT_EQ(c.x, 0.5f);
    EXPECT_FLOAT_EQ(c.y, 1.0f);
    EXPECT_FLOAT_EQ(c.z, 2.0f);
  }
}

// Each entry is the map's mean over its cell with weight cos theta: against the same map
// integrated over the cell's own parametrisation (stratified in r^2 and azimuth, where the
// weight is uniform; nearest texel), for normals across the grid, on a smooth sky (red, blue:
// within 2 %) with a bright patch (green). The table decides by texel centres (128 x 64 texels
// of 2.8 degrees), so where a cell's border cuts the patch its entry may miss or gain part of a
// texel column: green within 20 % per cell and 3 % on average.
TEST(SkyCells, EachEntryIsItsCellsCosineWeightedMean) {
  const int w = 128, h = 64;
  std::vector<double> rgb;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double v = 1.0 + 0.5 * std::cos(2.0 * kPi * x / w) + double(y) / h;
      const bool patch = y >= 20 && y < 30 && x >= 40 && x < 52;
      rgb.insert(rgb.end(), {v, patch ? 30.0 : v, 2.0 * v});
    }
  const std::vector<rp::gpu::rp_float4> table = rp::render::sky_cell_table({w, h, rgb.data()});
  const int side = int(RP_SKY_CELL_SIDE);
  double green_error = 0.0;
  int entries = 0;
  for (int j = 1; j < side; j += 4)
    for (int i = 0; i < side; i += 4) {
      const glm::dvec3 n = rp::render::sky_cell_normal(i, j);
      glm::dvec3 t, b;
      rp::render::sky_cell_basis(n, t, b);
      for (int k = 0; k < 16; ++k) {
        // the cell's (r^2, azimuth degrees) range
        const double r0 = k == 0 ? 0.0 : k <= 5 ? 1.0 / 16.0 : 6.0 / 16.0;
        const double r1 = k == 0 ? 1.0 / 16.0 : k <= 5 ? 6.0 / 16.0 : 1.0;
        const double a0 = k == 0 ? 0.0 : k <= 5 ? 72.0 * (k - 1) - 36.0 : 36.0 * (k - 6);
        const double a1 = k == 0 ? 360.0 : k <= 5 ? a0 + 72.0 : a0 + 36.0;
        glm::dvec3 sum(0.0);
        constexpr int kSteps = 60;
        for (int a = 0; a < kSteps; ++a)
          for (int r = 0; r < kSteps; ++r) {
            const double r2 = r0 + (r1 - r0) * (r + 0.5) / kSteps;
            const double phi = (a0 + (a1 - a0) * (a + 0.5) / kSteps) * kPi / 180.0;
            const glm::dvec3 d = std::sqrt(r2) * std::cos(phi) * t +
                                 std::sqrt(r2) * std::sin(phi) * b + std::sqrt(1.0 - r2) * n;
            double u = std::atan2(d.x, -d.z) / (2.0 * kPi);
            if (u < 0.0) u += 1.0;
            const int x = std::min(int(u * w), w - 1);
            const int y = std::min(int(std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi * h), h - 1);
            const size_t texel = (size_t(y) * w + x) * 3;
            sum += glm::dvec3(rgb[texel], rgb[texel + 1], rgb[texel + 2]);
          }
        const glm::dvec3 want = sum / double(kSteps * kSteps);
        const rp::gpu::rp_float4& got = table[(size_t(j) * side + i) * 16 + size_t(k)];
        EXPECT_NEAR(got.x, want.x, 0.02 * want.x) << i << " " << j << " cone " << k;
        EXPECT_NEAR(got.y, want.y, 0.2 * want.y) << i << " " << j << " cone " << k;
        EXPECT_NEAR(got.z, want.z, 0.02 * want.z) << i << " " << j << " cone " << k;
        green_error += std::fabs(got.y / want.y - 1.0);
        ++entries;
      }
    }
  EXPECT_LT(green_error / entries, 0.03);
}

// The kernels interpolate the table's rows around a world normal, through the turn: each grid
// normal turned into the world reads its own row (or, on the octahedron's folded edges, a row
// whose normal is the same) with weight 1, and any normal reads grid normals within 15 degrees
// (a grid cell's diagonal) with weights that sum to 1 and whose blend lies within 1.5 degrees.
TEST(SkyCells, KernelInterpolatesTheGridNormalsAroundForEveryTurn) {
  const int side = int(RP_SKY_CELL_SIDE);
  std::mt19937 rng(12);
  std::normal_distribution<float> g;
  for (const double turn : {0.0, 33.0, 250.0}) {
    rp::gpu::SkyGpu info{};
    info.turn = {float(std::cos(turn * kPi / 180.0)), float(std::sin(turn * kPi / 180.0)), 1.0f,
                 0.0f};
    info.cell_offset = 100;
    info.diffuse_cones = 1;
    const double c = info.turn.x, s = info.turn.y;
    std::vector<glm::vec4> normals;
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i) {
        const glm::dvec3 m = rp::render::sky_cell_normal(i, j);
        normals.emplace_back(glm::vec3(c * m.x + s * m.z, m.y, c * m.z - s * m.x), 0.0f);
      }
    const size_t grid = normals.size();
    for (int k = 0; k < 500; ++k)
      normals.emplace_back(glm::normalize(glm::vec3(g(rng), g(rng), g(rng))), 0.0f);
    auto& ctx = rp::test::context();
    rp::gpu::FrameConstants frame{};
    frame.sky = info;
    const size_t n = normals.size();
    ::cl::Buffer frame_buf(ctx.context, CL_MEM_READ_ONLY, sizeof frame);
    ctx.queue.enqueueWriteBuffer(frame_buf, CL_TRUE, 0, sizeof frame, &frame);
    ::cl::Buffer in(ctx.context, CL_MEM_READ_ONLY, n * 16);
    ctx.queue.enqueueWriteBuffer(in, CL_TRUE, 0, n * 16, normals.data());
    ::cl::Buffer rows_buf(ctx.context, CL_MEM_WRITE_ONLY, n * 16);
    ::cl::Buffer weights_buf(ctx.context, CL_MEM_WRITE_ONLY, n * 16);
    ::cl::Kernel kernel(test_program(), "sky_test_cells");
    kernel.setArg(0, frame_buf);
    kernel.setArg(1, in);
    kernel.setArg(2, rows_buf);
    kernel.setArg(3, weights_buf);
    ctx.queue.enqueueNDRangeKernel(kernel, ::cl::NullRange, ::cl::NDRange(n));
    std::vector<glm::uvec4> rows(n);
    std::vector<glm::vec4> weights(n);
    ctx.queue.enqueueReadBuffer(rows_buf, CL_TRUE, 0, n * 16, rows.data());
    ctx.queue.enqueueReadBuffer(weights_buf, CL_TRUE, 0, n * 16, weights.data());
    for (size_t q = 0; q < n; ++q) {
      const glm::dvec3 want(glm::vec3(normals[q]));
      EXPECT_NEAR(weights[q].x + weights[q].y + weights[q].z + weights[q].w, 1.0f, 1e-6f);
      glm::dvec3 blend(0.0);
      for (int r = 0; r < 4; ++r) {
        ASSERT_GE(rows[q][r], 100u);
        ASSERT_EQ((rows[q][r] - 100u) % 16u, 0u);
        const uint32_t cell = (rows[q][r] - 100u) / 16u;
        ASSERT_LT(cell, uint32_t(side * side));
        EXPECT_GE(weights[q][r], 0.0f);
        if (weights[q][r] < 1e-6f) continue;
        const glm::dvec3 m = rp::render::sky_cell_normal(int(cell % side), int(cell / side));
        const glm::dvec3 picked(c * m.x + s * m.z, m.y, c * m.z - s * m.x);
        blend += double(weights[q][r]) * picked;
        if (q < grid) {
          EXPECT_NEAR(weights[q][r], 1.0f, 1e-5f) << "grid normal " << q << " turn " << turn;
          EXPECT_NEAR(glm::dot(picked, want), 1.0, 1e-6) << "grid normal " << q;
        } else {
          EXPECT_GT(glm::dot(picked, want), std::cos(15.0 * kPi / 180.0)) << "normal " << q;
        }
      }
      EXPECT_GT(glm::dot(glm::normalize(blend), want), std::cos(1.5 * kPi / 180.0)) << q;
    }
  }
}
}  // namespace
