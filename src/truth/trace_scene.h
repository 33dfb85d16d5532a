// The path tracer's view of a frame (internal to truth/): Embree BVHs of the frame's geometry
// and the surface found by a ray (position, normals, albedo, emission), with the conventions of
// truth/path_tracer.h. The same layout as the Embree visibility backend
// (passes/embree_visibility.h): one HIGH quality BVH per mesh, every mesh instance an Embree
// instance of it, marbles, fireballs and particles as native spheres; built from the FrameScene
// directly, so the path tracer needs no OpenCL device.
//
//   scene         everything: what camera, gather and light-sample rays hit.
//   shadow scene  only the shadow casters (casts_shadow): what the lamp's shadow rays test;
//   light shadow scene  those and the instances with casts_light_shadow (the demo's box): what
//                 the sky's and the punctual lights' shadow rays test (the shadow scene itself
//                 when there are none).
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "scene/alpha_mask.h"
#include "scene/frame_scene.h"

namespace rp::truth {

// An Embree ray from `org` along `dir` (not normalised here) up to t_max, every mask bit set.
RTCRay make_ray(glm::vec3 org, glm::vec3 dir, float t_max);

// A mesh as Embree and the shading read it (object space).
struct TraceMesh {
  std::vector<float> positions;      // x, y, z, 0 per vertex (+ one padding vertex: Embree)
  std::vector<uint32_t> indices;     // 3 per triangle
  std::vector<glm::vec3> normals;    // per vertex
  std::vector<glm::vec2> uvs;        // per vertex
  std::vector<uint32_t> materials;   // per triangle
  std::vector<glm::vec4> tangents;   // per vertex, empty without a normal map (frame_scene.h)
  RTCScene bvh = nullptr;            // nullptr for a mesh without triangles
  const class TraceAssets* owner = nullptr;  // materials and textures (the alpha mask's filter)
  // Texture coordinates at barycentrics (b1, b2) of triangle `prim`.
  glm::vec2 uv_at(uint32_t prim, float b1, float b2) const;
};

// A texture decoded to linear values (rows top to bottom): rgb, 3 floats per texel (colour
// textures sRGB-decoded, data textures byte / 255).
struct LinearTexture {
  int width = 0, height = 0;
  std::vector<float> rgb;
  scene::TextureWrap wrap_u = scene::TextureWrap::kRepeat;
  scene::TextureWrap wrap_v = scene::TextureWrap::kRepeat;
  // Bilinear, texel centres at +0.5, v up, folded by the wrap modes (repeat: the arithmetic of
  // kernels/common/span_texture.h).
  glm::vec3 sample(glm::vec2 uv) const;
};

// A surface point found by a ray.
struct Surface {
  glm::vec3 p{0.0f};        // world position
  glm::vec3 ng{0.0f};       // unit geometric normal, facing the ray's origin
  glm::vec3 ns{0.0f};       // unit shading normal, on ng's side
  glm::vec3 albedo{0.0f};
  glm::vec3 emission{0.0f};
  scene::Specular specular{};  // the coat over albedo (src/shading/brdf.h); default none
  bool lights_scene = true;  // false: emission seen by the camera only (voxelize == false)
  uint32_t instance = 0xFFFFFFFFu, sphere = 0xFFFFFFFFu, material = 0xFFFFFFFFu;
};

// Static assets: meshes' BVHs and linear textures, built once per PathTracer.
class TraceAssets {
 public:
  explicit TraceAssets(const scene::SceneAssets& assets);
  ~TraceAssets();
  TraceAssets(const TraceAssets&) = delete;
  TraceAssets& operator=(const TraceAssets&) = delete;

  RTCDevice device() const { return device_; }
  const std::vector<TraceMesh>& meshes() const { return meshes_; }
  const std::vector<scene::Material>& materials() const { return materials_; }
  const std::vector<LinearTexture>& textures() const { return textures_; }
  // Where alpha-masked materials have holes (frame_scene.h AlphaMode).
  const scene::AlphaMasks& masks() const { return masks_; }
  void check(const char* what) const;  // throws std::runtime_error on a pending Embree error

 private:
  // Embree filter of meshes with alpha-masked materials: rejects hits in holes.
  static void alpha_filter(const RTCFilterFunctionNArguments* args);

  RTCDevice device_ = nullptr;
  std::vector<TraceMesh> meshes_;
  std::vector<scene::Material> materials_;
  std::vector<LinearTexture> textures_;
  scene::AlphaMasks masks_;
};

// One frame's top-level scenes over TraceAssets.
class TraceScene {
 public:
  TraceScene(const TraceAssets& assets, const scene::FrameScene& frame);
  ~TraceScene();
  TraceScene(const TraceScene&) = delete;
  TraceScene& operator=(const TraceScene&) = delete;

  // Who looks along a ray: the camera does not see the back faces of single-sided materials
  // (scene::Material::double_sided false, as the rasterizer culls them); light and every
  // later bounce see both sides.
  enum class Viewer { kLight, kCamera };
  // Nearest surface along org + t dir, t in (0, t_max); false when the ray leaves the scene.
  bool intersect(glm::vec3 org, glm::vec3 dir, float t_max, Surface& out,
                 Viewer viewer = Viewer::kLight) const;
  // True when a shadow caster lies on org + t dir, t in (0, t_max): the lamp's (shadowed) or
  // the sky's and the punctual lights' (light_shadowed).
  bool shadowed(glm::vec3 org, glm::vec3 dir, float t_max) const;
  bool light_shadowed(glm::vec3 org, glm::vec3 dir, float t_max) const;
  const scene::FrameScene& frame() const { return *frame_; }

 private:
  enum class Casters { kAll, kLamp, kLight };
  void add_instances(RTCScene top, Casters which);
  // True when the hit is a mesh triangle of a single-sided material seen from behind.
  bool back_of_single_sided(const RTCRayHit& rh) const;

  const TraceAssets* assets_;
  const scene::FrameScene* frame_;
  std::vector<glm::mat4> normal_matrices_;  // per instance: inverse transpose of model
  std::vector<float> sphere_points_, caster_points_;  // x, y, z, r per sphere (+ padding)
  std::vector<uint32_t> sphere_index_;                // scene's sphere primID -> frame sphere
  std::vector<uint32_t> caster_spheres_;              // shadow scene's sphere -> frame sphere
  unsigned sphere_geometry_ = 0;                      // geometry id of the spheres in scene_
  RTCScene scene_ = nullptr, shadow_scene_ = nullptr;
  RTCScene light_shadow_scene_ = nullptr;  // nullptr: shadow_scene_ serves
};

}  // namespace rp::truth
