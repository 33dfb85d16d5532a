// The cone tracing functions of kernels/common/cone_trace.h, run through small test kernels and
// compared with the double-precision C++ reference (cone_reference.h): quadrilinear sampling at
// fractional positions and levels, the anisotropic lookup, one cone (half- and quarter-diameter
// steps, level-jittered samples, the exit term), the 16-cone diffuse set with its near-field
// occlusion, and cases with known answers (empty volume, opaque wall, a closed box of one-sided
// walls, level blending).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cl/error.h"
#include "cl/program_cache.h"
#include "cone_reference.h"
#include "kernels/shared/voxel_layout.h"
#include "render/gpu_types.h"
#include "render/sky_texture.h"
#include "support/cl_fixture.h"

namespace {

using rp::test::cone::Chain;

// Test kernels around the header (not part of the product: built from the embedded header).
const char* kTestKernels = R"CLC(
/* top: coarsest level sampled; queries: xyz position, w level; apexes: the cone's apex */
__kernel void cone_test_sample(__global const float4* voxels, uint resolution, uint top,
                               __global const float4* queries, __global const float4* dirs,
                               __global const float4* apexes, __global float4* out) {
  const size_t i = get_global_id(0);
  const float3 d = dirs[i].xyz;
  out[i] = rp_cone_sample(voxels, resolution, top, rp_voxel_cone_dirs(d), d * d,
                          queries[i].xyz, queries[i].w, apexes[i].xyz);
}
__kernel void cone_test_trace(__global const float4* voxels, uint resolution, uint levels,
                              __global const float4* origins, __global const float4* dirs,
                              __global float4* out) {
  const size_t i = get_global_id(0);
  out[i] = rp_cone_trace(voxels, resolution, levels, origins[i].xyz, dirs[i].xyz);
}
/* dirs[i].w: 0 half-diameter steps, 1 quarter-diameter steps, 2 + u: level jitter u,
 * 10 + u: full-diameter steps with level jitter u and position jitter origins[i].w */
__kernel void cone_test_trace_mode(__global const float4* voxels, uint resolution, uint levels,
                                   __global const float4* origins, __global const float4* dirs,
                                   __global float4* out) {
  const size_t i = get_global_id(0);
  const float mode = dirs[i].w;
  out[i] = mode == 0.0f ? rp_cone_trace(voxels, resolution, levels, origins[i].xyz, dirs[i].xyz)
         : mode == 1.0f ? rp_cone_trace_fine(voxels, resolution, levels, origins[i].xyz, dirs[i].xyz)
         : mode < 10.0f ? rp_cone_trace_jittered(voxels, resolution, levels, origins[i].xyz,
                                                 dirs[i].xyz, mode - 2.0f)
                        : rp_cone_trace_coarse(voxels, resolution, levels, origins[i].xyz,
                                               dirs[i].xyz, origins[i].w, mode - 10.0f);
}
/* Aperture cones: origins[i].w = tan of the half-angle, dirs[i].w = 1 fine, 0 fast. */
__kernel void cone_test_trace_aperture(__global const float4* voxels, uint resolution,
                                       uint levels, __global const float4* origins,
                                       __global const float4* dirs, __global float4* out) {
  const size_t i = get_global_id(0);
  out[i] = dirs[i].w != 0.0f
               ? rp_cone_trace_aperture(voxels, resolution, levels, origins[i].xyz, dirs[i].xyz,
                                        origins[i].w, 1)
               : rp_cone_trace_aperture(voxels, resolution, levels, origins[i].xyz, dirs[i].xyz,
                                        origins[i].w, 0);
}
/* The set's directions: out[16 i + k] = cone k around normals[i]. */
__kernel void cone_test_set16(__global const float4* voxels, uint resolution, uint levels,
                              __global const float4* normals, __global float4* out) {
  const size_t i = get_global_id(0);
  const float3 n = normals[i].xyz;
  float3 t, b;
  rp_cone_basis(n, &t, &b);
  for (uint k = 0; k < 16u; ++k) out[16 * i + k] = (float4)(rp_cone_set16_dir(n, t, b, k), 0.0f);
}
/* frame: FrameConstants, zero (no sky) */
__kernel void cone_test_diffuse(__global const float4* voxels, uint resolution, uint levels,
                                __global const float4* points, __global const float4* normals,
                                __global const FrameConstants* frame,
                                __global const float4* sky, __global float4* out) {
  const size_t i = get_global_id(0);
  out[i] = (float4)(rp_cone_diffuse16(frame, sky, voxels, resolution, levels, points[i].xyz,
                                      normals[i].xyz),
                    0.0f);
}
)CLC";

const ::cl::Program& test_program() {
  static ::cl::Program program = [] {
    auto& ctx = rp::test::context();
    std::string source = rp::cl::kernel_source("common/cone_trace.h") + kTestKernels;
    ::cl::Program p(ctx.context, source);
    try {
      p.build(std::vector<::cl::Device>{ctx.info.device});
    } catch (const ::cl::Error&) {
      throw rp::cl::Error("cone test kernels: " +
                          p.getBuildInfo<CL_PROGRAM_BUILD_LOG>(ctx.info.device));
    }
    return p;
  }();
  return program;
}

// Runs test kernel `name` (voxels, resolution, `param`, inputs..., extras..., out) over the
// elements of the input arrays (all the same length; extras: buffers of any length); returns
// one float4 per element.
std::vector<glm::vec4> run_kernel(const char* name, const Chain& chain, uint32_t param,
                                  const std::vector<const std::vector<glm::vec4>*>& inputs,
                                  size_t outputs_per_element = 1,
                                  const std::vector<const std::vector<glm::vec4>*>& extras = {}) {
  auto& ctx = rp::test::context();
  const size_t n = inputs[0]->size();
  ::cl::Buffer voxels(ctx.context, CL_MEM_READ_ONLY, chain.voxels.size() * 16);
  ctx.queue.enqueueWriteBuffer(voxels, CL_TRUE, 0, chain.voxels.size() * 16, chain.voxels.data());
  ::cl::Kernel kernel(test_program(), name);
  cl_uint arg = 0;
  kernel.setArg(arg++, voxels);
  kernel.setArg(arg++, cl_uint(chain.resolution));
  kernel.setArg(arg++, cl_uint(param));
  std::vector<::cl::Buffer> buffers;
  for (const std::vector<glm::vec4>* input : inputs) {
    EXPECT_EQ(input->size(), n);
    buffers.emplace_back(ctx.context, CL_MEM_READ_ONLY, n * 16);
    ctx.queue.enqueueWriteBuffer(buffers.back(), CL_TRUE, 0, n * 16, input->data());
    kernel.setArg(arg++, buffers.back());
  }
  for (const std::vector<glm::vec4>* extra : extras) {
    buffers.emplace_back(ctx.context, CL_MEM_READ_ONLY, extra->size() * 16);
    ctx.queue.enqueueWriteBuffer(buffers.back(), CL_TRUE, 0, extra->size() * 16, extra->data());
    kernel.setArg(arg++, buffers.back());
  }
  const size_t m = n * outputs_per_element;
  ::cl::Buffer out(ctx.context, CL_MEM_WRITE_ONLY, m * 16);
  kernel.setArg(arg++, out);
  ctx.queue.enqueueNDRangeKernel(kernel, ::cl::NullRange, ::cl::NDRange(n));
  std::vector<glm::vec4> result(m);
  ctx.queue.enqueueReadBuffer(out, CL_TRUE, 0, m * 16, result.data());
  return result;
}

// One cone per (origin, direction) pair.
std::vector<glm::vec4> run_trace(const Chain& chain, const std::vector<glm::vec4>& origins,
                                 const std::vector<glm::vec4>& dirs) {
  return run_kernel("cone_test_trace", chain, chain.levels, {&origins, &dirs});
}

// One cone per (origin, direction) pair, direction w = mode (see cone_test_trace_mode).
std::vector<glm::vec4> run_trace_mode(const Chain& chain, const std::vector<glm::vec4>& origins,
                                      const std::vector<glm::vec4>& dirs) {
  return run_kernel("cone_test_trace_mode", chain, chain.levels, {&origins, &dirs});
}

// FrameConstants as float4s, with `sky` as its environment.
std::vector<glm::vec4> frame_with_sky(const rp::gpu::SkyGpu& sky) {
  rp::gpu::FrameConstants frame{};
  frame.sky = sky;
  std::vector<glm::vec4> out(sizeof frame / 16);
  std::memcpy(out.data(), &frame, sizeof frame);
  return out;
}

// The diffuse cone set per (point, normal) pair, under `environment` (none by default).
std::vector<glm::vec4> run_diffuse(const Chain& chain, const std::vector<glm::vec4>& points,
                                   const std::vector<glm::vec4>& normals,
                                   const rp::scene::Environment& environment = {}) {
  std::vector<glm::vec4> frame = frame_with_sky({}), texels(1, glm::vec4(0.0f));
  if (environment.enabled()) {
    const rp::render::SkyTexture sky = rp::render::build_sky_texture(*environment.map);
    frame = frame_with_sky(rp::render::sky_record(sky.info, environment));
    texels.resize(sky.texels.size());
    std::memcpy(texels.data(), sky.texels.data(), texels.size() * 16);
  }
  return run_kernel("cone_test_diffuse", chain, chain.levels, {&points, &normals}, 1,
                    {&frame, &texels});
}

// An environment of constant radiance `l` (an 8x4 map).
rp::scene::Environment constant_sky(glm::vec3 l) {
  auto map = std::make_shared<rp::scene::EnvironmentMap>();
  map->width = 8;
  map->height = 4;
  for (int i = 0; i < 32; ++i) map->rgb.insert(map->rgb.end(), {l.x, l.y, l.z});
  rp::scene::Environment e;
  e.map = std::move(map);
  return e;
}

// Quadrilinear samples over the whole chain (top = levels - 1).
std::vector<glm::vec4> run_sample(const Chain& chain, const std::vector<glm::vec4>& queries,
                                  const std::vector<glm::vec4>& dirs,
                                  const std::vector<glm::vec4>& apexes) {
  return run_kernel("cone_test_sample", chain, chain.levels - 1, {&queries, &dirs, &apexes});
}

glm::vec4 v4(const glm::dvec3& v, double w = 0.0) { return glm::vec4(glm::dvec4(v, w)); }

// An apex behind the box along every axis for a cone along d (row -1 or n on each axis: the
// volume facing +axis is chosen for d >= 0), so no row is skipped.
glm::vec4 far_apex(const glm::dvec3& d) {
  return v4(glm::dvec3(d.x >= 0.0 ? -10.0 : 10.0, d.y >= 0.0 ? -10.0 : 10.0,
                       d.z >= 0.0 ? -10.0 : 10.0));
}

// Random level-0 voxels (a fraction `fill` non-empty, opacity up to max_alpha, premultiplied
// radiance up to 2 * opacity), then the mips.
Chain random_chain(uint32_t resolution, uint32_t seed, double fill, double max_alpha) {
  uint32_t levels = 1;
  while ((resolution >> (levels - 1)) > 1) ++levels;
  Chain c(resolution, levels);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (uint32_t z = 0; z < resolution; ++z)
    for (uint32_t y = 0; y < resolution; ++y)
      for (uint32_t x = 0; x < resolution; ++x) {
        if (u(rng) >= fill) continue;
        double a = max_alpha * u(rng);
        c.at(0, 0, x, y, z) = glm::vec4(glm::dvec4(2.0 * a * u(rng), 2.0 * a * u(rng),
                                                   2.0 * a * u(rng), a));
      }
  c.build_mips();
  return c;
}

glm::dvec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
}

void expect_near4(const glm::vec4& got, const glm::dvec4& want, double tol, const std::string& what) {
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c], want[c], tol) << what << " component " << c;
}

TEST(ConeTrace, QuadrilinearSampleMatchesReferenceAtFractionalPositions) {
  // R = 8: levels 0..3; the directional levels differ per direction because the mips composite.
  Chain chain = random_chain(8, 7, 0.6, 1.0);
  // Make the six directional volumes of every level differ further (independent random values),
  // so picking a wrong volume cannot go unnoticed.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (size_t i = size_t(8 * 8 * 8); i < chain.voxels.size(); ++i)
    chain.voxels[i] = glm::vec4(glm::dvec4(u(rng), u(rng), u(rng), u(rng)));
  std::vector<glm::vec4> queries, dirs, far_apexes, near_apexes;
  const double levels[] = {0.0, 0.3, 0.65750, 1.0, 1.25, 1.9, 2.0, 2.5, 3.0, 4.2};
  for (double level : levels)
    for (int i = 0; i < 24; ++i) {
      // Positions over the whole box, including beyond the outermost voxel centres (clamped).
      glm::dvec3 p(u(rng) * 2.0 - 1.0, u(rng) * 2.0 - 1.0, u(rng) * 2.0 - 1.0);
      glm::dvec3 d = random_unit(rng);
      queries.push_back(v4(p, level));
      dirs.push_back(v4(d));
      far_apexes.push_back(far_apex(d));
      near_apexes.push_back(v4(p - (0.05 + 0.5 * u(rng)) * d));
    }
  auto plain = run_sample(chain, queries, dirs, far_apexes);
  auto skipping = run_sample(chain, queries, dirs, near_apexes);
  int differ = 0;
  for (size_t i = 0; i < plain.size(); ++i) {
    const glm::dvec3 p(queries[i]), d(dirs[i]), apex(near_apexes[i]);
    const std::string what = "sample " + std::to_string(i) + " level " + std::to_string(queries[i].w);
    expect_near4(plain[i], rp::test::cone::quadrilinear(chain, d, p, queries[i].w), 1e-5, what);
    expect_near4(skipping[i], rp::test::cone::quadrilinear(chain, d, p, queries[i].w, &apex), 1e-5,
                 what + " (apex near)");
    differ += glm::length(plain[i] - skipping[i]) > 1e-3;
  }
  EXPECT_GT(differ, 50);  // the near apexes do skip rows
}

// Every directional voxel of level 1 (4^3 for R = 8, voxels 0.5 wide) is (1, 0, 0, 0.5). A +x
// sample at x = -0.125 lies between the centres of rows 1 and 2 (tap weights 0.75 and 0.25);
// with the apex in row 1 only row 2 counts, with it in row 0 both do. For a -x cone the roles
// swap: with the apex in row 2 only row 1 counts.
TEST(ConeTrace, RowsAtOrBehindTheApexAreSkipped) {
  Chain chain(8, 4);
  for (uint32_t dir = 0; dir < 6; ++dir)
    for (uint32_t z = 0; z < 4; ++z)
      for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 4; ++x) chain.at(1, dir, x, y, z) = glm::vec4(1, 0, 0, 0.5f);
  const glm::dvec3 p(-0.125, 0.1, 0.3);
  struct Case {
    glm::dvec3 dir;
    double apex_x;
    double want;  // fraction of the voxel value
  };
  const Case cases[] = {
      {{1, 0, 0}, -0.3, 0.25},   // apex in row 1 (x in [-0.5, 0))
      {{1, 0, 0}, -0.7, 1.0},    // apex in row 0: rows 1 and 2 both ahead
      {{1, 0, 0}, 0.2, 0.0},     // apex in row 2: both taps behind it
      {{-1, 0, 0}, 0.2, 0.75},   // -x cone, apex in row 2: only row 1 is ahead
      {{-1, 0, 0}, 0.7, 1.0},    // apex in row 3
      {{-1, 0, 0}, -0.3, 0.0},   // apex in row 1
  };
  std::vector<glm::vec4> queries, dirs, apexes;
  for (const Case& c : cases) {
    queries.push_back(v4(p, 1.0));
    dirs.push_back(v4(c.dir));
    apexes.push_back(v4(glm::dvec3(c.apex_x, p.y, p.z)));
  }
  auto got = run_sample(chain, queries, dirs, apexes);
  for (size_t i = 0; i < got.size(); ++i)
    expect_near4(got[i], glm::dvec4(1, 0, 0, 0.5) * cases[i].want, 1e-6,
                 "case " + std::to_string(i));
}

// Every level holds one constant value (all six directions alike): the sample at level L must be
// the documented blend of the two levels around L, whatever the position and direction.
TEST(ConeTrace, LevelBlendFollowsTheFractionalLevel) {
  Chain chain(8, 4);
  const glm::dvec4 value[4] = {{0.1, 0.0, 0.0, 0.0}, {0.0, 0.2, 0.0, 0.0},
                               {0.0, 0.0, 0.4, 0.0}, {0.0, 0.0, 0.0, 0.8}};
  for (uint32_t level = 0; level < 4; ++level)
    for (uint32_t dir = 0; dir < (level == 0 ? 1u : 6u); ++dir) {
      const uint32_t n = 8 >> level;
      for (uint32_t z = 0; z < n; ++z)
        for (uint32_t y = 0; y < n; ++y)
          for (uint32_t x = 0; x < n; ++x) chain.at(level, dir, x, y, z) = glm::vec4(value[level]);
    }
  struct Case {
    double level;
    glm::dvec4 want;
  };
  const Case cases[] = {
      {0.0, value[0]},
      {0.25, 0.75 * value[0] + 0.25 * value[1]},
      {1.0, value[1]},
      {1.5, 0.5 * value[1] + 0.5 * value[2]},
      {2.75, 0.25 * value[2] + 0.75 * value[3]},
      {3.0, value[3]},
      {5.0, value[3]},  // past the top level: the top level
  };
  std::vector<glm::vec4> queries, dirs, apexes;
  const glm::dvec3 d = glm::normalize(glm::dvec3(-1.0, 2.0, 0.5));
  for (const Case& c : cases) {
    queries.push_back(v4(glm::dvec3(0.3, -0.7, 0.55), c.level));
    dirs.push_back(v4(d));
    apexes.push_back(far_apex(d));
  }
  auto got = run_sample(chain, queries, dirs, apexes);
  for (size_t i = 0; i < got.size(); ++i)
    expect_near4(got[i], cases[i].want, 1e-6, "level " + std::to_string(cases[i].level));
}

// Only the +x volumes (every level >= 1) hold anything: a +x cone sees it, a -x cone and cones
// perpendicular to x do not, a diagonal cone sees it with weight d.x^2. Then the same for -y.
TEST(ConeTrace, AnisotropicLookupPicksTheVolumesFacingTheCone) {
  for (uint32_t lit_dir : {RP_DIR_POS_X, RP_DIR_NEG_Y}) {
    Chain chain(8, 4);
    const glm::vec4 red(0.5f, 0.0f, 0.0f, 0.5f);
    for (uint32_t level = 1; level < 4; ++level) {
      const uint32_t n = 8 >> level;
      for (uint32_t z = 0; z < n; ++z)
        for (uint32_t y = 0; y < n; ++y)
          for (uint32_t x = 0; x < n; ++x) chain.at(level, lit_dir, x, y, z) = red;
    }
    const int axis = int(lit_dir / 2);
    const double sign = lit_dir % 2 == 0 ? 1.0 : -1.0;
    glm::dvec3 along(0.0), across(0.0);
    along[axis] = sign;
    across[(axis + 1) % 3] = 1.0;
    const glm::dvec3 diagonal = glm::normalize(along + across);
    std::vector<glm::dvec3> cone_dirs = {along, -along, across, -across, diagonal};
    std::vector<glm::vec4> queries, dirs, origins, apexes;
    for (const glm::dvec3& d : cone_dirs) {
      queries.push_back(v4(glm::dvec3(0.1, 0.2, -0.3), 1.5));
      dirs.push_back(v4(d));
      apexes.push_back(far_apex(d));
      origins.push_back(v4(glm::dvec3(0.0) - 0.6 * d));  // room for several samples
    }
    auto samples = run_sample(chain, queries, dirs, apexes);
    EXPECT_NEAR(samples[0].x, 0.5, 1e-6) << "cone along the lit direction";
    EXPECT_NEAR(samples[0].w, 0.5, 1e-6);
    for (int i = 1; i <= 3; ++i) EXPECT_EQ(samples[i], glm::vec4(0.0f)) << "cone " << i;
    EXPECT_NEAR(samples[4].x, 0.5 * 0.5, 1e-6) << "diagonal cone: weight d^2 = 1/2";

    auto cones = run_trace(chain, origins, dirs);
    EXPECT_GT(cones[0].x, 0.1) << "a cone along the lit direction sees it";
    for (int i = 1; i <= 3; ++i) EXPECT_EQ(cones[i], glm::vec4(0.0f)) << "cone " << i;
    for (size_t i = 0; i < cones.size(); ++i)
      expect_near4(cones[i], rp::test::cone::trace(chain, glm::dvec3(origins[i]), glm::dvec3(dirs[i])),
                   1e-5, "cone " + std::to_string(i));
  }
}

// Every way a cone steps and samples: half-diameter steps (quadrilinear), quarter-diameter
// steps (the reference mode), half-diameter steps with level-jittered samples, and
// full-diameter steps with position and level jitter (the fast mode). Jitters keep the sampled
// levels away from integers (no float vs double disagreement on a floor).
TEST(ConeTrace, OneConeMatchesReferenceTrace) {
  // Sparse, mostly translucent volume so cones travel through several levels before stopping.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double jitters[] = {0.1, 0.37, 0.73, 0.95};
  for (uint32_t resolution : {16u, 32u}) {
    Chain chain = random_chain(resolution, resolution, 0.25, 0.4);
    std::vector<glm::vec4> origins, dirs;
    std::vector<rp::test::cone::March> marches;
    auto add = [&](const glm::dvec3& o, const glm::dvec3& d) {
      for (int mode = 0; mode < 4; ++mode) {
        rp::test::cone::March m;
        m.fine = mode == 1;
        m.jitter = mode >= 2 ? jitters[origins.size() % 4] : -1.0;
        m.coarse = mode == 3;
        m.position_jitter = mode == 3 ? 0.61 : 0.0;  // levels k * 0.848 + 0.517 + jitter
        origins.push_back(v4(o, m.position_jitter));
        dirs.push_back(v4(d, mode < 2 ? double(mode) : (mode == 2 ? 2.0 : 10.0) + m.jitter));
        marches.push_back(m);
      }
    };
    for (int i = 0; i < 64; ++i) add(glm::dvec3(u(rng), u(rng), u(rng)) * 1.6 - 0.8, random_unit(rng));
    // Axis-aligned and exactly diagonal cones too (weights 1 / 0 and 1/2 / 0).
    for (const glm::dvec3& d : {glm::dvec3(1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1),
                                glm::normalize(glm::dvec3(1, 1, 0)),
                                glm::normalize(glm::dvec3(-1, 1, -1))})
      add(glm::dvec3(0.05, -0.1, 0.15), d);
    auto got = run_trace_mode(chain, origins, dirs);
    int far = 0;
    for (size_t i = 0; i < got.size(); ++i) {
      const glm::dvec4 want = rp::test::cone::trace(chain, glm::dvec3(origins[i]),
                                                    glm::dvec3(glm::vec3(dirs[i])), marches[i]);
      far += want.w < 0.95;  // left the box before becoming opaque
      expect_near4(got[i], want, 1e-5,
                   "R " + std::to_string(resolution) + " cone " + std::to_string(i) + " mode " +
                       std::to_string(dirs[i].w));
    }
    EXPECT_GT(far, 5);
  }
}

// The reflection cone of any aperture (rp_cone_trace_aperture) against the
// reference on random sparse chains: narrow cones (clamped to one voxel's diameter at first),
// the demo's floor lobe (0.187), the diffuse width and a rough coat's, in both modes (fine:
// quadrilinear half-diameter steps; fast: nearest level, full-diameter steps).
TEST(ConeTrace, ApertureConeMatchesReference) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double tans[] = {0.05, 0.1, 0.187, 0.4, 0.9};
  for (uint32_t resolution : {16u, 32u}) {
    Chain chain = random_chain(resolution, resolution + 1, 0.2, 0.4);
    std::vector<glm::vec4> origins, dirs;
    std::vector<rp::test::cone::Aperture> modes;
    std::vector<double> tan_of;
    for (int i = 0; i < 60; ++i) {
      const glm::dvec3 o = glm::dvec3(u(rng), u(rng), u(rng)) * 1.6 - 0.8;
      const glm::dvec3 d = random_unit(rng);
      const double t = tans[i % 5];
      for (int fine = 0; fine < 2; ++fine) {
        rp::test::cone::Aperture a;
        a.fine = fine == 1;
        origins.push_back(v4(o, t));
        dirs.push_back(v4(d, double(fine)));
        modes.push_back(a);
        tan_of.push_back(t);
      }
    }
    auto got = run_kernel("cone_test_trace_aperture", chain, chain.levels, {&origins, &dirs});
    int far = 0, lit = 0;
    for (size_t i = 0; i < got.size(); ++i) {
      const glm::dvec4 want = rp::test::cone::trace_aperture(
          chain, glm::dvec3(glm::vec3(origins[i])), glm::dvec3(glm::vec3(dirs[i])),
          double(origins[i].w), modes[i]);
      far += want.w < 0.95;
      lit += want.x > 0.05;
      expect_near4(got[i], want, 2e-5,
                   "R " + std::to_string(resolution) + " cone " + std::to_string(i) + " tan " +
                       std::to_string(tan_of[i]) + (modes[i].fine ? " fine" : " fast"));
    }
    EXPECT_GT(far, 5);
    EXPECT_GT(lit, 30);
  }
}

// A wider cone blurs: through a single bright voxel column, the narrow cone that points at it
// sees it brighter than the wide one, and a cone that misses it by 22 degrees sees it only
// when wide (the aperture really widens the footprint).
TEST(ConeTrace, ApertureWidensTheFootprint) {
  Chain chain(32, 6);
  for (uint32_t y = 0; y < 32; ++y) chain.at(0, 0, 24, y, 16) = glm::vec4(4.0f, 4.0f, 4.0f, 1.0f);
  chain.build_mips();
  const glm::dvec3 o(-0.5, 0.03, 0.03);
  const glm::dvec3 at = glm::normalize(glm::dvec3(24.5 / 16.0 - 1.0, 0.0, 16.5 / 16.0 - 1.0) - o);
  const glm::dvec3 off = glm::normalize(at + glm::dvec3(0.0, 0.0, 0.4));  // ~22 degrees off
  std::vector<glm::vec4> origins, dirs;
  for (double t : {0.1, 0.6})
    for (const glm::dvec3& d : {at, off}) {
      origins.push_back(v4(o, t));
      dirs.push_back(v4(d, 1.0));
    }
  auto got = run_kernel("cone_test_trace_aperture", chain, chain.levels, {&origins, &dirs});
  EXPECT_GT(got[0].x, 2.0f * got[2].x);  // narrow on target: sharper, brighter
  EXPECT_LT(got[1].x, 0.05f);            // narrow, off target: misses
  EXPECT_GT(got[3].x, 0.2f);             // wide, off target: sees it
}

// Half-diameter steps with level jitter u sample level floor(L + u): averaged over u in [0, 1)
// the sample is the quadrilinear blend. On a chain whose levels are constant (so a cone's path
// does not matter), the mean over 64 jitters of the first sample's contribution equals the
// quadrilinear cone's to within the jitter quadrature.
TEST(ConeTrace, LevelJitterAveragesToQuadrilinear) {
  Chain chain(16, 5);
  const double value[5] = {0.10, 0.05, 0.02, 0.01, 0.005};  // opacity per level, all directions
  for (uint32_t level = 0; level < 5; ++level)
    for (uint32_t dir = 0; dir < (level == 0 ? 1u : 6u); ++dir) {
      const uint32_t n = 16 >> level;
      for (uint32_t z = 0; z < n; ++z)
        for (uint32_t y = 0; y < n; ++y)
          for (uint32_t x = 0; x < n; ++x)
            chain.at(level, dir, x, y, z) = glm::vec4(glm::dvec4(value[level], 0.0, 0.0, value[level]));
    }
  const glm::dvec3 origin(-0.9, -0.85, -0.8), dir = glm::normalize(glm::dvec3(1.0, 0.9, 0.8));
  std::vector<glm::vec4> origins, dirs;
  const int kJitters = 64;
  for (int i = 0; i < kJitters; ++i) {
    origins.push_back(v4(origin));
    dirs.push_back(v4(dir, 2.0 + (i + 0.5) / kJitters));
  }
  origins.push_back(v4(origin));
  dirs.push_back(v4(dir, 0.0));
  auto got = run_trace_mode(chain, origins, dirs);
  double mean = 0.0;
  for (int i = 0; i < kJitters; ++i) mean += got[i].x / kJitters;
  EXPECT_GT(got[kJitters].x, 0.05);
  // Compositing is not linear in the samples, so the two differ slightly (measured 0.13 %).
  EXPECT_NEAR(mean, got[kJitters].x, 0.01 * got[kJitters].x);
}

TEST(ConeTrace, EmptyVolumeGivesZero) {
  Chain chain(16, 5);
  std::vector<glm::vec4> points, normals;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 32; ++i) {
    points.push_back(v4(glm::dvec3(u(rng), u(rng), u(rng))));
    normals.push_back(v4(random_unit(rng)));
  }
  for (const glm::vec4& v : run_trace(chain, points, normals))
    EXPECT_EQ(v, glm::vec4(0.0f));
  for (const glm::vec4& v : run_diffuse(chain, points, normals))
    EXPECT_EQ(v, glm::vec4(0.0f));
}

// Under a constant sky an empty volume lets every cone through: each of the 16 brings the sky's
// radiance, so their mean (irradiance / pi) is the sky's radiance (the furnace test of the
// cones: a white Lambertian surface there would be as bright as the sky).
TEST(ConeTrace, EmptyVolumeUnderAConstantSkyGivesTheSky) {
  Chain chain(16, 5);
  const glm::vec3 l(0.5f, 1.0f, 2.0f);
  std::vector<glm::vec4> points, normals;
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-0.8, 0.8);
  for (int i = 0; i < 32; ++i) {
    points.push_back(v4(glm::dvec3(u(rng), u(rng), u(rng))));
    normals.push_back(v4(random_unit(rng)));
  }
  for (const glm::vec4& v : run_diffuse(chain, points, normals, constant_sky(l)))
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[c], l[c], 1e-5f * l[c]);
}

// A dim sky with a bright softbox just above the horizon and a bright ground below it (128x64;
// the cones' table reads it as it is).
rp::scene::Environment horizon_softbox_sky(float rotate_deg) {
  auto map = std::make_shared<rp::scene::EnvironmentMap>();
  map->width = 128;
  map->height = 64;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 128; ++x) {
      glm::vec3 c(0.2f, 0.25f, 0.3f);
      if (y >= 32) c = glm::vec3(5.0f, 4.0f, 3.0f);                    // below the horizon
      if (y >= 27 && y < 32 && x >= 12 && x < 20) c = glm::vec3(60.0f);  // 0-14 degrees up
      map->rgb.insert(map->rgb.end(), {c.x, c.y, c.z});
    }
  rp::scene::Environment e;
  e.map = std::move(map);
  e.rotate_deg = rotate_deg;
  e.strength = 1.5f;
  return e;
}

// Irradiance / pi at unit normal n under `e`: the sum over the map's texels of radiance x cos x
// solid angle (the path tracer's turn: world direction d reads the map at to_map(d)).
glm::dvec3 irradiance_over_pi(const rp::scene::Environment& e, const glm::dvec3& n) {
  const rp::scene::EnvironmentMap& m = *e.map;
  const double a = e.rotate_deg * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
  glm::dvec3 sum(0.0);
  for (int y = 0; y < m.height; ++y) {
    const double theta = M_PI * (y + 0.5) / m.height;
    const double omega = 2.0 * M_PI / m.width *
                         (std::cos(M_PI * y / m.height) - std::cos(M_PI * (y + 1) / m.height));
    for (int x = 0; x < m.width; ++x) {
      const double phi = 2.0 * M_PI * (x + 0.5) / m.width;
      const glm::dvec3 md(std::sin(theta) * std::sin(phi), std::cos(theta),
                          -std::sin(theta) * std::cos(phi));
      const glm::dvec3 d(c * md.x + s * md.z, md.y, c * md.z - s * md.x);  // map -> world
      const double cos_n = glm::dot(d, n);
      if (cos_n <= 0.0) continue;
      const size_t t = (size_t(y) * m.width + x) * 3;
      sum += cos_n * omega * glm::dvec3(m.rgb[t], m.rgb[t + 1], m.rgb[t + 2]);
    }
  }
  return sum * double(e.strength) / M_PI;
}

// Through an empty volume the 16 cones bring the map's irradiance / pi for any sky, not only a
// constant one: each cone takes its cell's cosine-weighted mean. A bright patch near the horizon
// counts with its own small cosine, and what lies below the horizon not at all. (Reading the
// map prefiltered around each cone's axis gave an upward normal 1.96x the irradiance of such a
// sky.) Axis normals are grid normals of the table; others take the nearest, within 6 %.
TEST(ConeTrace, EmptyVolumeGathersTheIrradianceOfAnySkyForEveryTurn) {
  Chain chain(16, 5);
  std::mt19937 rng(9);
  std::vector<glm::dvec3> dirs = {{0, 1, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int i = 0; i < 12; ++i) {
    glm::dvec3 d = random_unit(rng);
    d.y = std::fabs(d.y);
    dirs.push_back(d);
  }
  std::vector<glm::vec4> points, normals;
  for (const glm::dvec3& d : dirs) {
    points.push_back(v4(glm::dvec3(0.1, -0.2, 0.3)));
    normals.push_back(v4(d));
  }
  for (const float turn : {0.0f, 40.0f, 217.0f}) {
    const rp::scene::Environment e = horizon_softbox_sky(turn);
    const std::vector<glm::vec4> got = run_diffuse(chain, points, normals, e);
    for (size_t i = 0; i < dirs.size(); ++i) {
      const glm::dvec3 want = irradiance_over_pi(e, glm::dvec3(glm::vec3(normals[i])));
      const double tolerance = i < 5 ? 0.02 : 0.06;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[i][c], want[c], tolerance * want[c])
            << "turn " << turn << " normal " << i << " channel " << c;
    }
  }
}

// A black opaque wall (x in [0, 0.5]) in front of a red emitter (x in [0.5, 1]), aligned with
// every mip level: a +x cone from the left sees almost nothing of the red; without the wall it
// sees it brightly. What leaks is trilinear filtering across the wall's back face: a coarse
// sample straddling it blends wall and emitter before the cone's opacity reaches 0.95
// (measured 0.042 of the emitter's 4.0 for the axis-aligned cones); tilted cones also read
// their small y/z weights (see below).
TEST(ConeTrace, OpaqueWallHidesWhatIsBehindIt) {
  for (bool wall : {true, false}) {
    Chain chain(16, 5);
    for (uint32_t z = 0; z < 16; ++z)
      for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 8; x < 16; ++x) {
          if (x < 12 && wall) chain.at(0, 0, x, y, z) = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
          if (x >= 12) chain.at(0, 0, x, y, z) = glm::vec4(4.0f, 0.0f, 0.0f, 1.0f);
        }
    chain.build_mips();
    std::vector<glm::vec4> origins, dirs;
    for (double y : {-0.5, 0.0, 0.3}) {
      origins.push_back(v4(glm::dvec3(-0.8, y, 0.1)));
      dirs.push_back(v4(glm::dvec3(1.0, 0.0, 0.0)));
      origins.push_back(v4(glm::dvec3(-0.6, y, -0.2)));
      dirs.push_back(v4(glm::normalize(glm::dvec3(1.0, 0.1, 0.05))));
    }
    auto got = run_trace(chain, origins, dirs);
    for (size_t i = 0; i < got.size(); ++i) {
      if (wall) {
        // Axis-aligned cones use only the +x volumes, where the wall is in front at every
        // level: only the trilinear leak at the back face (< 2 % of the emitter) gets through.
        // A tilted cone also reads the +y/+z volumes (weights d.y^2 + d.z^2 = 1 - d.x^2), which
        // composite along y/z and average across x, so at coarse levels they mix wall and
        // emitter: that weight times the emitter's radiance more.
        const double leak = (1.0 - double(dirs[i].x) * dirs[i].x) * 4.0 + 0.02 * 4.0;
        EXPECT_LE(got[i].x, leak) << "cone " << i << " sees through the wall";
        if (dirs[i].x == 1.0f) {
          EXPECT_LT(got[i].x, 0.02 * 4.0) << "cone " << i;
          EXPECT_GE(got[i].w, 0.95f) << "cone " << i;  // stopped at the wall
        }
      } else {
        EXPECT_GT(got[i].x, 1.0) << "cone " << i << " should see the red emitter";
      }
      expect_near4(got[i],
                   rp::test::cone::trace(chain, glm::dvec3(origins[i]), glm::dvec3(dirs[i])),
                   1e-5, "cone " + std::to_string(i));
    }
  }
}

TEST(ConeTrace, DiffuseConesMatchReference) {
  Chain chain = random_chain(16, 21, 0.3, 0.5);
  std::vector<glm::vec4> points, normals;
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-0.9, 0.9);
  std::vector<glm::dvec3> ns = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int i = 0; i < 26; ++i) ns.push_back(random_unit(rng));
  for (const glm::dvec3& n : ns) {
    points.push_back(v4(glm::dvec3(u(rng), u(rng), u(rng))));
    normals.push_back(v4(n));
  }
  auto got = run_diffuse(chain, points, normals);
  int occluded = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    const glm::dvec3 want =
        rp::test::cone::diffuse(chain, glm::dvec3(points[i]), glm::dvec3(normals[i]));
    expect_near4(got[i], glm::dvec4(want, 0.0), 1e-5, "point " + std::to_string(i));
    occluded += rp::test::cone::near_occlusion(chain, glm::dvec3(points[i]),
                                               glm::dvec3(normals[i])) > 0.01;
  }
  EXPECT_GT(occluded, 8);  // the near-field occlusion takes part
}

// The near-field occlusion counts surfaces that face p in front of it, not the surface's own
// back: a slab thinner than a level-1 voxel has its far face (which faces the cones) in the
// apex's trilinear footprint. R = 16 (level-1 voxels 0.25 wide, centres at -0.125, 0.125),
// an emitting ceiling, a floor point p at y = -0.05 (normal +y): its apex at y = 0.075 reads
// the level-1 row centred at -0.125 with weight 0.2, the mirror point at -0.175 with 0.8.
TEST(ConeTrace, NearOcclusionIgnoresTheSurfacesOwnBack) {
  Chain chain(16, 5);
  for (uint32_t z = 0; z < 16; ++z)
    for (uint32_t y = 12; y < 16; ++y)
      for (uint32_t x = 0; x < 16; ++x) chain.at(0, 0, x, y, z) = glm::vec4(1, 1, 1, 1);
  chain.build_mips();
  // One level-1 row of +y (what a cone going up sees), opaque and dark: y index `row`.
  auto opaque_row = [](Chain c, uint32_t row) {
    for (uint32_t z = 0; z < 8; ++z)
      for (uint32_t x = 0; x < 8; ++x) c.at(1, RP_DIR_POS_Y, x, row, z) = glm::vec4(0, 0, 0, 1);
    return c;
  };
  const Chain back = opaque_row(chain, 3);   // the slab's underside, below p
  const Chain front = opaque_row(chain, 4);  // a surface over p, facing it
  const glm::dvec3 p(0.01, -0.05, 0.02), n(0, 1, 0);
  EXPECT_EQ(rp::test::cone::near_occlusion(back, p, n), 0.0);
  EXPECT_GT(rp::test::cone::near_occlusion(front, p, n), 0.3);
  const std::vector<glm::vec4> points = {v4(p)}, normals = {v4(n)};
  const glm::vec4 open = run_diffuse(chain, points, normals)[0];
  const glm::vec4 with_back = run_diffuse(back, points, normals)[0];
  ASSERT_GT(open.x, 0.05f);
  EXPECT_NEAR(with_back.x, open.x, 1e-6f);
  EXPECT_LT(run_diffuse(front, points, normals)[0].x, 0.7f * open.x);

  // A mirror point outside the box reads nothing: a floor on the box's face keeps the
  // occlusion of what lies over it in the bottom row.
  const glm::dvec3 q(0.01, -1.0 + 0.02, 0.02);
  const Chain over_face = opaque_row(chain, 0);
  EXPECT_GT(rp::test::cone::near_occlusion(over_face, q, n), 0.3);
  EXPECT_LT(run_diffuse(over_face, {v4(q)}, normals)[0].x,
            0.7f * run_diffuse(chain, {v4(q)}, normals)[0].x);
}

// The 16-cone set: unit directions, cone 0 along n, five at sin^2 = 3.5/16 72 degrees apart,
// ten at sin^2 = 11/16 36 degrees apart and offset 18 degrees from the first ring; the kernel's
// table and basis give the reference's directions.
TEST(ConeTrace, DiffuseConeSetGeometry) {
  std::mt19937 rng(4);
  std::vector<glm::vec4> normals;
  for (int i = 0; i < 20; ++i)
    normals.push_back(v4(i == 0 ? glm::dvec3(0, 0, -1) : i == 1 ? glm::dvec3(0, 1, 0) : random_unit(rng)));
  auto kernel_dirs = run_kernel("cone_test_set16", Chain(2, 1), 1, {&normals}, 16);
  for (size_t i = 0; i < normals.size(); ++i) {
    const glm::dvec3 n(glm::vec3(normals[i]));
    glm::dvec3 dirs[16];
    rp::test::cone::diffuse_cones(n, dirs);
    for (int k = 0; k < 16; ++k) {
      EXPECT_NEAR(glm::length(dirs[k]), 1.0, 1e-6);
      const double c = glm::dot(dirs[k], n);
      EXPECT_NEAR(1.0 - c * c, k == 0 ? 0.0 : k < 6 ? 3.5 / 16.0 : 11.0 / 16.0, 1e-6) << k;
      for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(kernel_dirs[16 * i + k][a], dirs[k][a], 2e-6) << "normal " << i << " cone " << k;
    }
    // Azimuths: within each ring the projections onto the tangent plane are evenly spaced, and
    // ring 2 is offset half a step from ring 1.
    auto azimuth_cos = [&](int a, int b) {
      const glm::dvec3 pa = dirs[a] - glm::dot(dirs[a], n) * n, pb = dirs[b] - glm::dot(dirs[b], n) * n;
      return glm::dot(pa, pb) / (glm::length(pa) * glm::length(pb));
    };
    for (int k = 1; k < 6; ++k) EXPECT_NEAR(azimuth_cos(k, k % 5 + 1), std::cos(0.4 * M_PI), 1e-6);
    for (int k = 6; k < 16; ++k)
      EXPECT_NEAR(azimuth_cos(k, (k - 5) % 10 + 6), std::cos(0.2 * M_PI), 1e-6);
    EXPECT_NEAR(azimuth_cos(1, 6), std::cos(0.1 * M_PI), 1e-6);
  }
}

// A closed box whose walls radiate L. The old premise here, "every voxel opaque L,
// so every cone sees exactly L", no longer holds: with that chain the level-1 volumes facing n
// are opaque at the apex, and the near-field occlusion scales the estimate by 1 - 0.6. What is
// exactly true now, for one-sided walls (the outermost layer of level-0 voxels, opaque, each
// existing only for cones heading towards it, as the voxelizer's facing coverage makes them):
//   - everything a cone can composite has radiance L per unit opacity, so a cone's colour is
//     L times its opacity: the estimate's channels are in L's exact proportions;
//   - every cone ends on a wall: it either becomes opaque (>= 0.95) inside, or it leaves the
//     box, where the exit term reads the wall it leaves through as (L, 1). So the estimate is
//     between 0.95 L and L, for interior points and for points on a wall alike (a wall does
//     not see its own voxels: they face away from its cones), with no near-field occlusion;
//   - a point whose normal faces a wall from within a voxel is darkened by the near-field
//     occlusion, 1 - 0.6 a, a the opacity of the level-1 volume facing n at the apex.
// Without the exit term, cones at 45 degrees to a wall took about half their light (they read
// the wall through the d^2-weighted volumes), so the interior estimate fell well below 0.95 L.
TEST(ConeTrace, ClosedBoxOfOneSidedWallsGivesTheirRadiance) {
  const uint32_t r = 16;
  Chain chain(r, 5);
  const glm::vec4 l(0.7f, 0.2f, 1.5f, 1.0f);
  auto on_wall = [r](uint32_t x, uint32_t y, uint32_t z) {
    return x == 0 || y == 0 || z == 0 || x == r - 1 || y == r - 1 || z == r - 1;
  };
  for (uint32_t z = 0; z < r; ++z)
    for (uint32_t y = 0; y < r; ++y)
      for (uint32_t x = 0; x < r; ++x)
        if (on_wall(x, y, z)) chain.at(0, 0, x, y, z) = l;
  // A cone heading along +axis sees the wall at the + end of that axis (it faces -axis).
  chain.build_mips([r](uint32_t x, uint32_t y, uint32_t z, uint32_t dir) {
    const uint32_t v[3] = {x, y, z};
    return v[dir / 2] == (dir % 2 == 0 ? r - 1 : 0u) ? 1.0 : 0.0;
  });
  const double v0 = 2.0 / r;
  std::vector<glm::dvec3> ps = {{0.0, 0.0, 0.0},
                                {0.4, -0.5, 0.2},
                                {-0.3, 0.4, -0.3},
                                {0.1, -1.0 + 0.5 * v0, -0.3},   // on the floor, facing up
                                {1.0 - 0.5 * v0, 0.2, 0.35}};   // on the +x wall, facing -x
  std::vector<glm::dvec3> ns = {{0.0, 1.0, 0.0},
                                glm::normalize(glm::dvec3(1, -2, 3)),
                                glm::normalize(glm::dvec3(-1, 1, 1)),
                                {0.0, 1.0, 0.0},
                                {-1.0, 0.0, 0.0}};
  const size_t free_points = ps.size();
  // Facing the ceiling from inside its own voxel's neighbour: near-field occlusion.
  ps.push_back({-0.2, 1.0 - 1.5 * v0, 0.1});
  ns.push_back({0.0, 1.0, 0.0});
  std::vector<glm::vec4> points, normals;
  for (size_t i = 0; i < ps.size(); ++i) {
    points.push_back(v4(ps[i]));
    normals.push_back(v4(ns[i]));
  }
  const auto got = run_diffuse(chain, points, normals);
  for (size_t i = 0; i < got.size(); ++i) {
    const std::string what = "point " + std::to_string(i);
    const double near = rp::test::cone::near_occlusion(chain, ps[i], ns[i]);
    // The share of L the cones gathered, before the near-field occlusion.
    const double share = got[i].x / (l.x * (1.0 - near));
    for (int c = 1; c < 3; ++c)
      EXPECT_NEAR(got[i][c], share * (1.0 - near) * l[c], 1e-5) << what << ": L's hue";
    EXPECT_GE(share, 0.95 - 1e-5) << what;
    EXPECT_LE(share, 1.0 + 1e-5) << what;
    if (i < free_points)
      EXPECT_EQ(near, 0.0) << what;
    else
      EXPECT_GT(near, 0.1) << what << ": the ceiling a voxel away occludes";
    expect_near4(got[i], glm::dvec4(rp::test::cone::diffuse(chain, ps[i], ns[i]), 0.0), 1e-5,
                 what + " vs reference");
  }
  // Every cone ends on a wall (occlusion 1), so a bright sky outside adds nothing to what a
  // black one gives (a sky turns the cones' basis: rp_cone_sky_basis).
  EXPECT_EQ(run_diffuse(chain, points, normals, constant_sky(glm::vec3(1000.0f))),
            run_diffuse(chain, points, normals, constant_sky(glm::vec3(0.0f))));
}

}  // namespace
