// What the renderer needs to draw one frame, and the static assets it draws from.
// Plain C++ and GLM: the scene knows nothing of OpenCL (DESIGN.md). The renderer converts these
// into the GPU layouts of kernels/shared/types.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/environment.h"

namespace rp::scene {

// Pinhole camera. Angles in degrees, distances in world units (the box spans [-1,1]^3).
struct Camera {
  glm::vec3 position{0.0f, 0.0f, 2.7f};  // the open side (z = 1) just fills the 60 degree view
  glm::vec3 target{0.0f, 0.0f, 0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_y_deg = 60.0f;
  float near_plane = 0.1f;
  float far_plane = 4.0f;

  glm::mat4 view() const;                      // world -> view (right-handed, looks down -z)
  glm::mat4 projection(float aspect) const;    // view -> clip, OpenGL NDC (z in [-1,1])
};

// Point light at the lamp centre (outside the box, above the ceiling).
struct PointLight {
  glm::vec3 position{0.0f, 1.1f, 0.0f};
  float lamp_radius = 0.35f;       // radius of the icosphere the lamp cap is cut from
  glm::vec3 intensity{8.0f};       // radiant intensity (rgb), W/sr in scene units: the floor
                                   // centre (2.1 below) gets ~1.8, mid walls ~1.4 before tone map
  float shadow_fov_y_deg = 120.0f; // shadow-map frustum, looking down -y
  float shadow_near = 0.05f;
  float shadow_far = 2.5f;
  glm::mat4 view_proj() const;     // world -> shadow-map clip space
};

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec2 uv;
};

// Indexed triangle mesh in object space; one material per triangle.
struct Mesh {
  std::string name;
  std::vector<Vertex> vertices;
  std::vector<glm::uvec3> triangles;   // indices into vertices, counter-clockwise seen from outside
  std::vector<uint32_t> materials;     // per triangle, index into SceneAssets::materials
  // Per-vertex tangent frame for normal maps (glTF TANGENT: xyz unit tangent along +u, w = +-1
  // the bitangent's sign, bitangent = w * cross(normal, tangent)); empty when no material of
  // the mesh has a normal map.
  std::vector<glm::vec4> tangents;
  // A coarser stand-in (index into SceneAssets::meshes, or -1: none) drawn instead of this mesh
  // where the mesh's triangles are far smaller than what they are drawn into: by the voxelizer
  // in GI volumes of at most proxy_max_voxels voxels per side, into shadow maps of at most
  // proxy_max_shadow_texels texels per side. The voxels average many of the mesh's triangles
  // and the shadow filters span several texels, so a proxy with a fraction of the triangles
  // gives nearly the same result for a fraction of the cost. The camera always draws the mesh.
  int proxy = -1;
  uint32_t proxy_max_voxels = 0;
  uint32_t proxy_max_shadow_texels = 0;
};

// The specular coat over a surface's Lambertian base (the model and its formulas are
// src/shading/brdf.h). The default is no coat: plain Lambert.
struct Specular {
  float roughness = 1.0f;  // perceptual roughness in [0, 1]; GGX alpha = roughness^2
  float f0 = 0.0f;         // dielectric coat's reflectance at normal incidence, ((n-1)/(n+1))^2
                           // (0.04 for n = 1.5; at most 0.249); 0 and not metal = no coat
  bool metal = false;      // true: a metal, F0 = the albedo colour, no diffuse base
};

// How a material's base colour alpha is used (glTF alphaMode; BLEND is loaded as kMask).
enum class AlphaMode : uint8_t {
  kOpaque,  // alpha ignored
  kMask,    // a surface point with alpha < alpha_cutoff does not exist (leaves, chains): the
            // camera, shadows, voxelizer and path tracer all see through it
};

struct Material {
  std::string name;
  glm::vec3 albedo{0.8f};              // linear base colour (glTF baseColorFactor.rgb)
  glm::vec3 emission{0.0f};            // emitted radiance, linear rgb (glTF emissiveFactor x
                                       // KHR_materials_emissive_strength)
  int texture = -1;                    // base colour (sRGB rgb, linear alpha) in
                                       // SceneAssets::textures, or -1; multiplies albedo
  Specular specular{};                 // default: matte (no coat)
  // glTF metallic-roughness. A file's material maps onto `specular` as: roughness =
  // roughnessFactor, metal = metallicFactor >= 0.5, f0 = 0.04 for dielectrics. Where a texture
  // is given its G channel scales the roughness and its B channel the metallic factor per texel.
  float metallic = 0.0f;               // glTF metallicFactor in [0, 1]
  int metallic_roughness_texture = -1; // linear texture (G roughness, B metallic), or -1
  int normal_texture = -1;             // tangent-space normal map (linear rgb), or -1
  float normal_scale = 1.0f;           // glTF normalTexture.scale (x and y of the map)
  int emission_texture = -1;           // sRGB texture multiplying `emission`, or -1
  float opacity = 1.0f;                // base colour alpha (baseColorFactor.a), times texture alpha
  AlphaMode alpha_mode = AlphaMode::kOpaque;
  float alpha_cutoff = 0.5f;           // kMask: alpha below this is a hole
  bool double_sided = false;           // glTF doubleSided: back faces are shaded with the
                                       // flipped normal; the demo's closed meshes keep false
};

// How texture coordinates outside [0, 1] are folded back (glTF sampler wrapS / wrapT).
enum class TextureWrap : uint8_t { kRepeat, kClampToEdge, kMirroredRepeat };

// RGBA8 texture, rows top to bottom. Colour textures (base colour, emission) hold sRGB-encoded
// rgb; data textures (normal, metallic-roughness) hold linear values: `srgb` says which.
struct Texture {
  std::string name;
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;           // width * height * 4 bytes
  bool srgb = true;
  TextureWrap wrap_u = TextureWrap::kRepeat;
  TextureWrap wrap_v = TextureWrap::kRepeat;
};

// Everything uploaded once: meshes, materials, textures.
struct SceneAssets {
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
};

// The mesh the voxelizer takes for `mesh` in a GI volume of `voxel_resolution` voxels per side,
// and the one the shadow map draws at `shadow_size` texels per side: its proxy where it has
// one for that resolution, else the mesh itself.
uint32_t voxel_mesh(const std::vector<Mesh>& meshes, uint32_t mesh, uint32_t voxel_resolution);
uint32_t shadow_mesh(const std::vector<Mesh>& meshes, uint32_t mesh, uint32_t shadow_size);

// Axis-aligned box in world units.
struct Bounds {
  glm::vec3 lo{0.0f};
  glm::vec3 hi{0.0f};
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  glm::vec3 center() const { return 0.5f * (lo + hi); }
  glm::vec3 size() const { return hi - lo; }
};

// A punctual light of a loaded scene (glTF KHR_lights_punctual). Units follow the renderer's
// convention (DESIGN.md, "light units"): direct radiance from a Lambertian surface is
// albedo * intensity * cos(theta) * attenuation, with no 1/pi. The loader converts from glTF's
// photometric units as radiometric ones (candela as W/sr, lux as W/m^2): intensity = colour *
// glTF intensity / pi, so a white surface 1 m under a 1 cd point light reflects 1/pi.
enum class LightType : uint8_t { kDirectional, kPoint, kSpot };

struct PunctualLight {
  std::string name;
  LightType type = LightType::kPoint;
  glm::vec3 position{0.0f};            // world (point, spot)
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // unit, the way the light travels (directional,
                                       // spot): the node's -z axis
  glm::vec3 intensity{1.0f};           // rgb, see above; point/spot: x 1/d^2, directional: as is
  float range = 0.0f;                  // point/spot: 0 = infinite; else glTF's window
                                       // clamp(1 - (d / range)^4, 0, 1) multiplies 1/d^2
  float inner_cone = 0.0f;             // spot: radians from the axis, full intensity inside
  float outer_cone = 0.7853982f;       // spot: radians, zero outside; between: glTF's smooth
                                       // t = clamp((cos a - cos outer) / (cos inner - cos outer)),
                                       // attenuation t^2
  // A sun of the environment map (scene/environment_suns.h): the real-time modes light by it,
  // the path tracer finds its light in the map (Environment::residual) and leaves it out here.
  bool in_environment = false;
};

struct MeshInstance {
  uint32_t mesh = 0;                   // index into SceneAssets::meshes
  glm::mat4 model{1.0f};
  glm::mat4 prev_model{1.0f};
  bool casts_shadow = true;
  // Also in the shadows of the punctual lights and the sky (their shadow maps, the path
  // tracer's sky and punctual shadow rays) without casts_shadow: the demo's box, which must
  // not shadow its own lamp (hung inside the ceiling) but keeps the sun out.
  bool casts_light_shadow = false;
  // Part of the GI voxel volume. False for the lamp cap: the direct pass already lights the
  // scene with the analytic point light at its centre; voxelizing its emission too would count
  // the lamp's light twice.
  bool voxelize = true;
};

struct Sphere {
  glm::vec3 center{0.0f};
  glm::vec3 prev_center{0.0f};
  float radius = 0.05f;
  glm::vec3 albedo{0.8f};
  glm::vec3 emission{0.0f};
  Specular specular{};                 // marbles: demo::kMarbleSpecular; others matte
  bool casts_shadow = true;            // marbles occlude; fireballs and particles only emit
};

// One frame's dynamic state.
struct FrameScene {
  Camera camera;
  Camera prev_camera;
  PointLight light;                    // the demo's ceiling lamp, used only when `lamp` is true
  bool lamp = true;
  std::vector<PunctualLight> lights;   // a loaded scene's lights (the demo has none)
  Environment environment;             // sky or studio light from afar (none by default; the
                                       // path tracer's so far, scene/environment.h)
  std::vector<MeshInstance> instances;
  std::vector<Sphere> spheres;
  uint32_t frame_index = 0;
};

}  // namespace rp::scene
