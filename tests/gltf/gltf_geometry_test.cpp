// Meshes from glTF primitives: index types, texture coordinates, interleaving, sparse
// accessors, normals and tangents made where the file has none, primitives merged.
#include <gtest/gtest.h>

#include "gltf/gltf_writer.h"
#include "scene/gltf_loader.h"

namespace rp::test {
namespace {

using scene::load_gltf;
using scene::LoadedScene;

void expect_vec(glm::vec3 got, glm::vec3 want, float tol = 1e-5f) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

// One node drawing one mesh of the given primitives.
std::string single_mesh(GltfBuilder& b, const TempFolder& dir, const Json& primitives) {
  b.mesh(primitives);
  b.scene({b.node({{"mesh", 0}})});
  return b.write_gltf(dir, "scene");
}

TEST(GltfGeometry, ReadsUnsignedByteShortAndIntIndicesAlike) {
  for (const int type : {kU8, kU16, kU32}) {
    TempFolder dir;
    GltfBuilder b;
    const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
    const int idx = b.indices({0, 1, 2, 2, 1, 3}, type);
    const LoadedScene s =
        load_gltf(single_mesh(b, dir, {{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}}));
    ASSERT_EQ(s.assets.meshes.size(), 1u) << type;
    const scene::Mesh& m = s.assets.meshes[0];
    ASSERT_EQ(m.triangles.size(), 2u);
    // No NORMAL: flat shading, three vertices per triangle in triangle order.
    ASSERT_EQ(m.vertices.size(), 6u);
    expect_vec(m.vertices[m.triangles[1].x].position, {0, 1, 0});
    expect_vec(m.vertices[m.triangles[1].z].position, {1, 1, 0});
  }
}

TEST(GltfGeometry, DrawsUnindexedPositionsAsConsecutiveTriangles) {
  TempFolder dir;
  GltfBuilder b;
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}});
  const int nrm = b.vec3s(std::vector<glm::vec3>(6, {0, 0, 1}));
  const LoadedScene s =
      load_gltf(single_mesh(b, dir, {{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}}}));
  const scene::Mesh& m = s.assets.meshes.at(0);
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.triangles[1], glm::uvec3(3, 4, 5));
  expect_vec(m.vertices[4].position, {1, 0, 1});
}

TEST(GltfGeometry, FlipsTextureVToPointUp) {
  TempFolder dir;
  GltfBuilder b;
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int nrm = b.vec3s(std::vector<glm::vec3>(3, {0, 0, 1}));
  const int uv = b.vec2s({{0.25f, 0.1f}, {1, 0}, {0, 1}});
  const LoadedScene s = load_gltf(single_mesh(
      b, dir, {{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}}}}));
  const scene::Mesh& m = s.assets.meshes.at(0);
  EXPECT_FLOAT_EQ(m.vertices[0].uv.x, 0.25f);
  EXPECT_FLOAT_EQ(m.vertices[0].uv.y, 0.9f);  // texel row = (1 - v') * height = glTF's v
  EXPECT_FLOAT_EQ(m.vertices[2].uv.y, 0.0f);
}

TEST(GltfGeometry, ReadsNormalizedByteAndShortTexcoords) {
  TempFolder dir;
  GltfBuilder b;
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int nrm = b.vec3s(std::vector<glm::vec3>(3, {0, 0, 1}));
  const std::vector<uint8_t> u8 = {255, 0, 51, 255, 0, 0, 0, 0};  // 2 bytes per element, padded
  const int uv8 = b.accessor(b.view(u8), kU8, 3, "VEC2", 0, true);
  const std::vector<uint16_t> u16 = {65535, 0, 13107, 65535, 0, 0};
  const int uv16 = b.accessor(b.view(u16), kU16, 3, "VEC2", 0, true);
  b.mesh({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv8}}}},
          {{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv16}}}}});
  b.scene({b.node({{"mesh", 0}})});
  const LoadedScene s = load_gltf(b.write_gltf(dir, "scene"));
  const scene::Mesh& m = s.assets.meshes.at(0);
  ASSERT_EQ(m.vertices.size(), 6u);
  for (size_t base : {0u, 3u}) {
    EXPECT_NEAR(m.vertices[base].uv.x, 1.0f, 1e-6f);
    EXPECT_NEAR(m.vertices[base].uv.y, 1.0f, 1e-6f);  // v 0 -> v' 1
    EXPECT_NEAR(m.vertices[base + 1].uv.x, 0.2f, 1e-6f);
    EXPECT_NEAR(m.vertices[base + 1].uv.y, 0.0f, 1e-6f);
  }
}

TEST(GltfGeometry, HonoursByteStrideOfInterleavedAttributes) {
  TempFolder dir;
  GltfBuilder b;
  struct Interleaved {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
  };
  const std::vector<Interleaved> v = {{{0, 0, 0}, {0, 0, 1}, {0, 0}},
                                      {{2, 0, 0}, {0, 0, 1}, {1, 0}},
                                      {{0, 3, 0}, {0, 0, 1}, {0, 1}}};
  const int view = b.view(v, sizeof(Interleaved));
  const int pos = b.accessor(view, kF32, 3, "VEC3");
  const int nrm = b.accessor(view, kF32, 3, "VEC3", 12);
  const int uv = b.accessor(view, kF32, 3, "VEC2", 24);
  const LoadedScene s = load_gltf(single_mesh(
      b, dir, {{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}}}}));
  const scene::Mesh& m = s.assets.meshes.at(0);
  ASSERT_EQ(m.vertices.size(), 3u);
  expect_vec(m.vertices[1].position, {2, 0, 0});
  expect_vec(m.vertices[2].position, {0, 3, 0});
  expect_vec(m.vertices[2].normal, {0, 0, 1});
  EXPECT_FLOAT_EQ(m.vertices[1].uv.x, 1.0f);
  EXPECT_FLOAT_EQ(m.vertices[2].uv.y, 0.0f);
}

TEST(GltfGeometry, AppliesSparseAccessorValuesOverTheBase) {
  TempFolder dir;
  GltfBuilder b;
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const std::vector<uint8_t> which = {2, 0, 0, 0};
  const std::vector<glm::vec3> values = {{0, 5, 0}};
  const int which_view = b.view(which);
  const int values_view = b.view(values);
  b.doc["accessors"][pos]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", which_view}, {"componentType", kU8}}},
      {"values", {{"bufferView", values_view}}}};
  const LoadedScene s = load_gltf(single_mesh(b, dir, {{{"attributes", {{"POSITION", pos}}}}}));
  const scene::Mesh& m = s.assets.meshes.at(0);
  expect_vec(m.vertices[2].position, {0, 5, 0});
  expect_vec(m.vertices[1].position, {1, 0, 0});
}

TEST(GltfGeometry, GivesFlatNormalsOfTheTrianglePlaneWhenNormalsAreMissing) {
  TempFolder dir;
  GltfBuilder b;
  // A quad tilted about x: its plane's normal is (0, -sin 30, cos 30) seen from the CCW side.
  const float c = std::cos(glm::radians(30.0f)), s30 = std::sin(glm::radians(30.0f));
  const int pos = b.vec3s({{-1, c, s30}, {1, c, s30}, {-1, -c, -s30}, {1, -c, -s30}});
  const int idx = b.indices({0, 2, 1, 1, 2, 3});
  const LoadedScene s =
      load_gltf(single_mesh(b, dir, {{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}}));
  const scene::Mesh& m = s.assets.meshes.at(0);
  ASSERT_EQ(m.vertices.size(), 6u);
  for (const scene::Vertex& v : m.vertices) expect_vec(v.normal, {0, -s30, c});
}

TEST(GltfGeometry, MakesGivenNormalsUnitLength) {
  TempFolder dir;
  GltfBuilder b;
  const int pos = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int nrm = b.vec3s({{0, 0, 3}, {0, 0, 0.5f}, {0, 0, 0}});  // the last has no direction
  const LoadedScene s =
      load_gltf(single_mesh(b, dir, {{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}}}));
  const scene::Mesh& m = s.assets.meshes.at(0);
  for (const scene::Vertex& v : m.vertices) expect_vec(v.normal, {0, 0, 1});
}

// A quad whose uv runs +u along +x and glTF v down the image along -y: tangent +x; and its
// mirror image in u (u along -x): tangent -x, handedness flipped.
TEST(GltfGeometry, ComputesTangentsAlongUForANormalMappedQuad) {
  for (const bool mirrored_u : {false, true}) {
    TempFolder dir;
    GltfBuilder b;
    const GltfBuilder::Quad q = b.quad();
    const int nrm = b.vec3s(std::vector<glm::vec3>(4, {0, 0, 1}));
    int uv = q.uv;
    if (mirrored_u) uv = b.vec2s({{1, 0}, {0, 0}, {1, 1}, {0, 1}});
    const int image = b.image_in_buffer(png(1, 1, {128, 128, 255, 255}));
    b.material({{"normalTexture", {{"index", b.texture(image)}}}});
    const LoadedScene s = load_gltf(single_mesh(
        b, dir,
        {{{"attributes", {{"POSITION", q.position}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}},
          {"indices", q.indices},
          {"material", 0}}}));
    const scene::Mesh& m = s.assets.meshes.at(0);
    ASSERT_EQ(m.tangents.size(), m.vertices.size());
    for (const glm::vec4& t : m.tangents) {
      expect_vec(glm::vec3(t), {mirrored_u ? -1.0f : 1.0f, 0, 0});
      EXPECT_EQ(t.w, mirrored_u ? -1.0f : 1.0f);
      // The bitangent w * cross(n, t) points up the image (+y here) either way.
      expect_vec(t.w * glm::cross(glm::vec3(0, 0, 1), glm::vec3(t)), {0, 1, 0});
    }
  }
}

TEST(GltfGeometry, KeepsTheFilesTangentsAndLeavesThemOutWithoutANormalMap) {
  TempFolder dir;
  GltfBuilder b;
  const GltfBuilder::Quad q = b.quad();
  const int nrm = b.vec3s(std::vector<glm::vec3>(4, {0, 0, 1}));
  const int tan = b.vec4s(std::vector<glm::vec4>(4, {0, 2, 0, -1}));
  const int image = b.image_in_buffer(png(1, 1, {128, 128, 255, 255}));
  b.material({{"normalTexture", {{"index", b.texture(image)}}}});
  b.material({{"name", "plain"}});
  const Json attributes = {{"POSITION", q.position}, {"NORMAL", nrm}, {"TANGENT", tan}};
  b.mesh({{{"attributes", attributes}, {"indices", q.indices}, {"material", 0}}});
  b.mesh({{{"attributes", attributes}, {"indices", q.indices}, {"material", 1}}});
  b.scene({b.node({{"mesh", 0}}), b.node({{"mesh", 1}, {"translation", {5, 0, 0}}})});
  const LoadedScene s = load_gltf(b.write_gltf(dir, "scene"));
  ASSERT_EQ(s.assets.meshes.size(), 2u);
  ASSERT_EQ(s.assets.meshes[0].tangents.size(), 4u);
  EXPECT_EQ(s.assets.meshes[0].tangents[0], glm::vec4(0, 1, 0, -1));
  EXPECT_TRUE(s.assets.meshes[1].tangents.empty());
}

TEST(GltfGeometry, MergesPrimitivesIntoOneMeshWithAMaterialPerTriangle) {
  TempFolder dir;
  GltfBuilder b;
  const GltfBuilder::Quad q = b.quad();
  const int red = b.material({{"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}});
  const int blue = b.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 1, 1}}}}});
  const Json attributes = {{"POSITION", q.position}};
  b.mesh({{{"attributes", attributes}, {"indices", q.indices}, {"material", red}},
          {{"attributes", attributes}, {"indices", q.indices}, {"material", blue}},
          {{"attributes", attributes}, {"indices", q.indices}}});
  b.scene({b.node({{"mesh", 0}})});
  const LoadedScene s = load_gltf(b.write_gltf(dir, "scene"));
  ASSERT_EQ(s.assets.meshes.size(), 1u);
  const scene::Mesh& m = s.assets.meshes[0];
  ASSERT_EQ(m.triangles.size(), 6u);
  ASSERT_EQ(m.materials.size(), 6u);
  const auto& mats = s.assets.materials;
  EXPECT_EQ(mats[m.materials[0]].albedo, glm::vec3(1, 0, 0));
  EXPECT_EQ(mats[m.materials[2]].albedo, glm::vec3(0, 0, 1));
  // No material: glTF's default, white, fully metallic and rough.
  const scene::Material& fallback = mats[m.materials[5]];
  EXPECT_EQ(fallback.albedo, glm::vec3(1));
  EXPECT_EQ(fallback.metallic, 1.0f);
  EXPECT_TRUE(fallback.specular.metal);
  EXPECT_EQ(fallback.specular.roughness, 1.0f);
  for (const glm::uvec3& t : m.triangles)
    for (int k = 0; k < 3; ++k) EXPECT_LT(t[k], m.vertices.size());
}

TEST(GltfGeometry, SkipsPointsAndLinesWithOneWarning) {
  TempFolder dir;
  GltfBuilder b;
  const GltfBuilder::Quad q = b.quad();
  const Json attributes = {{"POSITION", q.position}};
  b.mesh({{{"attributes", attributes}, {"mode", 0}},
          {{"attributes", attributes}, {"mode", 1}},
          {{"attributes", attributes}, {"indices", q.indices}, {"mode", 4}}});
  b.scene({b.node({{"mesh", 0}})});
  const LoadedScene s = load_gltf(b.write_gltf(dir, "scene"));
  EXPECT_EQ(s.assets.meshes.at(0).triangles.size(), 2u);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("TRIANGLES"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("mesh 0 primitive 0, mesh 0 primitive 1"), std::string::npos)
      << s.warnings[0];
}

}  // namespace
}  // namespace rp::test
