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
  EXPECT_EQ(t.texels.size(), size_t(64 * 32 + 32 * 16 + 16 * 8 + 8 * 4 + 4 * 2 + 2 * 1));
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

}  // namespace
