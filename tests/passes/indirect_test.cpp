// The fast mode's indirect light (kernels/indirect.cl, light.cl's light_compose) against C++
// references written from the rules in common/indirect.h and the kernels' headers, on a small
// hand-made GBuffer (13x10 pixels: partial 4x4 blocks and a partial 8-pixel chunk) over a random
// voxel chain: the one cone per block, the spatial filter (first frame: no history), the
// temporal blend (second frame, still camera), and the upsampling + direct light of
// light_compose (its direct term against light_shade's).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cone_reference.h"
#include "passes/indirect.h"
#include "passes/light.h"
#include "passes/pass_names.h"
#include "render/gpu_scene.h"
#include "scene/demo_scene.h"
#include "shading/brdf.h"
#include "shading/brdf_tables.h"
#include "support/cl_fixture.h"

namespace {

namespace pass_name = rp::passes::pass_name;

using rp::passes::IndirectPass;

constexpr uint32_t kW = 13, kH = 10, kRes = 16;

// ---- common/indirect.h, restated ----------------------------------------------------------
uint32_t hash_u32(uint32_t v) {
  const uint32_t state = v * 747796405u + 2891336453u;
  const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
float hash_to_unit(uint32_t h) { return float(h >> 8) * (1.0f / 16777216.0f); }
const uint32_t kBayer[16] = {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};
uint32_t cone_index(uint32_t i, uint32_t j, uint32_t f) {
  return (kBayer[(j & 3u) * 4u + (i & 3u)] + 7u * f) & 15u;
}
float level_jitter(uint32_t i, uint32_t j, uint32_t f) {
  const float u = hash_to_unit(hash_u32(i ^ hash_u32(j ^ 0x9e3779b9u))) + 0.618034f * float(f & 1023u);
  return u - std::floor(u);
}
float position_jitter(uint32_t i, uint32_t j, uint32_t f) {
  const float u = hash_to_unit(hash_u32(j ^ hash_u32(i ^ 0x85ebca6bu))) + 0.754877666f * float(f & 1023u);
  return u - std::floor(u);
}
// Geometry weight of sample (normal s, plane offset sd) for a receiver at p with normal n.
double geometry_weight(const glm::dvec3& n, const glm::dvec3& p, const glm::dvec3& s, double sd,
                       double inv_sigma) {
  const double wn = std::pow(std::max(glm::dot(n, s), 0.0), 8.0);
  const double dist = (glm::dot(s, p) - sd) * inv_sigma;
  const double wp = std::max(1.0 - 0.25 * dist * dist, 0.0);
  return wn * wp * wp;
}
double inv_sigma(double depth, double pixel_scale) { return 1.0 / (depth * pixel_scale * 4.0); }

// ---- the fixture --------------------------------------------------------------------------
struct Pixel {
  glm::vec3 p, n, albedo, emission;
  float depth;
  bool covered;
  float gloss = 0.0f;  // GBuffer emission.w (the glossy fixture only)
};

// Surfaces inside the box: a floor-like plane, a tilted plane and a few background pixels, so
// that blocks see one surface, two, or none. At another frame size w x h the same surfaces,
// pixel (x, y) standing for (x kW / w, y kH / h) of the kW x kH frame.
std::vector<Pixel> make_gbuffer(uint32_t w = kW, uint32_t h = kH) {
  std::vector<Pixel> px(size_t(w) * h);
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const glm::vec3 tilted = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f));
  const float sx = float(kW) / float(w), sy = float(kH) / float(h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      Pixel& q = px[y * w + x];
      const float fx = float(x) * sx, fy = float(y) * sy;
      q.covered = !(fx >= 11.0f && fy >= 8.0f);  // a background corner
      const bool plane_a = fx + fy < 12.0f;
      q.n = plane_a ? glm::vec3(0, 1, 0) : tilted;
      const glm::vec3 base(-0.6f + 0.09f * fx, -0.5f + 0.05f * fy, -0.3f + 0.04f * fy);
      q.p = plane_a ? glm::vec3(base.x, -0.55f, base.z) : base - tilted * (glm::dot(base, tilted) - 0.1f);
      q.albedo = glm::vec3(0.3f + 0.5f * u(rng), 0.3f + 0.5f * u(rng), 0.3f + 0.5f * u(rng));
      q.emission = x == 3 && y == 2 ? glm::vec3(0.5f, 0.2f, 0.1f) : glm::vec3(0.0f);
      q.depth = 2.0f + 0.1f * fy;
      if (!q.covered) q = Pixel{glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f), 10.0f, false};
    }
  return px;
}

rp::test::cone::Chain random_chain() {
  rp::test::cone::Chain c(kRes, 5);
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (uint32_t z = 0; z < kRes; ++z)
    for (uint32_t y = 0; y < kRes; ++y)
      for (uint32_t x = 0; x < kRes; ++x) {
        if (u(rng) > 0.3) continue;
        const double a = 0.7 * u(rng);
        c.at(0, 0, x, y, z) = glm::vec4(glm::dvec4(3 * a * u(rng), 3 * a * u(rng), 3 * a * u(rng), a));
      }
  c.build_mips();
  return c;
}

class IndirectFixture {
 public:
  // glossy: the floor-like plane gets the demo floor's coat, the tilted plane the tumblers'
  // lacquer, except in the first two columns (matte: the uncoated samples' path).
  explicit IndirectFixture(bool glossy = false) : pixels_(make_gbuffer()), chain_(random_chain()) {
    if (glossy)
      for (uint32_t k = 0; k < pixels_.size(); ++k) {
        Pixel& q = pixels_[k];
        if (q.covered && k % kW >= 2)  // the first two columns stay matte
          q.gloss = rp::shading::gloss_code(q.n.y == 1.0f ? rp::scene::demo::kFloorSpecular
                                                          : rp::scene::demo::kTumblerSpecular);
      }
    auto& ctx = rp::test::context();
    scene_ = std::make_unique<rp::render::GpuScene>(ctx.context, ctx.queue, rp::scene::SceneAssets{});
    upload_gbuffer();
    voxels_ = ::cl::Buffer(ctx.context, CL_MEM_READ_ONLY, chain_.voxels.size() * 16);
    ctx.queue.enqueueWriteBuffer(voxels_, CL_TRUE, 0, chain_.voxels.size() * 16, chain_.voxels.data());
    shadow_.resize(ctx.context, 32);
    const std::vector<float> empty_map(32 * 32, 1.0f);
    ctx.queue.enqueueWriteBuffer(shadow_.depth, CL_TRUE, 0, empty_map.size() * 4, empty_map.data());
    pass_ = std::make_unique<IndirectPass>(ctx, rp::test::programs());
  }

  // The same surfaces drawn at w x h pixels (make_gbuffer): the next run() is of that size (the
  // render scale changed). Only run() and history-based checks follow the new size.
  void regrid(uint32_t w, uint32_t h) {
    width_ = w;
    height_ = h;
    pixels_ = make_gbuffer(w, h);
    upload_gbuffer();
  }

  // Runs the indirect pass for frame f (still camera) and reads every plane back.
  rp::passes::LowResIndirect run(uint32_t f) {
    rp::scene::FrameScene frame;
    frame.frame_index = f;
    frame.light.intensity = glm::vec3(3.0f, 2.5f, 2.0f);
    scene_->update(frame, width_, height_, 32, kRes);
    rp::cl::Profiler profiler(rp::test::context().queue);
    rp::passes::LowResIndirect lr = pass_->run(profiler, *scene_, gbuffer_, voxels_, kRes, 5);
    const auto times = profiler.collect();
    EXPECT_EQ(times.count(pass_name::kIndirectTrace), 1u);
    EXPECT_EQ(times.count(pass_name::kIndirectFilter), 1u);
    auto& q = rp::test::context().queue;
    const size_t plane = lr.plane;
    radiance.resize(3 * plane);
    position.resize(4 * plane);
    geom.resize(4 * plane);
    history.resize(5 * plane);
    q.enqueueReadBuffer(pass_->radiance_planes(), CL_TRUE, 0, radiance.size() * 4, radiance.data());
    q.enqueueReadBuffer(pass_->position_planes(), CL_TRUE, 0, position.size() * 4, position.data());
    q.enqueueReadBuffer(*lr.geometry, CL_TRUE, 0, geom.size() * 4, geom.data());
    q.enqueueReadBuffer(*lr.irradiance, CL_TRUE, 0, history.size() * 4, history.data());
    specular.resize(3 * plane);
    specular_filled.resize(3 * plane);
    q.enqueueReadBuffer(pass_->specular_planes(), CL_TRUE, 0, specular.size() * 4, specular.data());
    q.enqueueReadBuffer(*lr.specular, CL_TRUE, 0, specular_filled.size() * 4,
                        specular_filled.data());
    return lr;
  }

  // Light pass output (hdr, direct, indirect; float4 per pixel) with or without upsampling.
  void light(const rp::passes::LowResIndirect* lr, std::vector<float>& hdr,
             std::vector<float>& direct, std::vector<float>& indirect,
             std::vector<float>* specular_out = nullptr) {
    auto& ctx = rp::test::context();
    const size_t n = size_t(kW) * kH;
    ::cl::Buffer out(ctx.context, CL_MEM_READ_WRITE, n * 16);
    rp::passes::LightComponents parts{::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16),
                                      ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16),
                                      ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16)};
    rp::cl::Profiler profiler(ctx.queue);
    rp::passes::LightPass pass(ctx, rp::test::programs(), rp::render::ShadowMode::kHard);
    // The reference path with an empty chain: direct + emission only.
    static const rp::test::cone::Chain empty(kRes, 5);
    ::cl::Buffer empty_voxels(ctx.context, CL_MEM_READ_ONLY, empty.voxels.size() * 16);
    ctx.queue.enqueueWriteBuffer(empty_voxels, CL_TRUE, 0, empty.voxels.size() * 16, empty.voxels.data());
    pass.run(profiler, *scene_, gbuffer_, shadow_, lr ? voxels_ : empty_voxels, kRes, 5, out, &parts, lr);
    profiler.collect();
    hdr.resize(n * 4);
    direct.resize(n * 4);
    indirect.resize(n * 4);
    ctx.queue.enqueueReadBuffer(out, CL_TRUE, 0, n * 16, hdr.data());
    ctx.queue.enqueueReadBuffer(parts.direct, CL_TRUE, 0, n * 16, direct.data());
    ctx.queue.enqueueReadBuffer(parts.indirect, CL_TRUE, 0, n * 16, indirect.data());
    if (specular_out) {
      specular_out->resize(n * 4);
      ctx.queue.enqueueReadBuffer(parts.specular, CL_TRUE, 0, n * 16, specular_out->data());
    }
  }

  const Pixel& pixel(uint32_t x, uint32_t y) const { return pixels_[y * kW + x]; }
  const rp::test::cone::Chain& chain() const { return chain_; }
  // Uploads the voxel chain again with its radiance scaled by k (the light changed).
  void scale_voxels(float k) {
    std::vector<glm::vec4> v = chain_.voxels;
    for (glm::vec4& x : v) x = glm::vec4(glm::vec3(x) * k, x.w);
    rp::test::context().queue.enqueueWriteBuffer(voxels_, CL_TRUE, 0, v.size() * 16, v.data());
  }
  float pixel_scale() const { return rp::passes::pixel_scale(*scene_); }
  void reset_history() { pass_->reset_history(); }
  const rp::render::GpuScene& scene() const { return *scene_; }

  std::vector<float> radiance, position, geom, history, specular, specular_filled;

 private:
  // pixels_ into gbuffer_ (width_ x height_).
  void upload_gbuffer() {
    auto& ctx = rp::test::context();
    gbuffer_.resize(ctx.context, width_, height_);
    const size_t n = size_t(width_) * height_;
    std::vector<float> albedo(n * 4), nd(n * 4), pos(n * 4), em(n * 4);
    for (size_t i = 0; i < n; ++i) {
      const Pixel& q = pixels_[i];
      std::memcpy(&albedo[4 * i], &q.albedo, 12);
      albedo[4 * i + 3] = q.covered ? 1.0f : 0.0f;
      std::memcpy(&nd[4 * i], &q.n, 12);
      nd[4 * i + 3] = q.depth;
      std::memcpy(&pos[4 * i], &q.p, 12);
      pos[4 * i + 3] = q.covered ? 1.0f : 0.0f;
      std::memcpy(&em[4 * i], &q.emission, 12);
      em[4 * i + 3] = q.gloss;
    }
    ctx.queue.enqueueWriteBuffer(gbuffer_.albedo, CL_TRUE, 0, n * 16, albedo.data());
    ctx.queue.enqueueWriteBuffer(gbuffer_.normal_depth, CL_TRUE, 0, n * 16, nd.data());
    ctx.queue.enqueueWriteBuffer(gbuffer_.position, CL_TRUE, 0, n * 16, pos.data());
    ctx.queue.enqueueWriteBuffer(gbuffer_.emission, CL_TRUE, 0, n * 16, em.data());
  }

  uint32_t width_ = kW, height_ = kH;
  std::vector<Pixel> pixels_;
  rp::test::cone::Chain chain_;
  std::unique_ptr<rp::render::GpuScene> scene_;
  rp::render::GBuffer gbuffer_;
  rp::render::ShadowMap shadow_;
  ::cl::Buffer voxels_;
  std::unique_ptr<IndirectPass> pass_;
};

uint32_t lr_w() { return IndirectPass::low_res(kW); }
uint32_t lr_h() { return IndirectPass::low_res(kH); }
// Padded plane index of sample (i, j) (common/indirect.h).
size_t at(int i, int j) { return size_t(j + 2) * IndirectPass::plane_stride(lr_w()) + size_t(i + 2); }

// light_compose's joint-bilateral upsample of three low-resolution planes `src` (r, g, b,
// `plane` floats apart) at pixel (x, y) of surface q: the 2x2 block centres (4 i + 2) around
// it, bilinear times geometry weights, else the best geometric match, else plain bilinear.
glm::dvec3 upsample_ref(const std::vector<float>& geom, const std::vector<float>& src,
                        size_t plane, double pixel_scale, const Pixel& q, uint32_t x,
                        uint32_t y) {
  const double ux = (x - 1.5) / 4.0, uy = (y - 1.5) / 4.0;
  const int i0 = int(std::floor(ux)), j0 = int(std::floor(uy));
  const double fx = ux - i0, fy = uy - j0;
  double g[4], b[4];
  glm::dvec3 h[4];
  const double is = inv_sigma(q.depth, pixel_scale);
  for (int t = 0; t < 4; ++t) {
    const size_t s = at(i0 + (t & 1), j0 + (t >> 1));
    g[t] = geometry_weight(glm::dvec3(q.n), glm::dvec3(q.p),
                           glm::dvec3(geom[s], geom[plane + s], geom[2 * plane + s]),
                           geom[3 * plane + s], is);
    b[t] = ((t & 1) ? fx : 1.0 - fx) * ((t >> 1) ? fy : 1.0 - fy);
    h[t] = glm::dvec3(src[s], src[plane + s], src[2 * plane + s]);
  }
  double wsum = 0.0;
  glm::dvec3 v(0.0);
  for (int t = 0; t < 4; ++t) {
    wsum += b[t] * g[t];
    v += b[t] * g[t] * h[t];
  }
  if (wsum >= 1e-4) return v / wsum;
  const int best = int(std::max_element(g, g + 4) - g);
  return g[best] > 0.0 ? h[best] : b[0] * h[0] + b[1] * h[1] + b[2] * h[2] + b[3] * h[3];
}


// The sample pixel of block (i, j): pixel (1, 1) of the block, clamped to the image.
const Pixel& sample_pixel(const IndirectFixture& fx, uint32_t i, uint32_t j) {
  return fx.pixel(std::min(4 * i + 1, kW - 1), std::min(4 * j + 1, kH - 1));
}

TEST(Indirect, LayoutIsPaddedAndPlanar) {
  EXPECT_EQ(lr_w(), 4u);
  EXPECT_EQ(lr_h(), 3u);
  EXPECT_EQ(IndirectPass::plane_stride(4), 16u);
  EXPECT_EQ(IndirectPass::plane_stride(8), 16u);
  EXPECT_EQ(IndirectPass::plane_stride(9), 24u);
  EXPECT_EQ(IndirectPass::plane_size(4, 3), 16u * 7u);
}

// Checks the planes indirect_trace wrote for frame f: per block the sample pixel's geometry,
// and its radiance against the C++ cone reference (full-diameter steps with the block's two
// jitters, the exit term): cone cone_index(i, j, f) of the set, or the mean of all 16 when
// `whole_set`, times one minus the near-field occlusion; the padding stays zero.
void expect_traced_blocks(const IndirectFixture& fx, const rp::passes::LowResIndirect& lr,
                          uint32_t f, bool whole_set) {
  const size_t plane = lr.plane;
  int traced = 0, lit = 0;
  for (uint32_t j = 0; j < lr_h(); ++j)
    for (uint32_t i = 0; i < lr_w(); ++i) {
      const Pixel& q = sample_pixel(fx, i, j);
      const size_t s = at(int(i), int(j));
      glm::dvec3 want(0.0), n(0.0), p(0.0);
      if (q.covered) {
        n = glm::dvec3(q.n);
        p = glm::dvec3(q.p);
        glm::dvec3 dirs[16];
        rp::test::cone::diffuse_cones(n, dirs);
        rp::test::cone::March m;
        m.coarse = true;
        m.jitter = level_jitter(i, j, f);
        m.position_jitter = position_jitter(i, j, f);
        const glm::dvec3 apex = p + n * (2.0 / kRes);
        if (whole_set) {
          for (const glm::dvec3& d : dirs)
            want += glm::dvec3(rp::test::cone::trace(fx.chain(), apex, d, m));
          want /= 16.0;
        } else {
          want = glm::dvec3(rp::test::cone::trace(fx.chain(), apex, dirs[cone_index(i, j, f)], m));
        }
        // Scaled by the near-field occlusion at the sample, like the reference mode's set.
        want *= 1.0 - rp::test::cone::near_occlusion(fx.chain(), p, n);
        ++traced;
        lit += want.x + want.y + want.z > 0.01;
      }
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(fx.radiance[c * plane + s], want[c], 1e-5) << "block " << i << "," << j;
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(fx.geom[c * plane + s], n[c], 1e-6);
        EXPECT_NEAR(fx.position[c * plane + s], p[c], 1e-6);
      }
      EXPECT_NEAR(fx.geom[3 * plane + s], glm::dot(n, p), 1e-6);
      EXPECT_EQ(fx.position[3 * plane + s], q.covered ? q.depth : 0.0f);
    }
  EXPECT_EQ(traced, 11);  // block (3, 2) samples the background corner
  EXPECT_GE(lit, 5);
  for (int j = -2; j < int(lr_h()) + 2; ++j)
    for (int i = -2; i < int(IndirectPass::plane_stride(lr_w())) - 2; ++i) {
      if (i >= 0 && j >= 0 && i < int(lr_w()) && j < int(lr_h())) continue;
      for (int c = 0; c < 4; ++c) EXPECT_EQ(fx.geom[c * plane + at(i, j)], 0.0f);
    }
}

// Steady state (history valid): one cone per block, cone k of the set.
TEST(Indirect, EachBlockTracesItsConeOfTheSet) {
  IndirectFixture fx;
  const uint32_t f = 5;
  fx.run(f - 1);  // the first frame (no history) traces the whole set: see the next test
  const auto lr = fx.run(f);
  expect_traced_blocks(fx, lr, f, false);
}

// Without history (a fresh pass: first frame, reset, camera cut) every block traces all
// 16 cones of the set and stores their mean.
TEST(Indirect, WarmStartTracesTheWholeSetPerBlock) {
  IndirectFixture fx;
  const uint32_t f = 5;
  const auto lr = fx.run(f);
  expect_traced_blocks(fx, lr, f, true);
}

// Spatial estimate S of sample (i, j) from the planes of one frame.
glm::dvec3 spatial(const IndirectFixture& fx, size_t plane, int i, int j, double pixel_scale) {
  const size_t c = at(i, j);
  const glm::dvec3 n(fx.geom[c], fx.geom[plane + c], fx.geom[2 * plane + c]);
  const glm::dvec3 p(fx.position[c], fx.position[plane + c], fx.position[2 * plane + c]);
  const double is = inv_sigma(fx.position[3 * plane + c], pixel_scale);
  glm::dvec3 sum(0.0);
  double wsum = 0.0;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      const int ti = i + dx, tj = j + dy;
      if (ti < 0 || tj < 0 || ti >= int(lr_w()) || tj >= int(lr_h())) continue;
      const size_t t = at(ti, tj);
      const double w = (std::abs(dx) == 2 ? 0.5 : 1.0) * (std::abs(dy) == 2 ? 0.5 : 1.0) *
                       geometry_weight(n, p, glm::dvec3(fx.geom[t], fx.geom[plane + t], fx.geom[2 * plane + t]),
                                       fx.geom[3 * plane + t], is);
      sum += w * glm::dvec3(fx.radiance[t], fx.radiance[plane + t], fx.radiance[2 * plane + t]);
      wsum += w;
    }
  return sum / std::max(wsum, 1e-6);
}

// First frame: no history, so every sample's output is its spatial estimate with age 1.
TEST(Indirect, FirstFrameIsTheSpatialFilter) {
  IndirectFixture fx;
  const auto lr = fx.run(2);
  const size_t plane = lr.plane;
  int mixed = 0;
  for (int j = 0; j < int(lr_h()); ++j)
    for (int i = 0; i < int(lr_w()); ++i) {
      const size_t s = at(i, j);
      const bool covered = sample_pixel(fx, uint32_t(i), uint32_t(j)).covered;
      const glm::dvec3 want = covered ? spatial(fx, plane, i, j, lr.pixel_scale) : glm::dvec3(0.0);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(fx.history[c * plane + s], want[c], 1e-5 * (1.0 + std::abs(want[c])))
            << "sample " << i << "," << j;
      EXPECT_EQ(fx.history[3 * plane + s], covered ? 1.0f : 0.0f);
      const double lum = glm::dot(want, glm::dvec3(0.2126, 0.7152, 0.0722));
      EXPECT_NEAR(fx.history[4 * plane + s], lum * lum, 1e-5 * (1.0 + lum * lum));
      mixed += std::abs(want.x - fx.radiance[s]) > 1e-3;
    }
  EXPECT_GE(mixed, 5);  // the filter really mixes neighbours
}

// Second frame: every sample's history from the previous frame's planes, as indirect_filter's
// header says (reprojection with prev_view_proj_unjittered, block-centre shift, 3x3 blocks with
// tent + ring weights times geometry weights, minimum weight, age-based alpha). The hand-made
// positions do not lie under their pixels, so they reproject to other blocks (the first frame's
// test covers samples without history).
TEST(Indirect, SecondFrameBlendsWithTheReprojectedHistory) {
  IndirectFixture fx;
  fx.run(6);
  const std::vector<float> prev_geom = fx.geom, prev_history = fx.history;
  const auto lr = fx.run(7);
  const size_t plane = lr.plane;
  glm::dmat4 m;
  for (int c = 0; c < 4; ++c) {
    const auto& col = fx.scene().constants.prev_view_proj_unjittered.c[c];
    m[c] = glm::dvec4(col.x, col.y, col.z, col.w);
  }
  int with_history = 0, elsewhere = 0;
  for (int j = 0; j < int(lr_h()); ++j)
    for (int i = 0; i < int(lr_w()); ++i) {
      const size_t s = at(i, j);
      if (!sample_pixel(fx, uint32_t(i), uint32_t(j)).covered) continue;
      const glm::dvec3 n(fx.geom[s], fx.geom[plane + s], fx.geom[2 * plane + s]);
      const glm::dvec3 p(fx.position[s], fx.position[plane + s], fx.position[2 * plane + s]);
      const double is = inv_sigma(fx.position[3 * plane + s], lr.pixel_scale);
      const glm::dvec4 clip = m * glm::dvec4(p, 1.0);
      const double iw = 1.0 / (clip.w > 0.0 ? clip.w : 1.0);
      const double sx = (clip.x * iw * 0.5 + 0.5) * kW, sy = (0.5 - clip.y * iw * 0.5) * kH;
      const double ux = (sx - 1.0 - 0.5) / 4.0, uy = (sy - 1.0 - 0.5) / 4.0;
      const int ur = int(std::floor(std::clamp(ux, -1.0, double(lr_w())) + 0.5));
      const int vr = int(std::floor(std::clamp(uy, -1.0, double(lr_h())) + 0.5));
      auto g_at = [&](int ti, int tj) {
        const size_t t = at(ti, tj);
        return geometry_weight(n, p, glm::dvec3(prev_geom[t], prev_geom[plane + t], prev_geom[2 * plane + t]),
                               prev_geom[3 * plane + t], is);
      };
      const double ring = 0.1 * (1.0 - g_at(ur, vr));
      glm::dvec4 hist(0.0);
      double hw = 0.0, hm = 0.0;
      for (int b = -1; b <= 1; ++b)
        for (int a = -1; a <= 1; ++a) {
          const double w = (std::max(1.0 - std::abs(ux - (ur + a)), 0.0) + ring) *
                           (std::max(1.0 - std::abs(uy - (vr + b)), 0.0) + ring) * g_at(ur + a, vr + b);
          const size_t t = at(ur + a, vr + b);
          hist += w * glm::dvec4(prev_history[t], prev_history[plane + t], prev_history[2 * plane + t],
                                 prev_history[3 * plane + t]);
          hm += w * prev_history[4 * plane + t];
          hw += w;
        }
      const bool has = clip.w > 0.0 && hw >= 0.05;
      const glm::dvec4 h = has ? hist / hw : glm::dvec4(0.0);
      const double m2 = has ? hm / hw : 0.0;
      with_history += has;
      elsewhere += ur != i || vr != j;
      const glm::dvec3 sp = spatial(fx, plane, i, j, lr.pixel_scale);
      // Variance-guided alpha: smoothstep over 2..4 standard deviations of the luminance.
      const glm::dvec3 luma(0.2126, 0.7152, 0.0722);
      const double lum_s = glm::dot(sp, luma), lum_h = glm::dot(glm::dvec3(h), luma);
      const double sigma = std::sqrt(std::max(m2 - lum_h * lum_h, 0.0)) + 0.02 * lum_h + 1e-4;
      const double z = std::clamp((std::abs(lum_s - lum_h) / sigma - 2.0) * 0.5, 0.0, 1.0);
      const double lo = IndirectPass::kAlphaMin;
      const double alpha = std::max(1.0 / (h.w + 1.0), lo + (0.35 - lo) * z * z * (3.0 - 2.0 * z));
      const glm::dvec3 want = glm::dvec3(h) + alpha * (sp - glm::dvec3(h));
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(fx.history[c * plane + s], want[c], 2e-5 * (1.0 + std::abs(want[c])))
            << "sample " << i << "," << j;
      EXPECT_NEAR(fx.history[3 * plane + s], std::min(h.w + 1.0, 255.0), 1e-4);
      EXPECT_NEAR(fx.history[4 * plane + s], m2 + alpha * (lum_s * lum_s - m2), 2e-5 * (1.0 + m2));
    }
  EXPECT_GE(with_history, 5);
  EXPECT_GE(elsewhere, 5);
}

// A change of the render size (the render scale under --target-ms) keeps the history: the
// previous frame's planes, in the old size's layout, are resampled to the new blocks. Eight
// frames at 13x10, then the same surfaces at 19x14 (larger) and at 9x7 (smaller): samples that
// reproject onto their surface in the old grid continue their age (a fresh start would give 1
// everywhere, as reset_history() still does), blend into values between the old history's and
// the new estimate's, and the frame after a change (the old layout's slot reallocated) goes on.
TEST(Indirect, AChangeOfSizeResamplesTheHistory) {
  for (const auto& [w, h] : {std::pair{19u, 14u}, std::pair{9u, 7u}}) {
    IndirectFixture fx;
    for (uint32_t f = 1; f <= 8; ++f) fx.run(f);
    float old_lo = 1e30f, old_hi = -1e30f;
    {
      const size_t plane = IndirectPass::plane_size(lr_w(), lr_h());
      for (int j = 0; j < int(lr_h()); ++j)
        for (int i = 0; i < int(lr_w()); ++i)
          if (fx.history[3 * plane + at(i, j)] > 0.0f)
            for (int c = 0; c < 3; ++c) {
              old_lo = std::min(old_lo, fx.history[c * plane + at(i, j)]);
              old_hi = std::max(old_hi, fx.history[c * plane + at(i, j)]);
            }
    }
    fx.regrid(w, h);
    for (uint32_t f = 9; f <= 10; ++f) {
      const auto lr = fx.run(f);
      ASSERT_EQ(lr.width, IndirectPass::low_res(w));
      // this frame's spatial estimates are weighted means of its cone radiances
      float new_lo = 1e30f, new_hi = -1e30f;
      for (uint32_t j = 0; j < lr.height; ++j)
        for (uint32_t i = 0; i < lr.width; ++i)
          for (int c = 0; c < 3; ++c) {
            const float e = fx.radiance[c * lr.plane + size_t(j + 2) * lr.stride + i + 2];
            new_lo = std::min(new_lo, e);
            new_hi = std::max(new_hi, e);
          }
      const float lo = std::min(old_lo, new_lo), hi = std::max(old_hi, new_hi);
      int carried = 0;
      for (uint32_t j = 0; j < lr.height; ++j)
        for (uint32_t i = 0; i < lr.width; ++i) {
          const size_t s = size_t(j + 2) * lr.stride + i + 2;
          const float age = fx.history[3 * lr.plane + s];
          if (age == 0.0f) continue;  // background
          EXPECT_LE(age, float(f) + 1e-3f) << w << "x" << h << " frame " << f;  // weighted means
          if (age > float(f - 8)) {  // older than the new size: history from before the change
            ++carried;
            for (int c = 0; c < 3; ++c) {
              // history + alpha (estimate - history): between the two ranges (alpha <= 1)
              const float v = fx.history[c * lr.plane + s];
              EXPECT_GE(v, lo - 1e-5f) << w << "x" << h << " sample " << i << "," << j;
              EXPECT_LE(v, hi + 1e-5f) << w << "x" << h << " sample " << i << "," << j;
            }
          }
        }
      EXPECT_GE(carried, 3) << w << "x" << h << " frame " << f << ": the history is kept";
      old_lo = lo;  // the next frame's history lies within this frame's range
      old_hi = hi;
    }
  }
  // A reset (camera cut) still starts over at the new size.
  IndirectFixture fx;
  for (uint32_t f = 1; f <= 8; ++f) fx.run(f);
  fx.regrid(19, 14);
  fx.reset_history();
  const auto lr = fx.run(9);
  for (uint32_t j = 0; j < lr.height; ++j)
    for (uint32_t i = 0; i < lr.width; ++i) {
      const float age = fx.history[3 * lr.plane + size_t(j + 2) * lr.stride + i + 2];
      EXPECT_TRUE(age == 0.0f || age == 1.0f) << i << "," << j;
    }
}

// light_compose = light_shade's direct term and emission + albedo * the upsampled irradiance:
// block histories at the block centres (4 i + 2), bilinear times geometry weights, the best
// match or plain bilinear as fallbacks.
TEST(Indirect, ComposeUpsamplesTheBlocksAndMatchesTheDirectTerm) {
  IndirectFixture fx;
  const auto lr = fx.run(3);
  const size_t plane = lr.plane;
  std::vector<float> hdr_ref, direct_ref, indirect_ref, hdr, direct, indirect;
  fx.light(nullptr, hdr_ref, direct_ref, indirect_ref);
  fx.light(&lr, hdr, direct, indirect);
  int lit = 0;
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const Pixel& q = fx.pixel(x, y);
      const size_t o = 4 * (size_t(y) * kW + x);
      if (!q.covered) {
        for (int c = 0; c < 4; ++c) EXPECT_EQ(hdr[o + c], 0.0f) << x << "," << y;
        continue;
      }
      const glm::dvec3 irr = upsample_ref(fx.geom, fx.history, plane, lr.pixel_scale, q, x, y);
      const glm::dvec3 want_indirect = glm::dvec3(q.albedo) * irr;
      lit += want_indirect.x > 1e-3;
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(direct[o + c], direct_ref[o + c], 1e-6 + 1e-5 * std::abs(direct_ref[o + c]))
            << "direct " << x << "," << y;
        EXPECT_NEAR(indirect[o + c], want_indirect[c], 1e-5 * (1.0 + want_indirect[c]))
            << "indirect " << x << "," << y;
        EXPECT_NEAR(hdr[o + c], hdr_ref[o + c] + want_indirect[c], 2e-5 * (1.0 + hdr[o + c]))
            << "hdr " << x << "," << y;
      }
      EXPECT_EQ(hdr[o + 3], 1.0f);
    }
  EXPECT_GE(lit, 40);
}

// The fast mode's reflection cones on the glossy fixture: indirect_trace's
// specular planes against the C++ cone (nearest-level, full-diameter steps; tan from the roughness,
// at least 0.1) from the sample pixel's apex along its mirror direction (no SSR: the pass runs
// without SsrInputs), the odd checkerboard samples left as holes (-1), uncoated ones -2, the
// background -3; indirect_filter's filled planes (a hole: the geometry-weighted mean of its traced
// coated edge neighbours, else their plain mean, else 0; uncoated: 0); and light_compose's specular
// component = E_spec(mu_o) * those planes upsampled with the irradiance's weights (block centres 4
// i + 2, bilinear x geometry, the fallbacks).
TEST(Indirect, ReflectionConesPerBlockFilledAndUpsampled) {
  IndirectFixture fx(true);
  const auto lr = fx.run(2);
  const size_t plane = lr.plane;
  const glm::dvec3 cam(rp::scene::Camera{}.position);
  auto mirror = [&](const Pixel& q) {
    const glm::dvec3 n(q.n), v = glm::normalize(cam - glm::dvec3(q.p));
    return 2.0 * std::max(glm::dot(n, v), 0.0) * n - v;
  };
  int holes = 0, traced = 0, matte = 0;
  for (uint32_t j = 0; j < lr_h(); ++j)
    for (uint32_t i = 0; i < lr_w(); ++i) {
      const Pixel& q = sample_pixel(fx, i, j);
      const size_t s = at(int(i), int(j));
      glm::dvec3 want(-3.0);  // background
      if (q.covered && q.gloss == 0.0f) {
        want = glm::dvec3(-2.0);  // no coat
        ++matte;
      } else if (q.covered) {
        const float rough = rp::shading::decode_gloss(q.gloss).roughness;  // every pixel coated
        const double t = std::max(double(rp::shading::spec_cone_tan(rough)), 0.1);
        if (((i ^ j) & 1u) == 0u) {  // RP_INDIRECT_SPEC_CHECKER_TAN 0: every coat
          rp::test::cone::Aperture a;
          a.fine = false;
          want = glm::dvec3(rp::test::cone::trace_aperture(
              fx.chain(), glm::dvec3(q.p) + glm::dvec3(q.n) * (2.0 / kRes), mirror(q), t, a));
          ++traced;
        } else {
          want = glm::dvec3(-1.0);
          ++holes;
        }
      }
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(fx.specular[c * plane + s], want[c], 2e-5) << "block " << i << "," << j;
    }
  EXPECT_GE(holes, 3);
  EXPECT_GE(traced, 3);
  EXPECT_EQ(matte, 3);
  // the fill
  const double ps = lr.pixel_scale;
  int filled = 0;
  for (uint32_t j = 0; j < lr_h(); ++j)
    for (uint32_t i = 0; i < lr_w(); ++i) {
      const size_t s = at(int(i), int(j));
      glm::dvec3 want(fx.specular[s], fx.specular[plane + s], fx.specular[2 * plane + s]);
      if (want.x < -1.5) {
        want = glm::dvec3(0.0);  // no coat
      } else if (want.x < 0.0) {
        const glm::dvec3 n(fx.geom[s], fx.geom[plane + s], fx.geom[2 * plane + s]);
        const glm::dvec3 p(fx.position[s], fx.position[plane + s], fx.position[2 * plane + s]);
        const double is = inv_sigma(fx.position[3 * plane + s], ps);
        glm::dvec3 a(0.0), m(0.0);
        double aw = 0.0, mw = 0.0;
        for (const auto& [di, dj] : {std::pair{-1, 0}, std::pair{1, 0}, std::pair{0, -1}, std::pair{0, 1}}) {
          const size_t t = at(int(i) + di, int(j) + dj);
          const glm::dvec3 v(fx.specular[t], fx.specular[plane + t], fx.specular[2 * plane + t]);
          const glm::dvec3 gn(fx.geom[t], fx.geom[plane + t], fx.geom[2 * plane + t]);
          if (v.x < 0.0 || glm::dot(gn, gn) < 0.5) continue;  // hole, no coat, background, pad
          const double w = geometry_weight(n, p, gn, fx.geom[3 * plane + t], is);
          a += w * v;
          aw += w;
          m += v;
          mw += 1.0;
        }
        want = aw >= 1e-4 ? a / aw : m / std::max(mw, 1.0);
        ++filled;
      }
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(fx.specular_filled[c * plane + s], want[c], 1e-5 * (1.0 + want[c]))
            << "filled block " << i << "," << j;
    }
  EXPECT_EQ(filled, holes);
  // the upsampling in light_compose
  std::vector<float> hdr, direct, indirect, specular;
  fx.light(&lr, hdr, direct, indirect, &specular);
  std::vector<float> hdr0, direct0, indirect0, specular0;  // no indirect light: direct specular
  fx.light(nullptr, hdr0, direct0, indirect0, &specular0);
  const rp::shading::BrdfTables& tables = rp::shading::BrdfTables::get();
  int reflecting = 0;
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const Pixel& q = fx.pixel(x, y);
      if (!q.covered) continue;
      const size_t o = 4 * (size_t(y) * kW + x);
      const glm::dvec3 up =
          upsample_ref(fx.geom, fx.specular_filled, plane, lr.pixel_scale, q, x, y);
      const rp::shading::SurfaceBsdf bsdf =
          rp::shading::make_bsdf(rp::shading::decode_gloss(q.gloss), q.albedo);
      const float mu = float(glm::dot(glm::dvec3(q.n), glm::normalize(cam - glm::dvec3(q.p))));
      const glm::dvec3 e(rp::shading::coat_albedo_at(bsdf, mu, tables));
      const glm::dvec3 want = e * up;
      reflecting += want.x > 1e-3;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(specular[o + c] - specular0[o + c], want[c], 2e-3 * want[c] + 2e-5)
            << "specular " << x << "," << y;
    }
  EXPECT_GE(reflecting, 40);
}

// With a still camera the filled reflections blend the previous frame's value at the same
// block, clamped to the range of this frame's traced values at the block and its eight
// neighbours (traced: a coated sample on the checkerboard, value >= 0, with a surface, view depth
// > 0), with weight 1 - RP_INDIRECT_SPEC_ALPHA (0.1 for the current frame): here the light
// doubles between two frames of the same view, so every traced block's value is
// clamp(previous, lo, hi) + 0.1 (current - that). On the checkerboard a traced block's edge
// neighbours are holes, so its range comes from its diagonal neighbours: with the edge ones
// alone (the first version) the range was the block's own value and the history did nothing.
TEST(Indirect, StillCameraReflectionsBlendTheClampedHistory) {
  IndirectFixture fx(true);
  fx.run(0);
  const std::vector<float> before = fx.specular_filled;
  fx.scale_voxels(2.0f);
  const auto lr = fx.run(1);
  const size_t plane = lr.plane;
  int blended = 0, widened = 0;
  for (uint32_t j = 0; j < lr_h(); ++j)
    for (uint32_t i = 0; i < lr_w(); ++i) {
      const size_t s = at(int(i), int(j));
      if (fx.specular[s] < 0.0f) continue;  // holes (their fill is tested above) and matte
      for (int c = 0; c < 3; ++c) {
        const size_t o = c * plane;
        double lo = fx.specular[o + s], hi = lo;
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const size_t t = at(int(i) + di, int(j) + dj);
            if (fx.specular[t] >= 0.0f && fx.position[3 * plane + t] > 0.0f) {  // padding: -3
              lo = std::min(lo, double(fx.specular[o + t]));
              hi = std::max(hi, double(fx.specular[o + t]));
            }
          }
        const double prev = std::clamp(double(before[o + s]), lo, hi);
        const double want = prev + 0.1 * (fx.specular[o + s] - prev);
        widened += c == 0 && hi > lo;
        EXPECT_NEAR(fx.specular_filled[o + s], want, 1e-5 * (1.0 + want))
            << "block " << i << "," << j << " channel " << c;
      }
      blended += fx.specular_filled[s] < fx.specular[s] - 1e-4f;  // lagging the doubled light
    }
  EXPECT_GE(blended, 3);
  EXPECT_GE(widened, 4) << "traced blocks whose range holds more than their own value";
}

}  // namespace
