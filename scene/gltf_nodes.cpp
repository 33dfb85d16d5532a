// The node hierarchy (transforms composed from the roots down), and what nodes place besides
// meshes: KHR_lights_punctual lights and cameras.
#include <cmath>
#include <limits>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include "scene/gltf_internal.h"

namespace rp::scene::gltf {
namespace {

// A world matrix the renderer can use: every entry finite and within float range.
void check_matrix(const Context& ctx, const glm::dmat4& m, const std::string& where) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!fits_float(m[c][r])) ctx.fail(where + ": its transform is not finite (or too large)");
}

glm::dmat4 local_matrix(const Context& ctx, const tinygltf::Node& n, const std::string& where) {
  if (!n.matrix.empty()) {
    if (n.matrix.size() != 16) ctx.fail(where + ": matrix must have 16 numbers");
    glm::dmat4 m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        m[c][r] = n.matrix[static_cast<size_t>(4 * c + r)];  // column-major
    return m;
  }
  glm::dmat4 m(1.0);
  if (!n.translation.empty()) {
    if (n.translation.size() != 3) ctx.fail(where + ": translation must have 3 numbers");
    m[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
  }
  if (!n.rotation.empty()) {
    if (n.rotation.size() != 4) ctx.fail(where + ": rotation must have 4 numbers");
    // glTF stores (x, y, z, w); glm's constructor takes w first.
    const glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    const double len = glm::length(q);
    if (!(len > 1e-12) || !std::isfinite(len))
      ctx.fail(where + ": rotation is not a unit quaternion");
    m = m * glm::mat4_cast(q / len);
  }
  if (!n.scale.empty()) {
    if (n.scale.size() != 3) ctx.fail(where + ": scale must have 3 numbers");
    m = m * glm::dmat4(glm::dvec4(n.scale[0], 0, 0, 0), glm::dvec4(0, n.scale[1], 0, 0),
                       glm::dvec4(0, 0, n.scale[2], 0), glm::dvec4(0, 0, 0, 1));
  }
  return m;
}

// The unit direction of a world matrix's column, or nothing where the transform collapses it.
std::optional<glm::vec3> axis(const glm::dmat4& world, int column, double sign) {
  const glm::dvec3 a = sign * glm::dvec3(world[column]);
  const double len = glm::length(a);
  if (!(len > 1e-12) || !std::isfinite(len)) return std::nullopt;
  return glm::vec3(a / len);
}

}  // namespace

bool fits_float(double v) {
  return std::isfinite(v) && std::abs(v) <= static_cast<double>(std::numeric_limits<float>::max());
}

float to_float(const Context& ctx, double v, const std::string& where) {
  if (!fits_float(v)) ctx.fail(where + ": a value is not finite (or too large)");
  return static_cast<float>(v);
}

void walk_nodes(Context& ctx, const std::vector<int>& roots,
                const std::function<void(int node, const glm::dmat4& world)>& visit) {
  const std::vector<tinygltf::Node>& nodes = ctx.model->nodes;
  const std::string count = " (" + std::to_string(nodes.size()) + " nodes)";
  std::vector<int> parent(nodes.size(), -1);
  for (size_t i = 0; i < nodes.size(); ++i) {
    for (const int c : nodes[i].children) {
      if (c < 0 || static_cast<size_t>(c) >= nodes.size())
        ctx.fail("node " + std::to_string(i) + ": child " + std::to_string(c) + " does not exist" +
                 count);
      int& p = parent[static_cast<size_t>(c)];
      if (p != -1)
        ctx.fail("node " + std::to_string(c) + " has two parents (nodes " + std::to_string(p) +
                 " and " + std::to_string(i) + ")");
      p = static_cast<int>(i);
    }
  }
  std::vector<char> visited(nodes.size(), 0);
  const std::function<void(int, const glm::dmat4&, int)> walk =
      [&](int node, const glm::dmat4& above, int depth) {
        const std::string where = "node " + std::to_string(node);
        if (depth > ctx.limits.max_node_depth)
          ctx.fail(where + ": the node hierarchy is deeper than " +
                   std::to_string(ctx.limits.max_node_depth) + " levels");
        if (visited[static_cast<size_t>(node)])
          ctx.fail(where + " is reached twice (a cycle, or a root listed twice)");
        visited[static_cast<size_t>(node)] = 1;
        const tinygltf::Node& n = nodes[static_cast<size_t>(node)];
        const glm::dmat4 world = above * local_matrix(ctx, n, where);
        check_matrix(ctx, world, where);
        visit(node, world);
        for (const int c : n.children) walk(c, world, depth + 1);
      };
  for (const int r : roots) {
    if (r < 0 || static_cast<size_t>(r) >= nodes.size())
      ctx.fail("root node " + std::to_string(r) + " does not exist" + count);
    if (parent[static_cast<size_t>(r)] != -1)
      ctx.fail("root node " + std::to_string(r) + " is also a child of node " +
               std::to_string(parent[static_cast<size_t>(r)]));
    walk(r, glm::dmat4(1.0), 1);
  }
}

int node_light(const Context& ctx, int node) {
  const tinygltf::Node& n = ctx.model->nodes[static_cast<size_t>(node)];
  const auto ext = n.extensions.find("KHR_lights_punctual");
  if (ext == n.extensions.end() || !ext->second.Has("light")) return -1;
  const tinygltf::Value& light = ext->second.Get("light");
  if (!light.IsInt())
    ctx.fail("node " + std::to_string(node) + ": KHR_lights_punctual.light is not an index");
  return light.Get<int>();  // non-negative: checked before tinygltf parsed it
}

std::optional<PunctualLight> convert_light(Context& ctx, int index, const glm::dmat4& world,
                                           const std::string& where) {
  const std::vector<tinygltf::Light>& lights = ctx.model->lights;
  if (index < 0 || static_cast<size_t>(index) >= lights.size())
    ctx.fail(where + ": light " + std::to_string(index) + " does not exist (" +
             std::to_string(lights.size()) + " lights)");
  const tinygltf::Light& g = lights[static_cast<size_t>(index)];
  const std::string at = "light " + std::to_string(index);
  PunctualLight light;
  light.name = g.name.empty() ? at : g.name;
  glm::dvec3 colour(1.0);  // glTF's default: white
  if (!g.color.empty()) {
    if (g.color.size() != 3) ctx.fail(at + ": color must have 3 numbers");
    colour = glm::dvec3(g.color[0], g.color[1], g.color[2]);
    if (colour.x < 0 || colour.y < 0 || colour.z < 0) ctx.fail(at + ": color must not be negative");
  }
  if (!(g.intensity >= 0.0)) ctx.fail(at + ": intensity must not be negative");
  // Candela (point, spot) as W/sr and lux (directional) as W/m^2, then the renderer's
  // convention of no 1/pi in the Lambertian term (frame_scene.h): colour x intensity / pi.
  const glm::dvec3 intensity = colour * g.intensity / glm::pi<double>();
  for (int c = 0; c < 3; ++c) light.intensity[c] = to_float(ctx, intensity[c], at + " intensity");
  if (!(g.range >= 0.0)) ctx.fail(at + ": range must be positive (or absent: infinite)");
  light.range = to_float(ctx, g.range, at + " range");
  if (g.type == "directional") {
    light.type = LightType::kDirectional;
  } else if (g.type == "point") {
    light.type = LightType::kPoint;
  } else if (g.type == "spot") {
    light.type = LightType::kSpot;
    const double inner = g.spot.innerConeAngle, outer = g.spot.outerConeAngle;
    if (!(inner >= 0.0 && inner < outer && outer <= glm::half_pi<double>()))
      ctx.fail(at + ": spot cone angles must satisfy 0 <= inner < outer <= pi/2");
    light.inner_cone = static_cast<float>(inner);
    light.outer_cone = static_cast<float>(outer);
  } else {
    ctx.fail(at + ": type \"" + g.type.substr(0, 20) + "\" is not directional, point or spot");
  }
  light.position = glm::vec3(world[3]);
  // The light shines along the node's -Z axis.
  if (const auto dir = axis(world, 2, -1.0)) {
    light.direction = *dir;
  } else if (light.type != LightType::kPoint) {
    ctx.warnings.add("lights whose node's transform has no direction (zero scale) are left out",
                     where);
    return std::nullopt;
  }
  return light;
}

namespace {

// extras.rolypoly of a node or light, or nullptr.
const tinygltf::Value* rolypoly_extras(const tinygltf::Value& extras) {
  if (!extras.IsObject() || !extras.Has("rolypoly")) return nullptr;
  const tinygltf::Value& r = extras.Get("rolypoly");
  return r.IsObject() ? &r : nullptr;
}

}  // namespace

std::optional<PointLight> lamp_of(Context& ctx, int light, const PunctualLight& placed) {
  const tinygltf::Light& g = ctx.model->lights[static_cast<size_t>(light)];
  const tinygltf::Value* r = rolypoly_extras(g.extras);
  if (!r || !r->Has("lamp")) return std::nullopt;
  const std::string at = "light " + std::to_string(light) + ": extras.rolypoly.lamp";
  const tinygltf::Value& l = r->Get("lamp");
  if (!l.IsObject() || placed.type != LightType::kPoint)
    ctx.fail(at + " must be an object on a point light");
  PointLight lamp;
  lamp.position = placed.position;
  lamp.intensity = placed.intensity;
  auto number = [&](const char* key, float* out) {
    if (!l.Has(key)) return;  // PointLight's default
    const tinygltf::Value& v = l.Get(key);
    if (!v.IsNumber() || !fits_float(v.GetNumberAsDouble()))
      ctx.fail(at + "." + key + " must be a number");
    *out = static_cast<float>(v.GetNumberAsDouble());
  };
  number("radius", &lamp.lamp_radius);
  number("shadow_fov_y_deg", &lamp.shadow_fov_y_deg);
  number("shadow_near", &lamp.shadow_near);
  number("shadow_far", &lamp.shadow_far);
  if (!(lamp.lamp_radius > 0.0f && lamp.shadow_fov_y_deg > 0.0f && lamp.shadow_fov_y_deg < 180.0f &&
        lamp.shadow_near > 0.0f && lamp.shadow_far > lamp.shadow_near))
    ctx.fail(at +
             ": radius and shadow_near must be positive, shadow_fov_y_deg in (0, 180), "
             "shadow_far beyond shadow_near");
  return lamp;
}

void instance_flags(const Context& ctx, int node, MeshInstance* instance) {
  const tinygltf::Value* r = rolypoly_extras(ctx.model->nodes[static_cast<size_t>(node)].extras);
  if (!r) return;
  auto flag = [&](const char* key, bool* out) {
    if (!r->Has(key)) return;
    const tinygltf::Value& v = r->Get(key);
    if (!v.IsBool())
      ctx.fail("node " + std::to_string(node) + ": extras.rolypoly." + key +
               " must be true or false");
    *out = v.Get<bool>();
  };
  flag("casts_shadow", &instance->casts_shadow);
  flag("voxelize", &instance->voxelize);
}

std::optional<PlacedCamera> convert_camera(Context& ctx, int index, const glm::dmat4& world,
                                           const std::string& where) {
  const std::vector<tinygltf::Camera>& cameras = ctx.model->cameras;
  if (index < 0 || static_cast<size_t>(index) >= cameras.size())
    ctx.fail(where + ": camera " + std::to_string(index) + " does not exist (" +
             std::to_string(cameras.size()) + " cameras)");
  const tinygltf::Camera& g = cameras[static_cast<size_t>(index)];
  const std::string at = "camera " + std::to_string(index);
  if (g.type == "orthographic") {
    ctx.warnings.add("orthographic cameras are ignored", at);
    return std::nullopt;
  }
  if (g.type != "perspective")
    ctx.fail(at + ": type \"" + g.type.substr(0, 20) + "\" is not perspective or orthographic");
  const tinygltf::PerspectiveCamera& p = g.perspective;
  if (!(p.yfov > 0.0 && p.yfov < glm::pi<double>())) ctx.fail(at + ": yfov must be in (0, pi)");
  // Compared as the floats the renderer gets: 1e-50 is no positive float.
  if (!fits_float(p.znear) || !(static_cast<float>(p.znear) > 0.0f))
    ctx.fail(at + ": znear must be positive");
  if (p.zfar != 0.0 &&
      !(fits_float(p.zfar) && static_cast<float>(p.zfar) > static_cast<float>(p.znear)))
    ctx.fail(at + ": zfar must be greater than znear");
  const auto forward = axis(world, 2, -1.0), up = axis(world, 1, 1.0);
  if (!forward || !up) {
    ctx.warnings.add("cameras whose node's transform collapses an axis (zero scale) are ignored",
                     where);
    return std::nullopt;
  }
  PlacedCamera placed;
  Camera& c = placed.camera;
  c.position = glm::vec3(world[3]);
  c.target = c.position + *forward;  // the camera looks down its node's -Z axis, +Y up
  c.up = *up;
  c.fov_y_deg = static_cast<float>(glm::degrees(p.yfov));
  c.near_plane = static_cast<float>(p.znear);
  c.far_plane = static_cast<float>(p.zfar);
  placed.far_from_bounds = p.zfar == 0.0;
  return placed;
}

}  // namespace rp::scene::gltf
