// The path tracer's integrator and thread pool (conventions in truth/path_tracer.h).
#include "truth/path_tracer.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/punctual_light.h"
#include "shading/brdf.h"
#include "shading/brdf_tables.h"
#include "truth/environment.h"
#include "truth/sampling.h"
#include "truth/trace_scene.h"

namespace rp::truth {
namespace {

constexpr float kRayOffset = 1.0e-4f;   // world units (the box is 2 across)
constexpr float kFar = 1.0e30f;
constexpr uint32_t kRouletteAfter = 3;  // gathers before Russian roulette may end a path
constexpr float kCeilingY = 1.0f;       // the box's ceiling, where the lamp cap is cut

LampCap lamp_cap(const scene::PointLight& light) {
  return {light.position, light.lamp_radius, kCeilingY};
}

// Emissive spheres for next-event estimation, chosen in proportion to luminance x r^2 (their
// power up to a constant).
struct SphereLights {
  std::vector<uint32_t> sphere;  // frame sphere index
  std::vector<float> cdf;        // inclusive, last = 1
  std::vector<float> pick;       // probability of each entry
  std::vector<float> pick_of_sphere;  // per frame sphere: its probability (0 if not a light)

  explicit SphereLights(const scene::FrameScene& frame) : pick_of_sphere(frame.spheres.size()) {
    double total = 0.0;
    std::vector<double> power;
    for (size_t i = 0; i < frame.spheres.size(); ++i) {
      const scene::Sphere& s = frame.spheres[i];
      const double p = double(luminance(s.emission)) * double(s.radius) * double(s.radius);
      if (!(s.radius > 0.0f) || !(p > 0.0)) continue;
      sphere.push_back(uint32_t(i));
      power.push_back(p);
      total += p;
    }
    double running = 0.0;
    for (size_t k = 0; k < sphere.size(); ++k) {
      running += power[k];
      cdf.push_back(k + 1 == sphere.size() ? 1.0f : float(running / total));
      pick.push_back(float(power[k] / total));
      pick_of_sphere[sphere[k]] = pick.back();
    }
  }
  bool empty() const { return sphere.empty(); }
  size_t choose(float u) const {
    return size_t(std::upper_bound(cdf.begin(), cdf.end() - 1, u) - cdf.begin());
  }
};

shading::SurfaceBsdf bsdf_of(const Surface& s) { return shading::make_bsdf(s.specular, s.albedo); }
bool coated(const Surface& s) { return bsdf_of(s).coated(); }

// Radiance of one camera sample, split into the components of path_tracer.h.
struct SampleResult {
  glm::vec3 direct{0.0f}, indirect{0.0f}, emission{0.0f}, albedo{0.0f};
  glm::vec3 specular{0.0f};  // the coat's part of direct + indirect (path_tracer.h)
};

class Integrator {
 public:
  Integrator(const TraceScene& scene, const SphereLights& lights,
             const EnvironmentSampler& environment, uint32_t bounces, LampModel model)
      : scene_(scene),
        lights_(lights),
        env_(environment),
        bounces_(bounces),
        light_(scene.frame().light),
        model_(model),
        cap_(lamp_cap(light_)),
        cap_radiance_(light_.intensity / cap_.projected_radius2()) {}

  uint64_t rays = 0;

  // pi * f(wo, wi): the BRDF in rolypoly's light units (albedo for a Lambertian surface;
  // DESIGN.md "Light units", src/shading/brdf.h).
  glm::vec3 pi_f(const Surface& s, glm::vec3 wo, glm::vec3 wi) const {
    return shading::kPi * shading::eval_brdf(bsdf_of(s), s.ns, wo, wi, tables_).total();
  }
  // pi f and, in *spec (when given), its specular lobe's part (f_ss + f_ms).
  glm::vec3 pi_f(const Surface& s, glm::vec3 wo, glm::vec3 wi, glm::vec3* spec) const {
    const shading::BrdfValue v = shading::eval_brdf(bsdf_of(s), s.ns, wo, wi, tables_);
    if (spec) *spec = shading::kPi * v.specular;
    return shading::kPi * v.total();
  }

  // The direct light leaving `s` towards wo (unit, towards the previous vertex), rolypoly's
  // units: the demo's lamp (FrameScene::lamp), every punctual light of the frame and the
  // environment's share sampled by the map (the BRDF-sampled share is added where a gather
  // ray escapes). spec (optional): receives the coat's part of the result (0 for a matte
  // surface).
  glm::vec3 lamp(const Surface& s, glm::vec3 wo, Pcg32& rng, glm::vec3* spec = nullptr) {
    glm::vec3 sum = lights(s, wo, rng, spec);
    if (env_.enabled()) {
      glm::vec3 env_spec(0.0f);
      sum += environment_light(s, wo, rng, spec ? &env_spec : nullptr);
      if (spec) *spec += env_spec;
    }
    return sum;
  }

  // lamp() without the environment: the demo's lamp and the punctual lights, what the
  // real-time passes light directly (draws the same numbers first).
  glm::vec3 lights(const Surface& s, glm::vec3 wo, Pcg32& rng, glm::vec3* spec = nullptr) {
    if (scene_.frame().lights.empty()) return demo_lamp(s, wo, rng, spec);
    glm::vec3 sum = demo_lamp(s, wo, rng, spec);
    glm::vec3 light_spec(0.0f);
    for (const scene::PunctualLight& light : scene_.frame().lights) {
      if (light.in_environment) continue;  // its light is in the map: environment_light()
      sum += punctual(light, s, wo, spec ? &light_spec : nullptr);
      if (spec) *spec += light_spec;
    }
    return sum;
  }

  // The environment's light reflected by `s`, one direction sampled by the map (MIS weighted
  // against the BRDF's sampler, which the gather's escaping rays stand for). Draws two numbers,
  // only when there is an environment. sun (optional): receives the part of the result that
  // came from the environment's suns (EnvironmentSampler::sun_radiance).
  glm::vec3 environment_light(const Surface& s, glm::vec3 wo, Pcg32& rng, glm::vec3* spec,
                              glm::vec3* sun = nullptr) {
    if (spec) *spec = glm::vec3(0.0f);
    if (sun) *sun = glm::vec3(0.0f);
    const float u1 = rng.uniform(), u2 = rng.uniform();
    const EnvironmentSampler::Sample es = env_.sample(u1, u2);
    if (!(es.pdf > 0.0f)) return glm::vec3(0.0f);
    const float c = glm::dot(s.ns, es.dir);
    if (c <= 0.0f || glm::dot(s.ng, es.dir) <= 0.0f) return glm::vec3(0.0f);
    ++rays;
    if (scene_.light_shadowed(s.p + s.ng * kRayOffset, es.dir, kFar)) return glm::vec3(0.0f);
    const bool glossy = coated(s);
    const float bsdf_pdf =
        glossy ? shading::brdf_pdf(bsdf_of(s), s.ns, wo, es.dir, tables_) : c / kPi;
    // f L cos / pdf with pi f in rolypoly's units: (pi f / pi) L cos / pdf
    const float k = c / kPi / es.pdf * power_heuristic(es.pdf, bsdf_pdf);
    const glm::vec3 li = es.radiance * k;
    const glm::vec3 f = glossy ? pi_f(s, wo, es.dir, spec) : s.albedo;
    if (spec) *spec *= li;
    if (sun) *sun = f * (es.sun * k);
    return f * li;
  }

  // MIS weight of the environment reached by a gather ray of BRDF density bsdf_pdf.
  float environment_weight(glm::vec3 wi, float bsdf_pdf) const {
    return env_.enabled() ? power_heuristic(bsdf_pdf, env_.pdf(wi)) : 1.0f;
  }

  // One punctual light's direct light (scene/punctual_light.h), with a shadow ray.
  glm::vec3 punctual(const scene::PunctualLight& light, const Surface& s, glm::vec3 wo,
                     glm::vec3* spec) {
    if (spec) *spec = glm::vec3(0.0f);
    const scene::LightSample ls = scene::sample_light(light, s.p);
    const float c = glm::dot(s.ns, ls.l);
    if (!(ls.attenuation > 0.0f) || c <= 0.0f || glm::dot(s.ng, ls.l) <= 0.0f)
      return glm::vec3(0.0f);
    ++rays;
    if (scene_.light_shadowed(s.p + s.ng * kRayOffset, ls.l, ls.distance))
      return glm::vec3(0.0f);
    const glm::vec3 f = coated(s) ? pi_f(s, wo, ls.l, spec) : s.albedo;
    const glm::vec3 k = light.intensity * (c * ls.attenuation);
    if (spec) *spec *= k;
    return f * k;
  }

  // The demo's ceiling lamp (point or area model; none when FrameScene::lamp is false).
  glm::vec3 demo_lamp(const Surface& s, glm::vec3 wo, Pcg32& rng, glm::vec3* spec) {
    if (spec) *spec = glm::vec3(0.0f);
    if (!scene_.frame().lamp) return glm::vec3(0.0f);
    if (model_ == LampModel::kArea) return area_lamp(s, wo, rng, spec);
    if (light_.intensity == glm::vec3(0.0f)) return glm::vec3(0.0f);
    const glm::vec3 to_light = light_.position - s.p;
    const float d2 = glm::dot(to_light, to_light);
    const float d = std::sqrt(d2);
    const glm::vec3 l = to_light / d;
    const float c = glm::dot(s.ns, l);
    if (c <= 0.0f || glm::dot(s.ng, l) <= 0.0f) return glm::vec3(0.0f);
    ++rays;
    if (scene_.shadowed(s.p + s.ng * kRayOffset, l, d)) return glm::vec3(0.0f);
    const float e = std::clamp(l.y, 0.0f, 1.0f);
    const float falloff = 0.35f + e * (0.446f + 0.204f * e);  // direct_light.h rp_lamp_falloff
    const glm::vec3 f = coated(s) ? pi_f(s, wo, l, spec) : s.albedo;  // uncoated: as before
    const glm::vec3 k = light_.intensity * (c / d2 * falloff);
    if (spec) *spec *= k;
    return f * k;
  }

  // The area lamp's direct light leaving `s` (path_tracer.h "lamp, area"): one direction
  // uniform in the cone the lamp's sphere subtends, kept when it meets the cap.
  glm::vec3 area_lamp(const Surface& s, glm::vec3 wo, Pcg32& rng, glm::vec3* spec) {
    const float u1 = rng.uniform(), u2 = rng.uniform();  // always drawn: streams stay aligned
    if (light_.intensity == glm::vec3(0.0f)) return glm::vec3(0.0f);
    const glm::vec3 to_centre = cap_.centre - s.p;
    const float dist = glm::length(to_centre);
    if (dist <= cap_.radius * 1.0001f) return glm::vec3(0.0f);  // on the lamp itself
    const float omc = sphere_cone_omc(cap_.radius, dist);
    const glm::vec3 wi = sample_cone(to_centre / dist, omc, u1, u2);
    const float c = glm::dot(s.ns, wi);
    if (c <= 0.0f || glm::dot(s.ng, wi) <= 0.0f) return glm::vec3(0.0f);
    const float t = cap_.hit(s.p, wi);
    if (t < 0.0f) return glm::vec3(0.0f);  // the sphere above the ceiling: no lamp there
    ++rays;
    if (scene_.shadowed(s.p + s.ng * kRayOffset, wi, t)) return glm::vec3(0.0f);
    // f * L_e * cos / pdf, pdf = 1 / (2 pi omc); pi f = albedo for a Lambertian surface
    const glm::vec3 f = coated(s) ? pi_f(s, wo, wi, spec) : s.albedo;
    const glm::vec3 k = cap_radiance_ * (2.0f * c * omc);
    if (spec) *spec *= k;
    return f * k;
  }

  // Light from the emissive spheres reflected by `s`, sampled by the spheres (MIS weighted).
  // spec (optional): receives the coat's part of the result (0 for a matte surface).
  glm::vec3 sphere_light(const Surface& s, glm::vec3 wo, Pcg32& rng, glm::vec3* spec = nullptr) {
    if (spec) *spec = glm::vec3(0.0f);
    const float u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    if (lights_.empty()) return glm::vec3(0.0f);
    const size_t k = lights_.choose(u0);
    const scene::Sphere& light = scene_.frame().spheres[lights_.sphere[k]];
    const glm::vec3 to_centre = light.center - s.p;
    const float dist = glm::length(to_centre);
    if (dist <= light.radius * 1.0001f) return glm::vec3(0.0f);  // inside the light
    const float omc = sphere_cone_omc(light.radius, dist);
    const glm::vec3 wi = sample_cone(to_centre / dist, omc, u1, u2);
    const float c = glm::dot(s.ns, wi);
    if (c <= 0.0f || glm::dot(s.ng, wi) <= 0.0f) return glm::vec3(0.0f);
    ++rays;
    Surface hit;
    if (!scene_.intersect(s.p + s.ng * kRayOffset, wi, kFar, hit) ||
        hit.sphere != lights_.sphere[k])
      return glm::vec3(0.0f);  // something else is in front (or the tangent ray missed)
    const float light_pdf = lights_.pick[k] * cone_pdf(omc);
    if (coated(s)) {
      const float bsdf_pdf = shading::brdf_pdf(bsdf_of(s), s.ns, wo, wi, tables_);
      const glm::vec3 li =
          hit.emission * (c / kPi / light_pdf * power_heuristic(light_pdf, bsdf_pdf));
      const glm::vec3 f = pi_f(s, wo, wi, spec);
      if (spec) *spec *= li;
      return f * li;
    }
    const float bsdf_pdf = c / kPi;
    return s.albedo * hit.emission * (c / kPi / light_pdf * power_heuristic(light_pdf, bsdf_pdf));
  }

  // MIS weight of an emissive sphere reached by a cosine-sampled ray from `from` (pdf bsdf_pdf).
  float hit_weight(const Surface& from, const Surface& hit, float bsdf_pdf) const {
    const float pick = lights_.pick_of_sphere.empty() ? 0.0f : lights_.pick_of_sphere[hit.sphere];
    if (pick <= 0.0f) return 1.0f;
    const scene::Sphere& light = scene_.frame().spheres[hit.sphere];
    const float dist = glm::length(light.center - from.p);
    if (dist <= light.radius * 1.0001f) return 1.0f;  // never sampled from inside
    return power_heuristic(bsdf_pdf, pick * cone_pdf(sphere_cone_omc(light.radius, dist)));
  }

  SampleResult trace(glm::vec3 org, glm::vec3 dir, Pcg32& rng) {
    SampleResult r;
    Surface s;
    ++rays;
    if (!scene_.intersect(org, dir, kFar, s, TraceScene::Viewer::kCamera)) {
      r.emission = env_.radiance(dir);  // the sky seen directly (0 without an environment)
      return r;
    }
    r.emission = s.emission;
    r.albedo = s.albedo;
    glm::vec3 wo = -dir;  // towards the previous vertex
    // The environment's light at the seen surface is gathered light (the real-time passes
    // bring it through their cones): indirect, sampled right after the lights as lamp() does;
    // but its suns' part is direct, as the real-time passes light by them.
    r.direct = lights(s, wo, rng, &r.specular);
    if (env_.enabled()) {
      glm::vec3 env_spec(0.0f), env_sun(0.0f);
      const glm::vec3 env = environment_light(s, wo, rng, &env_spec, &env_sun);
      r.direct += env_sun;
      r.indirect += env - env_sun;
      r.specular += env_spec;
    }
    glm::vec3 beta(1.0f);  // throughput from the camera to s: f cos / pdf of the gathers so far
    // beta_s: the part of beta whose first gather went through the seen surface's specular
    // lobe (f_spec cos / pdf; the same factors after it), so r.specular collects the coat's
    // share of everything gathered there
    glm::vec3 beta_s(0.0f);
    for (uint32_t gather = 1; gather <= bounces_; ++gather) {
      const bool glossy = coated(s);
      if (s.albedo == glm::vec3(0.0f) && !glossy) break;
      glm::vec3 nee_spec;
      const glm::vec3 nee = sphere_light(s, wo, rng, &nee_spec);
      r.indirect += beta * nee;
      r.specular += gather == 1 ? nee_spec : beta_s * nee;
      const float u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
      if (gather > kRouletteAfter) {
        const float q = std::min(0.95f, std::max({beta.x, beta.y, beta.z}));
        if (!(u3 < q)) break;
        beta /= q;
        beta_s /= q;
      }
      glm::vec3 wi;
      float pdf;
      if (glossy) {
        // the BRDF's own sampler (brdf.h: GGX visible normals or cosine, by the coat's share);
        // the lobe choice draws one more number, so matte paths keep their streams
        const shading::BsdfSample bs =
            shading::sample_brdf(bsdf_of(s), s.ns, wo, rng.uniform(), u1, u2, tables_);
        if (!(bs.pdf > 0.0f)) break;
        wi = bs.wi;
        pdf = bs.pdf;
      } else {
        wi = sample_cosine_hemisphere(s.ns, u1, u2);
        pdf = glm::dot(s.ns, wi) / kPi;
      }
      const float c = glm::dot(s.ns, wi);
      if (c <= 0.0f || glm::dot(s.ng, wi) <= 0.0f) break;  // below the true surface
      // f cos / pdf: albedo for the cosine-sampled Lambertian surface
      if (glossy) {
        glm::vec3 f_spec;
        const glm::vec3 f = pi_f(s, wo, wi, &f_spec);
        const float k = c / (kPi * pdf);
        beta_s = gather == 1 ? f_spec * k : beta_s * (f * k);
        beta *= f * k;
      } else {
        beta_s *= s.albedo;
        beta *= s.albedo;
      }
      Surface next;
      ++rays;
      if (!scene_.intersect(s.p + s.ng * kRayOffset, wi, kFar, next)) {
        if (env_.enabled()) {  // the environment's BRDF-sampled share (MIS weighted)
          const float w = environment_weight(wi, pdf);
          const glm::vec3 sky = env_.radiance(wi) * w;
          // gathered light at every vertex, as the map-sampled share; the suns' part direct
          // at the first
          const glm::vec3 sun = gather == 1 ? env_.sun_radiance(wi) * w : glm::vec3(0.0f);
          r.direct += beta * sun;
          r.indirect += beta * (sky - sun);
          r.specular += beta_s * sky;
        }
        break;
      }
      if (next.lights_scene && next.emission != glm::vec3(0.0f)) {
        const float w = next.sphere != 0xFFFFFFFFu ? hit_weight(s, next, pdf) : 1.0f;
        r.indirect += beta * next.emission * w;
        r.specular += beta_s * next.emission * w;
      }
      s = next;
      wo = -wi;
      const glm::vec3 lit = lamp(s, wo, rng);
      r.indirect += beta * lit;
      r.specular += beta_s * lit;
    }
    return r;
  }

 private:
  const TraceScene& scene_;
  const SphereLights& lights_;
  const EnvironmentSampler& env_;
  uint32_t bounces_;
  scene::PointLight light_;
  LampModel model_;
  LampCap cap_;
  glm::vec3 cap_radiance_;  // L_e = I / a^2 (path_tracer.h)
  const shading::BrdfTables& tables_ = shading::BrdfTables::get();
};

// Camera rays: pixel coordinates (x right, y down, pixel centres at +0.5) -> world direction.
struct CameraRays {
  glm::dmat4 inv_view_proj;
  glm::vec3 origin;
  double width, height;
  CameraRays(const scene::Camera& camera, uint32_t w, uint32_t h)
      : inv_view_proj(glm::inverse(glm::dmat4(camera.projection(float(w) / float(h))) *
                                   glm::dmat4(camera.view()))),
        origin(camera.position),
        width(w),
        height(h) {}
  glm::vec3 direction(double px, double py) const {
    const glm::dvec4 ndc(2.0 * px / width - 1.0, 1.0 - 2.0 * py / height, 1.0, 1.0);
    const glm::dvec4 far = inv_view_proj * ndc;
    return glm::normalize(glm::vec3(glm::dvec3(far) / far.w) - origin);
  }
};

// Runs rows [0, rows) on `threads` workers (row order varies; each row writes only its own
// pixels), calling `progress` on this thread about ten times a second and stopping between rows
// when `cancel` is set.
template <class RowFn>
void run_rows(uint32_t rows, unsigned threads, RowFn row_fn, const ProgressFn& progress,
              const std::atomic<bool>* cancel) {
  std::atomic<uint32_t> next{0}, done{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::condition_variable finished;
  std::exception_ptr error;
  auto work = [&] {
    try {
      for (uint32_t y = next++; y < rows && !stop; y = next++) {
        row_fn(y);
        ++done;
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      if (!error) error = std::current_exception();
      stop = true;
    }
    std::lock_guard<std::mutex> lock(mutex);
    finished.notify_all();
  };
  std::vector<std::thread> pool;
  for (unsigned i = 0; i < threads; ++i) pool.emplace_back(work);
  {
    std::unique_lock<std::mutex> lock(mutex);
    while (done < rows && !stop) {
      finished.wait_for(lock, std::chrono::milliseconds(100));
      if (cancel && cancel->load()) stop = true;
      lock.unlock();
      if (progress) progress(done.load(), rows);
      lock.lock();
    }
  }
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  if (done < rows) throw PathTracer::Cancelled();
  if (progress) progress(rows, rows);
}

// Calls fn(wi, t) for each of the strata x strata stratum-centre directions of the cone
// area_lamp samples from p that meet the cap (t: the distance to it), and returns the solid angle
// each direction stands for, 2 pi omc / strata^2 (0 when p is on the lamp: nothing is called).
template <class Fn>
double for_cap_directions(const LampCap& cap, glm::vec3 p, uint32_t strata, Fn fn) {
  const glm::vec3 to_centre = cap.centre - p;
  const float dist = glm::length(to_centre);
  if (dist <= cap.radius * 1.0001f || strata == 0) return 0.0;
  const float omc = sphere_cone_omc(cap.radius, dist);
  for (uint32_t i = 0; i < strata; ++i)
    for (uint32_t j = 0; j < strata; ++j) {
      const glm::vec3 wi = sample_cone(to_centre / dist, omc, (float(i) + 0.5f) / float(strata),
                                       (float(j) + 0.5f) / float(strata));
      const float t = cap.hit(p, wi);
      if (t >= 0.0f) fn(wi, t);
    }
  return 2.0 * double(kPi) * double(omc) / (double(strata) * strata);
}

// PrimaryHit::lamp_unshadowed and lamp_fraction at `s` (path_tracer.h).
void area_lamp_fraction(const TraceScene& scene, const Surface& s, uint32_t strata,
                        PrimaryHit& hit) {
  const LampCap cap = lamp_cap(scene.frame().light);
  double seen = 0.0, lit = 0.0;  // sums of cos
  const double dw = for_cap_directions(cap, s.p, strata, [&](glm::vec3 wi, float t) {
    const float c = glm::dot(s.ns, wi);
    if (c <= 0.0f || glm::dot(s.ng, wi) <= 0.0f) return;
    seen += c;
    if (!scene.shadowed(s.p + s.ng * kRayOffset, wi, t)) lit += c;
  });
  if (!(seen > 0.0)) return;
  hit.lamp_unshadowed = float(seen * dw / double(kPi) / cap.projected_radius2());
  hit.lamp_fraction = float(lit / seen);
}

}  // namespace

float area_lamp_unshadowed(const scene::PointLight& light, glm::vec3 p, glm::vec3 n,
                           uint32_t strata) {
  const LampCap cap = lamp_cap(light);
  double seen = 0.0;  // sum of cos
  const double dw = for_cap_directions(cap, p, strata, [&](glm::vec3 wi, float) {
    seen += std::max(0.0f, glm::dot(n, wi));
  });
  return float(seen * dw / double(kPi) / cap.projected_radius2());
}

struct PathTracer::Impl {
  explicit Impl(const scene::SceneAssets& a)
      : start(std::chrono::steady_clock::now()),
        assets(a),
        build_ms(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() -
                                                           start)
                     .count()) {}
  std::chrono::steady_clock::time_point start;
  TraceAssets assets;
  double build_ms;
};

PathTracer::PathTracer(const scene::SceneAssets& assets) : impl_(std::make_unique<Impl>(assets)) {}
PathTracer::~PathTracer() = default;

double PathTracer::build_ms() const { return impl_->build_ms; }

PathTracedImage PathTracer::render(const scene::FrameScene& frame,
                                   const PathTraceSettings& settings, const ProgressFn& progress,
                                   const std::atomic<bool>* cancel) {
  if (settings.width == 0 || settings.height == 0 || settings.spp == 0)
    throw std::invalid_argument("path tracer: the size and the samples per pixel must be >= 1");
  const auto start = std::chrono::steady_clock::now();
  const TraceScene scene(impl_->assets, frame);
  const SphereLights lights(frame);
  const EnvironmentSampler environment(frame.environment);
  const CameraRays camera(frame.camera, settings.width, settings.height);
  const uint32_t w = settings.width, h = settings.height;
  PathTracedImage image;
  image.width = w;
  image.height = h;
  for (std::vector<float>* plane :
       {&image.combined, &image.direct, &image.indirect, &image.emission, &image.albedo,
        &image.specular})
    plane->assign(size_t(w) * h * 3, 0.0f);
  const unsigned threads =
      settings.threads ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
  std::atomic<uint64_t> rays{0};

  auto row = [&](uint32_t y) {
    Integrator integrator(scene, lights, environment, settings.bounces, settings.lamp);
    for (uint32_t x = 0; x < w; ++x) {
      const uint64_t pixel = uint64_t(y) * w + x;
      Pcg32 rng(settings.seed, pixel);
      glm::dvec3 sum[5] = {};  // direct, indirect, emission, albedo, specular
      for (uint32_t i = 0; i < settings.spp; ++i) {
        const float jx = rng.uniform(), jy = rng.uniform();
        const SampleResult r = integrator.trace(
            camera.origin, camera.direction(double(x) + jx, double(y) + jy), rng);
        sum[0] += glm::dvec3(r.direct);
        sum[1] += glm::dvec3(r.indirect);
        sum[2] += glm::dvec3(r.emission);
        sum[3] += glm::dvec3(r.albedo);
        sum[4] += glm::dvec3(r.specular);
      }
      const double inv = 1.0 / double(settings.spp);
      for (int c = 0; c < 3; ++c) {
        const size_t k = 3 * pixel + size_t(c);
        image.direct[k] = float(sum[0][c] * inv);
        image.indirect[k] = float(sum[1][c] * inv);
        image.emission[k] = float(sum[2][c] * inv);
        image.albedo[k] = float(sum[3][c] * inv);
        image.specular[k] = float(sum[4][c] * inv);
        image.combined[k] = float((sum[0][c] + sum[1][c] + sum[2][c]) * inv);
      }
    }
    rays += integrator.rays;
  };
  run_rows(h, threads, row, progress, cancel);
  image.rays = rays.load();
  image.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return image;
}

std::vector<PrimaryHit> PathTracer::primary_hits(const scene::FrameScene& frame, uint32_t width,
                                                 uint32_t height, uint32_t lamp_strata) {
  const TraceScene scene(impl_->assets, frame);
  const CameraRays camera(frame.camera, width, height);
  std::vector<PrimaryHit> hits(size_t(width) * height);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      Surface s;
      if (!scene.intersect(camera.origin, camera.direction(x + 0.5, y + 0.5), kFar, s,
                           TraceScene::Viewer::kCamera))
        continue;
      PrimaryHit& hit = hits[size_t(y) * width + x];
      hit.instance = s.instance;
      hit.sphere = s.sphere;
      hit.material = s.material;
      hit.position = s.p;
      const glm::vec3 to_light = frame.light.position - s.p;
      const float d = glm::length(to_light);
      hit.lamp_cos = glm::dot(s.ns, to_light / d);
      hit.lamp_visible = !scene.shadowed(s.p + s.ng * kRayOffset, to_light / d, d);
      if (lamp_strata > 0) area_lamp_fraction(scene, s, lamp_strata, hit);
    }
  return hits;
}

}  // namespace rp::truth
