// Well-formed files whose content cannot be drawn: references out of range, accessors outside
// their data or of the wrong type, values that are not finite, node graphs that are not trees,
// scenes without triangles, sizes past the limits, images that are missing or not images.
// Every refusal names the file and the place (node, mesh, primitive, accessor, image).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "gltf/gltf_writer.h"
#include "scene/gltf_internal.h"

namespace rp::test {
namespace {

std::string error_of(const std::string& path, const scene::gltf::Limits& limits = {}) {
  try {
    std::vector<uint8_t> bytes;
    std::string why;
    if (!scene::gltf::read_regular_file(path, limits.max_file_bytes, &bytes, &why)) return why;
    scene::gltf::load_gltf_from_memory(bytes, path, limits);
  } catch (const scene::SceneFileError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " loaded without an error";
  return {};
}

void expect_error(const std::string& path, const std::vector<std::string>& fragments,
                  const scene::gltf::Limits& limits = {}) {
  const std::string message = error_of(path, limits);
  EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
  for (const std::string& f : fragments)
    EXPECT_NE(message.find(f), std::string::npos) << "'" << f << "' is not in: " << message;
}

// A valid scene: a quad with normals (accessors 0 POSITION, 1 TEXCOORD_0, 2 indices, 3 NORMAL;
// bufferView i holds accessor i), mesh 0, node 0.
GltfBuilder valid() {
  GltfBuilder b;
  const GltfBuilder::Quad q = b.quad();
  const int nrm = b.vec3s(std::vector<glm::vec3>(4, {0, 0, 1}));
  b.mesh({{{"attributes", {{"POSITION", q.position}, {"NORMAL", nrm}}}, {"indices", q.indices}}});
  b.scene({b.node({{"mesh", 0}})});
  return b;
}

using Patch = GltfBuilder::Patch;

std::string broken(const TempFolder& dir, const std::string& stem, const Patch& patch) {
  return valid().write_gltf(dir, stem, patch);
}

TEST(GltfBadContent, RefusesReferencesOutOfRange) {
  TempFolder dir;
  expect_error(broken(dir, "mesh", [](Json& d) { d["nodes"][0]["mesh"] = 3; }),
               {"node 0", "mesh 3 does not exist"});
  expect_error(
      broken(dir, "material", [](Json& d) { d["meshes"][0]["primitives"][0]["material"] = 4; }),
      {"mesh 0 primitive 0", "material 4 does not exist"});
  expect_error(
      broken(dir, "accessor",
             [](Json& d) { d["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 42; }),
      {"mesh 0 primitive 0", "accessor 42 does not exist"});
  expect_error(broken(dir, "view", [](Json& d) { d["accessors"][3]["bufferView"] = 9; }),
               {"mesh 0 primitive 0", "accessor 3", "bufferView 9 does not exist"});
  expect_error(broken(dir, "child", [](Json& d) { d["nodes"][0]["children"] = {7}; }),
               {"node 0", "child 7"});
  expect_error(broken(dir, "root", [](Json& d) { d["scenes"][0]["nodes"] = {5}; }),
               {"root node 5"});
  expect_error(broken(dir, "scene", [](Json& d) { d["scene"] = 2; }), {"scene 2"});
  expect_error(broken(dir, "camera", [](Json& d) { d["nodes"][0]["camera"] = 0; }),
               {"node 0", "camera 0 does not exist"});
  expect_error(
      broken(dir, "light",
             [](Json& d) { d["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 2; }),
      {"node 0", "light 2 does not exist"});
  expect_error(broken(dir, "texture",
                      [](Json& d) {
                        d["materials"] = {{{"normalTexture", {{"index", 9}}}}};
                        d["meshes"][0]["primitives"][0]["material"] = 0;
                      }),
               {"material 0 normalTexture", "texture 9 does not exist"});
  expect_error(broken(dir, "image",
                      [](Json& d) {
                        d["textures"] = {{{"source", 7}}};
                        d["materials"] = {{{"emissiveTexture", {{"index", 0}}}}};
                        d["meshes"][0]["primitives"][0]["material"] = 0;
                      }),
               {"material 0 emissiveTexture", "image 7 does not exist"});
}

TEST(GltfBadContent, RefusesVertexIndicesPastTheVertexCount) {
  TempFolder dir;
  GltfBuilder b;
  const GltfBuilder::Quad q = b.quad();
  const int bad = b.indices({0, 1, 2, 2, 1, 4}, kU8);
  b.mesh({{{"attributes", {{"POSITION", q.position}}}, {"indices", bad}}});
  b.scene({b.node({{"mesh", 0}})});
  expect_error(b.write_gltf(dir, "scene"),
               {"mesh 0 primitive 0", "index 5 of accessor 3 is vertex 4"});
}

TEST(GltfBadContent, RefusesAccessorsReachingPastTheirBufferView) {
  TempFolder dir;
  expect_error(
      broken(dir, "count", [](Json& d) { d["accessors"][0]["count"] = 5; }),
      {"mesh 0 primitive 0 POSITION", "accessor 0", "reach byte 60 of bufferView 0, which has 48"});
  expect_error(broken(dir, "offset", [](Json& d) { d["accessors"][3]["byteOffset"] = 4; }),
               {"accessor 3", "reach byte 52"});
  // A stride makes 4 elements span 3 strides + 1 element.
  expect_error(broken(dir, "stride", [](Json& d) { d["bufferViews"][0]["byteStride"] = 16; }),
               {"accessor 0", "reach byte 60"});
  expect_error(broken(dir, "nobuffer", [](Json& d) { d["accessors"][0].erase("bufferView"); }),
               {"accessor 0 has no bufferView"});
}

TEST(GltfBadContent, RefusesAttributesAndIndicesOfTheWrongType) {
  TempFolder dir;
  expect_error(broken(dir, "vec2", [](Json& d) { d["accessors"][0]["type"] = "VEC2"; }),
               {"POSITION", "accessor 0 must be VEC3"});
  expect_error(broken(dir, "short", [](Json& d) { d["accessors"][3]["componentType"] = kU16; }),
               {"NORMAL", "accessor 3 must hold floats"});
  expect_error(broken(dir, "signed", [](Json& d) { d["accessors"][2]["componentType"] = kI16; }),
               {"primitive 0 indices: accessor 2 must be unsigned"});
  expect_error(broken(dir, "float", [](Json& d) { d["accessors"][2]["componentType"] = kF32; }),
               {"primitive 0 indices: accessor 2 must be unsigned"});
  expect_error(
      broken(dir, "noposition",
             [](Json& d) { d["meshes"][0]["primitives"][0]["attributes"].erase("POSITION"); }),
      {"mesh 0 primitive 0 has no POSITION"});
  expect_error(broken(dir, "counts", [](Json& d) { d["accessors"][3]["count"] = 3; }),
               {"mesh 0 primitive 0", "NORMAL has 3 elements, POSITION 4"});
}

TEST(GltfBadContent, RefusesSparseAccessorsOutsideTheirData) {
  TempFolder dir;
  GltfBuilder b = valid();
  const int which = b.view(std::vector<uint8_t>{9, 0, 0, 0});
  const int values = b.view(std::vector<glm::vec3>{{0, 5, 0}});
  b.doc["accessors"][0]["sparse"] = {{"count", 1},
                                     {"indices", {{"bufferView", which}, {"componentType", kU8}}},
                                     {"values", {{"bufferView", values}}}};
  expect_error(b.write_gltf(dir, "index"), {"accessor 0 (sparse)", "index 9 is not below count 4"});
  b.doc["accessors"][0]["sparse"]["count"] = 2;
  expect_error(b.write_gltf(dir, "count"), {"accessor 0 (sparse) values", "reach byte 24"});
}

TEST(GltfBadContent, RefusesNonFinitePositionsAndTransforms) {
  TempFolder dir;
  GltfBuilder b = valid();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(b.bin.data() + 12 * 2 + 4, &nan, 4);  // vertex 2's y
  expect_error(b.write_gltf(dir, "nan"), {"POSITION", "accessor 0 element 2 is not finite"});
  expect_error(broken(dir, "scale",
                      [](Json& d) {
                        d["nodes"][0]["scale"] = {1e200, 1, 1};
                      }),
               {"node 0", "transform is not finite"});
  expect_error(broken(dir, "matrix",
                      [](Json& d) {
                        d["nodes"][0]["matrix"] = {1e300, 0, 0, 0, 0, 1, 0, 0,
                                                   0,     0, 1, 0, 0, 0, 0, 1};
                      }),
               {"node 0", "transform"});
  expect_error(broken(dir, "rotation",
                      [](Json& d) {
                        d["nodes"][0]["rotation"] = {0, 0, 0, 0};
                      }),
               {"node 0", "rotation is not a unit quaternion"});
  expect_error(broken(dir, "short",
                      [](Json& d) {
                        d["nodes"][0]["translation"] = {1, 2};
                      }),
               {"node 0", "translation must have 3 numbers"});
}

TEST(GltfBadContent, RefusesNodeGraphsThatAreNotTrees) {
  TempFolder dir;
  // 0 -> 1 -> 0: the root is someone's child.
  expect_error(broken(dir, "cycle",
                      [](Json& d) {
                        d["nodes"][0]["children"] = {1};
                        d["nodes"][1] = {{"children", {0}}};
                      }),
               {"root node 0 is also a child of node 1"});
  // 0 -> 1 -> 2 -> 1: node 1 has two parents.
  expect_error(broken(dir, "loop",
                      [](Json& d) {
                        d["nodes"][0]["children"] = {1};
                        d["nodes"][1] = {{"children", {2}}};
                        d["nodes"][2] = {{"children", {1}}};
                      }),
               {"node 1 has two parents (nodes 0 and 2)"});
  expect_error(broken(dir, "self", [](Json& d) { d["nodes"][0]["children"] = {0}; }),
               {"root node 0"});
  expect_error(broken(dir, "twice",
                      [](Json& d) {
                        d["scenes"][0]["nodes"] = {0, 0};
                      }),
               {"node 0 is reached twice"});
  // A chain deeper than the limit.
  expect_error(broken(dir, "deep",
                      [](Json& d) {
                        for (int i = 0; i < 1100; ++i)
                          d["nodes"][static_cast<size_t>(i)]["children"] = {i + 1};
                        d["nodes"][1100] = {{"mesh", 0}};
                      }),
               {"deeper than 1024 levels"});
}

TEST(GltfBadContent, RefusesScenesWithNothingToDraw) {
  TempFolder dir;
  expect_error(broken(dir, "points", [](Json& d) { d["meshes"][0]["primitives"][0]["mode"] = 0; }),
               {"has no triangles to render"});
  expect_error(broken(dir, "nomesh", [](Json& d) { d["nodes"][0].erase("mesh"); }),
               {"has no triangles to render"});
  expect_error(broken(dir, "empty", [](Json& d) { d["scenes"][0]["nodes"] = Json::array(); }),
               {"has no triangles to render"});
}

TEST(GltfBadContent, RefusesScenesPastTheVertexTriangleAndTexelLimits) {
  TempFolder dir;
  scene::gltf::Limits small;
  small.max_vertices = 7;  // two quads: 8 vertices
  GltfBuilder b = valid();
  b.scene({0, b.node({{"mesh", b.mesh(b.doc["meshes"][0]["primitives"])}})});
  expect_error(b.write_gltf(dir, "vertices"), {"mesh 1 primitive 0", "more than 7 vertices"},
               small);
  small = {};
  small.max_triangles = 3;
  expect_error(b.write_gltf(dir, "triangles"), {"mesh 1 primitive 0", "more than 3 triangles"},
               small);
  // Many primitives reading one accessor: each read counts.
  small = {};
  small.max_accessor_reads = 20;  // each quad primitive reads 4 + 4 + 6 elements
  expect_error(b.write_gltf(dir, "reads"), {"mesh 1 primitive 0", "more than 20 accessor elements"},
               small);
  small = {};
  small.max_texels = 10;
  GltfBuilder t = valid();
  const int tex = t.texture(t.image_in_buffer(png(4, 4, std::vector<uint8_t>(64, 255))));
  t.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", tex}}}}}}};
  t.doc["meshes"][0]["primitives"][0]["material"] = 0;
  expect_error(t.write_gltf(dir, "texels"),
               {"material 0 baseColorTexture", "image 0", "more than 10 texels"}, small);
}

// Material 0 on the quad with base colour texture 0 from image 0 as given.
std::string textured(const TempFolder& dir, const std::string& stem, const Json& image,
                     const std::vector<uint8_t>& buffer_image = {}) {
  GltfBuilder b = valid();
  Json im = image;
  if (!buffer_image.empty()) im["bufferView"] = b.view(buffer_image);
  b.doc["images"] = {im};
  b.doc["textures"] = {{{"source", 0}}};
  b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  return b.write_gltf(dir, stem);
}

TEST(GltfBadContent, RefusesMissingUndecodableAndOversizedImages) {
  TempFolder dir;
  expect_error(textured(dir, "missing", {{"uri", "gone.png"}}),
               {"material 0 baseColorTexture", "image 0 ('gone.png') is missing",
                "No such file or directory"});
  dir.write("text.png", std::string("this is no image"));
  expect_error(textured(dir, "text", {{"uri", "text.png"}}),
               {"image 0 ('text.png') is neither PNG nor JPEG"});
  // A real PNG header on a cut-off body.
  std::vector<uint8_t> cut = png(8, 8, std::vector<uint8_t>(256, 7));
  cut.resize(40);
  expect_error(textured(dir, "cut", {{"mimeType", "image/png"}}, cut),
               {"image 0 cannot be decoded"});
  // Wider than 16384 texels.
  expect_error(textured(dir, "wide", {{"mimeType", "image/png"}},
                        png(16385, 1, std::vector<uint8_t>(16385 * 4, 0))),
               {"image 0 is 16385x1 texels, more than 16384 a side"});
  // A header claiming 16000 x 16000 texels over a few bytes of data: refused before the
  // decoder allocates a gigabyte for it.
  std::vector<uint8_t> claim = png(1, 1, {1, 2, 3, 4});
  for (size_t at : {16u, 20u}) {
    claim[at] = 0;
    claim[at + 1] = 0;
    claim[at + 2] = 0x3E;
    claim[at + 3] = 0x80;  // 16000, big-endian
  }
  expect_error(textured(dir, "claim", {{"mimeType", "image/png"}}, claim),
               {"image 0", "cannot hold 16000x16000 texels"});
}

TEST(GltfBadContent, RefusesBadLightsCamerasMaterialsAndVolumes) {
  TempFolder dir;
  auto with_light = [](const Json& light) {
    return [light](Json& d) {
      d["extensions"]["KHR_lights_punctual"]["lights"] = {light};
      d["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0;
    };
  };
  expect_error(broken(dir, "lamp", with_light({{"type", "lamp"}})), {"light 0", "\"lamp\""});
  expect_error(broken(dir, "cone",
                      with_light({{"type", "spot"},
                                  {"spot", {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.4}}}})),
               {"light 0", "spot cone"});
  expect_error(broken(dir, "dark", with_light({{"type", "point"}, {"intensity", -1}})),
               {"light 0", "intensity"});
  expect_error(broken(dir, "fov",
                      [](Json& d) {
                        d["cameras"] = {{{"type", "perspective"},
                                         {"perspective", {{"yfov", 0}, {"znear", 0.1}}}}};
                        d["nodes"][0]["camera"] = 0;
                      }),
               {"camera 0", "yfov"});
  expect_error(broken(dir, "alpha",
                      [](Json& d) {
                        d["materials"] = {{{"alphaMode", "ADD"}}};
                        d["meshes"][0]["primitives"][0]["material"] = 0;
                      }),
               {"material 0", "alphaMode \"ADD\""});
  expect_error(broken(dir, "lamp_spot",
                      with_light({{"type", "spot"},
                                  {"spot", Json::object()},
                                  {"extras", {{"rolypoly", {{"lamp", {{"radius", 0.3}}}}}}}})),
               {"light 0: extras.rolypoly.lamp"});
  expect_error(broken(dir, "lamp_near",
                      with_light({{"type", "point"},
                                  {"extras", {{"rolypoly", {{"lamp", {{"shadow_near", -1}}}}}}}})),
               {"light 0: extras.rolypoly.lamp", "shadow_near"});
  expect_error(broken(dir, "flag",
                      [](Json& d) { d["nodes"][0]["extras"]["rolypoly"]["casts_shadow"] = "no"; }),
               {"node 0", "casts_shadow must be true or false"});
  expect_error(
      broken(dir, "ior",
             [](Json& d) {
               d["materials"] = {{{"extensions", {{"KHR_materials_ior", {{"ior", 0.5}}}}}}};
               d["meshes"][0]["primitives"][0]["material"] = 0;
             }),
      {"material 0", "ior must be a number >= 1"});
  expect_error(
      broken(dir, "volume",
             [](Json& d) { d["scenes"][0]["extras"]["rolypoly"]["volume"] = {0, 0, 0, 1, -1, 1}; }),
      {"scene 0", "extras.rolypoly.volume"});
  expect_error(broken(dir, "volume5",
                      [](Json& d) {
                        d["asset"]["extras"]["rolypoly"]["volume"] = {0, 0, 0, 1, 1};
                      }),
               {"asset", "extras.rolypoly.volume"});
}

}  // namespace
}  // namespace rp::test
