// The voxelizer's texture level: a triangle samples the mip level matching the voxel
// size, lod = log2(voxel side * texels per world unit along the plane's most stretched
// direction), trilinear. Checked on a floor triangle with a known texel density: the reference's
// rule against hand-computed values (uniform, rotated and stretched uv), the device's lit voxels
// against an explicit trilinear sample at that level, and against the base level (which must
// differ: the test sees the level choice).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "passes/voxelize_reference.h"
#include "render/gpu_scene.h"
#include "render/texture_mips.h"
#include "support/cl_fixture.h"

namespace rp::test {
namespace {

constexpr uint32_t kR = 16;            // voxel side 2 / 16 = 0.125
constexpr uint32_t kShadowSize = 64;
constexpr int kTex = 32;               // 6 levels
constexpr float kFloorY = -0.47f;      // grid y 4.24: inside voxel layer 4, off its faces
constexpr float kHalf = 0.9f;          // the triangle's legs run from -0.9 to 0.9
constexpr float kTiles = 2.5f;         // uv 0..2.5 along each leg

scene::Texture random_texture(uint32_t seed) {
  scene::Texture t{"random", kTex, kTex, {}};
  uint32_t s = seed;
  for (int i = 0; i < kTex * kTex * 4; ++i) {
    s = s * 1664525u + 1013904223u;
    t.rgba.push_back(uint8_t(s >> 24));
  }
  return t;
}

// The floor triangle (right angle at (-0.9, y, -0.9), facing +y), uv = (u along x, v along z)
// scaled by (su, sv) and turned by `turn` radians in uv space.
scene::Mesh floor_triangle(float su, float sv, float turn, uint32_t material) {
  const glm::vec3 p[3] = {{-kHalf, kFloorY, -kHalf}, {kHalf, kFloorY, -kHalf},
                          {-kHalf, kFloorY, kHalf}};
  scene::Mesh m;
  m.name = "floor";
  for (const glm::vec3& q : p) {
    const float a = (q.x + kHalf) / (2 * kHalf) * su, b = (q.z + kHalf) / (2 * kHalf) * sv;
    const glm::vec2 uv(a * std::cos(turn) - b * std::sin(turn), a * std::sin(turn) + b * std::cos(turn));
    m.vertices.push_back({q, {0, 1, 0}, uv});
  }
  m.triangles = {{0, 2, 1}};
  m.materials = {material};
  return m;
}

float reference_lod(float su, float sv, float turn) {
  const scene::Mesh m = floor_triangle(su, sv, turn, 0);
  std::array<RefF3, 3> w, uv;
  for (int i = 0; i < 3; ++i) {
    const scene::Vertex& v = m.vertices[size_t(m.triangles[0][i])];
    w[size_t(i)] = {v.position.x, v.position.y, v.position.z};
    uv[size_t(i)] = {v.uv.x, v.uv.y, 0.0f};
  }
  return reference_texture_lod(w, uv, kTex, kTex, 6, kR);
}

TEST(VoxelizeTexture, LevelMatchesTheVoxelFootprint) {
  // kTex * kTiles texels over 1.8 world units; a voxel is 0.125 wide.
  const double want = std::log2(0.125 * kTex * kTiles / (2 * kHalf));  // 2.474
  EXPECT_NEAR(reference_lod(kTiles, kTiles, 0.0f), want, 1e-5);
  EXPECT_NEAR(reference_lod(kTiles, kTiles, 0.5f), want, 1e-5);  // turned uv: same footprint
  EXPECT_NEAR(reference_lod(kTiles, 1.0f, 0.0f), want, 1e-5);    // stretched: the larger axis
  EXPECT_NEAR(reference_lod(1.0f, kTiles, 0.3f), want, 1e-5);
  EXPECT_EQ(reference_lod(0.1f, 0.1f, 0.0f), 0.0f);  // magnified: the base level
}

// Lit voxel colours of the floor triangle with `material`.
std::vector<float> lit_level0(uint32_t material) {
  auto& ctx = context();
  scene::SceneAssets assets;
  assets.textures.push_back(random_texture(3));
  assets.materials = {{"textured", {1, 1, 1}, {0, 0, 0}, 0}, {"plain", {1, 1, 1}, {0, 0, 0}, -1}};
  assets.meshes.push_back(floor_triangle(kTiles, kTiles, 0.0f, material));
  scene::FrameScene frame;
  scene::MeshInstance inst;
  inst.mesh = 0;
  inst.model = inst.prev_model = glm::mat4(1.0f);
  frame.instances.push_back(inst);
  render::GpuScene gpu(ctx.context, ctx.queue, assets);
  gpu.update(frame, 16, 16, kShadowSize);
  const std::vector<float> unshadowed(size_t(kShadowSize) * kShadowSize, 1.0f);
  return run_voxelize(gpu, unshadowed, kR).level0;
}

TEST(VoxelizeTexture, DeviceSamplesTheMatchingLevelTrilinearly) {
  const std::vector<float> textured = lit_level0(0), plain = lit_level0(1);
  const render::MipChain chain = render::build_mip_chain(random_texture(3));
  // Level k as linear rgb, bilinear with wrap (texel row = (1 - v) * height).
  auto bilinear = [&](size_t k, double u, double v) {
    const render::MipLevel& l = chain.levels[k];
    const int w = int(l.width), h = int(l.height);
    const double x = u * w - 0.5, y = (1.0 - v) * h - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
    auto at = [&](double xi, double yi) {
      const int tx = ((int(xi) % w) + w) % w, ty = ((int(yi) % h) + h) % h;
      const uint32_t t = chain.texels[l.offset + size_t(ty) * w + tx];
      return glm::dvec3(render::srgb8_decode(t & 0xFF), render::srgb8_decode((t >> 8) & 0xFF),
                        render::srgb8_decode((t >> 16) & 0xFF));
    };
    return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx),
                    glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
  };
  const double lod = std::log2(0.125 * kTex * kTiles / (2 * kHalf));
  const size_t l0 = size_t(std::floor(lod));
  size_t checked = 0, bad = 0, differs = 0;
  const int j = 4;  // the floor's voxel layer
  for (int k = 0; k < int(kR); ++k)
    for (int i = 0; i < int(kR); ++i) {
      const double x = (i + 0.5) / 8.0 - 1.0, z = (k + 0.5) / 8.0 - 1.0;
      // Voxels well inside the triangle (its shading point is the voxel centre's projection).
      const double m = 0.2;
      if (x < -kHalf + m || z < -kHalf + m || x + z > -m) continue;
      const size_t v = (size_t(k) * kR + size_t(j)) * kR + size_t(i);
      const double u = (x + kHalf) / (2 * kHalf) * kTiles, vv = (z + kHalf) / (2 * kHalf) * kTiles;
      const glm::dvec3 want = glm::mix(bilinear(l0, u, vv), bilinear(l0 + 1, u, vv), lod - l0);
      const glm::dvec3 base = bilinear(0, u, vv);
      ++checked;
      for (int c = 0; c < 3; ++c) {
        ASSERT_GT(plain[4 * v + c], 0.05f) << "voxel " << v << " must be lit";
        const double ratio = textured[4 * v + c] / plain[4 * v + c];
        if (!(std::fabs(ratio - want[c]) <= 2e-3) && bad++ < 6)
          ADD_FAILURE() << "voxel " << i << "," << j << "," << k << " channel " << c << ": "
                        << ratio << " vs trilinear at lod " << lod << " " << want[c];
        differs += std::fabs(ratio - base[c]) > 0.03;
      }
    }
  EXPECT_EQ(bad, 0u);
  EXPECT_GT(checked, 20u);
  EXPECT_GT(differs, checked) << "the base level would not pass: the level choice is seen";
}

}  // namespace
}  // namespace rp::test
