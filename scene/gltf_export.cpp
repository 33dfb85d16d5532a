// The frame as a glTF document: nodes, meshes, materials, lights and the camera as JSON, the
// vertex, index and image bytes in one buffer (scene/gltf_export_buffer.h).
#include "scene/gltf_export.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "io/atomic_file.h"
#include "scene/gltf_export_buffer.h"

namespace rp::scene {
namespace gltf_export {
namespace {

// The unit sphere every Sphere is drawn with: 128 segments around, 64 rings from pole to pole.
// Its flattest faces (at the equator) lie 0.06 % of the radius inside the sphere, and every
// face is seen edge-on from some direction, so that is also the silhouette's largest error
// (64 x 32 would be 0.24 %).
constexpr int kSphereSegments = 128;
constexpr int kSphereRings = 64;

constexpr double kPi = std::numbers::pi;

[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("export_gltf: " + what);
}

// Binary data is written as is, so NaN and infinities are refused here (JSON numbers are
// checked by json_number); glTF readers refuse them.
bool all_finite(const std::vector<float>& values) {
  return std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); });
}

Json vec_json(const glm::vec3& v) { return json_numbers(&v.x, 3); }

// Column-major, as glTF's node.matrix and glm's storage.
Json matrix_json(const glm::mat4& m) { return json_numbers(&m[0][0], 16); }

// `v` = unit * scale with scale a power of two and the largest component of `unit` in (0.5, 1]
// (v itself when it is zero). Dividing by a power of two is exact, so a reader multiplying the
// two back gets the very floats written.
struct Split {
  glm::vec3 unit;
  double scale = 1.0;
};
Split split_power_of_two(const glm::vec3& v) {
  const float peak = std::max({v.x, v.y, v.z});
  if (!std::isfinite(peak)) fail("the frame holds a number that is not finite");
  if (!(peak > 0.0f)) return {v, 1.0};
  int exponent = 0;
  if (std::frexp(peak, &exponent) == 0.5f) --exponent;  // peak = 2^(exponent - 1): unit 1
  return {v / std::ldexp(1.0f, exponent), std::ldexp(1.0, exponent)};
}

// KHR_materials_ior's index for the coat's reflectance f0 = ((n - 1) / (n + 1))^2. f0 = 0 (no
// coat) is n = 1, which reflects nothing, as the renderer's matte surfaces.
double ior_of(float f0) {
  const double s = std::sqrt(std::clamp(static_cast<double>(f0), 0.0, 0.99));
  return (1.0 + s) / (1.0 - s);
}

// The loader reads specular.metal as metallicFactor >= 0.5, and a metallic-roughness texture's
// B channel scales the factor per texel: a factor that agrees with `metal` is kept as given
// (a loaded file's), else the coat decides (0 or 1).
float metallic_factor(const Material& m) {
  if ((m.metallic >= 0.5f) == m.specular.metal) return m.metallic;
  return m.specular.metal ? 1.0f : 0.0f;
}

int wrap_code(TextureWrap wrap) {
  switch (wrap) {
    case TextureWrap::kClampToEdge:
      return 33071;
    case TextureWrap::kMirroredRepeat:
      return 33648;
    case TextureWrap::kRepeat:
      break;
  }
  return 10497;
}

// A quaternion [x, y, z, w] turning -z (a glTF light's axis) onto unit `d`.
Json rotation_from_minus_z(const glm::vec3& direction) {
  const double len = std::sqrt(glm::dot(glm::dvec3(direction), glm::dvec3(direction)));
  if (!(len > 0.0) || !std::isfinite(len)) fail("a light's direction is not a direction");
  const glm::dvec3 d = glm::dvec3(direction) / len;
  const double c = -d.z;                              // dot(-z, d)
  if (c < -1.0 + 1e-12) return {0.0, 1.0, 0.0, 0.0};  // d = +z: half a turn about y
  // Half-angle form: (cross(a, d), 1 + dot(a, d)) normalised, a = -z.
  glm::dvec4 q(d.y, -d.x, 0.0, 1.0 + c);
  q /= std::sqrt(glm::dot(q, q));
  return {json_number(static_cast<float>(q.x)), json_number(static_cast<float>(q.y)),
          json_number(static_cast<float>(q.z)), json_number(static_cast<float>(q.w))};
}

struct SphereGeometry {
  Json attributes;
  int indices = -1;
};

class Exporter {
 public:
  explicit Exporter(const SceneAssets& assets) : assets_(assets) {}

  void add_instances(const FrameScene& frame);
  void add_spheres(const FrameScene& frame);
  void add_lights(const FrameScene& frame);
  void add_camera(const Camera& camera);
  Json document(const ExportOptions& options, bool embed_buffer) const;
  const std::string& buffer_bytes() const { return buffer_.bytes(); }

 private:
  void use_extension(const std::string& name);
  int texture(int index);
  int material(const Material& m);
  int mesh(uint32_t index);
  SphereGeometry sphere_geometry();
  void add_light(Json light, const std::string& name, LightType type, const glm::vec3& position,
                 const glm::vec3& direction);

  const SceneAssets& assets_;
  BufferBuilder buffer_;
  Json nodes_ = Json::array(), meshes_ = Json::array(), materials_ = Json::array();
  Json textures_ = Json::array(), images_ = Json::array(), samplers_ = Json::array();
  Json lights_ = Json::array(), cameras_ = Json::array();
  std::vector<std::string> extensions_;  // extensionsUsed, in order of first use
  std::map<uint32_t, int> material_of_;  // SceneAssets index -> glTF index
  std::map<int, int> texture_of_;
  std::map<std::pair<int, int>, int> sampler_of_;  // (wrapS, wrapT) -> glTF sampler
  std::map<uint32_t, int> mesh_of_;                // -1: a mesh without triangles, not written
};

void Exporter::use_extension(const std::string& name) {
  if (std::find(extensions_.begin(), extensions_.end(), name) == extensions_.end())
    extensions_.push_back(name);
}

int Exporter::texture(int index) {
  if (index < 0 || static_cast<size_t>(index) >= assets_.textures.size())
    fail("a material uses texture " + std::to_string(index) + " of " +
         std::to_string(assets_.textures.size()));
  if (const auto it = texture_of_.find(index); it != texture_of_.end()) return it->second;
  const Texture& t = assets_.textures[static_cast<size_t>(index)];
  const std::pair<int, int> wrap{wrap_code(t.wrap_u), wrap_code(t.wrap_v)};
  auto sampler = sampler_of_.find(wrap);
  if (sampler == sampler_of_.end()) {
    samplers_.push_back({{"wrapS", wrap.first}, {"wrapT", wrap.second}});
    sampler = sampler_of_.emplace(wrap, static_cast<int>(samplers_.size() - 1)).first;
  }
  Json image = {{"bufferView", buffer_.add_view(encode_png(t), 0)}, {"mimeType", "image/png"}};
  Json tex = {{"sampler", sampler->second}, {"source", images_.size()}};
  if (!t.name.empty()) image["name"] = tex["name"] = t.name;
  images_.push_back(std::move(image));
  textures_.push_back(std::move(tex));
  return texture_of_[index] = static_cast<int>(textures_.size() - 1);
}

int Exporter::material(const Material& m) {
  const glm::vec4 base(m.albedo, m.opacity);
  Json pbr = {{"baseColorFactor", json_numbers(&base.x, 4)}};
  if (m.texture >= 0) pbr["baseColorTexture"] = {{"index", texture(m.texture)}};
  pbr["metallicFactor"] = json_number(metallic_factor(m));
  pbr["roughnessFactor"] = json_number(m.specular.roughness);
  if (m.metallic_roughness_texture >= 0)
    pbr["metallicRoughnessTexture"] = {{"index", texture(m.metallic_roughness_texture)}};
  Json j = Json::object();
  if (!m.name.empty()) j["name"] = m.name;
  j["pbrMetallicRoughness"] = std::move(pbr);
  if (m.normal_texture >= 0) {
    Json normal = {{"index", texture(m.normal_texture)}};
    if (m.normal_scale != 1.0f) normal["scale"] = json_number(m.normal_scale);
    j["normalTexture"] = std::move(normal);
  }
  // emissiveFactor is at most 1 per component; KHR_materials_emissive_strength carries the rest.
  const Split emission = m.emission.x > 1.0f || m.emission.y > 1.0f || m.emission.z > 1.0f
                             ? split_power_of_two(m.emission)
                             : Split{m.emission, 1.0};
  if (emission.unit != glm::vec3(0.0f)) j["emissiveFactor"] = vec_json(emission.unit);
  if (m.emission_texture >= 0) j["emissiveTexture"] = {{"index", texture(m.emission_texture)}};
  if (m.alpha_mode == AlphaMode::kMask) {
    j["alphaMode"] = "MASK";
    j["alphaCutoff"] = json_number(m.alpha_cutoff);
  }
  if (m.double_sided) j["doubleSided"] = true;
  Json extensions = Json::object();
  if (emission.scale != 1.0) {
    extensions["KHR_materials_emissive_strength"] = {{"emissiveStrength", emission.scale}};
    use_extension("KHR_materials_emissive_strength");
  }
  // Every material names its ior: glTF's default (1.5, f0 0.04) is not the renderer's (no coat).
  extensions["KHR_materials_ior"] = {{"ior", ior_of(m.specular.f0)}};
  use_extension("KHR_materials_ior");
  j["extensions"] = std::move(extensions);
  materials_.push_back(std::move(j));
  return static_cast<int>(materials_.size() - 1);
}

int Exporter::mesh(uint32_t index) {
  if (index >= assets_.meshes.size())
    fail("an instance draws mesh " + std::to_string(index) + " of " +
         std::to_string(assets_.meshes.size()));
  if (const auto it = mesh_of_.find(index); it != mesh_of_.end()) return it->second;
  const Mesh& m = assets_.meshes[index];
  const size_t n = m.vertices.size();
  if (m.materials.size() != m.triangles.size())
    fail("mesh '" + m.name + "' has " + std::to_string(m.triangles.size()) + " triangles but " +
         std::to_string(m.materials.size()) + " materials");
  if (!m.tangents.empty() && m.tangents.size() != n)
    fail("mesh '" + m.name + "' has " + std::to_string(n) + " vertices but " +
         std::to_string(m.tangents.size()) + " tangents");
  // Triangles by material, each group in the mesh's order: one primitive each.
  std::map<uint32_t, std::vector<size_t>> groups;
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const glm::uvec3& tri = m.triangles[t];
    if (tri.x >= n || tri.y >= n || tri.z >= n)
      fail("mesh '" + m.name + "' triangle " + std::to_string(t) + " indexes past its " +
           std::to_string(n) + " vertices");
    if (m.materials[t] >= assets_.materials.size())
      fail("mesh '" + m.name + "' triangle " + std::to_string(t) + " uses material " +
           std::to_string(m.materials[t]) + " of " + std::to_string(assets_.materials.size()));
    groups[m.materials[t]].push_back(t);
  }
  if (groups.empty()) return mesh_of_[index] = -1;  // glTF meshes need a primitive

  Json primitives = Json::array();
  std::vector<uint32_t> remap(n);
  std::vector<bool> used;
  for (const auto& [material_index, triangles] : groups) {
    // Only the vertices this primitive uses, in the mesh's order.
    used.assign(n, false);
    for (const size_t t : triangles)
      for (int k = 0; k < 3; ++k) used[m.triangles[t][k]] = true;
    std::vector<float> positions, normals, uvs, tangents;
    uint32_t count = 0;
    for (size_t v = 0; v < n; ++v) {
      if (!used[v]) continue;
      remap[v] = count++;
      const Vertex& vx = m.vertices[v];
      positions.insert(positions.end(), {vx.position.x, vx.position.y, vx.position.z});
      normals.insert(normals.end(), {vx.normal.x, vx.normal.y, vx.normal.z});
      uvs.insert(uvs.end(), {vx.uv.x, 1.0f - vx.uv.y});  // glTF's v runs down the image
      if (!m.tangents.empty()) {
        const glm::vec4& t = m.tangents[v];
        tangents.insert(tangents.end(), {t.x, t.y, t.z, t.w});
      }
    }
    std::vector<uint32_t> indices;
    indices.reserve(triangles.size() * 3);
    for (const size_t t : triangles)
      for (int k = 0; k < 3; ++k) indices.push_back(remap[m.triangles[t][k]]);
    if (!all_finite(positions) || !all_finite(normals) || !all_finite(uvs) || !all_finite(tangents))
      fail("mesh '" + m.name + "' has a vertex attribute that is not finite");
    Json attributes = {{"POSITION", buffer_.add_floats(positions, 3, true)},
                       {"NORMAL", buffer_.add_floats(normals, 3, false)},
                       {"TEXCOORD_0", buffer_.add_floats(uvs, 2, false)}};
    if (!tangents.empty()) attributes["TANGENT"] = buffer_.add_floats(tangents, 4, false);
    int gltf_material = 0;
    if (const auto it = material_of_.find(material_index); it != material_of_.end()) {
      gltf_material = it->second;
    } else {
      gltf_material = material_of_[material_index] = material(assets_.materials[material_index]);
    }
    primitives.push_back({{"attributes", std::move(attributes)},
                          {"indices", buffer_.add_indices(indices, count)},
                          {"material", gltf_material}});
  }
  Json mesh = Json::object();
  if (!m.name.empty()) mesh["name"] = m.name;
  mesh["primitives"] = std::move(primitives);
  meshes_.push_back(std::move(mesh));
  return mesh_of_[index] = static_cast<int>(meshes_.size() - 1);
}

void Exporter::add_instances(const FrameScene& frame) {
  for (const MeshInstance& inst : frame.instances) {
    const int gltf_mesh = mesh(inst.mesh);
    if (gltf_mesh < 0) continue;
    Json node = Json::object();
    if (const std::string& name = assets_.meshes[inst.mesh].name; !name.empty())
      node["name"] = name;
    node["mesh"] = gltf_mesh;
    if (inst.model != glm::mat4(1.0f)) node["matrix"] = matrix_json(inst.model);
    Json flags = Json::object();
    if (!inst.casts_shadow) flags["casts_shadow"] = false;
    if (!inst.voxelize) flags["voxelize"] = false;
    if (!flags.empty()) node["extras"] = {{"rolypoly", std::move(flags)}};
    nodes_.push_back(std::move(node));
  }
}

SphereGeometry Exporter::sphere_geometry() {
  std::vector<float> positions, normals, uvs;
  for (int i = 0; i <= kSphereRings; ++i) {  // ring i at polar angle pi i / rings from +y
    const double theta = kPi * i / kSphereRings;
    const bool pole = i == 0 || i == kSphereRings;
    const double y = i == 0 ? 1.0 : i == kSphereRings ? -1.0 : std::cos(theta);
    const double r = pole ? 0.0 : std::sin(theta);
    for (int j = 0; j <= kSphereSegments; ++j) {  // column `segments` repeats 0 at u = 1 (seam)
      const double phi = 2.0 * kPi * j / kSphereSegments;
      // u grows eastwards seen from outside (+x towards -z), so textures are not mirrored.
      const glm::vec3 p(static_cast<float>(r * std::cos(phi)), static_cast<float>(y),
                        static_cast<float>(-r * std::sin(phi)));
      positions.insert(positions.end(), {p.x, p.y, p.z});
      normals.insert(normals.end(), {p.x, p.y, p.z});
      uvs.insert(uvs.end(),
                 {static_cast<float>(j) / kSphereSegments, static_cast<float>(i) / kSphereRings});
    }
  }
  std::vector<uint32_t> indices;
  const auto at = [](int i, int j) { return static_cast<uint32_t>(i * (kSphereSegments + 1) + j); };
  for (int i = 0; i < kSphereRings; ++i) {
    for (int j = 0; j < kSphereSegments; ++j) {
      // a d    counter-clockwise seen from outside; the pole rows' degenerate halves are
      // b c    left out
      const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (i != kSphereRings - 1) indices.insert(indices.end(), {a, b, c});
      if (i != 0) indices.insert(indices.end(), {a, c, d});
    }
  }
  SphereGeometry g;
  g.attributes = {{"POSITION", buffer_.add_floats(positions, 3, true)},
                  {"NORMAL", buffer_.add_floats(normals, 3, false)},
                  {"TEXCOORD_0", buffer_.add_floats(uvs, 2, false)}};
  g.indices = buffer_.add_indices(indices, positions.size() / 3);
  return g;
}

void Exporter::add_spheres(const FrameScene& frame) {
  SphereGeometry geometry;
  std::map<std::array<float, 9>, int> mesh_of_material;
  for (size_t i = 0; i < frame.spheres.size(); ++i) {
    const Sphere& s = frame.spheres[i];
    const std::array<float, 9> key = {
        s.albedo.x,           s.albedo.y,    s.albedo.z,
        s.emission.x,         s.emission.y,  s.emission.z,
        s.specular.roughness, s.specular.f0, s.specular.metal ? 1.0f : 0.0f};
    // The map needs ordered keys, which NaN is not.
    if (!all_finite({key.begin(), key.end()}) || !all_finite({s.radius}))
      fail("sphere " + std::to_string(i) + " holds a number that is not finite");
    // A zero scale is no valid node transform, and there is nothing to draw.
    if (!(s.radius > 0.0f)) continue;
    if (geometry.indices < 0) geometry = sphere_geometry();
    auto it = mesh_of_material.find(key);
    if (it == mesh_of_material.end()) {
      Material m;
      m.name = "sphere material " + std::to_string(mesh_of_material.size());
      m.albedo = s.albedo;
      m.emission = s.emission;
      m.specular = s.specular;
      m.metallic = s.specular.metal ? 1.0f : 0.0f;
      const int gltf_material = material(m);
      // Each sphere mesh is the same geometry under another material: the accessors are shared.
      meshes_.push_back({{"name", "sphere " + std::to_string(mesh_of_material.size())},
                         {"primitives", Json::array({{{"attributes", geometry.attributes},
                                                      {"indices", geometry.indices},
                                                      {"material", gltf_material}}})}});
      it = mesh_of_material.emplace(key, static_cast<int>(meshes_.size() - 1)).first;
    }
    glm::mat4 model(s.radius);
    model[3] = glm::vec4(s.center, 1.0f);
    Json node = {{"name", "sphere " + std::to_string(i)},
                 {"mesh", it->second},
                 {"matrix", matrix_json(model)}};
    if (!s.casts_shadow) node["extras"] = {{"rolypoly", {{"casts_shadow", false}}}};
    nodes_.push_back(std::move(node));
  }
}

void Exporter::add_light(Json light, const std::string& name, LightType type,
                         const glm::vec3& position, const glm::vec3& direction) {
  Json node = Json::object();
  if (!name.empty()) node["name"] = name;
  if (type != LightType::kDirectional) node["translation"] = vec_json(position);
  if (type != LightType::kPoint) node["rotation"] = rotation_from_minus_z(direction);
  node["extensions"] = {{"KHR_lights_punctual", {{"light", lights_.size()}}}};
  lights_.push_back(std::move(light));
  nodes_.push_back(std::move(node));
  use_extension("KHR_lights_punctual");
}

// KHR_lights_punctual's colour and intensity for the renderer's rgb intensity, which is
// colour * glTF intensity / pi (frame_scene.h): candela (or lux) read as W/sr (or W/m^2).
Json light_json(const std::string& name, const char* type, const glm::vec3& intensity) {
  const Split split = split_power_of_two(intensity);
  Json light = Json::object();
  if (!name.empty()) light["name"] = name;
  light["type"] = type;
  const bool black = split.unit == glm::vec3(0.0f);  // written as white at intensity 0
  light["color"] = vec_json(black ? glm::vec3(1.0f) : split.unit);
  light["intensity"] = black ? 0.0 : kPi * split.scale;
  return light;
}

void Exporter::add_lights(const FrameScene& frame) {
  if (frame.lamp) {
    // The demo's lamp: a point light, and the rest of PointLight for the loader to restore it.
    const PointLight& lamp = frame.light;
    Json light = light_json("lamp", "point", lamp.intensity);
    light["extras"] = {{"rolypoly",
                        {{"lamp",
                          {{"radius", json_number(lamp.lamp_radius)},
                           {"shadow_fov_y_deg", json_number(lamp.shadow_fov_y_deg)},
                           {"shadow_near", json_number(lamp.shadow_near)},
                           {"shadow_far", json_number(lamp.shadow_far)}}}}}};
    add_light(std::move(light), "lamp", LightType::kPoint, lamp.position, {});
  }
  for (const PunctualLight& l : frame.lights) {
    static constexpr const char* kTypes[] = {"directional", "point", "spot"};
    Json light = light_json(l.name, kTypes[static_cast<int>(l.type)], l.intensity);
    if (l.type != LightType::kDirectional && l.range > 0.0f) light["range"] = json_number(l.range);
    if (l.type == LightType::kSpot) {
      // glTF wants 0 <= inner < outer <= pi/2. The renderer's inner >= outer is a hard edge:
      // inner just below outer, which a float reader rounds back to outer.
      const double outer = std::clamp(static_cast<double>(l.outer_cone), 1e-6, kPi / 2.0);
      const double inner =
          std::clamp(static_cast<double>(l.inner_cone), 0.0, std::nextafter(outer, 0.0));
      light["spot"] = {{"innerConeAngle", inner}, {"outerConeAngle", outer}};
    }
    add_light(std::move(light), l.name, l.type, l.position, l.direction);
  }
}

void Exporter::add_camera(const Camera& camera) {
  if (!(camera.fov_y_deg > 0.0f && camera.fov_y_deg < 180.0f && camera.near_plane > 0.0f &&
        camera.far_plane > camera.near_plane))
    fail("the camera's field of view or clip planes are out of range");
  // inverse(view()): the camera's own axes (x right, y up, looking down -z) in world space.
  const glm::dvec3 position(camera.position);
  const glm::dvec3 f = glm::normalize(glm::dvec3(camera.target) - position);
  const glm::dvec3 s = glm::normalize(glm::cross(f, glm::dvec3(camera.up)));
  const glm::dvec3 u = glm::cross(s, f);
  if (!std::isfinite(s.x + s.y + s.z + f.x + f.y + f.z))
    fail("the camera has no view direction (target at its position, or up along the view)");
  const glm::mat4 world(glm::vec4(glm::vec3(s), 0.0f), glm::vec4(glm::vec3(u), 0.0f),
                        glm::vec4(glm::vec3(-f), 0.0f), glm::vec4(camera.position, 1.0f));
  cameras_.push_back({{"name", "camera"},
                      {"type", "perspective"},
                      {"perspective",
                       {{"yfov", camera.fov_y_deg * kPi / 180.0},
                        {"znear", json_number(camera.near_plane)},
                        {"zfar", json_number(camera.far_plane)}}}});
  nodes_.push_back({{"name", "camera"}, {"camera", 0}, {"matrix", matrix_json(world)}});
}

Json Exporter::document(const ExportOptions& options, bool embed_buffer) const {
  Json doc = {{"asset", {{"version", "2.0"}, {"generator", "rolypoly"}}}};
  if (!extensions_.empty()) doc["extensionsUsed"] = extensions_;
  Json scene = {{"name", "rolypoly frame"}, {"nodes", Json::array()}};
  for (size_t i = 0; i < nodes_.size(); ++i) scene["nodes"].push_back(i);
  if (options.volume) {
    const Bounds& v = *options.volume;
    if (v.empty()) fail("the volume is empty");
    scene["extras"] = {{"rolypoly",
                        {{"volume", Json::array({json_number(v.lo.x), json_number(v.lo.y),
                                                 json_number(v.lo.z), json_number(v.hi.x),
                                                 json_number(v.hi.y), json_number(v.hi.z)})}}}};
  }
  doc["scene"] = 0;
  doc["scenes"] = Json::array({std::move(scene)});
  // glTF's top-level arrays hold at least one item when present.
  const auto put = [&doc](const char* key, const Json& array) {
    if (!array.empty()) doc[key] = array;
  };
  put("nodes", nodes_);
  put("cameras", cameras_);
  put("meshes", meshes_);
  put("materials", materials_);
  put("textures", textures_);
  put("images", images_);
  put("samplers", samplers_);
  put("accessors", buffer_.accessors());
  put("bufferViews", buffer_.views());
  if (!buffer_.bytes().empty()) {
    Json buffer = {{"byteLength", buffer_.bytes().size()}};
    if (embed_buffer) buffer["uri"] = data_uri(buffer_.bytes());
    doc["buffers"] = Json::array({std::move(buffer)});
  }
  if (!lights_.empty()) doc["extensions"] = {{"KHR_lights_punctual", {{"lights", lights_}}}};
  return doc;
}

bool is_gltf_text(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".gltf";
}

}  // namespace
}  // namespace gltf_export

void export_gltf(const SceneAssets& assets, const FrameScene& frame,
                 const std::filesystem::path& path, const ExportOptions& options) {
  using namespace gltf_export;
  Exporter exporter(assets);
  exporter.add_instances(frame);
  exporter.add_spheres(frame);
  exporter.add_lights(frame);
  exporter.add_camera(frame.camera);
  const bool text = is_gltf_text(path);
  const Json doc = exporter.document(options, text);
  // Names come from assets and files: invalid UTF-8 is replaced rather than refused.
  const auto dump = [&doc](int indent) {
    return doc.dump(indent, ' ', false, nlohmann::detail::error_handler_t::replace);
  };
  if (text) {
    io::write_file(path, dump(1) + "\n");
  } else {
    io::write_file(path, glb(dump(-1), exporter.buffer_bytes()));
  }
}

}  // namespace rp::scene
