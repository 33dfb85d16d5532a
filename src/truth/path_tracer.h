// Ground truth: an unbiased Monte Carlo path tracer of a scene::FrameScene on the
// host's cores with Embree, with exactly rolypoly's conventions, so that every real-time mode can
// be held against it pixel by pixel (bench/src/accuracy_report.h).
//
// Conventions (the same as the real-time passes; DESIGN.md "Ground truth is part of the product"):
//   camera    pinhole at Camera::position; pixel (x, y), (0, 0) top-left, is box filtered: each
//             sample is a ray through a uniformly random point of the pixel, unprojected with the
//             unjittered inverse view-projection of Camera::view() / projection(width / height).
//   surfaces  Lambertian, albedo = material albedo x bilinear texture (wrap, texel centres at
//             +0.5, rows top to bottom, v up; sRGB decoded exactly), emission = material
//             emission (meshes) or Sphere::emission. With a specular coat (Material::specular,
//             Sphere::specular) the BRDF of src/shading/brdf.h (GGX + Kulla-Conty over
//             the weighted Lambertian base): the lamp and the sphere lights evaluate it
//             (pi f in place of albedo below), gathers sample it (GGX visible normals or cosine,
//             chosen by the coat's share of the reflected energy; MIS with the mixture's pdf). Shading normal: mesh vertex normals
//             interpolated and transformed by the inverse transpose of the model matrix; spheres
//             analytic.
//   lamp      (LampModel::kPoint, the default) the point light of kernels/common/direct_light.h:
//             at a point p with normal n,
//             L_direct = albedo * I * max(n.l, 0) / d^2 * falloff(l.y) * V, falloff(s) = 0.35 +
//             s (0.446 + 0.204 s) for s = clamp(l.y, 0, 1), V = 1 unless a shadow caster (an
//             instance or sphere with casts_shadow) lies between p and the lamp centre. I is pi
//             times a physical radiant intensity, so no 1/pi appears (DESIGN.md "Light units").
//   lamp, area  (PathTraceSettings::lamp = LampModel::kArea, the truth for soft
//             shadows) the lamp cap itself emits: the part below the ceiling y = 1 of the sphere
//             of radius r = light.lamp_radius around light.position (truth::LampCap), a
//             Lambertian emitter of constant radiance L_e = I / a^2, a^2 = r^2 - h^2 = 0.1125 for
//             r = 0.35 and the centre h = 0.1 above the ceiling. Why: a surface reflects
//             albedo / pi * integral of L_e cos over the cap's solid angle; far away that solid
//             angle is A(w) / d^2 with A(w) the cap's projected area seen from direction w, and
//             from straight below A = pi a^2 (the cut circle is the outline), so the light is
//             albedo * L_e * a^2 * cos / d^2 = albedo * I * cos / d^2: the point model with
//             falloff(1) = 1 (falloff(s) is the point model's fit of A(w) / (pi a^2)). Nearer
//             the lamp the area model is brighter, since the emitting surface lies 0.1 to 0.35
//             below the centre: at the floor centre albedo * L_e * a^2 / (2^2 + a^2) = I / 4.11
//             against the point model's I / 2.1^2 = I / 4.41, +7.2 %. Next-event estimation:
//             one direction per lit surface, uniform in the cone the whole sphere subtends (pdf
//             1 / (2 pi (1 - cos))), kept when it meets the cap below the ceiling, then a shadow
//             ray to that point against the shadow casters (as the point model: the box and the
//             cap never occlude): albedo * L_e * cos * 2 (1 - cos_max). Gather rays that hit the
//             cap add nothing (voxelize == false), so the cap's light is counted once, by
//             next-event estimation only (one strategy, no MIS); the camera still sees the cap's
//             material emission (the emission component, as the real-time GBuffer shows it).
//   lights    a loaded scene's punctual lights (FrameScene::lights: directional, point, spot;
//             scene/punctual_light.h) light every surface directly like the lamp, each with
//             one shadow ray towards it; the lamp itself only when FrameScene::lamp is set.
//             Their shadow rays (and the sky's) test casts_shadow and casts_light_shadow
//             instances: the demo's box keeps a sky's sun out, not its own lamp's light.
//             They count as the direct component and, after a gather, as lamp-lit surfaces do.
//             An environment's suns (PunctualLight::in_environment) are left out: their light
//             is in the map, which is sampled whole (components below).
//   materials a file's materials as the renderer reads them: alpha-masked holes are skipped
//             by every ray (an Embree filter), normal maps tilt the shading normal in the
//             interpolated tangent frame, metallic-roughness and emission textures scale their
//             factors per texel (scene/frame_scene.h Material).
//   emitters  mesh emission is counted where a path hits it, except on instances that are not
//             part of the GI volume (MeshInstance::voxelize == false: the lamp cap), which the
//             camera sees but whose light is already the point light; emissive spheres (fireball,
//             particles) are also sampled by next-event estimation, chosen in proportion to their
//             power (luminance x r^2) and sampled uniformly in the cone they subtend, combined with
//             the hits of cosine-sampled rays by multiple importance sampling (power heuristic).
//   bounces   rolypoly's meaning: the lamp lights surfaces directly; every other light arrives by
//             gathering (the voxel cone tracer's job in the real-time passes). `bounces` = N
//             counts the gathers: light that left an emitter or a lamp-lit surface and was
//             reflected by at most N surfaces besides the one the camera sees. 0 = the direct
//             lamp light and the emission the camera sees; 1 = plus one gather (emitters and
//             lamp-lit surfaces seen from the camera's surface), as the real-time passes model
//             today. Russian roulette only after the third gather (unbiased).
//   components (per pixel, the mean over its samples, linear radiance in the renderer's units):
//             direct   = the lamp's and the punctual lights' direct light at the surface the
//                        camera sees, and the environment's suns' part of the map there
//                        (Environment::residual: the real-time passes light by them)
//             emission = that surface's own emission, or the environment where no surface is
//             indirect = everything else reaching the camera from it (gathered light), the
//                        environment's light included (the real-time passes gather the sky
//                        through their cones)
//             combined = direct + indirect + emission
//             albedo   = that surface's albedo (0 where no surface: background)
//             specular = the part of direct + indirect that the seen surface's coat reflects:
//                        the lamp through its specular lobe (f_ss + f_ms), and every path
//                        whose first gather's throughput is taken with the lobe's part of the
//                        BRDF (f_spec cos / pdf: the mixture sampler's paths, either lobe
//                        chosen, weighted by the lobe's share of f); 0 on matte surfaces
//             so they mean the same as the light pass's direct / indirect terms, the GBuffer's
//             emission and albedo, and its HDR output (kernels/light.cl).
//   noise     every pixel draws from its own random stream (seed, pixel index), and a pixel is
//             traced start to end by one thread: the image is bit-identical for any thread count.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "scene/frame_scene.h"

namespace rp::truth {

// How the lamp lights surfaces (see the header): kPoint, the real-time passes' model (the
// default), or kArea, the emitting cap (soft shadows).
enum class LampModel { kPoint, kArea };

struct PathTraceSettings {
  uint32_t width = 720, height = 720;
  uint32_t spp = 64;      // samples per pixel (>= 1)
  uint32_t bounces = 1;   // gathers, see the header (0 = direct only)
  uint64_t seed = 1;      // random streams (per pixel)
  unsigned threads = 0;   // 0 = every hardware thread
  LampModel lamp = LampModel::kPoint;
};

// Linear float RGB images: 3 floats per pixel, row-major, top row first (index 3 (y w + x) + c).
struct PathTracedImage {
  uint32_t width = 0, height = 0;
  std::vector<float> combined, direct, indirect, emission, albedo, specular;
  uint64_t rays = 0;      // every ray traced (camera, gather, shadow and light-sample rays)
  double seconds = 0.0;   // wall clock of the render
  double rays_per_second() const { return seconds > 0.0 ? double(rays) / seconds : 0.0; }
};

// What the camera sees at a pixel's centre (for the accuracy report's named regions).
struct PrimaryHit {
  static constexpr uint32_t kNone = 0xFFFFFFFFu;
  uint32_t instance = kNone;  // FrameScene::instances index, or kNone
  uint32_t sphere = kNone;    // FrameScene::spheres index, or kNone
  uint32_t material = kNone;  // SceneAssets::materials index of a mesh hit, or kNone
  glm::vec3 position{0.0f};   // world-space hit point (the accuracy report's marble regions)
  float lamp_cos = 0.0f;      // dot(shading normal, direction to the lamp centre)
  bool lamp_visible = false;  // no shadow caster between the point and the lamp centre
  // Only when primary_hits was given lamp_strata > 0, for the area lamp (LampModel::kArea):
  // lamp_unshadowed = the integral of cos over the cap's solid angle / (pi a^2), so that the
  // area lamp's unshadowed direct light is albedo * I * lamp_unshadowed (-> cos / d^2 far
  // away); lamp_fraction = the part of that integral no shadow caster blocks (1 lit, 0 umbra,
  // between: penumbra), -1 where the cap is not seen at all. Deterministic (stratified).
  float lamp_unshadowed = 0.0f;
  float lamp_fraction = -1.0f;
  bool hit() const { return instance != kNone || sphere != kNone; }
};

// The area lamp's unshadowed light factor at point p with unit normal n, as
// PrimaryHit::lamp_unshadowed (no shadow casters): the integral of cos over the cap's solid
// angle / (pi a^2), from strata^2 stratified directions; the area lamp's direct light there is
// albedo * I * this when nothing blocks it (the point model's counterpart is cos / d^2 *
// falloff).
float area_lamp_unshadowed(const scene::PointLight& light, glm::vec3 p, glm::vec3 n,
                           uint32_t strata = 64);

// Called between rows from the thread that called render(): rows finished so far, rows in all.
using ProgressFn = std::function<void(uint32_t done, uint32_t total)>;

class PathTracer {
 public:
  // Builds one BVH per mesh and the linear textures. Throws std::runtime_error (Embree errors,
  // meshes referring to missing vertices, materials or textures).
  explicit PathTracer(const scene::SceneAssets& assets);
  ~PathTracer();
  PathTracer(const PathTracer&) = delete;
  PathTracer& operator=(const PathTracer&) = delete;

  // Wall-clock milliseconds the constructor took (the BVHs and linear textures).
  double build_ms() const;

  // Path traces `frame` (its camera, light, instances and spheres; the previous-frame fields are
  // ignored). `progress` (optional) is called about ten times a second; when `cancel` (optional)
  // becomes true the render stops early and throws Cancelled. Throws std::invalid_argument for
  // a zero size or spp.
  PathTracedImage render(const scene::FrameScene& frame, const PathTraceSettings& settings,
                         const ProgressFn& progress = {},
                         const std::atomic<bool>* cancel = nullptr);

  // The surface at each pixel centre (width * height entries, row-major) with the lamp's
  // visibility there: the regions of the accuracy report. lamp_strata > 0: also the area
  // lamp's lamp_unshadowed and lamp_fraction, from lamp_strata^2 stratified directions of the
  // cone that next-event estimation samples.
  std::vector<PrimaryHit> primary_hits(const scene::FrameScene& frame, uint32_t width,
                                       uint32_t height, uint32_t lamp_strata = 0);

  struct Cancelled : std::runtime_error {
    Cancelled() : std::runtime_error("path tracing cancelled") {}
  };

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rp::truth
