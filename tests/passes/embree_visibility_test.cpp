// The Embree visibility backend against the compute rasterizer: the same frame through both
// gives the same ids on all but exact-edge pixels and the same depth where the ids agree (the
// rasterizer is itself checked against a C++ reference in visibility_demo_test.cpp); whole
// frames agree by PSNR; Embree output does not depend on the thread count. A disabled test
// measures both backends at 720x720 (run with --gtest_also_run_disabled_tests).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "passes/embree_visibility.h"
#include "passes/pass_names.h"
#include "passes/visibility.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "scene/demo_scene.h"
#include "scene/world.h"
#include "support/cl_fixture.h"
#include "support/image_metrics.h"

namespace rp::test {
namespace {

namespace pass_name = rp::passes::pass_name;

struct HostVisibility {
  std::vector<float> depth;
  std::vector<uint32_t> ids;  // (instance, primitive) per pixel
  std::vector<float> bary;
};

HostVisibility read_back(const render::VisibilityBuffer& vb) {
  const size_t n = size_t(vb.width) * vb.height;
  HostVisibility h{std::vector<float>(n), std::vector<uint32_t>(2 * n), std::vector<float>(2 * n)};
  ::cl::CommandQueue& q = context().queue;
  q.enqueueReadBuffer(vb.depth, CL_TRUE, 0, n * sizeof(float), h.depth.data());
  q.enqueueReadBuffer(vb.ids, CL_TRUE, 0, 2 * n * sizeof(uint32_t), h.ids.data());
  q.enqueueReadBuffer(vb.bary, CL_TRUE, 0, 2 * n * sizeof(float), h.bary.data());
  return h;
}

// The busy scene: 30 marbles and a fireball after `steps` fixed steps (tumblers rocking,
// particles once the fireball has burnt a marble).
scene::FrameScene busy_frame(int steps) {
  scene::WorldConfig config;
  config.marbles = true;
  config.fireball = true;
  scene::World world(config);
  world.advance(steps);
  scene::FrameScene frame;
  world.fill_frame(frame);
  return frame;
}

// Depth of the ray through pixel centre (x, y) at its hit with the surface (instance,
// primitive), in double from the float matrices and vertices: the reference both backends are
// measured against. NaN when the exact ray misses (a sphere silhouette).
struct ExactDepth {
  const scene::SceneAssets& assets;
  const render::GpuScene& gpu;
  const scene::FrameScene& frame;
  glm::dmat4 vp, inv;

  ExactDepth(const scene::SceneAssets& a, const render::GpuScene& g, const scene::FrameScene& f)
      : assets(a), gpu(g), frame(f) {
    for (int c = 0; c < 4; ++c) {
      const gpu::rp_float4& col = g.constants.view_proj.c[c];
      vp[c] = glm::dvec4(col.x, col.y, col.z, col.w);
    }
    inv = glm::inverse(vp);
  }

  double operator()(uint32_t x, uint32_t y, uint32_t instance, uint32_t primitive) const {
    const double nx = (double(x) + 0.5) * 2.0 / double(gpu.constants.width) - 1.0;
    const double ny = 1.0 - (double(y) + 0.5) * 2.0 / double(gpu.constants.height);
    const glm::dvec4 n4 = inv * glm::dvec4(nx, ny, -1.0, 1.0);
    const glm::dvec4 f4 = inv * glm::dvec4(nx, ny, 1.0, 1.0);
    const glm::dvec3 o = glm::dvec3(n4) / n4.w, d = glm::dvec3(f4) / f4.w - o;
    double t;
    if (instance & RP_ID_SPHERE_BIT) {
      const gpu::rp_float4 s = gpu.host_spheres[instance & ~RP_ID_SPHERE_BIT].center_radius;
      const glm::dvec3 c = o - glm::dvec3(s.x, s.y, s.z);
      const double a = glm::dot(d, d), b = glm::dot(c, d), q = glm::dot(c, c) - double(s.w) * s.w;
      const double disc = b * b - a * q;
      if (disc < 0.0) return std::nan("");
      t = (-b - std::sqrt(disc)) / a;
      if (t < 0.0) t = (-b + std::sqrt(disc)) / a;
    } else {
      const scene::MeshInstance& mi = frame.instances[instance];
      const scene::Mesh& mesh = assets.meshes[mi.mesh];
      const glm::uvec3 tri = mesh.triangles[primitive];
      const glm::dmat4 model(mi.model);
      auto world = [&](uint32_t v) {
        return glm::dvec3(model * glm::dvec4(glm::dvec3(mesh.vertices[v].position), 1.0));
      };
      const glm::dvec3 v0 = world(tri.x), v1 = world(tri.y), v2 = world(tri.z);
      const glm::dvec3 n = glm::cross(v1 - v0, v2 - v0);
      t = glm::dot(v0 - o, n) / glm::dot(d, n);
    }
    const glm::dvec4 clip = vp * glm::dvec4(o + t * d, 1.0);
    return clip.z / clip.w * 0.5 + 0.5;
  }
};

struct Agreement {
  double id_percent = 0.0;
  size_t agreeing = 0, depth_over = 0, raster_off = 0, bary_over = 0;
  double max_depth_diff = 0.0, max_embree_error = 0.0, max_raster_error = 0.0;
  double max_bary_diff = 0.0;
  size_t sphere_pixels = 0, triangle_pixels = 0, background = 0;
};

constexpr double kDepthTolerance = 1e-4;  // raster vs Embree, where the ids agree
constexpr double kExactTolerance = 1e-5;  // Embree vs the double-precision reference

Agreement compare(const HostVisibility& raster, const HostVisibility& embree,
                  const ExactDepth& exact) {
  Agreement a;
  const uint32_t w = exact.gpu.constants.width;
  const size_t n = raster.depth.size();
  for (size_t i = 0; i < n; ++i) {
    const uint32_t inst = raster.ids[2 * i], prim = raster.ids[2 * i + 1];
    if (inst != embree.ids[2 * i] || prim != embree.ids[2 * i + 1]) continue;
    ++a.agreeing;
    const double diff = std::fabs(double(raster.depth[i]) - double(embree.depth[i]));
    a.max_depth_diff = std::max(a.max_depth_diff, diff);
    if (inst == RP_ID_NONE) {
      ++a.background;
      continue;
    }
    const double truth = exact(uint32_t(i % w), uint32_t(i / w), inst, prim);
    const double embree_error = std::isnan(truth) ? 0.0 : std::fabs(embree.depth[i] - truth);
    a.max_embree_error = std::max(a.max_embree_error, embree_error);
    if (!std::isnan(truth))
      a.max_raster_error = std::max(a.max_raster_error, std::fabs(raster.depth[i] - truth));
    if (diff > kDepthTolerance) {
      ++a.depth_over;
      // Tolerated only where the rasterizer is the one that is off (grazing triangles).
      if (embree_error <= kExactTolerance) ++a.raster_off;
    }
    if (inst & RP_ID_SPHERE_BIT) {
      ++a.sphere_pixels;
    } else {
      ++a.triangle_pixels;
      double bd = 0.0;
      for (int k = 0; k < 2; ++k)
        bd = std::max(bd, double(std::fabs(raster.bary[2 * i + k] - embree.bary[2 * i + k])));
      a.max_bary_diff = std::max(a.max_bary_diff, bd);
      a.bary_over += bd > 1e-3;
    }
  }
  a.id_percent = 100.0 * double(a.agreeing) / double(n);
  return a;
}

struct Backends {
  explicit Backends(scene::SceneAssets a = scene::make_demo_assets(scene::default_asset_dir()))
      : assets(std::move(a)) {}
  scene::SceneAssets assets;
  render::GpuScene gpu{context().context, context().queue, assets};
  passes::VisibilityPass raster{context(), programs()};
  passes::EmbreeVisibilityPass embree{context(), assets};
  rp::cl::Profiler profiler{context().queue};
  render::VisibilityBuffer vb;

  // Both buffers of `frame` at w x h with TAA jitter (16-frame cycle) as the renderer uses it.
  std::pair<HostVisibility, HostVisibility> both(const scene::FrameScene& frame, uint32_t w,
                                                 uint32_t h) {
    gpu.update(frame, w, h, 64, 32, 16);
    if (vb.width != w || vb.height != h) vb.resize(context().context, w, h);
    raster.render(profiler, gpu, vb);
    profiler.collect();
    HostVisibility r = read_back(vb);
    embree.render(profiler, gpu, vb);
    rp::cl::PassTimes t = profiler.collect();
    EXPECT_TRUE(t.count(pass_name::kVisibility)) << "the upload is recorded under the pass name";
    return {r, read_back(vb)};
  }
};

void expect_agreement(const std::string& what, const Agreement& a, size_t min_spheres) {
  std::printf("[ agree    ] %s: ids agree on %.4f %% of pixels (%zu triangle, %zu sphere, %zu "
              "background). Where they agree: max |depth raster - Embree| %.3g, over %.0e on "
              "%zu pixels (%zu of them where the rasterizer is off); max depth error vs double "
              "reference: Embree %.3g, raster %.3g; max |bary diff| %.3g, over 1e-3 on %zu "
              "pixels\n",
              what.c_str(), a.id_percent, a.triangle_pixels, a.sphere_pixels, a.background,
              a.max_depth_diff, kDepthTolerance, a.depth_over, a.raster_off, a.max_embree_error,
              a.max_raster_error, a.max_bary_diff, a.bary_over);
  EXPECT_GE(a.id_percent, 99.5) << what;
  // Embree's depth is exact to float rounding everywhere.
  EXPECT_LE(a.max_embree_error, kExactTolerance) << what;
  // The rasterizer's depth is exact to float rounding too, grazing triangles included
  // (common/raster.h RP_RASTER_DEPTH: normalised by the pixel's own edge sum; the screen-space
  // depth plane it replaced was off by up to 4.2e-4 there), so the two agree everywhere.
  EXPECT_LE(a.max_raster_error, kExactTolerance) << what;
  EXPECT_EQ(a.depth_over, 0u) << what;
  // Barycentrics: both are ill-conditioned on grazing triangles; elsewhere they agree.
  EXPECT_LE(double(a.bary_over), 0.002 * double(a.triangle_pixels)) << what;
  EXPECT_GT(a.triangle_pixels, 1000u) << what;
  EXPECT_GE(a.sphere_pixels, min_spheres) << what;
}

TEST(EmbreeVisibility, AgreesWithTheRasterizerOnTheDemo) {
  Backends b;
  for (uint32_t frame_index : {0u, 5u}) {
    scene::FrameScene frame = scene::make_demo_frame(b.assets, frame_index);
    auto [r, e] = b.both(frame, 160, 120);
    expect_agreement("demo frame " + std::to_string(frame_index),
                     compare(r, e, ExactDepth(b.assets, b.gpu, frame)), 0);
  }
}

TEST(EmbreeVisibility, AgreesWithTheRasterizerWithSpheres) {
  Backends b;
  for (int steps : {120, 480}) {
    scene::FrameScene frame = busy_frame(steps);
    std::printf("[ scene    ] after %d steps: %zu instances, %zu spheres\n", steps,
                frame.instances.size(), frame.spheres.size());
    ASSERT_GE(frame.spheres.size(), 31u);  // 30 marbles + fireball (+ particles)
    auto [r, e] = b.both(frame, 160, 160);
    expect_agreement("busy scene, " + std::to_string(steps) + " steps",
                     compare(r, e, ExactDepth(b.assets, b.gpu, frame)), 200);
  }
}

TEST(EmbreeVisibility, AgreesWithTheRasterizerThroughAlphaMaskedHoles) {
  // The demo with a card in front of the back wall, cut by an alpha-masked texture (holes of
  // 2x2 texels, a few at alpha 0.5 so bilinear ramps cross the cutoff, tiled 3 times).
  scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  scene::Texture holes;
  holes.name = "holes";
  holes.width = holes.height = 8;
  for (int i = 0; i < 64; ++i) {
    const int block = (i % 8) / 2 + 4 * (i / 16);
    holes.rgba.insert(holes.rgba.end(),
                      {200, 200, 200, uint8_t(block % 3 == 0 ? 0 : block % 5 == 1 ? 128 : 255)});
  }
  assets.textures.push_back(holes);
  scene::Material cut;
  cut.name = "cut";
  cut.texture = int(assets.textures.size()) - 1;
  cut.alpha_mode = scene::AlphaMode::kMask;
  assets.materials.push_back(cut);
  scene::Mesh card;
  card.name = "card";
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  card.vertices = {{{-0.7f, -0.6f, -0.3f}, n, {0.0f, 0.0f}}, {{0.7f, -0.6f, -0.3f}, n, {3.0f, 0.0f}},
                   {{0.7f, 0.6f, -0.3f}, n, {3.0f, 3.0f}}, {{-0.7f, 0.6f, -0.3f}, n, {0.0f, 3.0f}}};
  card.triangles = {{0, 1, 2}, {0, 2, 3}};
  card.materials.assign(2, uint32_t(assets.materials.size() - 1));
  assets.meshes.push_back(card);
  Backends b(std::move(assets));
  scene::FrameScene frame = scene::make_demo_frame(b.assets, 0);
  scene::MeshInstance inst;
  inst.mesh = uint32_t(b.assets.meshes.size() - 1);
  frame.instances.push_back(inst);
  const uint32_t card_instance = uint32_t(frame.instances.size() - 1);
  auto [r, e] = b.both(frame, 160, 120);
  const Agreement a = compare(r, e, ExactDepth(b.assets, b.gpu, frame));
  std::printf("[ agree    ] alpha-masked card: ids agree on %.4f %% of pixels\n", a.id_percent);
  EXPECT_GE(a.id_percent, 99.0);
  EXPECT_EQ(a.depth_over, 0u);
  // Both backends see the card and the wall through its holes.
  size_t card_pixels = 0, through = 0;
  for (uint32_t y = 40; y < 80; ++y)
    for (uint32_t x = 60; x < 100; ++x) {
      const size_t i = size_t(y) * 160 + x;
      const bool on_card = e.ids[2 * i] == card_instance;
      card_pixels += on_card && r.ids[2 * i] == card_instance;
      through += !on_card && r.ids[2 * i] != card_instance;
    }
  EXPECT_GT(card_pixels, 300u);
  EXPECT_GT(through, 300u);
}

TEST(EmbreeVisibility, AgreesWithTheRasterizerOnSingleSidedBackFaces) {
  // Four small cards in front of the demo's back wall, their meshes' front towards -z (away
  // from the camera): single-sided as they are (not seen), double-sided (seen), single-sided
  // and mirrored in x (the front stays towards -z: not seen), single-sided and turned half
  // round about y (the front towards the camera: seen). The identity one lies in Embree's
  // static scene, the others are instances.
  scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  scene::Material single, both;
  single.name = "single";
  both.name = "both";
  both.double_sided = true;
  assets.materials.push_back(single);
  assets.materials.push_back(both);
  const uint32_t single_index = uint32_t(assets.materials.size() - 2);
  for (const uint32_t material : {single_index, single_index + 1}) {
    scene::Mesh card;
    card.name = "card";
    const glm::vec3 n(0.0f, 0.0f, -1.0f);
    card.vertices = {{{-0.2f, -0.2f, 0.0f}, n, {0, 0}}, {{0.2f, -0.2f, 0.0f}, n, {1, 0}},
                     {{0.2f, 0.2f, 0.0f}, n, {1, 1}}, {{-0.2f, 0.2f, 0.0f}, n, {0, 1}}};
    card.triangles = {{0, 2, 1}, {0, 3, 2}};  // clockwise seen from +z
    card.materials.assign(2, material);
    assets.meshes.push_back(card);
  }
  const uint32_t single_mesh = uint32_t(assets.meshes.size() - 2);
  Backends b(std::move(assets));
  scene::FrameScene frame = scene::make_demo_frame(b.assets, 0);
  const uint32_t first = uint32_t(frame.instances.size());
  auto card = [&](uint32_t mesh, glm::vec3 at, glm::mat4 turn) {
    scene::MeshInstance inst;
    inst.mesh = mesh;
    inst.model = glm::translate(glm::mat4(1.0f), at) * turn;
    inst.prev_model = inst.model;
    frame.instances.push_back(inst);
  };
  const glm::mat4 id(1.0f);
  card(single_mesh, {0.0f, 0.0f, 0.0f}, id);  // identity: Embree's static scene
  card(single_mesh + 1, {0.45f, 0.3f, -0.3f}, id);
  card(single_mesh, {-0.45f, 0.3f, -0.3f}, glm::scale(id, glm::vec3(-1.0f, 1.0f, 1.0f)));
  card(single_mesh, {0.45f, -0.3f, -0.3f},
       glm::rotate(id, glm::radians(180.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
  auto [r, e] = b.both(frame, 160, 120);
  const Agreement a = compare(r, e, ExactDepth(b.assets, b.gpu, frame));
  std::printf("[ agree    ] single-sided cards: ids agree on %.4f %% of pixels\n", a.id_percent);
  EXPECT_GE(a.id_percent, 99.5);
  EXPECT_EQ(a.depth_over, 0u);
  size_t seen[2][4] = {};
  for (size_t i = 0; i < size_t(160) * 120; ++i)
    for (uint32_t k = 0; k < 4; ++k) {
      seen[0][k] += r.ids[2 * i] == first + k;
      seen[1][k] += e.ids[2 * i] == first + k;
    }
  for (int backend = 0; backend < 2; ++backend) {
    SCOPED_TRACE(backend == 0 ? "raster" : "Embree");
    EXPECT_EQ(seen[backend][0], 0u);
    EXPECT_GT(seen[backend][1], 100u);
    EXPECT_EQ(seen[backend][2], 0u);
    EXPECT_GT(seen[backend][3], 100u);
  }
}

TEST(EmbreeVisibility, OutputDoesNotDependOnTheThreadCount) {
  scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  render::GpuScene gpu{context().context, context().queue, assets};
  rp::cl::Profiler profiler{context().queue};
  passes::EmbreeVisibilityPass one{context(), assets, 1}, many{context(), assets, 5};
  EXPECT_EQ(one.threads(), 1u);
  EXPECT_EQ(many.threads(), 5u);
  render::VisibilityBuffer vb;
  vb.resize(context().context, 99, 61);  // not a multiple of the 4x4 packets
  for (int steps : {60, 200}) {
    gpu.update(busy_frame(steps), 99, 61, 64, 32, 16);
    one.render(profiler, gpu, vb);
    profiler.collect();
    HostVisibility a = read_back(vb);
    many.render(profiler, gpu, vb);
    profiler.collect();
    HostVisibility b = read_back(vb);
    EXPECT_EQ(a.depth, b.depth);
    EXPECT_EQ(a.ids, b.ids);
    EXPECT_EQ(a.bary, b.bary);
  }
}

render::RenderSettings small_settings(render::VisibilityBackend backend) {
  render::RenderSettings s;
  s.width = s.height = 96;
  s.shadow_size = 256;
  s.voxel_resolution = 32;
  s.visibility = backend;
  return s;
}

TEST(EmbreeVisibility, WholeFramesMatchTheRasterBackend) {
  scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  render::Renderer raster(context(), programs(), assets,
                          small_settings(render::VisibilityBackend::kRaster));
  render::Renderer embree(context(), programs(), assets,
                          small_settings(render::VisibilityBackend::kEmbree));
  render::Renderer embree2(context(), programs(), assets,
                           small_settings(render::VisibilityBackend::kEmbree));
  scene::WorldConfig config;
  config.marbles = config.fireball = true;
  scene::World world(config);
  std::vector<uint8_t> a, b, c;
  double worst = 1e9;
  for (int frame = 0; frame < 6; ++frame) {  // TAA, bloom and motion blur on: same jitter
    world.advance(4);
    scene::FrameScene f;
    world.fill_frame(f);
    raster.render(f);
    rp::cl::PassTimes t = embree.render(f);
    EXPECT_TRUE(t.count(pass_name::kVisibilityHost));
    embree2.render(f);
    raster.read_rgba8(a);
    embree.read_rgba8(b);
    embree2.read_rgba8(c);
    const double psnr = psnr_rgb8(a, b);
    worst = std::min(worst, psnr);
    EXPECT_GE(psnr, 40.0) << "frame " << frame;
    EXPECT_EQ(b, c) << "two Embree renders of frame " << frame << " differ";
  }
  std::printf("[ psnr     ] raster vs Embree backend, 6 frames of the busy scene at 96x96 "
              "(TAA, bloom, motion blur on): worst %.2f dB\n",
              worst);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Measurement, not a check: median visibility cost of each backend at 720x720.
TEST(EmbreeVisibility, DISABLED_Timings720) {
  Backends b;
  const uint32_t size = 720;
  render::VisibilityBuffer vb;
  vb.resize(context().context, size, size);
  const char* names[] = {"demo", "busy (30 marbles, fireball, particles)"};
  for (int which = 0; which < 2; ++which) {
    scene::FrameScene frame =
        which == 0 ? scene::make_demo_frame(b.assets) : busy_frame(480);
    std::vector<double> raster_ms, embree_host_ms, upload_ms;
    for (int i = 0; i < 8; ++i) {
      frame.frame_index = uint32_t(i);
      b.gpu.update(frame, size, size, 1024, 64, 16);
      b.raster.render(b.profiler, b.gpu, vb);
      rp::cl::PassTimes t = b.profiler.collect();
      if (i > 0) raster_ms.push_back(t[pass_name::kVisibility]);
      double host = b.embree.render(b.profiler, b.gpu, vb);
      t = b.profiler.collect();
      if (i > 0) {
        embree_host_ms.push_back(host);
        upload_ms.push_back(t[pass_name::kVisibility]);
      }
    }
    std::printf("[ timing   ] %s %ux%u (%zu spheres), median of 7: raster %.2f ms device; "
                "Embree %.2f ms host (%u threads) + %.2f ms upload\n",
                names[which], size, size, frame.spheres.size(), median(raster_ms),
                median(embree_host_ms), b.embree.threads(), median(upload_ms));
  }
}

}  // namespace
}  // namespace rp::test
