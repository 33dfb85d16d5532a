// Voxelize pass on small hand-made scenes: identical fixed-point sums to the C++ reference
// (tests/passes/voxelize_reference.cpp) for triangles (thinner than a voxel, through voxel
// corners, on a voxel face, rotated by an instance, partly outside the volume) and spheres;
// lit values to a tolerance; a thin slanted strip without gaps (6-connected, dense samples
// covered, nothing far from the strip); sphere coverage and opacity; overflow saturation; an
// empty scene; the pass name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <memory>
#include <ostream>
#include <random>
#include <set>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "cl/error.h"
#include "passes/pass_names.h"
#include "passes/voxel_mips.h"
#include "passes/voxelize.h"
#include "passes/voxelize_reference.h"
#include "render/gpu_scene.h"
#include "render/voxel_volume.h"
#include "support/cl_fixture.h"

namespace rp::test {
namespace {

// Large enough that the slope bias (up to 9 texels at grazing light) stays far below the
// receivers' depths, so an all-zero map shadows everything.
constexpr uint32_t kShadowSize = 256;

struct TriSpec {
  glm::vec3 a, b, c;
  uint32_t material = 0;
};

scene::Mesh make_mesh(const std::vector<TriSpec>& tris) {
  scene::Mesh mesh;
  mesh.name = "test";
  for (const TriSpec& t : tris) {
    const glm::vec3 n = glm::normalize(glm::cross(t.b - t.a, t.c - t.a));
    const uint32_t base = static_cast<uint32_t>(mesh.vertices.size());
    mesh.vertices.push_back({t.a, n, {0.1f, 0.2f}});
    mesh.vertices.push_back({t.b, n, {0.9f, 0.3f}});
    mesh.vertices.push_back({t.c, n, {0.4f, 0.8f}});
    mesh.triangles.push_back({base, base + 1, base + 2});
    mesh.materials.push_back(t.material);
  }
  return mesh;
}

// Materials 0..2 plain (2 has no emission), 3 textured with a 4x4 texture of varied colours,
// 4 alpha-masked by an 8x8 texture with holes (mirrored in u, clamped in v), 5 masked with an
// opacity below its cutoff (never there).
scene::SceneAssets base_assets() {
  scene::SceneAssets assets;
  assets.materials = {
      {"m0", {0.8f, 0.6f, 0.4f}, {1.5f, 0.25f, 3.0f}, -1},
      {"m1", {0.3f, 0.9f, 0.5f}, {0.7f, 2.2f, 0.1f}, -1},
      {"m2", {0.5f, 0.5f, 0.5f}, {0.0f, 0.0f, 0.0f}, -1},
      {"m3", {1.0f, 0.9f, 0.8f}, {0.2f, 0.3f, 0.4f}, 0},
  };
  scene::Texture tex;
  tex.name = "checker";
  tex.width = tex.height = 4;
  for (int i = 0; i < 16; ++i) {
    tex.rgba.push_back(static_cast<uint8_t>(40 + 13 * i));
    tex.rgba.push_back(static_cast<uint8_t>(200 - 9 * i));
    tex.rgba.push_back(static_cast<uint8_t>((i % 3) * 90 + 20));
    tex.rgba.push_back(255);
  }
  assets.textures.push_back(tex);
  scene::Texture holes;
  holes.name = "holes";
  holes.width = holes.height = 8;
  holes.wrap_u = scene::TextureWrap::kMirroredRepeat;
  holes.wrap_v = scene::TextureWrap::kClampToEdge;
  for (int i = 0; i < 64; ++i) {
    const int block = (i % 8) / 2 + 4 * (i / 16);
    holes.rgba.insert(holes.rgba.end(), {uint8_t(90 + 2 * i), 160, uint8_t(250 - 3 * i),
                                         uint8_t(block % 3 == 0 ? 0 : block % 5 == 1 ? 128 : 255)});
  }
  assets.textures.push_back(holes);
  scene::Material cut{"m4", {0.9f, 0.7f, 0.5f}, {0.3f, 0.1f, 0.6f}, 1};
  cut.alpha_mode = scene::AlphaMode::kMask;
  cut.alpha_cutoff = 0.5f;
  scene::Material gone{"m5", {0.9f, 0.9f, 0.9f}, {2.0f, 2.0f, 2.0f}, -1};
  gone.alpha_mode = scene::AlphaMode::kMask;
  gone.opacity = 0.2f;
  gone.alpha_cutoff = 0.3f;
  assets.materials.push_back(cut);
  assets.materials.push_back(gone);
  return assets;
}

scene::Sphere sphere(glm::vec3 c, float r, glm::vec3 emission, glm::vec3 albedo = glm::vec3(0.6f)) {
  scene::Sphere s;
  s.center = s.prev_center = c;
  s.radius = r;
  s.albedo = albedo;
  s.emission = emission;
  return s;
}

// One scene: meshes of `assets`, one instance per entry of `models` (mesh i), spheres.
struct Scene {
  scene::SceneAssets assets;
  scene::FrameScene frame;
  std::unique_ptr<render::GpuScene> gpu;

  void upload() {
    gpu = std::make_unique<render::GpuScene>(context().context, context().queue, assets);
    gpu->update(frame, 16, 16, kShadowSize);
  }
};

void add_instance(Scene& s, uint32_t mesh, const glm::mat4& model) {
  scene::MeshInstance inst;
  inst.mesh = mesh;
  inst.model = inst.prev_model = model;
  s.frame.instances.push_back(inst);
}

std::vector<float> uniform_shadow(float depth) {
  return std::vector<float>(size_t(kShadowSize) * kShadowSize, depth);
}

// Counts differing elements, reporting the first few.
size_t count_mismatches(const std::vector<uint32_t>& got, const std::vector<uint32_t>& want,
                        const char* what) {
  EXPECT_EQ(got.size(), want.size()) << what;
  size_t bad = 0;
  for (size_t i = 0; i < std::min(got.size(), want.size()); ++i)
    if (got[i] != want[i] && bad++ < 6)
      ADD_FAILURE() << what << " element " << i << ": " << got[i] << " vs reference " << want[i];
  return bad;
}

// Device sums against the reference (compare_sums: words 0-3 and the overflow bits exactly,
// the facing coverage exactly up to the reference's slack); returns the differing voxels.
size_t sums_mismatches(const VoxelSums& got, const VoxelSums& want, const char* what) {
  std::vector<std::string> first;
  const size_t bad = compare_sums(got, want, &first);
  for (const std::string& line : first) ADD_FAILURE() << what << " " << line;
  return bad;
}

// Word w of voxel v.
uint32_t word(const VoxelSums& s, size_t v, size_t w) { return s.accum[kAccumWords * v + w]; }

// The scene of the exact test: R = 16 (voxel 0.125 wide).
Scene exact_scene() {
  Scene s;
  s.assets = base_assets();
  std::vector<TriSpec> tris = {
      // Thinner than a voxel: a long sliver, slanted in all three axes.
      {{-0.8f, -0.3f, 0.1f}, {0.7f, 0.35f, -0.2f}, {0.7001f, 0.352f, -0.19f}, 0},
      // Through voxel corners: all vertices on corners (multiples of 0.125) of the plane
      // x + y + z = 0, edges through further corners (e.g. (0.125, 0.125, -0.25)).
      {{0.5f, -0.25f, -0.25f}, {-0.25f, 0.5f, -0.25f}, {-0.25f, -0.25f, 0.5f}, 1},
      // Exactly on a voxel face (y = 0.25 is grid 10): touches both layers.
      {{-0.6f, 0.25f, -0.6f}, {0.6f, 0.25f, -0.3f}, {0.0f, 0.25f, 0.7f}, 0},
      // Larger than the volume on one side (clipped), no emission.
      {{-1.5f, -0.9f, -1.5f}, {1.5f, -0.9f, -1.5f}, {0.0f, -0.95f, 1.5f}, 2},
      // Entirely outside.
      {{1.2f, 0.0f, 0.0f}, {1.5f, 0.2f, 0.0f}, {1.3f, 0.1f, 0.4f}, 1},
      // Textured.
      {{-0.9f, 0.6f, 0.8f}, {-0.2f, 0.7f, 0.6f}, {-0.5f, 0.2f, 0.9f}, 3},
      // Small (within 2 voxels: shaded once at its centroid), textured, across a voxel face.
      {{0.55f, 0.6f, -0.7f}, {0.62f, 0.65f, -0.72f}, {0.58f, 0.7f, -0.66f}, 3},
      // Alpha-masked: a large card with holes, small ones kept or cut whole, an invisible one.
      {{-0.95f, -0.7f, -0.9f}, {0.9f, -0.6f, -0.8f}, {0.1f, 0.45f, -0.85f}, 4},
      {{0.3f, 0.3f, 0.3f}, {0.38f, 0.35f, 0.33f}, {0.33f, 0.4f, 0.38f}, 4},
      {{-0.1f, 0.3f, 0.3f}, {-0.02f, 0.35f, 0.33f}, {-0.07f, 0.4f, 0.38f}, 4},
      {{0.6f, 0.3f, 0.3f}, {0.68f, 0.35f, 0.33f}, {0.63f, 0.4f, 0.38f}, 4},
      {{-0.7f, 0.0f, 0.5f}, {0.2f, 0.1f, 0.6f}, {-0.3f, 0.5f, 0.4f}, 5},
  };
  s.assets.meshes.push_back(make_mesh(tris));
  // A second mesh drawn through a rotating, translating instance.
  s.assets.meshes.push_back(make_mesh({{{-0.3f, -0.2f, 0.0f}, {0.3f, -0.1f, 0.05f},
                                        {0.0f, 0.35f, -0.1f}, 1},
                                       {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f},
                                        {0.0f, 0.0f, 0.0f}, 0}}));  // degenerate: skipped
  add_instance(s, 0, glm::mat4(1.0f));
  add_instance(s, 1, glm::rotate(glm::translate(glm::mat4(1.0f), {0.31f, -0.42f, 0.27f}), 0.7f,
                                 glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f))));
  s.frame.spheres = {
      sphere({0.25f, 0.25f, 0.25f}, 0.01f, {5.0f, 1.0f, 0.5f}),  // tiny, on a voxel corner
      sphere({-0.4f, 0.1f, -0.55f}, 0.06f, {0.5f, 3.0f, 1.0f}),  // just under half a voxel
      sphere({0.3f, -0.5f, 0.45f}, 0.3f, {0.2f, 0.4f, 0.9f}),    // large
      sphere({-0.6875f, -0.5625f, 0.3125f}, 0.07f, {1.0f, 1.0f, 1.0f}),  // at a voxel centre
      sphere({0.95f, 0.0f, -0.1f}, 0.2f, {2.0f, 0.0f, 0.0f}),    // partly outside
  };
  s.frame.light.intensity = glm::vec3(0.0f);  // emission only: exact radiance
  s.upload();
  return s;
}

TEST(Voxelize, IdenticalSumsToReference) {
  Scene s = exact_scene();
  const std::vector<float> shadow = uniform_shadow(1.0f);
  const VoxelGpuOutput got = run_voxelize(*s.gpu, shadow, 16);
  const VoxelSums want = reference_voxelize(reference_input(s.assets, s.frame, *s.gpu, shadow), 16);
  EXPECT_EQ(sums_mismatches(got.sums, want, "sums"), 0u);
  const std::vector<float> level0 = reference_resolve(want);
  size_t bad = 0;
  for (size_t i = 0; i < level0.size(); ++i)
    if (!(std::fabs(got.level0[i] - level0[i]) <= 1e-6f * std::fabs(level0[i])) && bad++ < 6)
      ADD_FAILURE() << "level 0 element " << i << ": " << got.level0[i] << " vs " << level0[i];
  EXPECT_EQ(bad, 0u);
  EXPECT_EQ(got.times.count(rp::passes::pass_name::kVoxelize), 1u);

  // Not vacuous: every primitive left voxels, and the face triangle touches both layers.
  size_t touched = 0;
  size_t facing[6] = {};  // voxels with coverage in each facing half
  for (size_t v = 0; v < want.overflow.size(); ++v) {
    touched += word(want, v, 3) != 0;
    for (int h = 0; h < 6; ++h) facing[h] += facing_half(got.sums, v, h / 2, h % 2) != 0;
  }
  EXPECT_GT(touched, 300u);
  for (int h = 0; h < 6; ++h) EXPECT_GT(facing[h], 20u) << "facing half " << h;
  auto alpha = [&](int x, int y, int z) {
    return word(got.sums, size_t((z * 16 + y) * 16 + x), 3);
  };
  // Columns (x, z) = (8, 7) and (7, 6) lie inside the footprint of the triangle on y = 0.25.
  EXPECT_NE(alpha(8, 9, 7), 0u);
  EXPECT_NE(alpha(8, 10, 7), 0u);
  EXPECT_NE(alpha(7, 9, 6), 0u);
  EXPECT_NE(alpha(7, 10, 6), 0u);

  // The masked materials cut voxels: with them opaque, more voxels are touched.
  scene::SceneAssets opaque = s.assets;
  for (scene::Material& m : opaque.materials) m.alpha_mode = scene::AlphaMode::kOpaque;
  const VoxelSums all = reference_voxelize(reference_input(opaque, s.frame, *s.gpu, shadow), 16);
  size_t touched_opaque = 0;
  for (size_t v = 0; v < all.overflow.size(); ++v) touched_opaque += word(all, v, 3) != 0;
  EXPECT_GT(touched_opaque, touched + 40) << "the holes and the invisible triangle";
}

TEST(Voxelize, LitMatchesReferenceAndShadowedIsEmissionOnly) {
  Scene s = exact_scene();
  s.frame.light.intensity = glm::vec3(6.0f, 5.0f, 4.0f);
  s.upload();
  const VoxelRefInput base = reference_input(s.assets, s.frame, *s.gpu, uniform_shadow(1.0f));

  // Empty shadow map: lit everywhere the surface faces the lamp. Lighting agrees to rounding.
  const VoxelGpuOutput lit = run_voxelize(*s.gpu, uniform_shadow(1.0f), 16);
  const VoxelSums lit_ref = reference_voxelize(base, 16);
  const std::vector<float> lit_level0 = reference_resolve(lit_ref);
  size_t bad = 0, brighter = 0;
  for (size_t v = 0; v < lit_ref.overflow.size(); ++v) {
    if (word(lit.sums, v, 3) != word(lit_ref, v, 3) && bad++ < 6)
      ADD_FAILURE() << "opacity sum differs at voxel " << v;
    for (int c = 0; c < 3; ++c) {
      const float g = lit.level0[4 * v + c], r = lit_level0[4 * v + c];
      if (!(std::fabs(g - r) <= 2e-4f + 2e-4f * std::fabs(r)) && bad++ < 6)
        ADD_FAILURE() << "voxel " << v << " channel " << c << ": " << g << " vs " << r;
    }
  }
  EXPECT_EQ(bad, 0u);

  // Fully occluded map (depth 0 = at the near plane): exactly the emission-only sums.
  const std::vector<float> occluded = uniform_shadow(0.0f);
  const VoxelGpuOutput dark = run_voxelize(*s.gpu, occluded, 16);
  VoxelRefInput dark_in = base;
  dark_in.shadow = occluded;
  EXPECT_EQ(sums_mismatches(dark.sums, reference_voxelize(dark_in, 16), "occluded"), 0u);
  Scene unlit = exact_scene();  // intensity 0
  const VoxelGpuOutput emission_only = run_voxelize(*unlit.gpu, uniform_shadow(1.0f), 16);
  EXPECT_EQ(count_mismatches(dark.sums.accum, emission_only.sums.accum, "occluded vs unlit"), 0u);
  size_t facing_diff = 0;
  for (size_t v = 0; v < lit_ref.overflow.size(); ++v) {
    brighter += word(lit.sums, v, 0) > word(dark.sums, v, 0);
    for (size_t w = 4; w < kAccumWords; ++w)  // the facing coverage does not see the light
      facing_diff += word(lit.sums, v, w) != word(dark.sums, v, w);
  }
  EXPECT_EQ(facing_diff, 0u);
  EXPECT_GT(brighter, 100u);  // the light does reach the voxels
}

// A striped shadow map (occluder columns 2 texels wide every 5 at depth 0.5, between the lamp
// and the scene): the 4 soft-shadow taps see 0 to 4 of them, so voxels get partial
// visibility; lighting agrees with the reference to rounding except where a tap's texel lies
// within rounding of a texel border (a few voxels).
TEST(Voxelize, SoftShadowMatchesReference) {
  Scene s = exact_scene();
  s.frame.light.intensity = glm::vec3(6.0f, 5.0f, 4.0f);
  s.upload();
  std::vector<float> stripes = uniform_shadow(1.0f);
  for (size_t i = 0; i < stripes.size(); ++i)
    if (i % kShadowSize % 5 < 2) stripes[i] = 0.5f;
  const VoxelGpuOutput got = run_voxelize(*s.gpu, stripes, 16);
  const VoxelSums want = reference_voxelize(reference_input(s.assets, s.frame, *s.gpu, stripes), 16);
  const std::vector<float> want0 = reference_resolve(want);
  const VoxelGpuOutput lit = run_voxelize(*s.gpu, uniform_shadow(1.0f), 16);
  size_t bad = 0, dimmer = 0;
  for (size_t v = 0; v < want.overflow.size(); ++v) {
    bool differs = false;
    for (int c = 0; c < 3; ++c) {
      const float g = got.level0[4 * v + c], r = want0[4 * v + c];
      differs |= !(std::fabs(g - r) <= 2e-4f + 2e-4f * std::fabs(r));
    }
    bad += differs;
    dimmer += got.level0[4 * v] < lit.level0[4 * v] - 1e-4f;
  }
  EXPECT_LE(bad, 3u);
  EXPECT_GT(dimmer, 50u);  // the stripes do shadow
}

// Many triangles over several instances (more than the 16 lanes of a CPU work-item, a mix of
// small and large ones, an instance that is not voxelized in between): the sums at every lane
// count (ROLYPOLY_VOXELIZE_SPAN: 1 is the GPU layout) and with a large triangle's columns shared
// by several work-items (ROLYPOLY_VOXELIZE_SLICES, as on GPUs) equal the reference exactly for
// emission and agree to rounding when lit.
struct SpanLayout {
  const char* span;
  const char* slices;
};
void PrintTo(const SpanLayout& l, std::ostream* os) {
  *os << "span " << l.span << ", slices " << l.slices;
}
class VoxelizeSpans : public ::testing::TestWithParam<SpanLayout> {};

Scene many_triangles_scene() {
  Scene s;
  s.assets = base_assets();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> pos(-1.1f, 1.1f), size(0.01f, 0.6f);
  std::vector<TriSpec> tris;
  for (int i = 0; i < 70; ++i) {
    const glm::vec3 a(pos(rng), pos(rng), pos(rng));
    const float k = i % 5 == 0 ? 3.0f * size(rng) : 0.2f * size(rng);  // some large ones
    const glm::vec3 b = a + k * glm::vec3(pos(rng), pos(rng), pos(rng));
    const glm::vec3 c = a + k * glm::vec3(pos(rng), pos(rng), pos(rng));
    tris.push_back({a, b, c, uint32_t(i % 4)});
  }
  s.assets.meshes.push_back(make_mesh(tris));
  add_instance(s, 0, glm::mat4(1.0f));
  add_instance(s, 0, glm::rotate(glm::mat4(1.0f), 0.9f, glm::vec3(0.3f, 1.0f, 0.2f)));
  s.frame.instances.back().voxelize = false;
  add_instance(s, 0, glm::scale(glm::translate(glm::mat4(1.0f), {0.1f, -0.2f, 0.05f}),
                                glm::vec3(0.8f, 1.1f, 0.9f)));
  s.frame.light.intensity = glm::vec3(0.0f);  // emission only: exact radiance
  s.upload();
  return s;
}

TEST_P(VoxelizeSpans, SumsMatchTheReference) {
  struct SpanEnv {
    explicit SpanEnv(const SpanLayout& l) {
      setenv("ROLYPOLY_VOXELIZE_SPAN", l.span, 1);
      setenv("ROLYPOLY_VOXELIZE_SLICES", l.slices, 1);
    }
    ~SpanEnv() {
      unsetenv("ROLYPOLY_VOXELIZE_SPAN");
      unsetenv("ROLYPOLY_VOXELIZE_SLICES");
    }
  } env(GetParam());
  for (int which = 0; which < 2; ++which) {
    Scene s = which == 0 ? exact_scene() : many_triangles_scene();
    const std::vector<float> shadow = uniform_shadow(1.0f);
    const VoxelGpuOutput got = run_voxelize(*s.gpu, shadow, 16);
    const VoxelSums want =
        reference_voxelize(reference_input(s.assets, s.frame, *s.gpu, shadow), 16);
    EXPECT_EQ(sums_mismatches(got.sums, want, "sums"), 0u);

    s.frame.light.intensity = glm::vec3(6.0f, 5.0f, 4.0f);
    s.upload();
    const VoxelGpuOutput lit = run_voxelize(*s.gpu, shadow, 16);
    const std::vector<float> lit_ref = reference_resolve(
        reference_voxelize(reference_input(s.assets, s.frame, *s.gpu, shadow), 16));
    size_t bad = 0;
    for (size_t i = 0; i < lit_ref.size(); ++i)
      if (!(std::fabs(lit.level0[i] - lit_ref[i]) <= 2e-4f + 2e-4f * std::fabs(lit_ref[i])) &&
          bad++ < 6)
        ADD_FAILURE() << "lit element " << i << ": " << lit.level0[i] << " vs " << lit_ref[i];
    EXPECT_EQ(bad, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Spans, VoxelizeSpans,
                         ::testing::Values(SpanLayout{"1", "1"}, SpanLayout{"4", "1"},
                                           SpanLayout{"8", "1"}, SpanLayout{"16", "1"},
                                           SpanLayout{"1", "16"}, SpanLayout{"8", "4"}),
                         [](const ::testing::TestParamInfo<SpanLayout>& p) {
                           return std::string("span") + p.param.span + "_slices" +
                                  p.param.slices;
                         });

// The static surface cache (voxelize_large's samples of instances that have not moved) across
// frames of one pass: all instances still (all cached), one moved (rebuilt without it, its
// large triangles shaded directly), the same frame again (cache reused), a resolution change
// (tracking restarts). Every frame's sums equal the reference exactly (emission only) and the
// lit levels agree with the pass run without the cache (and without shared columns) bit for bit.
TEST(Voxelize, StaticCacheGivesTheSameSumsAsFrameByFrame) {
  Scene s = many_triangles_scene();
  const std::vector<float> shadow = uniform_shadow(1.0f);
  passes::VoxelizePass pass(context(), programs());
  render::VoxelVolume vol;
  const glm::mat4 moved =
      glm::rotate(glm::translate(glm::mat4(1.0f), {0.05f, 0.1f, -0.02f}), 0.3f,
                  glm::vec3(0.0f, 1.0f, 0.0f));
  struct Step {
    bool move;
    uint32_t r;
  };
  for (const Step step : {Step{false, 16}, Step{true, 16}, Step{false, 16}, Step{false, 32}}) {
    if (step.move) s.frame.instances[0].model = s.frame.instances[0].prev_model = moved;
    for (float intensity : {0.0f, 5.0f}) {
      s.frame.light.intensity = glm::vec3(intensity);
      s.gpu->update(s.frame, 16, 16, kShadowSize);
      // The cached pass shares each large triangle's columns among 4 work-items (as GPUs do),
      // the direct one does not.
      setenv("ROLYPOLY_VOXELIZE_SLICES", "4", 1);
      const VoxelGpuOutput got = run_voxelize(pass, vol, *s.gpu, shadow, step.r);
      unsetenv("ROLYPOLY_VOXELIZE_SLICES");
      if (intensity == 0.0f) {
        const VoxelSums want =
            reference_voxelize(reference_input(s.assets, s.frame, *s.gpu, shadow), step.r);
        EXPECT_EQ(sums_mismatches(got.sums, want, "sums"), 0u);
      }
      setenv("ROLYPOLY_VOXELIZE_CACHE", "0", 1);
      const VoxelGpuOutput direct = run_voxelize(*s.gpu, shadow, step.r);
      unsetenv("ROLYPOLY_VOXELIZE_CACHE");
      EXPECT_EQ(count_mismatches(got.sums.accum, direct.sums.accum, "cached vs direct"), 0u);
      EXPECT_TRUE(got.level0 == direct.level0) << "level 0 with and without the cache";
    }
  }
}

// The cached samples' direct light (the lamp's, with its shadow map) is stored and reused
// while what it depends on stays the same: the lights, the shadow views and every instance and
// sphere (the renderer draws the shadow maps from them and redraws them only when one
// changes), and the depth buffer itself. Reuse is visible by rewriting the map behind the
// pass's back: the stored light stays; a moved sphere then makes the pass compute it again.
TEST(Voxelize, StaticCacheReusesTheDirectLightWhileLightsAndObjectsStayStill) {
  constexpr uint32_t kR = 16;
  Scene s = many_triangles_scene();
  s.frame.light.intensity = glm::vec3(5.0f);
  s.gpu->update(s.frame, 16, 16, kShadowSize);
  const std::vector<float> open = uniform_shadow(1.0f), closed = uniform_shadow(0.0f);
  const auto per_frame = [&](const std::vector<float>& shadow) {
    setenv("ROLYPOLY_VOXELIZE_CACHE", "0", 1);
    VoxelGpuOutput out = run_voxelize(*s.gpu, shadow, kR);
    unsetenv("ROLYPOLY_VOXELIZE_CACHE");
    return out.level0;
  };
  const std::vector<float> lit = per_frame(open), dark = per_frame(closed);
  ASSERT_FALSE(lit == dark) << "the shadow map must light the voxels";

  passes::VoxelizePass pass(context(), programs());
  render::VoxelVolume vol;
  render::ShadowMap map;  // one depth buffer for every run, as the renderer's
  const auto cached = [&](const std::vector<float>& shadow) {
    return run_voxelize(pass, vol, *s.gpu, shadow, kR, nullptr, 0, &map).level0;
  };
  EXPECT_TRUE(cached(closed) == dark) << "the run that builds the cache";
  EXPECT_TRUE(cached(closed) == dark) << "the next run, reusing the stored light";
  EXPECT_TRUE(cached(open) == dark) << "the map changed behind the pass: the stored light stays";

  s.frame.spheres = {sphere({0.3f, -0.5f, 0.45f}, 0.1f, {0.0f, 0.0f, 0.0f})};
  s.gpu->update(s.frame, 16, 16, kShadowSize);
  const std::vector<float> with_sphere = per_frame(open);
  EXPECT_TRUE(cached(open) == with_sphere) << "an object moved: the light is computed again";
  s.frame.spheres[0].center.x += 0.01f;
  s.gpu->update(s.frame, 16, 16, kShadowSize);
  EXPECT_TRUE(cached(closed) == per_frame(closed)) << "the sphere moved again";
  s.frame.light.intensity = glm::vec3(4.0f, 5.0f, 6.0f);
  s.gpu->update(s.frame, 16, 16, kShadowSize);
  EXPECT_TRUE(cached(open) == per_frame(open)) << "the lamp changed";
  EXPECT_TRUE(cached(open) == per_frame(open)) << "and stays";
}

// The fast mode's bounce-light refresh (VoxelizePass::set_bounce_refresh_stride): the cached
// samples keep the bounce grid's light of the run that last refreshed them, one in `stride` of
// them refreshed per run. The run that builds the cache refreshes all; after the grid changes,
// one run brings about a quarter of the cached voxels up to date (and not all of them), and
// `stride` runs all of them: the volume then equals the per-frame pass's bit for bit.
TEST(Voxelize, StaticCacheRefreshesTheBounceLightOverStrideRuns) {
  Scene s = many_triangles_scene();
  const std::vector<float> shadow = uniform_shadow(1.0f);
  constexpr uint32_t kR = 16, kCells = 16, kStride = 4;
  s.frame.light.intensity = glm::vec3(5.0f);
  s.gpu->update(s.frame, 16, 16, kShadowSize);
  // Two grids of six faces per cell (rgb irradiance / pi, w the age: gathered), deterministic.
  const size_t faces = size_t(kCells) * kCells * kCells * 6;
  const auto grid_values = [&](uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 0.5f);
    std::vector<float> g(faces * 4);
    for (size_t i = 0; i < faces; ++i) g[4 * i] = u(rng), g[4 * i + 1] = u(rng),
                                       g[4 * i + 2] = u(rng), g[4 * i + 3] = 1.0f;
    return g;
  };
  const std::vector<float> grid_a = grid_values(1), grid_b = grid_values(2);
  rp::cl::Context& ctx = context();
  ::cl::Buffer grid(ctx.context, CL_MEM_READ_WRITE, faces * 16);
  const auto write_grid = [&](const std::vector<float>& g) {
    ctx.queue.enqueueWriteBuffer(grid, CL_TRUE, 0, g.size() * sizeof(float), g.data());
  };
  const auto per_frame = [&](const std::vector<float>& g) {
    write_grid(g);
    setenv("ROLYPOLY_VOXELIZE_CACHE", "0", 1);
    VoxelGpuOutput out = run_voxelize(*s.gpu, shadow, kR, &grid, kCells);
    unsetenv("ROLYPOLY_VOXELIZE_CACHE");
    return out;
  };
  const VoxelGpuOutput want_a = per_frame(grid_a), want_b = per_frame(grid_b);
  ASSERT_NE(want_a.level0, want_b.level0) << "the two grids must light the voxels differently";

  // The fraction of the voxels lit differently by the two grids that a volume shows as B.
  size_t differing = 0;
  for (size_t v = 0; v < want_a.level0.size() / 4; ++v)
    differing += !std::equal(&want_a.level0[4 * v], &want_a.level0[4 * v + 4],
                             &want_b.level0[4 * v]);
  ASSERT_GT(differing, 100u);
  const auto fraction_at_b = [&](const VoxelGpuOutput& got) {
    size_t at_b = 0;
    for (size_t v = 0; v < got.level0.size() / 4; ++v) {
      const bool differs =
          !std::equal(&want_a.level0[4 * v], &want_a.level0[4 * v + 4], &want_b.level0[4 * v]);
      at_b += differs && std::equal(&got.level0[4 * v], &got.level0[4 * v + 4],
                                    &want_b.level0[4 * v]);
    }
    return double(at_b) / double(differing);
  };
  // Each pass builds its cache under grid A (refreshing all), then runs once under grid B.
  const auto pass_with_stride = [&](uint32_t stride, render::VoxelVolume& vol) {
    auto pass = std::make_unique<passes::VoxelizePass>(context(), programs());
    pass->set_bounce_refresh_stride(stride);
    write_grid(grid_a);
    const VoxelGpuOutput first = run_voxelize(*pass, vol, *s.gpu, shadow, kR, &grid, kCells);
    EXPECT_TRUE(first.level0 == want_a.level0) << "the run that builds the cache refreshes all";
    write_grid(grid_b);
    return pass;
  };
  // Voxels without cached samples (small triangles only, shaded every run) show B at once:
  // the baseline is a pass that refreshes almost nothing (1 in 256).
  render::VoxelVolume vol_slow, vol;
  auto slow = pass_with_stride(256, vol_slow);
  const double baseline =
      fraction_at_b(run_voxelize(*slow, vol_slow, *s.gpu, shadow, kR, &grid, kCells));
  ASSERT_LT(baseline, 0.8) << "most differing voxels must hold cached samples";
  auto pass = pass_with_stride(kStride, vol);
  for (uint32_t run = 1; run <= kStride; ++run) {
    const VoxelGpuOutput got = run_voxelize(*pass, vol, *s.gpu, shadow, kR, &grid, kCells);
    if (run == 1) {
      // The cached voxels refresh together (the hash is per voxel): about 1 in kStride.
      const double refreshed = (fraction_at_b(got) - baseline) / (1.0 - baseline);
      EXPECT_GT(refreshed, 0.12) << "one run refreshes about a quarter";
      EXPECT_LT(refreshed, 0.40) << "one run refreshes about a quarter, not all";
    }
    if (run < kStride) EXPECT_FALSE(got.level0 == want_b.level0) << "run " << run;
    else EXPECT_TRUE(got.level0 == want_b.level0) << "after " << kStride << " runs: all fresh";
  }
  // Stride 1: every run exact.
  pass->set_bounce_refresh_stride(1);
  write_grid(grid_a);
  EXPECT_TRUE(run_voxelize(*pass, vol, *s.gpu, shadow, kR, &grid, kCells).level0 ==
              want_a.level0);
}

// ---- no gaps ----

glm::dvec3 closest_on_triangle(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  // Ericson, Real-Time Collision Detection 5.1.5, in double precision.
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

TEST(Voxelize, ThinSlantedStripHasNoGaps) {
  const uint32_t R = 32;  // voxel 0.0625; the strip is 0.012 wide
  Scene s;
  s.assets = base_assets();
  std::vector<TriSpec> tris;
  auto curve = [](float t) {
    return glm::vec3(-0.8f + 1.6f * t, -0.6f + 1.1f * t + 0.2f * std::sin(3.0f * t),
                     -0.5f + 0.9f * t * t);
  };
  const glm::vec3 width = glm::normalize(glm::vec3(0.3f, -0.2f, 1.0f)) * 0.006f;
  const int segments = 30;
  for (int i = 0; i < segments; ++i) {
    const glm::vec3 p0 = curve(float(i) / segments), p1 = curve(float(i + 1) / segments);
    tris.push_back({p0 - width, p1 - width, p1 + width, 0});
    tris.push_back({p0 - width, p1 + width, p0 + width, 0});
  }
  s.assets.meshes.push_back(make_mesh(tris));
  add_instance(s, 0, glm::mat4(1.0f));
  s.upload();
  const VoxelGpuOutput got = run_voxelize(*s.gpu, uniform_shadow(1.0f), R);

  auto index = [&](int x, int y, int z) { return (size_t(z) * R + size_t(y)) * R + size_t(x); };
  std::vector<char> in_set(size_t(R) * R * R, 0);
  size_t count = 0;
  for (size_t v = 0; v < in_set.size(); ++v) count += in_set[v] = word(got.sums, v, 3) != 0;
  ASSERT_GT(count, 40u);

  // 1. Exactly the voxels the exact test accepts for some triangle (brute force, all voxels).
  size_t missing = 0, extra = 0;
  for (int z = 0; z < int(R); ++z)
    for (int y = 0; y < int(R); ++y)
      for (int x = 0; x < int(R); ++x) {
        bool any = false;
        for (const TriSpec& t : tris) {
          const std::array<RefF3, 3> obj = {RefF3{t.a.x, t.a.y, t.a.z}, RefF3{t.b.x, t.b.y, t.b.z},
                                            RefF3{t.c.x, t.c.y, t.c.z}};
          if (reference_triangle_box(reference_grid_triangle(s.gpu->host_instances[0].model, obj, R),
                                     R, x, y, z)) {
            any = true;
            break;
          }
        }
        missing += any && !in_set[index(x, y, z)];
        extra += !any && in_set[index(x, y, z)];
      }
  EXPECT_EQ(missing, 0u);
  EXPECT_EQ(extra, 0u);

  // 2. 6-connected (closed boxes: a connected surface crossing an edge or corner touches every
  //    voxel sharing it).
  std::vector<char> seen(in_set.size(), 0);
  std::deque<glm::ivec3> queue;
  for (size_t v = 0; v < in_set.size() && queue.empty(); ++v)
    if (in_set[v]) {
      queue.push_back(glm::ivec3(int(v % R), int(v / R % R), int(v / (size_t(R) * R))));
      seen[v] = 1;
    }
  size_t reached = 0;
  const glm::ivec3 steps[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  while (!queue.empty()) {
    const glm::ivec3 v = queue.front();
    queue.pop_front();
    ++reached;
    for (const glm::ivec3& d : steps) {
      const glm::ivec3 w = v + d;
      if (w.x < 0 || w.y < 0 || w.z < 0 || w.x >= int(R) || w.y >= int(R) || w.z >= int(R)) continue;
      const size_t i = index(w.x, w.y, w.z);
      if (in_set[i] && !seen[i]) {
        seen[i] = 1;
        queue.push_back(w);
      }
    }
  }
  EXPECT_EQ(reached, count) << "the strip's voxels are not 6-connected";

  // 3. Dense samples on every triangle fall into touched voxels (independent of the SAT code).
  size_t uncovered = 0;
  const int n = 48;
  for (const TriSpec& t : tris)
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n - i; ++j) {
        const glm::dvec3 a(t.a), b(t.b), c(t.c);
        const glm::dvec3 p = a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n);
        const glm::ivec3 v = glm::ivec3(glm::floor((p + 1.0) * (R * 0.5)));
        uncovered += !in_set[index(v.x, v.y, v.z)];
      }
  EXPECT_EQ(uncovered, 0u);

  // 4. Nothing far away: every touched voxel's centre is within half a diagonal of the strip.
  const double s_world = 2.0 / R, reach = std::sqrt(3.0) * 0.5 * s_world * (1.0 + 1e-5);
  size_t far_away = 0;
  for (int z = 0; z < int(R); ++z)
    for (int y = 0; y < int(R); ++y)
      for (int x = 0; x < int(R); ++x) {
        if (!in_set[index(x, y, z)]) continue;
        const glm::dvec3 c = (glm::dvec3(x, y, z) + 0.5) * s_world - 1.0;
        double best = 1e9;
        for (const TriSpec& t : tris)
          best = std::min(best, glm::length(c - closest_on_triangle(c, glm::dvec3(t.a),
                                                                    glm::dvec3(t.b),
                                                                    glm::dvec3(t.c))));
        far_away += best > reach;
      }
  EXPECT_EQ(far_away, 0u);
}

// ---- spheres ----

TEST(Voxelize, SpheresCoverTheVoxelsTheyIntersect) {
  const uint32_t R = 32;
  const double s_world = 2.0 / R;
  Scene s;
  s.assets = base_assets();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> pos(-0.8f, 0.8f);
  for (float r : {0.004f, 0.02f, 0.04f, 0.1f, 0.3f, 0.012f, 0.05f})
    s.frame.spheres.push_back(sphere({pos(rng), pos(rng), pos(rng)}, r, {1.0f, 2.0f, 3.0f}));
  // A tiny sphere centred on a voxel corner: its projected area splits evenly over 8 voxels.
  const glm::vec3 corner(-1.0f + 10 * 0.0625f, -1.0f + 12 * 0.0625f, -1.0f + 7 * 0.0625f);
  s.frame.spheres.push_back(sphere(corner, 0.004f, {1.0f, 1.0f, 1.0f}));
  s.upload();
  const VoxelGpuOutput got = run_voxelize(*s.gpu, uniform_shadow(1.0f), R);

  size_t mismatched = 0, ambiguous = 0, touched = 0;
  for (int z = 0; z < int(R); ++z)
    for (int y = 0; y < int(R); ++y)
      for (int x = 0; x < int(R); ++x) {
        bool hit = false, unsure = false;
        for (const scene::Sphere& sp : s.frame.spheres) {
          double d2 = 0;
          const glm::dvec3 c(sp.center);
          const double lo[3] = {x * s_world - 1.0, y * s_world - 1.0, z * s_world - 1.0};
          for (int a = 0; a < 3; ++a) {
            const double d = std::max({lo[a] - c[a], c[a] - (lo[a] + s_world), 0.0});
            d2 += d * d;
          }
          const double r2 = double(sp.radius) * sp.radius;
          hit |= d2 < r2;
          unsure |= std::fabs(d2 - r2) < 1e-6 * r2;
        }
        const size_t v = (size_t(z) * R + y) * R + x;
        const bool in = word(got.sums, v, 3) != 0;
        touched += in;
        if (unsure) {
          ++ambiguous;
          continue;
        }
        mismatched += in != hit;
      }
  EXPECT_EQ(mismatched, 0u);
  EXPECT_LT(ambiguous, 3u);
  EXPECT_GT(touched, 500u);

  // Opacity: the corner sphere's 8 voxels share pi (r / s)^2; a voxel well inside the large
  // sphere is opaque.
  const int cx = 10, cy = 12, cz = 7;
  double sum = 0;
  for (int dz = -1; dz <= 0; ++dz)
    for (int dy = -1; dy <= 0; ++dy)
      for (int dx = -1; dx <= 0; ++dx)
        sum += got.level0[4 * ((size_t(cz + dz) * R + (cy + dy)) * R + (cx + dx)) + 3];
  const double expected = M_PI * std::pow(0.004 / s_world, 2.0);
  EXPECT_NEAR(sum, expected, 1e-4);
  const glm::dvec3 big(s.frame.spheres[4].center);
  const glm::ivec3 inside = glm::ivec3(glm::floor((big + 1.0) / s_world));
  EXPECT_EQ(got.level0[4 * ((size_t(inside.z) * R + inside.y) * R + inside.x) + 3], 1.0f);
}

TEST(Voxelize, OverflowSaturatesInsteadOfWrapping) {
  Scene s;
  s.assets = base_assets();
  for (int i = 0; i < 6; ++i)
    s.frame.spheres.push_back(sphere({0.1f, 0.1f, 0.1f}, 0.2f, {20000.0f, 1.0f, 0.0f}));
  s.frame.light.intensity = glm::vec3(0.0f);
  s.upload();
  const std::vector<float> shadow = uniform_shadow(1.0f);
  const VoxelGpuOutput got = run_voxelize(*s.gpu, shadow, 16);
  const VoxelSums want = reference_voxelize(reference_input(s.assets, s.frame, *s.gpu, shadow), 16);
  EXPECT_EQ(sums_mismatches(got.sums, want, "sums"), 0u);
  // The voxel holding the centre: six opaque contributions of red 20000 (sum 120000 > 65536).
  const size_t v = (size_t(8) * 16 + 8) * 16 + 8;  // grid (8.8, 8.8, 8.8)
  EXPECT_EQ(got.sums.overflow[v], 1u);
  EXPECT_FLOAT_EQ(got.level0[4 * v + 0], render::kVoxelSaturatedSum / 6.0f);
  EXPECT_FLOAT_EQ(got.level0[4 * v + 1], 1.0f);
  EXPECT_FLOAT_EQ(got.level0[4 * v + 3], 1.0f);
}

// ---- facing coverage ----

// A floor quad (two triangles, normal +y, inside voxel layer y = 2 of R = 16) and a large
// sphere: the floor's voxels have coverage only in the half facing +y (128 per triangle
// touching the voxel), the sphere's in all six halves alike; both exactly as the reference.
// Through the mip builder, level 1 over the floor is opaque for cones travelling -y (onto its
// front), transparent for cones leaving its front (+y) and for cones along x or z (edge-on);
// the sphere's level-1 voxel at its centre is opaque in all six directions.
TEST(Voxelize, FacingCoverageOfAWallAndASphere) {
  const uint32_t R = 16;
  const float y = -0.7f;  // grid (y + 1) * 8 = 2.4: layer 2
  Scene s;
  s.assets = base_assets();
  const float e = 0.45f;  // grid 4.4 .. 11.6: voxels 4 .. 11 along x and z
  s.assets.meshes.push_back(make_mesh({{{-e, y, -e}, {-e, y, e}, {e, y, -e}, 2},
                                       {{-e, y, e}, {e, y, e}, {e, y, -e}, 2}}));
  add_instance(s, 0, glm::mat4(1.0f));
  const glm::vec3 centre(0.3f, 0.4f, 0.2f);  // grid (10.4, 11.2, 9.6); radius 2.4 voxels
  s.frame.spheres.push_back(sphere(centre, 0.3f, {1.0f, 0.5f, 0.25f}));
  s.frame.light.intensity = glm::vec3(0.0f);
  s.upload();
  const std::vector<float> shadow = uniform_shadow(1.0f);
  passes::VoxelizePass pass(context(), programs());
  render::VoxelVolume vol;
  const VoxelGpuOutput got = run_voxelize(pass, vol, *s.gpu, shadow, R);
  const VoxelSums want = reference_voxelize(reference_input(s.assets, s.frame, *s.gpu, shadow), R);
  EXPECT_EQ(sums_mismatches(got.sums, want, "sums"), 0u);
  for (uint32_t slack : want.facing_slack) EXPECT_EQ(slack, 0u);  // axis-aligned: no ties

  auto index = [&](int x, int yy, int z) { return (size_t(z) * R + size_t(yy)) * R + size_t(x); };
  size_t floor_voxels = 0, sphere_voxels = 0;
  for (int z = 0; z < int(R); ++z)
    for (int yy = 0; yy < int(R); ++yy)
      for (int x = 0; x < int(R); ++x) {
        const size_t v = index(x, yy, z);
        const uint32_t opacity = word(got.sums, v, 3);
        EXPECT_EQ(word(got.sums, v, 7), 0u);
        if (opacity == 0) {
          for (size_t w = 4; w < 7; ++w) EXPECT_EQ(word(got.sums, v, w), 0u) << "empty voxel " << v;
          continue;
        }
        if (yy == 2) {  // the floor: one opaque contribution per triangle touching the voxel
          ++floor_voxels;
          const uint32_t triangles = opacity >> 16;
          EXPECT_EQ(opacity & 0xFFFFu, 0u);
          EXPECT_TRUE(triangles == 1u || triangles == 2u);
          EXPECT_EQ(word(got.sums, v, 4), 0u) << "x coverage at " << v;
          EXPECT_EQ(word(got.sums, v, 5), 128u * triangles) << "+y only at " << v;
          EXPECT_EQ(word(got.sums, v, 6), 0u) << "z coverage at " << v;
          EXPECT_TRUE(x >= 4 && x <= 11 && z >= 4 && z <= 11) << x << " " << z;
        } else {  // the sphere: the same coverage in all six halves (0 where a < 1/256)
          const uint32_t w4 = word(got.sums, v, 4);
          sphere_voxels += w4 != 0u;
          EXPECT_EQ(w4 & 0xFFFFu, w4 >> 16);
          EXPECT_EQ(word(got.sums, v, 5), w4);
          EXPECT_EQ(word(got.sums, v, 6), w4);
        }
      }
  EXPECT_EQ(floor_voxels, 64u);  // x, z = 4 .. 11
  EXPECT_GT(sphere_voxels, 100u);
  // The voxel at the sphere's centre: one full contribution in each half.
  EXPECT_EQ(word(got.sums, index(10, 11, 9), 4), 128u | (128u << 16));

  // Level 1 from this volume.
  passes::VoxelMipsPass mips(context(), programs());
  rp::cl::Profiler profiler(context().queue);
  mips.run(profiler, vol);
  std::vector<float> chain(vol.chain_elements() * 4);
  context().queue.enqueueReadBuffer(vol.chain, CL_TRUE, 0, chain.size() * sizeof(float),
                                    chain.data());
  const uint32_t n = R / 2;
  auto level1_alpha = [&](uint32_t dir, uint32_t x, uint32_t yy, uint32_t z) {
    return chain[4 * (size_t(rp::gpu::rp_voxel_offset(R, 1, dir)) + (z * n + yy) * n + x) + 3];
  };
  for (uint32_t z = 2; z <= 5; ++z)
    for (uint32_t x = 2; x <= 5; ++x) {  // parents whose children all hold the floor
      EXPECT_EQ(level1_alpha(RP_DIR_NEG_Y, x, 1, z), 1.0f) << "onto the floor's front";
      for (uint32_t dir : {RP_DIR_POS_Y, RP_DIR_POS_X, RP_DIR_NEG_X, RP_DIR_POS_Z, RP_DIR_NEG_Z})
        EXPECT_EQ(level1_alpha(dir, x, 1, z), 0.0f) << "direction " << dir;
    }
  for (uint32_t dir = 0; dir < 6; ++dir)
    EXPECT_EQ(level1_alpha(dir, 5, 5, 4), 1.0f) << "sphere, direction " << dir;
}

TEST(Voxelize, EmptySceneGivesEmptyVolume) {
  Scene s;
  s.upload();
  const VoxelGpuOutput got = run_voxelize(*s.gpu, uniform_shadow(1.0f), 8);
  size_t nonzero = 0;
  for (float f : got.level0) nonzero += f != 0.0f;
  for (uint32_t u : got.sums.accum) nonzero += u != 0u;
  EXPECT_EQ(nonzero, 0u);
}

TEST(Voxelize, RejectsMismatchedConstants) {
  Scene s = exact_scene();
  render::VoxelVolume vol;
  vol.resize(context().context, 16);
  render::ShadowMap sm;
  sm.resize(context().context, kShadowSize);
  passes::VoxelizePass pass(context(), programs());
  rp::cl::Profiler profiler(context().queue);
  s.gpu->constants.voxel_resolution = 32;  // the volume is 16^3
  s.gpu->constants.voxel_levels = 6;
  EXPECT_THROW(pass.run(profiler, *s.gpu, sm, vol), rp::cl::Error);
}

}  // namespace
}  // namespace rp::test
