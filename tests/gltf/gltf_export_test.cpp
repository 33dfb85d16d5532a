// The glTF exporter (scene/gltf_export.h) read back without the loader: the demo's frame as .glb
// and .gltf keeps glTF 2.0's structural rules (gltf_export_checks.h), and what the file says
// (triangles, matrices, materials, textures, lights, camera, volume) is exactly the frame's.
// gltf_export_round_trip_test.cpp reads the same files with scene/gltf_loader.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <memory>
#include <numbers>
#include <set>
#include <stdexcept>

#include <stb/stb_image.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gltf/gltf_export_checks.h"
#include "scene/demo_scene.h"
#include "scene/gltf_export.h"

namespace rp::test::gltf_export_checks {
namespace {

using nlohmann::json;
constexpr double kPi = std::numbers::pi;

ExportedFile export_and_read(const std::filesystem::path& file, const scene::FrameScene& frame,
                             const scene::ExportOptions& options = demo_options(),
                             const scene::SceneAssets& assets = demo_assets()) {
  scene::export_gltf(assets, frame, file, options);
  return read_exported(file);
}

glm::vec3 vec3_of(const json& a) {
  return {a[0].get<float>(), a[1].get<float>(), a[2].get<float>()};
}

glm::mat4 matrix_of(const json& node) {
  glm::mat4 m(1.0f);
  if (node.contains("matrix"))
    for (int i = 0; i < 16; ++i)
      glm::value_ptr(m)[i] = node["matrix"][static_cast<size_t>(i)].get<float>();
  return m;
}

// A glTF mesh's object-space triangle corners, primitives in order.
std::vector<glm::vec3> file_corners(const ExportedFile& f, const json& mesh) {
  std::vector<glm::vec3> out;
  for (const json& p : mesh["primitives"]) {
    const std::vector<float> pos = floats(f, p["attributes"]["POSITION"].get<int>());
    for (const uint32_t i : indices(f, p["indices"].get<int>()))
      out.emplace_back(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
  }
  return out;
}

const json& material_named(const ExportedFile& f, const std::string& name) {
  for (const json& m : f.doc["materials"])
    if (m.value("name", "") == name) return m;
  throw std::runtime_error("no material " + name);
}

// The file's texture `index` decoded, against `want`: identical bytes and wrap modes.
void expect_texture(const ExportedFile& f, int index, const scene::Texture& want) {
  const json& t = f.doc["textures"][static_cast<size_t>(index)];
  const std::string png =
      view_bytes(f, f.doc["images"][t["source"].get<size_t>()]["bufferView"].get<int>());
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> pixels(
      stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png.data()),
                            static_cast<int>(png.size()), &w, &h, &channels, 4),
      &stbi_image_free);
  ASSERT_TRUE(pixels) << want.name;
  ASSERT_EQ(w, want.width);
  ASSERT_EQ(h, want.height);
  EXPECT_TRUE(std::equal(want.rgba.begin(), want.rgba.end(), pixels.get())) << want.name;
  const auto code = [](scene::TextureWrap m) {
    return m == scene::TextureWrap::kRepeat        ? 10497
           : m == scene::TextureWrap::kClampToEdge ? 33071
                                                   : 33648;
  };
  const json& sampler = f.doc["samplers"][t["sampler"].get<size_t>()];
  EXPECT_EQ(sampler["wrapS"], code(want.wrap_u)) << want.name;
  EXPECT_EQ(sampler["wrapT"], code(want.wrap_v)) << want.name;
}

// A glTF material against the scene material it was written from.
void expect_material(const ExportedFile& f, const json& g, const scene::Material& m,
                     const scene::SceneAssets& assets = demo_assets()) {
  SCOPED_TRACE(m.name);
  const json& pbr = g["pbrMetallicRoughness"];
  for (int c = 0; c < 3; ++c)
    EXPECT_EQ(pbr["baseColorFactor"][static_cast<size_t>(c)].get<float>(), m.albedo[c]);
  EXPECT_EQ(pbr["baseColorFactor"][3].get<float>(), m.opacity);
  EXPECT_EQ(pbr["roughnessFactor"].get<float>(), m.specular.roughness);
  EXPECT_EQ(pbr["metallicFactor"].get<float>() >= 0.5f, m.specular.metal);
  EXPECT_NEAR(f0_of_ior(g["extensions"]["KHR_materials_ior"]["ior"].get<double>()), m.specular.f0,
              1e-7);
  // emissiveFactor x emissiveStrength gives the very floats back; the factor stays <= 1.
  const glm::vec3 factor =
      g.contains("emissiveFactor") ? vec3_of(g["emissiveFactor"]) : glm::vec3(0.0f);
  const float strength =
      g["extensions"].contains("KHR_materials_emissive_strength")
          ? g["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"].get<float>()
          : 1.0f;
  EXPECT_EQ(factor * strength, m.emission);
  EXPECT_LE(std::max({factor.x, factor.y, factor.z}), 1.0f);
  if (m.texture >= 0)
    expect_texture(f, pbr["baseColorTexture"]["index"].get<int>(),
                   assets.textures.at(static_cast<size_t>(m.texture)));
  else
    EXPECT_FALSE(pbr.contains("baseColorTexture"));
  EXPECT_EQ(g.value("alphaMode", "OPAQUE"),
            m.alpha_mode == scene::AlphaMode::kMask ? "MASK" : "OPAQUE");
  EXPECT_EQ(g.value("doubleSided", false), m.double_sided);
}

TEST(GltfExport, DemoFrameIsAValidGlb) {
  ExportFolder dir;
  const ExportedFile f =
      export_and_read(dir.file("demo.glb"), scene::make_demo_frame(demo_assets()));
  EXPECT_TRUE(f.problems.empty()) << describe(f.problems);
  EXPECT_EQ(f.doc["asset"]["generator"], "rolypoly");
  // The proxy is no instance's mesh: three meshes, not four.
  std::vector<std::string> meshes;
  for (const json& m : f.doc["meshes"]) meshes.push_back(m["name"]);
  EXPECT_EQ(meshes, (std::vector<std::string>{"cornell_box", "lamp_cap", "tumbler"}));
  const std::set<std::string> used = f.doc["extensionsUsed"];
  EXPECT_EQ(used, (std::set<std::string>{"KHR_materials_ior", "KHR_materials_emissive_strength",
                                         "KHR_lights_punctual"}));
  // Seven instances, the lamp's light, the camera.
  ASSERT_EQ(f.doc["nodes"].size(), 9u);
  EXPECT_EQ(f.doc["scenes"][0]["nodes"].size(), 9u);
  // Small meshes index with unsigned shorts.
  for (const json& m : f.doc["meshes"])
    for (const json& p : m["primitives"])
      EXPECT_EQ(f.doc["accessors"][p["indices"].get<size_t>()]["componentType"], 5123);
}

TEST(GltfExport, DemoNodesHoldTheInstancesTrianglesAndFlags) {
  ExportFolder dir;
  const scene::FrameScene frame = scene::make_demo_frame(demo_assets());
  const ExportedFile f = export_and_read(dir.file("demo.glb"), frame);
  ASSERT_TRUE(f.problems.empty()) << describe(f.problems);
  for (size_t i = 0; i < frame.instances.size(); ++i) {
    SCOPED_TRACE("instance " + std::to_string(i));
    const scene::MeshInstance& inst = frame.instances[i];
    const scene::Mesh& mesh = demo_assets().meshes[inst.mesh];
    const json& node = f.doc["nodes"][i];
    EXPECT_EQ(node["name"], mesh.name);
    EXPECT_EQ(node.contains("matrix"), inst.model != glm::mat4(1.0f));
    EXPECT_EQ(matrix_of(node), inst.model);
    const json& g = f.doc["meshes"][node["mesh"].get<size_t>()];
    // Object-space corners, bit for bit, grouped by material; one primitive per material.
    EXPECT_EQ(file_corners(f, g), corners_by_material(mesh));
    const std::map<uint32_t, size_t> per_material = triangles_per_material(mesh);
    ASSERT_EQ(g["primitives"].size(), per_material.size());
    size_t p = 0;
    for (const auto& [material, triangles] : per_material) {
      const json& prim = g["primitives"][p++];
      EXPECT_EQ(f.doc["materials"][prim["material"].get<size_t>()]["name"],
                demo_assets().materials[material].name);
      EXPECT_EQ(f.doc["accessors"][prim["indices"].get<size_t>()]["count"], 3 * triangles);
      EXPECT_FALSE(prim["attributes"].contains("TANGENT"));  // no normal maps in the demo
    }
    // Flags that are not true travel as extras.
    const json flags = node.contains("extras") ? node["extras"]["rolypoly"] : json::object();
    EXPECT_EQ(flags.value("casts_shadow", true), inst.casts_shadow);
    EXPECT_EQ(flags.value("voxelize", true), inst.voxelize);
    EXPECT_EQ(flags.size(), size_t(!inst.casts_shadow) + size_t(!inst.voxelize));
  }
  // The floor (material 0, the box's first primitive) holds the box's floor vertices in their
  // order; glTF's v runs down the image, so the file's v is 1 - v.
  const scene::Mesh& box = demo_assets().meshes[scene::demo::kBoxMesh];
  std::vector<bool> used(box.vertices.size(), false);
  for (size_t t = 0; t < box.triangles.size(); ++t)
    if (box.materials[t] == scene::demo::kFloorMaterial)
      for (int k = 0; k < 3; ++k) used[box.triangles[t][k]] = true;
  const json& floor = f.doc["meshes"][0]["primitives"][0];
  const std::vector<float> uv = floats(f, floor["attributes"]["TEXCOORD_0"].get<int>());
  size_t k = 0;
  for (size_t v = 0; v < box.vertices.size(); ++v) {
    if (!used[v]) continue;
    ASSERT_LT(2 * k + 1, uv.size());
    EXPECT_EQ(uv[2 * k], box.vertices[v].uv.x);
    EXPECT_EQ(uv[2 * k + 1], 1.0f - box.vertices[v].uv.y);
    ++k;
  }
  EXPECT_EQ(2 * k, uv.size());
}

TEST(GltfExport, DemoMaterialsKeepAlbedoCoatEmissionAndTextures) {
  ExportFolder dir;
  const ExportedFile f =
      export_and_read(dir.file("demo.glb"), scene::make_demo_frame(demo_assets()));
  ASSERT_TRUE(f.problems.empty()) << describe(f.problems);
  ASSERT_EQ(f.doc["materials"].size(), demo_assets().materials.size());
  for (const scene::Material& m : demo_assets().materials)
    expect_material(f, material_named(f, m.name), m);
  // The lamp glows above 1: its strength carries the rest, a power of two.
  const json& lamp = material_named(f, "lamp");
  const double strength = lamp["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"];
  EXPECT_GT(strength, 1.0);
  EXPECT_EQ(std::exp2(std::round(std::log2(strength))), strength);
  // Matte walls: ior 1 (no coat); the floor's varnish: f0 0.04.
  EXPECT_EQ(material_named(f, "back_wall")["extensions"]["KHR_materials_ior"]["ior"], 1.0);
  EXPECT_EQ(f.doc["images"].size(), 2u);
}

TEST(GltfExport, LampCameraAndVolume) {
  ExportFolder dir;
  scene::FrameScene frame = scene::make_demo_frame(demo_assets());
  frame.light.intensity = {9.0f, 8.0f, 7.0f};  // not white: the colour carries the ratio
  const ExportedFile f = export_and_read(dir.file("demo.glb"), frame);
  ASSERT_TRUE(f.problems.empty()) << describe(f.problems);
  const json& lights = f.doc["extensions"]["KHR_lights_punctual"]["lights"];
  ASSERT_EQ(lights.size(), 1u);
  const json& lamp = lights[0];
  EXPECT_EQ(lamp["type"], "point");
  // Renderer intensity = colour * glTF intensity / pi (frame_scene.h).
  const glm::vec3 back =
      vec3_of(lamp["color"]) * static_cast<float>(lamp["intensity"].get<double>() / kPi);
  EXPECT_EQ(back, frame.light.intensity);
  const json& extra = lamp["extras"]["rolypoly"]["lamp"];
  EXPECT_EQ(extra["radius"].get<float>(), frame.light.lamp_radius);
  EXPECT_EQ(extra["shadow_fov_y_deg"].get<float>(), frame.light.shadow_fov_y_deg);
  EXPECT_EQ(extra["shadow_near"].get<float>(), frame.light.shadow_near);
  EXPECT_EQ(extra["shadow_far"].get<float>(), frame.light.shadow_far);
  const json& lamp_node = f.doc["nodes"][7];
  EXPECT_EQ(lamp_node["extensions"]["KHR_lights_punctual"]["light"], 0);
  EXPECT_EQ(vec3_of(lamp_node["translation"]), frame.light.position);
  EXPECT_FALSE(lamp_node.contains("mesh"));

  const json& cam_node = f.doc["nodes"][8];
  const json& cam = f.doc["cameras"][cam_node["camera"].get<size_t>()];
  EXPECT_NEAR(cam["perspective"]["yfov"].get<double>(), frame.camera.fov_y_deg * kPi / 180.0, 1e-9);
  EXPECT_EQ(cam["perspective"]["znear"].get<float>(), frame.camera.near_plane);
  EXPECT_EQ(cam["perspective"]["zfar"].get<float>(), frame.camera.far_plane);
  EXPECT_FALSE(cam["perspective"].contains("aspectRatio"));
  const glm::mat4 world = matrix_of(cam_node), want = glm::inverse(frame.camera.view());
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(world[c][r], want[c][r], 1e-6) << c << "," << r;

  EXPECT_EQ(f.doc["scenes"][0]["extras"]["rolypoly"]["volume"],
            json::array({-1.0, -1.0, -1.0, 1.0, 1.0, 1.0}));
  const ExportedFile plain = export_and_read(dir.file("plain.glb"), frame, {});
  EXPECT_FALSE(plain.doc["scenes"][0].contains("extras"));
  frame.lamp = false;
  const ExportedFile dark = export_and_read(dir.file("dark.glb"), frame);
  EXPECT_TRUE(dark.problems.empty()) << describe(dark.problems);
  EXPECT_FALSE(dark.doc.contains("extensions"));
  EXPECT_EQ(dark.doc["nodes"].size(), 8u);
}

TEST(GltfExport, MarblesAreUvSpheresWithinATenthOfAPercent) {
  ExportFolder dir;
  scene::FrameScene frame = demo_frame_with_marbles();
  scene::Sphere ember = frame.spheres[1];  // same material as the second marble, no shadow
  ember.center = {0.4f, -0.5f, 0.1f};
  ember.radius = 0.02f;
  ember.casts_shadow = false;
  frame.spheres.push_back(ember);
  const ExportedFile f = export_and_read(dir.file("marbles.glb"), frame);
  ASSERT_TRUE(f.problems.empty()) << describe(f.problems);
  const size_t first = frame.instances.size();
  ASSERT_EQ(f.doc["nodes"].size(), first + 3 + 2);
  // Two distinct materials: two meshes, one geometry.
  const json& a = f.doc["meshes"][f.doc["nodes"][first]["mesh"].get<size_t>()]["primitives"][0];
  const json& b = f.doc["meshes"][f.doc["nodes"][first + 1]["mesh"].get<size_t>()]["primitives"][0];
  EXPECT_NE(a["material"], b["material"]);
  EXPECT_EQ(a["attributes"], b["attributes"]);
  EXPECT_EQ(a["indices"], b["indices"]);
  EXPECT_EQ(f.doc["nodes"][first + 2]["mesh"], f.doc["nodes"][first + 1]["mesh"]);
  EXPECT_EQ(f.doc["nodes"][first + 2]["extras"]["rolypoly"]["casts_shadow"], false);
  EXPECT_FALSE(f.doc["nodes"][first].contains("extras"));
  for (size_t s = 0; s < frame.spheres.size(); ++s) {
    const glm::mat4 m = matrix_of(f.doc["nodes"][first + s]);
    EXPECT_EQ(m, glm::mat4(glm::vec4(frame.spheres[s].radius, 0, 0, 0),
                           glm::vec4(0, frame.spheres[s].radius, 0, 0),
                           glm::vec4(0, 0, frame.spheres[s].radius, 0),
                           glm::vec4(frame.spheres[s].center, 1)));
  }
  scene::Material marble;
  marble.name = "sphere material 0";
  marble.albedo = frame.spheres[0].albedo;
  marble.specular = frame.spheres[0].specular;
  expect_material(f, f.doc["materials"][a["material"].get<size_t>()], marble);

  // The unit sphere: vertices on it, faces counter-clockwise seen from outside, and no face
  // (so no silhouette, whichever way it is seen) more than 0.1 % of the radius inside.
  const std::vector<float> pos = floats(f, a["attributes"]["POSITION"].get<int>());
  const std::vector<uint32_t> idx = indices(f, a["indices"].get<int>());
  for (size_t i = 0; i < pos.size(); i += 3)
    ASSERT_NEAR(glm::length(glm::dvec3(pos[i], pos[i + 1], pos[i + 2])), 1.0, 1e-6);
  double nearest = 1.0;
  for (size_t t = 0; t < idx.size(); t += 3) {
    const auto p = [&](size_t k) {
      return glm::dvec3(pos[3 * idx[t + k]], pos[3 * idx[t + k] + 1], pos[3 * idx[t + k] + 2]);
    };
    const glm::dvec3 n = glm::cross(p(1) - p(0), p(2) - p(0));
    ASSERT_GT(glm::dot(n, p(0) + p(1) + p(2)), 0.0) << "triangle " << t / 3;
    nearest = std::min(nearest, glm::dot(glm::normalize(n), p(0)));
  }
  EXPECT_GE(nearest, 0.999);
}

TEST(GltfExport, GltfTextEmbedsTheSameBufferAsADataUri) {
  ExportFolder dir;
  const scene::FrameScene frame = demo_frame_with_marbles();
  const ExportedFile glb = export_and_read(dir.file("demo.glb"), frame);
  const ExportedFile text = export_and_read(dir.file("demo.GLTF"), frame);
  EXPECT_TRUE(text.problems.empty()) << describe(text.problems);
  EXPECT_EQ(text.bin, glb.bin);
  json without_uri = text.doc;
  without_uri["buffers"][0].erase("uri");
  EXPECT_EQ(without_uri, glb.doc);
}

TEST(GltfExport, EveryMaterialFeatureTangentsAndLightsAreWritten) {
  ExportFolder dir;
  const SyntheticScene s = synthetic_scene();
  const ExportedFile f = export_and_read(dir.file("synthetic.glb"), s.frame, {}, s.assets);
  ASSERT_TRUE(f.problems.empty()) << describe(f.problems);
  const json& prims = f.doc["meshes"][0]["primitives"];
  ASSERT_EQ(prims.size(), 2u);
  for (const json& p : prims) EXPECT_TRUE(p["attributes"].contains("TANGENT"));
  // Only the vertices each primitive uses: 4 for the quad, 3 for the triangle.
  EXPECT_EQ(f.doc["accessors"][prims[0]["attributes"]["POSITION"].get<size_t>()]["count"], 4);
  EXPECT_EQ(f.doc["accessors"][prims[1]["attributes"]["POSITION"].get<size_t>()]["count"], 3);
  EXPECT_EQ(floats(f, prims[1]["attributes"]["TANGENT"].get<int>())[11], -1.0f);

  const json& all = material_named(f, "everything");
  const scene::Material& m = s.assets.materials[0];
  EXPECT_EQ(all["alphaMode"], "MASK");
  EXPECT_EQ(all["alphaCutoff"].get<float>(), m.alpha_cutoff);
  EXPECT_EQ(all["doubleSided"], true);
  EXPECT_EQ(all["normalTexture"]["scale"].get<float>(), m.normal_scale);
  EXPECT_EQ(all["pbrMetallicRoughness"]["metallicFactor"].get<float>(), m.metallic);
  EXPECT_EQ(vec3_of(all["emissiveFactor"]), glm::vec3(0.75f, 0.375f, 0.0f));
  EXPECT_EQ(all["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"], 4.0);
  EXPECT_NEAR(f0_of_ior(all["extensions"]["KHR_materials_ior"]["ior"].get<double>()), m.specular.f0,
              1e-7);
  const json& pbr = all["pbrMetallicRoughness"];
  expect_texture(f, pbr["baseColorTexture"]["index"].get<int>(), s.assets.textures[0]);
  expect_texture(f, all["normalTexture"]["index"].get<int>(), s.assets.textures[1]);
  expect_texture(f, pbr["metallicRoughnessTexture"]["index"].get<int>(), s.assets.textures[2]);
  expect_texture(f, all["emissiveTexture"]["index"].get<int>(), s.assets.textures[3]);
  EXPECT_EQ(f.doc["samplers"].size(), 2u);  // (clamp, mirrored) and (repeat, repeat)
  EXPECT_EQ(material_named(f, "gold")["pbrMetallicRoughness"]["metallicFactor"], 1.0);

  // Lights: -z turned onto each direction; the spot's hard edge as inner just below outer.
  const json& lights = f.doc["extensions"]["KHR_lights_punctual"]["lights"];
  ASSERT_EQ(lights.size(), s.frame.lights.size());
  for (size_t i = 0; i < lights.size(); ++i) {
    const scene::PunctualLight& l = s.frame.lights[i];
    const json& node = f.doc["nodes"][1 + i];
    SCOPED_TRACE(l.name);
    EXPECT_EQ(lights[i]["name"], l.name);
    const glm::vec3 back = vec3_of(lights[i]["color"]) *
                           static_cast<float>(lights[i]["intensity"].get<double>() / kPi);
    EXPECT_EQ(back, l.intensity);
    EXPECT_EQ(node.contains("translation"), l.type != scene::LightType::kDirectional);
    if (l.type == scene::LightType::kPoint) {
      EXPECT_FALSE(node.contains("rotation"));
      EXPECT_EQ(lights[i]["range"].get<float>(), l.range);
      continue;
    }
    const json& q = node["rotation"];
    const glm::quat rotation(q[3].get<float>(), q[0].get<float>(), q[1].get<float>(),
                             q[2].get<float>());
    const glm::vec3 d = rotation * glm::vec3(0.0f, 0.0f, -1.0f);
    EXPECT_NEAR(glm::distance(d, l.direction), 0.0f, 1e-6f);
  }
  const json& hard = lights[3]["spot"];
  EXPECT_LT(hard["innerConeAngle"].get<double>(), hard["outerConeAngle"].get<double>());
  EXPECT_EQ(hard["innerConeAngle"].get<float>(), 0.5f);
}

TEST(GltfExport, LargeMeshesIndexWithUnsignedInts) {
  scene::SceneAssets assets;
  assets.materials.resize(1);
  scene::Mesh strip;
  strip.name = "strip";
  for (uint32_t i = 0; i < 70000; ++i)
    strip.vertices.push_back(
        {glm::vec3(float(i / 2) * 1e-4f, float(i % 2), 0.0f), glm::vec3(0, 0, 1), glm::vec2(0)});
  for (uint32_t i = 0; i + 2 < 70000; ++i) strip.triangles.push_back({i, i + 1, i + 2});
  strip.materials.assign(strip.triangles.size(), 0);
  assets.meshes = {strip};
  scene::FrameScene frame;
  frame.instances.resize(1);
  ExportFolder dir;
  const ExportedFile f = export_and_read(dir.file("strip.glb"), frame, {}, assets);
  ASSERT_TRUE(f.problems.empty()) << describe(f.problems);
  const json& p = f.doc["meshes"][0]["primitives"][0];
  EXPECT_EQ(f.doc["accessors"][p["indices"].get<size_t>()]["componentType"], 5125);
  EXPECT_EQ(indices(f, p["indices"].get<int>()).size(), 3 * strip.triangles.size());
}

TEST(GltfExport, RefusesWhatTheAssetsCannotDrawAndWritesNothing) {
  ExportFolder dir;
  scene::FrameScene frame = scene::make_demo_frame(demo_assets());
  frame.instances[2].mesh = 99;
  EXPECT_THROW(scene::export_gltf(demo_assets(), frame, dir.file("bad.glb")),
               std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.glb")));
  scene::SceneAssets broken = demo_assets();
  broken.textures[0].rgba.pop_back();
  EXPECT_THROW(
      scene::export_gltf(broken, scene::make_demo_frame(demo_assets()), dir.file("bad.glb")),
      std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.glb")));
  // A missing folder: the write fails (io::WriteError) and leaves nothing.
  EXPECT_THROW(scene::export_gltf(demo_assets(), scene::make_demo_frame(demo_assets()),
                                  dir.file("missing/demo.glb")),
               std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(dir.file("missing")));
}

// The checker itself: files broken on purpose are caught, so a clean report means something.
TEST(GltfExport, TheCheckerCatchesBrokenFiles) {
  ExportFolder dir;
  const std::filesystem::path file = dir.file("demo.gltf");
  scene::export_gltf(demo_assets(), scene::make_demo_frame(demo_assets()), file, demo_options());
  const json good = read_exported(file).doc;
  const auto broken = [&](const std::function<void(json&)>& edit) {
    json doc = good;
    edit(doc);
    std::ofstream(dir.file("broken.gltf")) << doc.dump();
    return describe(read_exported(dir.file("broken.gltf")).problems);
  };
  EXPECT_EQ(broken([](json&) {}), "");
  EXPECT_NE(broken([](json& d) { d["accessors"][0]["min"][0] = -2.0; }).find("min/max"),
            std::string::npos);
  EXPECT_NE(broken([](json& d) { d["accessors"][0].erase("max"); }).find("no min and max"),
            std::string::npos);
  EXPECT_NE(broken([](json& d) { d["bufferViews"][1]["byteOffset"] = 970; }).find("not 4-aligned"),
            std::string::npos);
  EXPECT_NE(
      broken([](json& d) { d["accessors"][1]["count"] = 100000; }).find("past its buffer view"),
      std::string::npos);
  EXPECT_NE(broken([](json& d) { d["extensionsUsed"].erase(2); }).find("not in extensionsUsed"),
            std::string::npos);
  EXPECT_NE(broken([](json& d) {
              d["nodes"][7]["extensions"]["KHR_lights_punctual"]["light"] = 3;
            }).find("light is no index"),
            std::string::npos);
  EXPECT_NE(broken([](json& d) { d["buffers"][0]["byteLength"] = 4; }).find("byteLength"),
            std::string::npos);
  EXPECT_NE(broken([](json& d) {
              d["meshes"][0]["primitives"][0]["material"] = 42;
            }).find("no index into materials"),
            std::string::npos);
}

}  // namespace
}  // namespace rp::test::gltf_export_checks
