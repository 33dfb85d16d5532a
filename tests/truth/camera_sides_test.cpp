// The path tracer's camera rays and single-sided materials (truth/trace_scene.h Viewer): the
// camera passes through the back of a single-sided material (glTF doubleSided false, as the
// rasterizer culls it), light rays and double-sided materials see both sides, and a
// mirroring model matrix keeps the front on the same side of the surface.
#include <gtest/gtest.h>

#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/frame_scene.h"
#include "truth/trace_scene.h"

namespace rp::truth {
namespace {

// A unit quad in the z = 0 plane, its front towards +z (counter-clockwise seen from there) or
// towards -z.
scene::Mesh quad(bool front_towards_plus_z, uint32_t material) {
  scene::Mesh m;
  m.name = front_towards_plus_z ? "towards +z" : "towards -z";
  const glm::vec3 n(0.0f, 0.0f, front_towards_plus_z ? 1.0f : -1.0f);
  m.vertices = {{{-0.5f, -0.5f, 0.0f}, n, {0, 0}},
                {{0.5f, -0.5f, 0.0f}, n, {1, 0}},
                {{0.5f, 0.5f, 0.0f}, n, {1, 1}},
                {{-0.5f, 0.5f, 0.0f}, n, {0, 1}}};
  m.triangles = front_towards_plus_z ? std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}}
                                     : std::vector<glm::uvec3>{{0, 2, 1}, {0, 3, 2}};
  m.materials.assign(2, material);
  return m;
}

TEST(CameraSides, CameraRaysPassTheBackOfSingleSidedMaterialsOnly) {
  scene::SceneAssets assets;
  scene::Material double_sided, single_sided;
  double_sided.name = "double";
  double_sided.double_sided = true;
  single_sided.name = "single";
  assets.materials = {double_sided, single_sided};
  // meshes: 2 * (front towards +z) + material
  for (const bool towards : {false, true})
    for (uint32_t material : {0u, 1u}) assets.meshes.push_back(quad(towards, material));
  const TraceAssets trace_assets(assets);

  // The ray comes from +z; a far wall (double-sided) behind the tested quad.
  const glm::vec3 org(0.1f, 0.05f, 3.0f), dir(0.0f, 0.0f, -1.0f);
  int cases = 0;
  for (const bool towards : {false, true})
    for (uint32_t material : {0u, 1u})
      for (const bool mirrored : {false, true}) {
        scene::FrameScene frame;
        scene::MeshInstance tested, wall;
        tested.mesh = (towards ? 2u : 0u) + material;
        tested.model =
            glm::scale(glm::mat4(1.0f), glm::vec3(mirrored ? -1.0f : 1.0f, 1.0f, 1.0f));
        wall.mesh = 0;  // double-sided
        wall.model = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -1.0f));
        frame.instances = {tested, wall};
        const TraceScene scene(trace_assets, frame);
        SCOPED_TRACE(::testing::Message() << "front towards +z " << towards << " material "
                                          << material << " mirrored " << mirrored);
        // a mirror in x keeps the front on the +z side: the camera sees the quad unless it is
        // single-sided and turned away
        const bool seen = material == 0u || towards;
        Surface s;
        ASSERT_TRUE(scene.intersect(org, dir, 100.0f, s, TraceScene::Viewer::kCamera));
        EXPECT_EQ(s.instance, seen ? 0u : 1u);
        EXPECT_NEAR(s.p.z, seen ? 0.0f : -1.0f, 1e-5f);
        ASSERT_TRUE(scene.intersect(org, dir, 100.0f, s));  // light sees every side
        EXPECT_EQ(s.instance, 0u);
        ++cases;
      }
  EXPECT_EQ(cases, 8);
}

}  // namespace
}  // namespace rp::truth
