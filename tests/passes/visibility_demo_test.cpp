// The compute rasterizer on the demo scene (Cornell box, lamp cap, five tumblers): agreement
// with the C++ reference at a small size, and the per-pass device times at 256 and 720 pixels
// (printed and recorded as test properties; they are measurements, not pass/fail criteria).
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "passes/pass_names.h"
#include "passes/reference_raster.h"
#include "passes/visibility.h"
#include "render/gpu_scene.h"
#include "scene/demo_scene.h"
#include "support/cl_fixture.h"

namespace rp::test {
namespace {

namespace pass_name = rp::passes::pass_name;

glm::mat4 to_glm(const gpu::rp_mat4& m) {
  glm::mat4 out;
  for (int c = 0; c < 4; ++c) out[c] = glm::vec4(m.c[c].x, m.c[c].y, m.c[c].z, m.c[c].w);
  return out;
}

struct Demo {
  scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  scene::FrameScene frame = scene::make_demo_frame(assets);
  render::GpuScene gpu{context().context, context().queue, assets};
  passes::VisibilityPass pass{context(), programs()};
  rp::cl::Profiler profiler{context().queue};
};

TEST(VisibilityDemo, MatchesReference) {
  Demo d;
  const uint32_t w = 72, h = 72, shadow = 64;
  d.gpu.update(d.frame, w, h, shadow);
  render::VisibilityBuffer vb;
  vb.resize(context().context, w, h);
  render::ShadowMap sm;
  sm.resize(context().context, shadow);
  d.pass.render(d.profiler, d.gpu, vb);
  d.pass.render_shadow(d.profiler, d.gpu, sm);
  d.profiler.collect();

  const size_t n = size_t(w) * h;
  std::vector<glm::uvec2> ids(n);
  std::vector<float> depth(n), shadow_depth(size_t(shadow) * shadow);
  context().queue.enqueueReadBuffer(vb.ids, CL_TRUE, 0, n * sizeof(glm::uvec2), ids.data());
  context().queue.enqueueReadBuffer(vb.depth, CL_TRUE, 0, n * sizeof(float), depth.data());
  context().queue.enqueueReadBuffer(sm.depth, CL_TRUE, 0, shadow_depth.size() * sizeof(float),
                                    shadow_depth.data());

  RefView view;
  view.view_proj = to_glm(d.gpu.constants.view_proj);
  view.inv_view_proj = to_glm(d.gpu.constants.inv_view_proj);
  view.width = w;
  view.height = h;
  RefImage r = reference_raster(d.assets, d.frame, view);
  int id_errors = 0, depth_errors = 0;
  std::vector<int> per_instance(d.frame.instances.size(), 0);
  for (size_t i = 0; i < n; ++i) {
    id_errors += ids[i] != r.ids[i];
    depth_errors += !(std::abs(depth[i] - r.depth[i]) <= 1e-5f * r.depth[i]);
    if (ids[i].x < per_instance.size()) ++per_instance[ids[i].x];
  }
  EXPECT_EQ(id_errors, 0);
  EXPECT_EQ(depth_errors, 0);
  for (size_t i = 0; i < per_instance.size(); ++i)
    EXPECT_GT(per_instance[i], 0) << "instance " << i << " not visible";

  RefView light;
  light.view_proj = to_glm(d.gpu.constants.light_view_proj);
  light.inv_view_proj = glm::inverse(light.view_proj);
  light.width = light.height = shadow;
  light.depth_only = true;
  RefImage rs = reference_raster(d.assets, d.frame, light);
  int shadow_errors = 0, occluded = 0;
  for (size_t i = 0; i < shadow_depth.size(); ++i) {
    shadow_errors += !(std::abs(shadow_depth[i] - rs.depth[i]) <= 1e-5f * rs.depth[i]);
    occluded += shadow_depth[i] < 1.0f;
  }
  EXPECT_EQ(shadow_errors, 0);
  EXPECT_GT(occluded, 20);  // the tumblers cast shadows (the box and lamp do not)
}

TEST(VisibilityDemo, DeviceTimes) {
  Demo d;
  for (uint32_t size : {256u, 720u}) {
    d.gpu.update(d.frame, size, size, 1024);
    render::VisibilityBuffer vb;
    vb.resize(context().context, size, size);
    render::ShadowMap sm;
    sm.resize(context().context, 1024);
    double best_vis = 1e30, best_shadow = 1e30;
    for (int frame = 0; frame < 4; ++frame) {  // the first one grows the tile lists
      d.pass.render(d.profiler, d.gpu, vb);
      d.pass.render_shadow(d.profiler, d.gpu, sm);
      rp::cl::PassTimes t = d.profiler.collect();
      ASSERT_TRUE(t.count(pass_name::kVisibility) && t.count(pass_name::kShadowMap));
      if (frame > 0) {
        best_vis = std::min(best_vis, t[pass_name::kVisibility]);
        best_shadow = std::min(best_shadow, t[pass_name::kShadowMap]);
      }
    }
    std::printf("[ timing   ] demo %ux%u: visibility %.2f ms, shadow_map (1024^2) %.2f ms on %s\n",
                size, size, best_vis, best_shadow, context().info.name.c_str());
    RecordProperty("visibility_ms_" + std::to_string(size), std::to_string(best_vis));
    RecordProperty("shadow_map_ms_" + std::to_string(size), std::to_string(best_shadow));
    EXPECT_GT(best_vis, 0.0);
  }
}

}  // namespace
}  // namespace rp::test
