// Sky light by precomputed radiance transfer (seeds 002/003): the environment's
// spherical-harmonic coefficients dotted with every vertex's transfer vector, then per pixel
// interpolated over its triangle by the visibility buffer's barycentrics (kernels/prt.cl). The output,
// E / pi per pixel (float4: rgb, a = 1 where a transfer was found), is what the light pass adds
// to its diffuse indirect term (LightPass::run's prt) in place of the cones' sky. The
// transfer itself is computed on the host (truth/prt_transfer.h) by the caller; this pass holds
// it on the device, turns the environment's coefficients each frame (shading::
// sh_turn_environment: a rotation, no re-projection) and shades. Pass name "prt".
//
// An environment's suns (scene/environment_suns.h) are directional lights with shadow maps; the
// residual map is gathered here. With an interreflected transfer that keeps its shadowed part
// (PrtShading::shadowed), the bounces of every sun are gathered here too, the map's from the
// whole map and the other directional lights' (the clear sky's sun, a scene's) as radiance
// pi I delta(w - w_light), whose coefficients are pi I Y_i(w_light):
//     E = T . (L(map) + L(lights)) - T_shadowed . (L(map - residual) + L(lights)),
// and the GI volume leaves those lights out (carries_suns_bounce(): the renderer tells the
// scene), since their bounce by PRT's traced transfer is closer to the truth than the cones'.
// Point and spot lights have no distant radiance: their bounce stays with the volume.
//
// Where the transfer also traced the directional lights' bounces per vertex for their
// directions (PrtShading::sun_bounce) and every directional light of the frame still shines
// from one of them, those replace the band-limited bounce:
//     E = T . L(residual) + sum_j pi I_j * B_j,
// exact for each sun's direction (25 coefficients smear a low sun's bounce over the horizon,
// where the transfer as a function of the light's direction jumps). A turned map or a moved
// light falls back to the formula above.
//
// Where the transfer also traced the glow around the map's suns (scene/environment_glow.h,
// PrtShading::glow) and the map is still the one it was traced for, turned as it was, the glow
// leaves the band-limited sky and its traced light is added instead (either formula above):
//     E = T . L(residual - glow) + ... + strength * G,
// which keeps the sharp edges of a studio's softboxes out of 9 or 25 coefficients. A turned map
// takes the glow back into the SH sky.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "passes/frame_memory.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"
#include "scene/frame_scene.h"
#include "scene/environment.h"
#include "scene/environment_glow.h"

namespace rp::passes {

// Per-vertex transfer for the device: truth::PrtTransfer's numbers without its host-only parts.
struct PrtShading {
  int bands = 3;          // 3 (9 coefficients) or 5 (25)
  uint32_t channels = 1;  // 1: grey (the same T for r, g, b); 3: RGB
  // Vertex-major: vertex v, channel c, coefficient i at (v * channels + c) * bands^2 + i;
  // E_c = sum_i T_{c,i} L_{c,i} (irradiance; the receiver's albedo not included).
  std::vector<float> coefficients;
  // Empty, or (interreflected transfer with bounces) the grey shadowed transfer it started from:
  // vertex v's coefficient i at v * bands^2 + i (truth::PrtTransfer::shadowed).
  std::vector<float> shadowed;
  // Per frame instance, in the frame's order: its mesh (scene::MeshInstance::mesh) and its
  // first PRT vertex (vertex v of the mesh is PRT vertex first + v); kNoTransfer: none.
  struct Instance {
    uint32_t mesh = 0, first = 0;
  };
  static constexpr uint32_t kNoTransfer = 0xFFFFFFFFu;
  std::vector<Instance> instances;
  // Empty, or (with shadowed) the directions towards the directional lights whose bounces were
  // traced, and those bounces: vertex v, sun j, channel c at (v * suns + j) * 3 + c, the
  // irradiance after 1..N bounces per unit irradiance of the sun (truth::PrtTransfer::
  // sun_bounce).
  std::vector<glm::vec3> sun_directions;
  std::vector<float> sun_bounce;
  // Empty, or the glow's traced light per vertex, rgb at v * 3 (truth::PrtTransfer::glow: the
  // irradiance at strength 1, first vertex and bounces), traced for `glow_source` (an
  // environment's glow) turned by glow_turn_deg.
  std::vector<float> glow;
  std::shared_ptr<const scene::EnvironmentGlow> glow_source;
  float glow_turn_deg = 0.0f;

  uint32_t vertex_count() const {
    const size_t per = size_t(channels) * size_t(bands) * size_t(bands);
    return per == 0 ? 0 : uint32_t(coefficients.size() / per);
  }
};

class PrtSkyPass {
 public:
  // Uploads the transfer. Throws rp::cl::Error when it does not fit `scene` (an instance's
  // mesh that does not exist, vertices past the transfer's end, bands other than 3 or 5).
  PrtSkyPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
             const render::GpuScene& scene, const PrtShading& prt);
  ~PrtSkyPass();

  // E / pi of the frame's environment (turned and scaled as `environment` says; black without
  // one) and of its directional lights' bounces (`lights`, where carries_suns_bounce()) at
  // every pixel of `vis` into output() (grown to vis' size). Enqueues only.
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
           const render::VisibilityBuffer& vis, const scene::Environment& environment,
           const std::vector<scene::PunctualLight>& lights);

  const ::cl::Buffer& output() const { return out_; }

  // Whether the suns' bounces are this pass's (the transfer keeps its shadowed part), so the
  // GI volume must leave the environment's suns and the directional lights out.
  bool carries_suns_bounce() const { return has_shadowed_; }
  // Whether the last run took the suns' bounces from their traced per-vertex columns (every
  // directional light shone from a traced direction) rather than through the SH transfer.
  bool suns_traced() const { return exact_suns_; }
  // Whether the last run took the glow around the map's suns from its traced per-vertex light.
  bool glow_traced() const { return glow_active_; }

  // Device memory of output() for a width x height frame (passes/frame_memory.h; it only
  // grows); what the pass holds now.
  static uint64_t frame_bytes(uint32_t width, uint32_t height) {
    return std::max<uint64_t>(1, pixel_count(width, height)) * 16;
  }
  uint64_t frame_device_bytes() const { return buffer_bytes({&out_}); }

 private:
  void update_environment(const scene::Environment& environment,
                          const std::vector<scene::PunctualLight>& lights);
  // pi I Y_i(-direction) summed over the directional lights not in the environment into `out`
  // (left empty without any, or without the shadowed transfer; its capacity is kept, so the
  // per-frame call allocates nothing once the lights are known).
  void directional_coefficients(const std::vector<scene::PunctualLight>& lights,
                                std::vector<glm::dvec3>& out) const;
  // Each traced sun's intensity I_j (rgb, the lights' units) into `out` when every directional
  // light of `lights` shines from one of sun_directions_ (within 0.01 degrees); false (out
  // cleared) otherwise or without traced suns.
  bool traced_sun_intensities(const std::vector<scene::PunctualLight>& lights,
                              std::vector<glm::vec3>& out) const;

  const rp::cl::Context* context_;
  ::cl::Kernel vertex_kernel_, kernel_;  // prt_vertex_irradiance, prt_shade
  int bands_ = 3;
  uint32_t channels_ = 1;
  bool has_shadowed_ = false;
  ::cl::Buffer transfer_, offsets_, env_, out_;
  ::cl::Buffer shadowed_, sun_env_;  // PrtShading::shadowed; the suns' L / pi (or 1 float)
  ::cl::Buffer vertex_e_;        // float4 per PRT vertex: E / pi of the coefficients in env_
  bool vertex_e_fresh_ = false;  // vertex_e_ holds env_'s E (recomputed after each upload)
  uint32_t vertex_count_ = 0, offset_count_ = 0;
  size_t out_bytes_ = 0;
  // The gathered light's coefficients unturned at strength 1 (projected once per map; the whole
  // map's when the suns' bounces are gathered, else the residual's), the suns' alone (empty when
  // they are not gathered), and what env_ and sun_env_ hold.
  std::shared_ptr<const scene::EnvironmentMap> projected_map_, projected_residual_;
  std::vector<glm::dvec3> unturned_, unturned_suns_;
  // directional_coefficients of the last upload, and this frame's (compared, then swapped)
  std::vector<glm::dvec3> directional_, directional_next_;
  // The traced suns: their directions, bounces (sun_bounce_) and this upload's intensities
  // (sun_i_: float4 per traced sun); traced_sun_intensities of the last upload and this
  // frame's.
  std::vector<glm::vec3> sun_directions_;
  ::cl::Buffer sun_bounce_, sun_i_;
  std::vector<glm::vec3> sun_intensity_, sun_intensity_next_;
  bool exact_suns_ = false;
  // The traced glow: its per-vertex light (glow_, or 1 float), what it was traced for, its
  // texels' coefficients unturned at strength 1, and whether this upload uses it.
  ::cl::Buffer glow_;
  std::shared_ptr<const scene::EnvironmentGlow> glow_source_;
  float glow_turn_deg_ = 0.0f;
  std::vector<glm::dvec3> unturned_glow_;
  bool glow_active_ = false;
  float uploaded_turn_ = 0.0f, uploaded_strength_ = -1.0f;
  bool uploaded_enabled_ = false, suns_uploaded_ = false;
};

}  // namespace rp::passes
