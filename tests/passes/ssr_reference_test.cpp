// The reference mode's screen-space reflections (kernels/light.cl, light_shade, with
// kernels/common/ssr.h marched at level 0) against a C++ reference that marches the mirror ray
// in small world-space steps and looks each point up in the same screen: the first pixel whose
// surface the ray reaches (its view depth at least the pixel's, within the thickness) is the
// hit. The scene, ray cast per pixel centre on the host: a coated floor (y = -0.9; the left
// half roughness 0.1, SSR at full weight, the right half 0.31, half weight) in front of a matte
// back wall (z = -0.9) whose previous-frame colour is a smooth gradient, and background around
// them (rays that leave the picture miss). Expected specular component of every floor pixel:
// E_spec(mu_o) (cone + c (ssr - cone)), c = (roughness fade) x (screen-edge fade), ssr the
// previous colour over the lobe's footprint at the hit (one pixel for the sharp half, about 1.6
// pixels' radius for the other), the cone the C++ trace_aperture on a random chain; 0 for the
// rest. Without a previous frame the same
// pixels take the cone alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "cone_reference.h"
#include "passes/light.h"
#include "render/gpu_scene.h"
#include "shading/brdf.h"
#include "shading/brdf_tables.h"
#include "support/cl_fixture.h"
#include "support/direct_light_ref.h"

namespace {

constexpr uint32_t kW = 40, kH = 30, kRes = 16;
constexpr double kPlane = -0.9;  // the floor's y and the back wall's z

struct Surfel {
  bool covered = false;
  glm::dvec3 p{0.0}, n{0.0};
  double depth = 4.0;  // view depth (the far plane for the background, as the GBuffer)
  double z01 = 1.0;    // the visibility buffer's depth
  float gloss = 0.0f;
  glm::dvec3 prev{0.0};  // the previous frame's light output (the wall's gradient)
};

struct Screen {
  glm::dmat4 vp;
  glm::dvec3 cam, fwd;
  std::vector<Surfel> px;

  // The screen position (pixels, y down), z01 and view depth of world point q.
  bool project(const glm::dvec3& q, glm::dvec2& s, double& depth) const {
    const glm::dvec4 c = vp * glm::dvec4(q, 1.0);
    if (c.w <= 0.05) return false;
    s = glm::dvec2((c.x / c.w * 0.5 + 0.5) * kW, (0.5 - c.y / c.w * 0.5) * kH);
    depth = c.w;
    return true;
  }
};

Screen make_screen(const rp::scene::Camera& camera, float floor_left, float floor_right) {
  Screen sc;
  const float aspect = float(kW) / float(kH);
  sc.vp = glm::dmat4(camera.projection(aspect) * camera.view());
  sc.cam = glm::dvec3(camera.position);
  sc.fwd = glm::normalize(glm::dvec3(camera.target) - sc.cam);
  const glm::dmat4 inv = glm::inverse(sc.vp);
  sc.px.resize(kW * kH);
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const glm::dvec2 ndc((x + 0.5) / kW * 2.0 - 1.0, 1.0 - (y + 0.5) / kH * 2.0);
      const glm::dvec4 a = inv * glm::dvec4(ndc, -1.0, 1.0), b = inv * glm::dvec4(ndc, 1.0, 1.0);
      const glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
      Surfel& s = sc.px[y * kW + x];
      double best = 1e9;
      const double tf = (kPlane - o.y) / d.y, tw = (kPlane - o.z) / d.z;
      const glm::dvec3 pf = o + tf * d, pw = o + tw * d;
      if (tf > 0.0 && std::abs(pf.x) <= 1.0 && pf.z >= kPlane && pf.z <= 1.0) {
        best = tf;
        s.covered = true;
        s.p = pf;
        s.n = glm::dvec3(0, 1, 0);
        s.gloss = pf.x < 0.0 ? floor_left : floor_right;
      }
      if (tw > 0.0 && tw < best && std::abs(pw.x) <= 1.0 && pw.y >= kPlane && pw.y <= 1.0) {
        s.covered = true;
        s.p = pw;
        s.n = glm::dvec3(0, 0, 1);
        s.gloss = 0.0f;
        // green: stripes about 4 pixels apart, so that averaging over the lobe shows
        s.prev = glm::dvec3(0.5 + 0.3 * pw.x, 0.6 + 0.3 * std::sin(4.0 * M_PI * pw.x), 0.4);
      }
      if (!s.covered) continue;
      const glm::dvec4 c = sc.vp * glm::dvec4(s.p, 1.0);
      s.depth = c.w;
      s.z01 = c.z / c.w * 0.5 + 0.5;
      if (s.gloss != 0.0f) s.prev = glm::dvec3(0.3);
    }
  return sc;
}

// The previous frame's colour over the coat's lobe at hit surfel h (pixel centre q, no
// velocity): the GGX lobe's half width at half maximum, tan = 1.2872 a / (1 - 0.41421 a^2) with
// a = roughness^2, times the distance from p, projected at the hit's view depth (h / 2 /
// tan(fov_y / 2) pixels per unit of depth); under half a pixel the hit pixel alone, else the
// mean of the hit pixel and the covered on-screen pixels at 8 points on that circle.
glm::dvec3 footprint(const Screen& sc, const rp::scene::Camera& camera, const glm::dvec3& p,
                     double rough, const Surfel& h, glm::dvec2 q) {
  const double a = std::max(rough * rough, 1e-4);
  const double tan_lobe = 1.2872 * a / (1.0 - 0.41421 * a * a);
  const double radius = glm::length(h.p - p) * tan_lobe * 0.5 * kH /
                        std::tan(glm::radians(double(camera.fov_y_deg)) * 0.5) / h.depth;
  if (radius < 0.5) return h.prev;
  glm::dvec3 sum = h.prev;
  double n = 1.0;
  for (int k = 0; k < 8; ++k) {
    const double ang = k * 0.78539816;
    const glm::dvec2 t = q + radius * glm::dvec2(std::cos(ang), std::sin(ang));
    if (t.x < 0.0 || t.y < 0.0 || t.x >= kW || t.y >= kH) continue;
    const Surfel& f = sc.px[int(t.y) * kW + int(t.x)];
    if (!f.covered) continue;
    sum += f.prev;
    n += 1.0;
  }
  return sum / n;
}

// The C++ march: the ray from p along unit r in steps of 1e-3 world units, up to 3 units; a
// hit is the first pixel (at least 1.5 pixels from the start along the screen's major axis)
// whose covered surface the ray point reaches in view depth, within 0.06 + 2 % of the depth.
std::optional<glm::ivec2> march(const Screen& sc, const glm::dvec3& p, const glm::dvec3& r) {
  glm::dvec2 s0, s1;
  double d0 = 0.0, d1 = 0.0;
  if (!sc.project(p, s0, d0) || !sc.project(p + 3.0 * r, s1, d1)) return std::nullopt;
  const bool major_x = std::abs(s1.x - s0.x) >= std::abs(s1.y - s0.y);
  for (double t = 0.0; t <= 3.0; t += 1e-3) {
    glm::dvec2 s;
    double depth = 0.0;
    if (!sc.project(p + t * r, s, depth)) return std::nullopt;
    if (std::abs(major_x ? s.x - s0.x : s.y - s0.y) < 1.5) continue;
    if (s.x < 0.0 || s.y < 0.0 || s.x >= kW || s.y >= kH) return std::nullopt;
    const glm::ivec2 q(int(s.x), int(s.y));
    const Surfel& f = sc.px[q.y * kW + q.x];
    if (f.covered && depth >= f.depth && depth - f.depth <= 0.06 + 0.02 * f.depth) return q;
  }
  return std::nullopt;
}

// The light pass's specular component (rgba per pixel) on the screen's GBuffer.
std::vector<float> run_light(const Screen& sc, const rp::test::cone::Chain& chain,
                             bool with_history) {
  auto& ctx = rp::test::context();
  rp::render::GpuScene scene(ctx.context, ctx.queue, rp::scene::SceneAssets{});
  rp::scene::FrameScene frame;
  scene.update(frame, kW, kH, 32);
  const size_t n = size_t(kW) * kH;
  std::vector<float> albedo(4 * n, 0.0f), nd(4 * n, 0.0f), pos(4 * n, 0.0f), em(4 * n, 0.0f),
      z01(n), prev(4 * n, 0.0f), vel(2 * n, 0.0f);
  for (size_t i = 0; i < n; ++i) {
    const Surfel& s = sc.px[i];
    z01[i] = float(s.z01);
    nd[4 * i + 3] = float(s.depth);
    if (!s.covered) continue;
    for (int c = 0; c < 3; ++c) {
      albedo[4 * i + c] = 0.5f;
      nd[4 * i + c] = float(s.n[c]);
      pos[4 * i + c] = float(s.p[c]);
      prev[4 * i + c] = float(s.prev[c]);
    }
    albedo[4 * i + 3] = pos[4 * i + 3] = prev[4 * i + 3] = 1.0f;
    em[4 * i + 3] = s.gloss;
  }
  rp::render::GBuffer gb;
  gb.resize(ctx.context, kW, kH);
  ctx.queue.enqueueWriteBuffer(gb.albedo, CL_TRUE, 0, n * 16, albedo.data());
  ctx.queue.enqueueWriteBuffer(gb.normal_depth, CL_TRUE, 0, n * 16, nd.data());
  ctx.queue.enqueueWriteBuffer(gb.position, CL_TRUE, 0, n * 16, pos.data());
  ctx.queue.enqueueWriteBuffer(gb.emission, CL_TRUE, 0, n * 16, em.data());
  ctx.queue.enqueueWriteBuffer(gb.velocity, CL_TRUE, 0, n * 8, vel.data());
  ::cl::Buffer depth(ctx.context, CL_MEM_READ_WRITE, n * 4);
  ::cl::Buffer prev_hdr(ctx.context, CL_MEM_READ_WRITE, n * 16);
  ctx.queue.enqueueWriteBuffer(depth, CL_TRUE, 0, n * 4, z01.data());
  ctx.queue.enqueueWriteBuffer(prev_hdr, CL_TRUE, 0, n * 16, prev.data());
  rp::render::ShadowMap sm;  // every pixel in the lamp's shadow: no direct specular
  sm.resize(ctx.context, 32);
  const std::vector<float> map = rp::test::with_sheet_back_plane(std::vector<float>(32 * 32, 0.0f));
  ctx.queue.enqueueWriteBuffer(sm.depth, CL_TRUE, 0, map.size() * 4, map.data());
  ::cl::Buffer voxels(ctx.context, CL_MEM_READ_ONLY, chain.voxels.size() * 16);
  ctx.queue.enqueueWriteBuffer(voxels, CL_TRUE, 0, chain.voxels.size() * 16, chain.voxels.data());
  ::cl::Buffer hdr(ctx.context, CL_MEM_READ_WRITE, n * 16);
  rp::passes::LightComponents comp{::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16),
                                   ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16),
                                   ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16)};
  rp::cl::Profiler profiler(ctx.queue);
  rp::passes::LightPass pass(ctx, rp::test::programs(), rp::render::ShadowMode::kHard);
  const rp::passes::SsrInputs ssr{&depth, &prev_hdr, &gb.velocity};
  pass.run(profiler, scene, gb, sm, voxels, chain.resolution, chain.levels, hdr, &comp, nullptr,
           with_history ? &ssr : nullptr);
  profiler.collect();
  std::vector<float> out(4 * n);
  ctx.queue.enqueueReadBuffer(comp.specular, CL_TRUE, 0, n * 16, out.data());
  return out;
}

TEST(Ssr, ReferenceModeReflectsTheScreenLikeAWorldSpaceMarch) {
  using rp::shading::gloss_code;
  const rp::scene::Camera camera;
  const float sharp = gloss_code(rp::scene::Specular{0.1f, 0.04f, false});
  const float fading = gloss_code(rp::scene::Specular{0.31f, 0.04f, false});
  const Screen sc = make_screen(camera, sharp, fading);
  const rp::test::cone::Chain chain = rp::test::cone::random_chain(kRes, 23);
  const std::vector<float> got = run_light(sc, chain, true);
  const std::vector<float> cone_only = run_light(sc, chain, false);
  const rp::shading::BrdfTables& tables = rp::shading::BrdfTables::get();
  int floor = 0, hits = 0, faded = 0, misses = 0, exact = 0, spread = 0, spread_exact = 0;
  for (uint32_t i = 0; i < kW * kH; ++i) {
    const Surfel& s = sc.px[i];
    glm::dvec3 want(0.0), want_cone(0.0), tol(2e-5);
    bool averaged = false;
    if (s.covered && s.gloss != 0.0f) {
      ++floor;
      const rp::scene::Specular coat = rp::shading::decode_gloss(s.gloss);
      const glm::dvec3 v = glm::normalize(sc.cam - s.p);
      const glm::dvec3 r = 2.0 * std::max(glm::dot(s.n, v), 0.0) * s.n - v;
      const glm::dvec3 e(rp::shading::coat_albedo_at(
          rp::shading::make_bsdf(coat, glm::vec3(0.5f)), float(glm::dot(s.n, v)), tables));
      const glm::dvec3 cone(rp::test::cone::trace_aperture(
          chain, s.p + s.n * (2.0 / kRes), r, rp::shading::spec_cone_tan(coat.roughness)));
      want_cone = e * cone;
      double c = 0.0;
      glm::dvec3 ssr(0.0);
      if (const auto hit = march(sc, s.p, r); hit) {
        const Surfel& h = sc.px[hit->y * kW + hit->x];
        if (glm::dot(h.n, r) < 0.0) {
          const glm::dvec2 q(hit->x + 0.5, hit->y + 0.5);
          const double edge = std::min(std::min(q.x, kW - q.x), std::min(q.y, kH - q.y)) /
                              (0.06 * std::min(kW, kH));
          c = std::clamp((0.34 - coat.roughness) / 0.06, 0.0, 1.0) * std::clamp(edge, 0.0, 1.0);
          ssr = footprint(sc, camera, s.p, coat.roughness, h, q);
          averaged = c > 0.0 && glm::length(ssr - h.prev) > 1e-6;  // over the lobe
          spread += averaged;
        }
      }
      hits += c >= 0.999;
      faded += c > 0.0 && c < 0.999;
      misses += c == 0.0;
      want = e * (cone + c * (ssr - cone));
      // one pixel along the wall's colours (the wall is about 15 pixels across 2 units; the
      // stripes change green by up to 0.5 per pixel): a march that lands one pixel off
      tol = glm::dvec3(5e-3) * glm::abs(want) + 2e-5 + e * c * glm::dvec3(0.045, 0.5, 0.0);
    }
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_NEAR(got[4 * i + ch], want[ch], tol[ch])
          << "pixel " << i % kW << "," << i / kW << " channel " << ch;
      // the cone in float against double: up to 0.4 % where it leaves the box near the floor's
      // front edge
      EXPECT_NEAR(cone_only[4 * i + ch], want_cone[ch], 5e-3 * want_cone[ch] + 2e-5)
          << "no history, pixel " << i % kW << "," << i / kW;
    }
    bool same = true;
    for (int ch = 0; ch < 3; ++ch)
      same = same && std::abs(got[4 * i + ch] - want[ch]) <= 5e-3 * std::abs(want[ch]) + 2e-5;
    exact += s.gloss != 0.0f && same;
    spread_exact += averaged && same;
  }
  std::printf("reference SSR: %d floor pixels, %d full hits, %d faded, %d misses, %d averaged "
              "over the lobe, %d as the C++ march\n", floor, hits, faded, misses, spread, exact);
  EXPECT_GE(floor, 150);
  EXPECT_GE(hits, 40) << "floor pixels reflecting the wall at full weight";
  EXPECT_GE(faded, 40) << "half-weight coats and the screen edge";
  EXPECT_GE(misses, 10) << "rays leaving the picture";
  EXPECT_GE(spread, 5) << "hits whose colour is averaged over the lobe's footprint";
  EXPECT_EQ(spread_exact, spread) << "the lobe's average as the C++ one";
  EXPECT_GE(exact, floor * 95 / 100) << "the same hit pixel for (nearly) all of the floor";
}

}  // namespace
