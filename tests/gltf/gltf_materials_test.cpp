// glTF materials as rolypoly's: metallic-roughness on the specular coat, textures with their
// colour spaces and wrap modes, emission, alpha modes; images from files, data URIs and
// buffer views.
#include <gtest/gtest.h>

#include "gltf/gltf_writer.h"
#include "scene/gltf_loader.h"

namespace rp::test {
namespace {

using scene::load_gltf;
using scene::LoadedScene;

constexpr int kClamp = 33071, kMirror = 33648, kRepeat = 10497;

// A quad drawn with each of `materials` (one primitive each).
LoadedScene with_materials(GltfBuilder& b, const TempFolder& dir,
                           const std::vector<Json>& materials) {
  const GltfBuilder::Quad q = b.quad();
  const int nrm = b.vec3s(std::vector<glm::vec3>(4, {0, 0, 1}));
  Json primitives = Json::array();
  for (const Json& m : materials)
    primitives.push_back(
        {{"attributes", {{"POSITION", q.position}, {"NORMAL", nrm}, {"TEXCOORD_0", q.uv}}},
         {"indices", q.indices},
         {"material", b.material(m)}});
  b.mesh(primitives);
  b.scene({b.node({{"mesh", 0}})});
  return load_gltf(b.write_gltf(dir, "scene"));
}

const std::vector<uint8_t> kTwoTexels = {10, 20, 30, 255, 200, 100, 50, 128};

TEST(GltfMaterials, MapsMetallicRoughnessOntoTheSpecularCoat) {
  TempFolder dir;
  GltfBuilder b;
  const LoadedScene s = with_materials(
      b, dir,
      {{{"pbrMetallicRoughness", {{"metallicFactor", 0.7}, {"roughnessFactor", 0.3}}}},
       {{"pbrMetallicRoughness", {{"metallicFactor", 0.2}, {"roughnessFactor", 0.9}}}},
       {{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1.0, 0.4}}}}}});
  ASSERT_EQ(s.assets.materials.size(), 3u);
  const scene::Material& metal = s.assets.materials[0];
  EXPECT_TRUE(metal.specular.metal);
  EXPECT_FLOAT_EQ(metal.metallic, 0.7f);
  EXPECT_FLOAT_EQ(metal.specular.roughness, 0.3f);
  const scene::Material& dielectric = s.assets.materials[1];
  EXPECT_FALSE(dielectric.specular.metal);
  EXPECT_FLOAT_EQ(dielectric.specular.f0, 0.04f);
  EXPECT_FLOAT_EQ(dielectric.specular.roughness, 0.9f);
  const scene::Material& coloured = s.assets.materials[2];
  EXPECT_EQ(coloured.albedo, glm::vec3(0.5f, 0.25f, 1.0f));
  EXPECT_FLOAT_EQ(coloured.opacity, 0.4f);
  EXPECT_EQ(coloured.metallic, 1.0f);  // glTF's defaults: metallic 1, roughness 1
  EXPECT_EQ(coloured.specular.roughness, 1.0f);
  EXPECT_EQ(coloured.alpha_mode, scene::AlphaMode::kOpaque);
  EXPECT_FALSE(coloured.double_sided);
}

TEST(GltfMaterials, DerivesTheCoatsReflectanceFromKhrMaterialsIor) {
  TempFolder dir;
  GltfBuilder b;
  b.use_extension("KHR_materials_ior");
  auto ior = [](double n) { return Json{{"extensions", {{"KHR_materials_ior", {{"ior", n}}}}}}; };
  const LoadedScene s = with_materials(b, dir, {ior(1.5), ior(1.0), ior(2.0), Json::object()});
  const auto& m = s.assets.materials;
  EXPECT_FLOAT_EQ(m.at(0).specular.f0, 0.04f);
  EXPECT_FLOAT_EQ(m.at(1).specular.f0, 0.0f);  // n = 1: no coat
  EXPECT_FLOAT_EQ(m.at(2).specular.f0, 1.0f / 9.0f);
  EXPECT_FLOAT_EQ(m.at(3).specular.f0, 0.04f);  // glTF's default n = 1.5
  EXPECT_TRUE(s.warnings.empty());
}

TEST(GltfMaterials, GivesOneImageUsedAsColourAndAsDataATextureForEach) {
  TempFolder dir;
  GltfBuilder b;
  const int tex = b.texture(b.image_in_buffer(png(2, 1, kTwoTexels)));
  const LoadedScene s = with_materials(
      b, dir,
      {{{"pbrMetallicRoughness",
         {{"baseColorTexture", {{"index", tex}}}, {"metallicRoughnessTexture", {{"index", tex}}}}},
        {"normalTexture", {{"index", tex}, {"scale", 0.5}}},
        {"emissiveTexture", {{"index", tex}}},
        {"emissiveFactor", {1, 1, 1}}}});
  ASSERT_EQ(s.assets.textures.size(), 2u);
  const scene::Material& m = s.assets.materials.at(0);
  ASSERT_GE(m.texture, 0);
  EXPECT_TRUE(s.assets.textures[static_cast<size_t>(m.texture)].srgb);
  EXPECT_EQ(m.emission_texture, m.texture);
  ASSERT_GE(m.normal_texture, 0);
  EXPECT_NE(m.normal_texture, m.texture);
  EXPECT_FALSE(s.assets.textures[static_cast<size_t>(m.normal_texture)].srgb);
  EXPECT_EQ(m.metallic_roughness_texture, m.normal_texture);
  EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
  for (const scene::Texture& t : s.assets.textures) {
    EXPECT_EQ(t.width, 2);
    EXPECT_EQ(t.height, 1);
    EXPECT_EQ(t.rgba, kTwoTexels);
  }
}

TEST(GltfMaterials, ReadsWrapModesFromTheSampler) {
  TempFolder dir;
  GltfBuilder b;
  const int image = b.image_in_buffer(png(2, 1, kTwoTexels));
  const int clamped = b.texture(image, b.sampler(kClamp, kMirror));
  const int repeated = b.texture(image, b.sampler(kRepeat, kClamp));
  const int plain = b.texture(image);
  const LoadedScene s =
      with_materials(b, dir,
                     {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", clamped}}}}}},
                      {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", repeated}}}}}},
                      {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", plain}}}}}}});
  ASSERT_EQ(s.assets.textures.size(), 3u);
  auto tex = [&](size_t m) {
    return s.assets.textures[static_cast<size_t>(s.assets.materials[m].texture)];
  };
  EXPECT_EQ(tex(0).wrap_u, scene::TextureWrap::kClampToEdge);
  EXPECT_EQ(tex(0).wrap_v, scene::TextureWrap::kMirroredRepeat);
  EXPECT_EQ(tex(1).wrap_u, scene::TextureWrap::kRepeat);
  EXPECT_EQ(tex(1).wrap_v, scene::TextureWrap::kClampToEdge);
  EXPECT_EQ(tex(2).wrap_u, scene::TextureWrap::kRepeat);
  EXPECT_EQ(tex(2).wrap_v, scene::TextureWrap::kRepeat);
}

TEST(GltfMaterials, MultipliesEmissionByKhrEmissiveStrength) {
  TempFolder dir;
  GltfBuilder b;
  b.use_extension("KHR_materials_emissive_strength");
  const LoadedScene s = with_materials(
      b, dir,
      {{{"emissiveFactor", {1, 0.5, 0}},
        {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}},
       {{"emissiveFactor", {0.25, 0.5, 1}}}});
  EXPECT_EQ(s.assets.materials.at(0).emission, glm::vec3(4, 2, 0));
  EXPECT_EQ(s.assets.materials.at(1).emission, glm::vec3(0.25f, 0.5f, 1));
  EXPECT_TRUE(s.warnings.empty());
}

TEST(GltfMaterials, MakesMaskAndBlendCutoutsAndKeepsDoubleSided) {
  TempFolder dir;
  GltfBuilder b;
  const LoadedScene s =
      with_materials(b, dir,
                     {{{"alphaMode", "MASK"}, {"alphaCutoff", 0.3}, {"doubleSided", true}},
                      {{"alphaMode", "BLEND"}},
                      {{"alphaMode", "OPAQUE"}}});
  const auto& m = s.assets.materials;
  EXPECT_EQ(m[0].alpha_mode, scene::AlphaMode::kMask);
  EXPECT_FLOAT_EQ(m[0].alpha_cutoff, 0.3f);
  EXPECT_TRUE(m[0].double_sided);
  EXPECT_EQ(m[1].alpha_mode, scene::AlphaMode::kMask);
  EXPECT_FLOAT_EQ(m[1].alpha_cutoff, 0.5f);
  EXPECT_EQ(m[2].alpha_mode, scene::AlphaMode::kOpaque);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("BLEND"), std::string::npos);
  EXPECT_NE(s.warnings[0].find("material 1"), std::string::npos) << s.warnings[0];
}

TEST(GltfMaterials, DecodesPngAndJpegFromFilesDataUrisAndBufferViewsToRgba8) {
  TempFolder dir;
  GltfBuilder b;
  dir.write("my tex.png", png(2, 1, kTwoTexels));  // referenced percent-encoded
  const std::vector<uint8_t> grey(4 * 8 * 8, 128);
  const int file = b.texture(b.image_uri("my%20tex.png"));
  const int uri = b.texture(b.image_uri("data:image/png;base64," + base64(png(2, 1, kTwoTexels))));
  const int view = b.texture(b.image_in_buffer(jpeg(8, 8, grey), "image/jpeg"));
  const LoadedScene s =
      with_materials(b, dir,
                     {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", file}}}}}},
                      {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", uri}}}}}},
                      {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", view}}}}}}});
  ASSERT_EQ(s.assets.textures.size(), 3u);
  EXPECT_EQ(s.assets.textures[0].rgba, kTwoTexels);
  EXPECT_EQ(s.assets.textures[1].rgba, kTwoTexels);
  const scene::Texture& j = s.assets.textures[2];
  ASSERT_EQ(j.width, 8);
  ASSERT_EQ(j.rgba.size(), 8u * 8u * 4u);
  EXPECT_NEAR(j.rgba[0], 128, 3);
  EXPECT_EQ(j.rgba[3], 255);  // JPEG has no alpha: opaque
}

TEST(GltfMaterials, WarnsOnceAboutTextureCoordinateSetsBeyondTheFirst) {
  TempFolder dir;
  GltfBuilder b;
  const int tex = b.texture(b.image_in_buffer(png(2, 1, kTwoTexels)));
  const LoadedScene s = with_materials(
      b, dir,
      {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", tex}, {"texCoord", 1}}}}}},
       {{"emissiveTexture", {{"index", tex}, {"texCoord", 2}}}}});
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("TEXCOORD_0"), std::string::npos);
  EXPECT_NE(s.warnings[0].find("material 0 baseColorTexture, material 1 emissiveTexture"),
            std::string::npos)
      << s.warnings[0];
  EXPECT_EQ(s.assets.materials.at(0).texture, 0);  // still used, with TEXCOORD_0
}

TEST(GltfMaterials, LoadsOnlyTheMaterialsAndImagesTheSceneDraws) {
  TempFolder dir;
  GltfBuilder b;
  // Material 0 needs a missing image, and no primitive uses it.
  b.material({{"pbrMetallicRoughness",
               {{"baseColorTexture", {{"index", b.texture(b.image_uri("gone.png"))}}}}}});
  const LoadedScene s = with_materials(b, dir, {{{"name", "used"}}});
  ASSERT_EQ(s.assets.materials.size(), 1u);
  EXPECT_EQ(s.assets.materials[0].name, "used");
  EXPECT_TRUE(s.assets.textures.empty());
}

}  // namespace
}  // namespace rp::test
