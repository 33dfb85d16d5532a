// The motion blur's shutter (render::Effects::shutter, --shutter) reaches the renderer through
// the command line's embedded render settings: a frame whose instances moved since the previous
// one blurs more with a wider-open shutter, and not at all with a closed one.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "app/render_session.h"
#include "cl/pocl_cache.h"
#include "scene/demo_scene.h"

namespace rp::test {
namespace {

// The demo frame as if everything had moved 30 cm along +x since the previous frame (TAA and
// bloom off, so the final image is the light pass's, blurred or not).
std::vector<uint8_t> render_moved(bool motion_blur, float shutter) {
  app::CommonOptions common;
  common.render.voxel_resolution = 32;
  common.render.shadow_size = 128;
  common.render.effects.taa = false;
  common.render.effects.bloom = false;
  common.render.effects.motion_blur = motion_blur;
  common.render.effects.shutter = shutter;
  app::RenderSession session(common, 64, 64);
  std::vector<uint8_t> rgba;
  double frame_ms = 0.0;
  session.render(scene::make_demo_frame(session.assets(), 0), rgba, frame_ms);  // the history
  scene::FrameScene frame = scene::make_demo_frame(session.assets(), 1);
  for (scene::MeshInstance& instance : frame.instances)
    instance.prev_model = glm::translate(glm::mat4(1.0f), glm::vec3(-0.3f, 0.0f, 0.0f)) *
                          instance.model;
  session.render(frame, rgba, frame_ms);
  return rgba;
}

TEST(Shutter, WiderOpenBlursMoreAndClosedBlursNothing) {
  rp::cl::ensure_pocl_cache_dir();
  const std::vector<uint8_t> off = render_moved(false, 0.5f);
  const std::vector<uint8_t> closed = render_moved(true, 0.0f);
  const std::vector<uint8_t> half = render_moved(true, 0.5f);
  const std::vector<uint8_t> open = render_moved(true, 1.0f);
  EXPECT_EQ(closed, off) << "a closed shutter blurs nothing";
  // Mean absolute difference from the sharp frame, per channel value.
  auto blur = [&](const std::vector<uint8_t>& img) {
    double sum = 0.0;
    for (size_t i = 0; i < img.size(); ++i) sum += std::abs(int(img[i]) - int(off[i]));
    return sum / double(img.size());
  };
  EXPECT_GT(blur(half), 0.5) << blur(half);
  std::printf("mean |blurred - sharp|: shutter 0.5 %.3f, shutter 1 %.3f\n", blur(half),
              blur(open));
  EXPECT_GT(blur(open), 1.2 * blur(half)) << "half " << blur(half) << ", open " << blur(open);
}

}  // namespace
}  // namespace rp::test
