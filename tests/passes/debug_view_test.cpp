// Debug views on hand-filled buffers, against the mappings documented in kernels/debug_view.cl
// computed here in double precision: GBuffer views, the shadow map, tone-mapped radiance, and
// the voxel view against an exact ray / voxel-grid traversal. Codes may differ by one where a
// value sits on a rounding boundary (float vs double).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cl/error.h"
#include "cone_reference.h"
#include "kernels/shared/voxel_layout.h"
#include "passes/debug_view.h"
#include "passes/pass_names.h"
#include "render/gpu_scene.h"
#include "support/cl_fixture.h"

namespace {

using rp::passes::DebugView;

constexpr uint32_t kW = 20, kH = 12;  // neither a multiple of the 16x16 work-group
constexpr uint32_t kShadow = 8;

int q(double v) { return int(std::lround(255.0 * std::clamp(v, 0.0, 1.0))); }
double srgb(double y) {
  y = std::clamp(y, 0.0, 1.0);
  return y <= 0.0031308 ? 12.92 * y : 1.055 * std::pow(y, 1.0 / 2.4) - 0.055;
}
double tone(double x) { return std::max(x, 0.0) / (1.0 + std::max(x, 0.0)); }

struct Rgb {
  int r, g, b;
};

class DebugFixture {
 public:
  DebugFixture() {
    auto& ctx = rp::test::context();
    scene_ = std::make_unique<rp::render::GpuScene>(ctx.context, ctx.queue,
                                                    rp::scene::SceneAssets{});
    frame_.camera.position = {1.5f, 1.1f, 2.0f};  // outside the box, looking at it obliquely
    frame_.camera.target = {0.1f, -0.2f, 0.0f};
    scene_->update(frame_, kW, kH, kShadow);
    gbuffer_.resize(ctx.context, kW, kH);
    shadow_.resize(ctx.context, kShadow);
    rgba_ = ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, kW * kH * 4);
  }

  const rp::scene::FrameScene& frame() const { return frame_; }
  rp::render::GBuffer& gbuffer() { return gbuffer_; }
  rp::render::ShadowMap& shadow() { return shadow_; }
  rp::render::GpuScene& scene() { return *scene_; }

  template <typename T>
  void write(::cl::Buffer& buffer, const std::vector<T>& data) {
    rp::test::context().queue.enqueueWriteBuffer(buffer, CL_TRUE, 0, data.size() * sizeof(T),
                                                 data.data());
  }

  std::vector<Rgb> run(const rp::passes::DebugViewSettings& settings,
                       const rp::passes::DebugViewInputs& inputs) {
    auto& ctx = rp::test::context();
    rp::cl::Profiler profiler(ctx.queue);
    rp::passes::DebugViewPass pass(ctx, rp::test::programs());
    pass.run(profiler, *scene_, settings, inputs, rgba_);
    EXPECT_EQ(profiler.collect().count(rp::passes::pass_name::kDebugView), 1u);
    std::vector<uint32_t> packed(kW * kH);
    ctx.queue.enqueueReadBuffer(rgba_, CL_TRUE, 0, packed.size() * 4, packed.data());
    std::vector<Rgb> out;
    for (uint32_t p : packed) {
      EXPECT_EQ(p >> 24, 255u);
      out.push_back({int(p & 255u), int((p >> 8) & 255u), int((p >> 16) & 255u)});
    }
    return out;
  }

 private:
  rp::scene::FrameScene frame_;
  std::unique_ptr<rp::render::GpuScene> scene_;
  rp::render::GBuffer gbuffer_;
  rp::render::ShadowMap shadow_;
  ::cl::Buffer rgba_;
};

void expect_rgb(const Rgb& got, int r, int g, int b, const std::string& what) {
  EXPECT_LE(std::abs(got.r - r), 1) << what << " red " << got.r << " want " << r;
  EXPECT_LE(std::abs(got.g - g), 1) << what << " green " << got.g << " want " << g;
  EXPECT_LE(std::abs(got.b - b), 1) << what << " blue " << got.b << " want " << b;
}

// Deterministic pseudo-random GBuffer: every third pixel background.
struct HandGBuffer {
  std::vector<glm::vec4> albedo, normal_depth, position;
  std::vector<glm::vec2> velocity;
  HandGBuffer() {
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (uint32_t i = 0; i < kW * kH; ++i) {
      const bool covered = i % 3 != 0;
      glm::vec3 n = glm::normalize(glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
      albedo.push_back(covered ? glm::vec4(u(rng), u(rng), u(rng), 1.0f) : glm::vec4(0.0f));
      normal_depth.push_back(glm::vec4(n, covered ? 0.1f + 4.2f * u(rng) : 4.0f));
      position.push_back(glm::vec4(u(rng), u(rng), u(rng), covered ? 1.0f : 0.0f));
      velocity.push_back(covered ? glm::vec2(40.0f * u(rng) - 20.0f, 40.0f * u(rng) - 20.0f)
                                 : glm::vec2(0.0f));
    }
  }
};

TEST(DebugView, GBufferViews) {
  DebugFixture fx;
  HandGBuffer hand;
  fx.write(fx.gbuffer().albedo, hand.albedo);
  fx.write(fx.gbuffer().normal_depth, hand.normal_depth);
  fx.write(fx.gbuffer().position, hand.position);
  fx.write(fx.gbuffer().velocity, hand.velocity);
  rp::passes::DebugViewInputs in;
  in.gbuffer = &fx.gbuffer();
  const double near = fx.frame().camera.near_plane, far = fx.frame().camera.far_plane;

  auto albedo = fx.run({DebugView::kAlbedo}, in);
  auto normal = fx.run({DebugView::kNormal}, in);
  auto depth = fx.run({DebugView::kDepth}, in);
  auto velocity = fx.run({DebugView::kVelocity}, in);
  for (uint32_t i = 0; i < kW * kH; ++i) {
    const std::string at = "pixel " + std::to_string(i);
    const glm::dvec4 a(hand.albedo[i]), nd(hand.normal_depth[i]);
    expect_rgb(albedo[i], q(srgb(a.x)), q(srgb(a.y)), q(srgb(a.z)), "albedo " + at);
    if (hand.position[i].w != 0.0f)
      expect_rgb(normal[i], q(0.5 + 0.5 * nd.x), q(0.5 + 0.5 * nd.y), q(0.5 + 0.5 * nd.z),
                 "normal " + at);
    else
      expect_rgb(normal[i], 0, 0, 0, "normal background " + at);
    const int grey = q((nd.w - near) / (far - near));
    expect_rgb(depth[i], grey, grey, grey, "depth " + at);
    const glm::dvec2 v = glm::clamp(glm::dvec2(hand.velocity[i]) / 16.0, -1.0, 1.0);
    expect_rgb(velocity[i], q(0.5 + 0.5 * v.x), q(0.5 + 0.5 * v.y), q(0.5), "velocity " + at);
  }
  // The normal view of a known normal, spelled out: n = (1, 0, 0) -> (255, 128, 128).
  hand.normal_depth[0] = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  hand.position[0].w = 1.0f;
  fx.write(fx.gbuffer().normal_depth, hand.normal_depth);
  fx.write(fx.gbuffer().position, hand.position);
  expect_rgb(fx.run({DebugView::kNormal}, in)[0], 255, 128, 128, "normal +x");
}

TEST(DebugView, ShadowMapIsStretchedOverTheImage) {
  DebugFixture fx;
  std::vector<float> map(kShadow * kShadow);
  for (uint32_t i = 0; i < map.size(); ++i) map[i] = i % 7 == 0 ? 1.0f : 0.2f + 0.79f * float(i) / 64.0f;
  fx.write(fx.shadow().depth, map);
  rp::passes::DebugViewInputs in;
  in.shadow = &fx.shadow();
  auto got = fx.run({DebugView::kShadowMap}, in);
  const double near = fx.frame().light.shadow_near, far = fx.frame().light.shadow_far;
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const uint32_t tx = x * kShadow / kW, ty = y * kShadow / kH;
      const double d = map[ty * kShadow + tx];
      const double z = d * 2.0 - 1.0;
      const double lin = 2.0 * near * far / ((far + near) - z * (far - near));
      const int grey = d >= 1.0 ? 255 : q((lin - near) / (far - near));
      expect_rgb(got[y * kW + x], grey, grey, grey,
                 "pixel " + std::to_string(x) + "," + std::to_string(y));
    }
}

TEST(DebugView, DirectIndirectAndSpecularAreToneMapped) {
  DebugFixture fx;
  auto& ctx = rp::test::context();
  std::vector<glm::vec4> direct(kW * kH), indirect(kW * kH), specular(kW * kH);
  for (uint32_t i = 0; i < kW * kH; ++i) {
    direct[i] = glm::vec4(0.01f * float(i), 3.0f - 0.01f * float(i), 0.5f, 1.0f);
    indirect[i] = glm::vec4(0.002f * float(i), 0.0f, 0.3f, 1.0f);
    specular[i] = glm::vec4(0.2f, 0.004f * float(i), 0.0f, 1.0f);
  }
  rp::passes::LightComponents components{::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, kW * kH * 16),
                                         ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, kW * kH * 16),
                                         ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, kW * kH * 16)};
  fx.write(components.direct, direct);
  fx.write(components.indirect, indirect);
  fx.write(components.specular, specular);
  rp::passes::DebugViewInputs in;
  in.light = &components;
  for (DebugView view : {DebugView::kDirect, DebugView::kIndirect, DebugView::kSpecular}) {
    const auto& src = view == DebugView::kDirect     ? direct
                      : view == DebugView::kIndirect ? indirect
                                                     : specular;
    auto got = fx.run({view}, in);
    for (uint32_t i = 0; i < kW * kH; ++i) {
      const glm::dvec4 c(src[i]);
      expect_rgb(got[i], q(srgb(tone(c.x))), q(srgb(tone(c.y))), q(srgb(tone(c.z))),
                 std::string(rp::name_of(view)) + " pixel " + std::to_string(i));
    }
  }
}

// Exact traversal of the voxel grid of one volume (n^3 over [-1,1]^3) by camera rays: every
// plane crossing along the ray is collected and sorted; each segment's midpoint names the voxel
// it lies in; every voxel is composited once, front to back.
glm::dvec3 voxel_ray_ref(const rp::test::cone::Chain& chain, uint32_t level, uint32_t dir,
                         const glm::dvec3& o, const glm::dvec3& d) {
  const int n = int(chain.size(level));
  const double cell = 2.0 / n;
  double t0 = 0.0, t1 = 1e30;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-15) {
      if (std::abs(o[a]) > 1.0) return glm::dvec3(0.0);
      continue;
    }
    double ta = (-1.0 - o[a]) / d[a], tb = (1.0 - o[a]) / d[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  if (t0 >= t1) return glm::dvec3(0.0);
  std::vector<double> ts = {t0, t1};
  for (int a = 0; a < 3; ++a)
    if (std::abs(d[a]) > 1e-15)
      for (int k = 1; k < n; ++k) {
        double t = (-1.0 + k * cell - o[a]) / d[a];
        if (t > t0 && t < t1) ts.push_back(t);
      }
  std::sort(ts.begin(), ts.end());
  glm::dvec3 colour(0.0);
  double alpha = 0.0;
  for (size_t i = 0; i + 1 < ts.size(); ++i) {
    if (ts[i + 1] - ts[i] < 1e-9) continue;
    const glm::dvec3 m = o + d * (0.5 * (ts[i] + ts[i + 1]));
    glm::uvec3 v;
    for (int a = 0; a < 3; ++a) v[a] = uint32_t(std::clamp(int(std::floor((m[a] + 1.0) / cell)), 0, n - 1));
    const glm::dvec4 s(chain.at(level, dir, v.x, v.y, v.z));
    colour += (1.0 - alpha) * glm::dvec3(s);
    alpha += (1.0 - alpha) * s.w;
    if (alpha >= 0.999) break;
  }
  return colour;
}

TEST(DebugView, VoxelsViewMatchesAnExactGridTraversal) {
  DebugFixture fx;
  auto& ctx = rp::test::context();
  rp::test::cone::Chain chain(8, 4);
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (glm::vec4& v : chain.voxels)
    if (u(rng) < 0.5f) {
      float a = 0.2f + 0.8f * u(rng);
      v = glm::vec4(2.0f * a * u(rng), 2.0f * a * u(rng), 2.0f * a * u(rng), a);
    }
  ::cl::Buffer voxels(ctx.context, CL_MEM_READ_ONLY, chain.voxels.size() * 16);
  fx.write(voxels, chain.voxels);
  rp::passes::DebugViewInputs in;
  in.voxels = &voxels;
  in.voxel_resolution = 8;
  in.voxel_levels = 4;
  const glm::dmat4 inv(glm::inverse(glm::dmat4(fx.frame().camera.projection(float(kW) / kH)) *
                                    glm::dmat4(fx.frame().camera.view())));
  int hits = 0;
  for (uint32_t level : {0u, 1u, 2u})
    for (uint32_t dir : {RP_DIR_POS_X, RP_DIR_NEG_Y}) {
      rp::passes::DebugViewSettings settings{DebugView::kVoxels, level, dir};
      auto got = fx.run(settings, in);
      for (uint32_t y = 0; y < kH; ++y)
        for (uint32_t x = 0; x < kW; ++x) {
          const glm::dvec2 ndc((x + 0.5) / kW * 2.0 - 1.0, 1.0 - (y + 0.5) / kH * 2.0);
          glm::dvec4 a = inv * glm::dvec4(ndc, -1.0, 1.0), b = inv * glm::dvec4(ndc, 1.0, 1.0);
          const glm::dvec3 o = glm::dvec3(a) / a.w;
          const glm::dvec3 d = glm::normalize(glm::dvec3(b) / b.w - o);
          const glm::dvec3 c = voxel_ray_ref(chain, level, level == 0 ? 0 : dir, o, d);
          hits += c.x + c.y + c.z > 0.0;
          expect_rgb(got[y * kW + x], q(srgb(tone(c.x))), q(srgb(tone(c.y))), q(srgb(tone(c.z))),
                     "level " + std::to_string(level) + " dir " + std::to_string(dir) +
                         " pixel " + std::to_string(x) + "," + std::to_string(y));
        }
    }
  EXPECT_GT(hits, 400);  // of 6 x 240 rays (the box covers about half the image)
}

TEST(DebugView, NamesKeysAndErrors) {
  EXPECT_EQ(rp::parse_name<DebugView>("shadow-map"), DebugView::kShadowMap);
  EXPECT_EQ(rp::parse_name<DebugView>("final"), DebugView::kFinal);
  EXPECT_FALSE(rp::parse_name<DebugView>("shadow"));
  const auto table = names(DebugView{});
  for (size_t i = 0; i < table.size(); ++i) {  // every view, in enum order
    EXPECT_EQ(size_t(table[i].value), i);
    EXPECT_EQ(rp::name_of(*rp::parse_name<DebugView>(table[i].name)), table[i].name);
  }
  EXPECT_EQ(table.back().value, DebugView::kSpecular);  // the last enumerator has its row
  EXPECT_EQ(rp::passes::parse_voxel_dir("-y"), RP_DIR_NEG_Y);
  EXPECT_FALSE(rp::passes::parse_voxel_dir("y"));
  EXPECT_EQ(rp::passes::debug_view_for_key('1'), DebugView::kFinal);
  EXPECT_EQ(rp::passes::debug_view_for_key('6'), DebugView::kShadowMap);
  EXPECT_EQ(rp::passes::debug_view_for_key('9'), DebugView::kVoxels);
  EXPECT_EQ(rp::passes::debug_view_for_key('0'), DebugView::kSpecular);
  EXPECT_FALSE(rp::passes::debug_view_for_key('M'));

  DebugFixture fx;
  auto& ctx = rp::test::context();
  rp::cl::Profiler profiler(ctx.queue);
  rp::passes::DebugViewPass pass(ctx, rp::test::programs());
  ::cl::Buffer out(ctx.context, CL_MEM_READ_WRITE, kW * kH * 4);
  auto message = [&](const rp::passes::DebugViewSettings& s, const rp::passes::DebugViewInputs& in) {
    try {
      pass.run(profiler, fx.scene(), s, in, out);
    } catch (const rp::cl::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  rp::passes::DebugViewInputs none;
  EXPECT_NE(message({DebugView::kFinal}, none).find("not a debug view"), std::string::npos);
  EXPECT_NE(message({DebugView::kNormal}, none).find("needs the GBuffer"), std::string::npos);
  EXPECT_NE(message({DebugView::kDirect}, none).find("components"), std::string::npos);
  ::cl::Buffer voxels(ctx.context, CL_MEM_READ_ONLY, rp::gpu::rp_voxel_total(8, 4) * 16);
  rp::passes::DebugViewInputs vin;
  vin.voxels = &voxels;
  vin.voxel_resolution = 8;
  vin.voxel_levels = 4;
  EXPECT_NE(message({DebugView::kVoxels, 4, 0}, vin).find("level 4 does not exist"),
            std::string::npos);
  EXPECT_NE(message({DebugView::kVoxels, 1, 6}, vin).find("direction"), std::string::npos);
  vin.voxel_resolution = 16;  // the buffer is too small for 16^3
  EXPECT_NE(message({DebugView::kVoxels, 1, 0}, vin).find("smaller"), std::string::npos);
  profiler.collect();
}

}  // namespace
