#include "passes/prt_sky.h"

#include <cmath>
#include <string>

#include "cl/buffer.h"
#include "cl/error.h"
#include "cl/kernel_args.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"
#include "shading/spherical_harmonics.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 16;        // 16x16 work-groups, one pixel each
constexpr size_t kVertexGroup = 64;  // prt_vertex_irradiance: one vertex a work-item
constexpr int32_t kNoOffset = INT32_MIN;  // RP_PRT_NO_TRANSFER in kernels/prt.cl
constexpr double kPi = 3.14159265358979323846;
constexpr double kInvPi = 0.318309886183790671538;

constexpr const char* kLessMemory = "fewer SH bands (--prt-bands 3) need less";

}  // namespace

PrtSkyPass::PrtSkyPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                       const render::GpuScene& scene, const PrtShading& prt)
    : context_(&context), bands_(prt.bands), channels_(prt.channels) {
  if (prt.bands != 3 && prt.bands != 5)
    throw rp::cl::Error("prt pass: " + std::to_string(prt.bands) + " SH bands (3 or 5 expected)");
  if (prt.channels != 1 && prt.channels != 3)
    throw rp::cl::Error("prt pass: " + std::to_string(prt.channels) +
                        " colour channels (1 or 3 expected)");
  const uint32_t vertices = prt.vertex_count();
  const size_t count = size_t(prt.bands) * size_t(prt.bands);
  has_shadowed_ = !prt.shadowed.empty();
  if (has_shadowed_ && (prt.channels != 3 || prt.shadowed.size() != size_t(vertices) * count))
    throw rp::cl::Error("prt pass: a shadowed transfer of " + std::to_string(prt.shadowed.size()) +
                        " floats beside " + std::to_string(vertices) +
                        " vertices' RGB transfer (" + std::to_string(vertices * count) +
                        " expected)");
  std::vector<int32_t> offsets;
  offsets.reserve(prt.instances.size());
  for (size_t i = 0; i < prt.instances.size(); ++i) {
    const PrtShading::Instance& inst = prt.instances[i];
    if (inst.first == PrtShading::kNoTransfer) {
      offsets.push_back(kNoOffset);
      continue;
    }
    if (inst.mesh >= scene.meshes.size())
      throw rp::cl::Error("prt pass: instance " + std::to_string(i) + " has mesh " +
                          std::to_string(inst.mesh) + ", which the scene does not have");
    const render::MeshRange& mesh = scene.meshes[inst.mesh];
    if (uint64_t(inst.first) + mesh.vertex_count > vertices)
      throw rp::cl::Error("prt pass: instance " + std::to_string(i) + "'s " +
                          std::to_string(mesh.vertex_count) + " vertices from " +
                          std::to_string(inst.first) + " lie past the transfer's " +
                          std::to_string(vertices));
    offsets.push_back(int32_t(int64_t(inst.first) - int64_t(mesh.first_vertex)));
  }
  offset_count_ = uint32_t(offsets.size());
  const std::string what = "the PRT transfer (" + std::to_string(vertices) + " vertices x " +
                           std::to_string(prt.channels * prt.bands * prt.bands) + " floats)";
  transfer_ =
      rp::cl::upload_buffer(context.context, context.queue, prt.coefficients, what, kLessMemory);
  offsets_ = rp::cl::upload_buffer(context.context, context.queue, offsets,
                                   "the PRT instance offsets");
  const std::vector<float> no_sky(size_t(shading::kShMaxCount) * 4, 0.0f);  // until a sky comes
  for (::cl::Buffer* b : {&env_, &sun_env_}) {
    *b = rp::cl::make_buffer(context.context, CL_MEM_READ_ONLY,
                             size_t(shading::kShMaxCount) * 4 * sizeof(float),
                             "the environment's SH coefficients");
    context.queue.enqueueWriteBuffer(*b, CL_TRUE, 0, no_sky.size() * sizeof(float),
                                     no_sky.data());
  }
  shadowed_ = rp::cl::upload_buffer(context.context, context.queue, prt.shadowed,
                                    "the PRT shadowed transfer", kLessMemory);
  const size_t suns = prt.sun_directions.size();
  if (suns > 0 && (!has_shadowed_ || prt.sun_bounce.size() != size_t(vertices) * suns * 3))
    throw rp::cl::Error("prt pass: " + std::to_string(prt.sun_bounce.size()) +
                        " floats of traced sun bounces for " + std::to_string(suns) +
                        " suns and " + std::to_string(vertices) + " vertices" +
                        (has_shadowed_ ? "" : " without the shadowed transfer"));
  for (const glm::vec3& d : prt.sun_directions) sun_directions_.push_back(glm::normalize(d));
  sun_bounce_ = rp::cl::upload_buffer(context.context, context.queue, prt.sun_bounce,
                                      "the PRT suns' traced bounces", kLessMemory);
  sun_i_ = rp::cl::make_buffer(context.context, CL_MEM_READ_ONLY,
                               std::max<size_t>(1, suns) * 4 * sizeof(float),
                               "the PRT suns' intensities");
  if (!prt.glow.empty() && (prt.glow.size() != size_t(vertices) * 3 || !prt.glow_source))
    throw rp::cl::Error("prt pass: " + std::to_string(prt.glow.size()) +
                        " floats of traced glow for " + std::to_string(vertices) + " vertices" +
                        (prt.glow_source ? "" : " without the glow they were traced for"));
  glow_ = rp::cl::upload_buffer(context.context, context.queue, prt.glow,
                                "the PRT glow's traced light", kLessMemory);
  if (!prt.glow.empty()) {
    glow_source_ = prt.glow_source;
    glow_turn_deg_ = prt.glow_turn_deg;
    unturned_glow_ = shading::sh_project_glow(*glow_source_, bands_);
  }
  vertex_count_ = vertices;
  vertex_e_ = rp::cl::make_buffer(context.context, CL_MEM_READ_WRITE,
                                  std::max<size_t>(1, vertices) * 16,
                                  "the PRT vertices' sky light (float4 per vertex)");
  vertex_kernel_ = programs.kernel("prt.cl", "prt_vertex_irradiance");
  kernel_ = programs.kernel("prt.cl", "prt_shade");
}

PrtSkyPass::~PrtSkyPass() = default;

void PrtSkyPass::directional_coefficients(const std::vector<scene::PunctualLight>& lights,
                                          std::vector<glm::dvec3>& out) const {
  out.clear();
  if (!has_shadowed_) return;
  double y[shading::kShMaxCount];
  for (const scene::PunctualLight& l : lights) {
    if (l.type != scene::LightType::kDirectional || l.in_environment) continue;
    // Radiance pi I delta(w + direction): the irradiance it gives a surface facing it is pi I,
    // the light pass's albedo I cos / (albedo / pi) (scene/frame_scene.h's units).
    if (out.empty()) out.assign(size_t(bands_ * bands_), glm::dvec3(0.0));
    shading::sh_eval(-glm::normalize(glm::dvec3(l.direction)), bands_, y);
    for (size_t i = 0; i < out.size(); ++i) out[i] += kPi * glm::dvec3(l.intensity) * y[i];
  }
}

bool PrtSkyPass::traced_sun_intensities(const std::vector<scene::PunctualLight>& lights,
                                        std::vector<glm::vec3>& out) const {
  out.assign(sun_directions_.size(), glm::vec3(0.0f));
  if (sun_directions_.empty()) return false;
  constexpr float kSameDirection = 0.99999998f;  // cos 0.01 degrees
  for (const scene::PunctualLight& l : lights) {
    if (l.type != scene::LightType::kDirectional) continue;
    const glm::vec3 towards = -glm::normalize(l.direction);
    size_t j = 0;
    while (j < sun_directions_.size() && !(glm::dot(towards, sun_directions_[j]) >= kSameDirection))
      ++j;
    if (j == sun_directions_.size()) {
      out.clear();
      return false;
    }
    out[j] += l.intensity;
  }
  return true;
}

void PrtSkyPass::update_environment(const scene::Environment& environment,
                                    const std::vector<scene::PunctualLight>& lights) {
  const bool enabled = environment.enabled();
  directional_coefficients(lights, directional_next_);
  const bool exact = traced_sun_intensities(lights, sun_intensity_next_);
  // the glow traced for this map, turned as it is now
  const bool glow = enabled && glow_source_ != nullptr && environment.glow == glow_source_ &&
                    environment.rotate_deg == glow_turn_deg_;
  const bool lights_changed = directional_next_ != directional_ || exact != exact_suns_ ||
                              sun_intensity_next_ != sun_intensity_ || glow != glow_active_;
  glow_active_ = glow;
  if (lights_changed) {
    std::swap(directional_, directional_next_);
    std::swap(sun_intensity_, sun_intensity_next_);
    exact_suns_ = exact;
  }
  if (enabled &&
      (environment.map != projected_map_ || environment.residual != projected_residual_)) {
    // Without suns, or without the shadowed transfer, the gathered map (the residual: the suns
    // light the scene as directional lights, their bounce through the GI volume). Else the
    // whole map, less the suns' shadowed light.
    const bool suns = has_shadowed_ && environment.residual != nullptr;
    const auto project = [&](const std::shared_ptr<const scene::EnvironmentMap>& map) {
      return shading::sh_project_environment(scene::Environment{map, 1.0f, 0.0f, nullptr, nullptr},
                                             bands_);
    };
    unturned_ = project(suns ? environment.map : environment.gathered_map());
    unturned_suns_.clear();
    if (suns) {
      unturned_suns_ = project(environment.residual);
      for (size_t i = 0; i < unturned_suns_.size(); ++i)
        unturned_suns_[i] = unturned_[i] - unturned_suns_[i];
    }
    projected_map_ = environment.map;
    projected_residual_ = environment.residual;
    uploaded_strength_ = -1.0f;  // force the upload
  }
  if (!lights_changed && enabled == uploaded_enabled_ &&
      (!enabled || (environment.rotate_deg == uploaded_turn_ &&
                    environment.strength == uploaded_strength_)))
    return;
  vertex_e_fresh_ = false;
  // The map's part turned and scaled; the directional lights' in world space already (none
  // with traced suns: their bounces come from sun_bounce_, and the map's suns are taken out).
  const auto upload = [&](const ::cl::Buffer& buffer, const std::vector<glm::dvec3>& unturned,
                          const std::vector<glm::dvec3>* minus) {
    std::vector<glm::dvec3> sum(size_t(shading::kShMaxCount), glm::dvec3(0.0));
    if (enabled && !unturned.empty()) {
      std::vector<glm::dvec3> part = unturned;
      if (minus != nullptr && !minus->empty())
        for (size_t i = 0; i < part.size(); ++i) part[i] -= (*minus)[i];
      if (&buffer == &env_ && glow_active_)  // the glow is traced: out of the SH sky
        for (size_t i = 0; i < part.size(); ++i) part[i] -= unturned_glow_[i];
      const std::vector<glm::dvec3> turned =
          shading::sh_turn_environment(part, environment.rotate_deg, environment.strength);
      std::copy(turned.begin(), turned.end(), sum.begin());
    }
    if (!exact_suns_)
      for (size_t i = 0; i < directional_.size(); ++i) sum[i] += directional_[i];
    std::vector<float> env(size_t(shading::kShMaxCount) * 4, 0.0f);
    for (size_t i = 0; i < sum.size(); ++i)
      for (int c = 0; c < 3; ++c) env[4 * i + size_t(c)] = float(sum[i][c] * kInvPi);
    context_->queue.enqueueWriteBuffer(buffer, CL_TRUE, 0, env.size() * sizeof(float),
                                       env.data());
  };
  if (exact_suns_) {
    upload(env_, unturned_, &unturned_suns_);  // the residual: T . L(map - suns)
    std::vector<float> sun_i(sun_intensity_.size() * 4, 0.0f);
    for (size_t j = 0; j < sun_intensity_.size(); ++j)
      for (int c = 0; c < 3; ++c) sun_i[4 * j + size_t(c)] = sun_intensity_[j][c];  // E / pi
    context_->queue.enqueueWriteBuffer(sun_i_, CL_TRUE, 0, sun_i.size() * sizeof(float),
                                       sun_i.data());
    suns_uploaded_ = false;
  } else {
    upload(env_, unturned_, nullptr);
    upload(sun_env_, unturned_suns_, nullptr);
    suns_uploaded_ = (enabled && !unturned_suns_.empty()) || !directional_.empty();
  }
  uploaded_enabled_ = enabled;
  uploaded_turn_ = environment.rotate_deg;
  uploaded_strength_ = environment.strength;
}

void PrtSkyPass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                     const render::VisibilityBuffer& vis, const scene::Environment& environment,
                     const std::vector<scene::PunctualLight>& lights) {
  const uint32_t w = scene.constants.width, h = scene.constants.height;
  if (vis.width != w || vis.height != h)
    throw rp::cl::Error("prt pass: frame size " + std::to_string(w) + "x" + std::to_string(h) +
                        " does not match the visibility buffer (" + std::to_string(vis.width) +
                        "x" + std::to_string(vis.height) + ")");
  const size_t bytes = size_t(frame_bytes(w, h));
  if (out_bytes_ < bytes) {
    out_ = rp::cl::make_buffer(context_->context, CL_MEM_READ_WRITE, bytes,
                               "the PRT sky light (float4 per pixel)");
    out_bytes_ = bytes;
  }
  if (w == 0 || h == 0) return;
  update_environment(environment, lights);
  if (vertex_count_ > 0 && !vertex_e_fresh_) {
    // the vertices' E / pi: again only when the sky's coefficients changed (a turn, a strength)
    gpu::PrtVertexParams params{};
    params.vertex_count = vertex_count_;
    params.channels = channels_;
    params.coefficients = uint32_t(bands_ * bands_);
    params.suns = suns_uploaded_ ? 1u : 0u;
    params.traced_suns = exact_suns_ ? uint32_t(sun_directions_.size()) : 0u;
    params.glow_scale = glow_active_ ? float(double(environment.strength) * kInvPi) : 0.0f;
    rp::cl::bind_args(vertex_kernel_, transfer_, env_, shadowed_, sun_env_, sun_bounce_, sun_i_,
                      glow_, vertex_e_, params);
    profiler.enqueue(pass_name::kPrt, vertex_kernel_,
                     ::cl::NDRange(rp::cl::round_up(vertex_count_, kVertexGroup)),
                     ::cl::NDRange(kVertexGroup));
    vertex_e_fresh_ = true;
  }
  rp::cl::bind_args(kernel_, scene.frame, vis.ids, vis.bary, scene.instances, scene.triangles,
                    vertex_e_, offsets_, cl_uint(offset_count_), out_);
  profiler.enqueue(pass_name::kPrt, kernel_,
                   ::cl::NDRange(rp::cl::round_up(w, kGroup), rp::cl::round_up(h, kGroup)),
                   ::cl::NDRange(kGroup, kGroup));
}

}  // namespace rp::passes
