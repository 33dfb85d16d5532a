// Per-vertex transfer vectors of precomputed radiance transfer (see prt_transfer.h).
#include "truth/prt_transfer.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "shading/spherical_harmonics.h"
#include "truth/trace_scene.h"

namespace rp::truth {
namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr unsigned kInvalid = RTC_INVALID_GEOMETRY_ID;
constexpr uint32_t kChunk = 16;  // vertices a worker takes at a time

// One vertex of the frame, world space, with where its rays start.
struct PrtVertex {
  glm::dvec3 n{0.0};      // unit shading normal, or zero (degenerate: no transfer)
  glm::vec3 origin{0.0f};  // the vertex nudged off edges and its own triangles (header)
};

// One entry of a vertex's bounce row: vertex `target`'s previous-bounce transfer, per channel,
// times `w` adds to the row's vertex (w = albedo * barycentric / N summed over the row's rays;
// summed in double, stored as float: the same arithmetic whether rows are kept or rebuilt).
struct RowEntry {
  uint32_t target;
  float w[3];
};
struct HitEntry {
  uint32_t target;
  glm::dvec3 w;
};

// Radical inverse in base 2 (van der Corput) of k, in [0, 1).
double radical_inverse(uint32_t k) {
  k = (k << 16) | (k >> 16);
  k = ((k & 0x00FF00FFu) << 8) | ((k & 0xFF00FF00u) >> 8);
  k = ((k & 0x0F0F0F0Fu) << 4) | ((k & 0xF0F0F0F0u) >> 4);
  k = ((k & 0x33333333u) << 2) | ((k & 0xCCCCCCCCu) >> 2);
  k = ((k & 0x55555555u) << 1) | ((k & 0xAAAAAAAAu) >> 1);
  return double(k) * (1.0 / 4294967296.0);
}

// The Hammersley set mapped to the cosine-weighted hemisphere about +z (density cos / pi).
std::vector<glm::dvec3> cosine_hammersley(uint32_t n) {
  std::vector<glm::dvec3> dirs(n);
  for (uint32_t k = 0; k < n; ++k) {
    const double u1 = (double(k) + 0.5) / double(n), phi = 2.0 * kPiD * radical_inverse(k);
    const double r = std::sqrt(u1);
    dirs[k] = {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u1))};
  }
  return dirs;
}

// Local +z to unit normal n (Duff et al. 2017, as shading/basis.h, in double).
glm::dvec3 to_world(glm::dvec3 n, glm::dvec3 v) {
  const double sign = std::copysign(1.0, n.z), a = -1.0 / (sign + n.z), b = n.x * n.y * a;
  const glm::dvec3 t(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::dvec3 bt(b, sign + n.y * n.y * a, -n.y);
  return v.x * t + v.y * bt + v.z * n;
}

// Runs fn(v) for v in [0, n) on `threads` workers in chunks (each v writes only its own
// outputs), reporting done / n through `report` on this thread about ten times a second.
template <class Fn>
void run_parallel(uint32_t n, unsigned threads, Fn fn, const std::function<void(double)>& report,
                  const std::atomic<bool>* cancel) {
  std::atomic<uint32_t> next{0}, done{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::condition_variable finished;
  std::exception_ptr error;
  unsigned running = threads;
  auto work = [&] {
    try {
      auto go = [&] { return !stop && !(cancel && cancel->load()); };
      for (uint32_t b = next.fetch_add(kChunk); b < n && go(); b = next.fetch_add(kChunk)) {
        const uint32_t e = std::min(n, b + kChunk);
        for (uint32_t v = b; v < e; ++v) fn(v);
        done += e - b;
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      if (!error) error = std::current_exception();
      stop = true;
    }
    std::lock_guard<std::mutex> lock(mutex);
    --running;
    finished.notify_all();
  };
  std::vector<std::thread> pool;
  for (unsigned i = 0; i < threads; ++i) pool.emplace_back(work);
  {
    std::unique_lock<std::mutex> lock(mutex);
    while (running > 0) {
      finished.wait_for(lock, std::chrono::milliseconds(100));
      if (cancel && cancel->load()) stop = true;
      lock.unlock();
      if (report && n > 0) report(double(done.load()) / double(n));
      lock.lock();
    }
  }
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  if (done < n) throw PrtCancelled();
}

// The frame's instances as one Embree scene over the assets' per-mesh BVHs; instance i has
// geometry id i (the frame's order), so a hit's instID names the frame instance.
class InstanceScene {
 public:
  InstanceScene(const TraceAssets& assets, const scene::FrameScene& frame)
      : scene_(rtcNewScene(assets.device())) {
    for (size_t i = 0; i < frame.instances.size(); ++i) {
      const scene::MeshInstance& inst = frame.instances[i];
      const TraceMesh& mesh = assets.meshes()[inst.mesh];
      if (mesh.bvh == nullptr) continue;
      RTCGeometry g = rtcNewGeometry(assets.device(), RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(g, mesh.bvh);
      rtcSetGeometryTimeStepCount(g, 1);
      rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &inst.model[0][0]);
      rtcCommitGeometry(g);
      rtcAttachGeometryByID(scene_, g, unsigned(i));
      rtcReleaseGeometry(g);
    }
    rtcCommitScene(scene_);
    assets.check("building the PRT scene");
  }
  ~InstanceScene() { rtcReleaseScene(scene_); }
  InstanceScene(const InstanceScene&) = delete;
  InstanceScene& operator=(const InstanceScene&) = delete;
  RTCScene get() const { return scene_; }

 private:
  RTCScene scene_;
};

// World-space vertices of every instance, with their ray origins (header: "Ray origins").
std::vector<PrtVertex> build_vertices(const scene::SceneAssets& assets,
                                      const scene::FrameScene& frame, PrtTransfer& out) {
  std::vector<PrtVertex> verts;
  for (const scene::MeshInstance& inst : frame.instances) {
    const scene::Mesh& mesh = assets.meshes[inst.mesh];
    const size_t nv = mesh.vertices.size();
    out.instances.push_back({uint32_t(out.positions.size()), uint32_t(nv)});
    // Per vertex: the sum of its triangles' centroids and of their area-weighted normals (the
    // fallback for a zero vertex normal), in object space.
    std::vector<glm::dvec3> centroid(nv, glm::dvec3(0.0)), face_n(nv, glm::dvec3(0.0));
    std::vector<uint32_t> valence(nv, 0);
    for (const glm::uvec3& t : mesh.triangles) {
      const glm::dvec3 a(mesh.vertices[t.x].position), b(mesh.vertices[t.y].position),
          c(mesh.vertices[t.z].position);
      const glm::dvec3 fn = glm::cross(b - a, c - a);
      for (uint32_t k : {t.x, t.y, t.z}) {
        centroid[k] += (a + b + c) / 3.0;
        face_n[k] += fn;
        ++valence[k];
      }
    }
    const glm::dmat4 model(inst.model);
    const glm::dmat3 nm = glm::transpose(glm::inverse(glm::dmat3(model)));
    for (size_t v = 0; v < nv; ++v) {
      const glm::dvec3 p(model * glm::dvec4(glm::dvec3(mesh.vertices[v].position), 1.0));
      glm::dvec3 n = nm * glm::dvec3(mesh.vertices[v].normal);
      if (!(glm::length(n) > 1e-12)) n = nm * face_n[v];
      n = glm::length(n) > 1e-12 ? glm::normalize(n) : glm::dvec3(0.0);
      glm::dvec3 c = p;
      if (valence[v] > 0)
        c = glm::dvec3(model * glm::dvec4(centroid[v] / double(valence[v]), 1.0));
      out.positions.emplace_back(p);
      out.normals.emplace_back(n);
      PrtVertex pv;
      pv.n = n;
      pv.origin = glm::vec3(p + 0.01 * (c - p));  // the normal offset follows (frame size)
      verts.push_back(pv);
    }
  }
  if (!out.positions.empty()) {
    glm::vec3 lo = out.positions[0], hi = lo;
    for (glm::vec3 p : out.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const float eps = 1e-4f * std::max(glm::length(hi - lo), 1e-3f);
    for (PrtVertex& v : verts) v.origin += eps * glm::vec3(v.n);
  }
  return verts;
}

}  // namespace

glm::dvec3 PrtTransfer::irradiance(uint32_t vertex, const std::vector<glm::dvec3>& env) const {
  glm::dvec3 e(0.0);
  for (uint32_t c = 0; c < 3; ++c) {
    const float* t = at(vertex, channels == 3 ? c : 0);
    for (int i = 0; i < count(); ++i) e[int(c)] += double(t[i]) * env[size_t(i)][int(c)];
  }
  return e;
}

PrtTransfer compute_prt_transfer(const scene::SceneAssets& assets, const scene::FrameScene& frame,
                                 const PrtSettings& settings, const PrtProgressFn& progress,
                                 const std::atomic<bool>* cancel) {
  if (settings.bands != 3 && settings.bands != 5)
    throw std::invalid_argument("PRT: " + std::to_string(settings.bands) +
                                " SH bands (3 or 5)");
  if (settings.samples == 0 && settings.kind != PrtKind::kUnshadowed)
    throw std::invalid_argument("PRT: zero samples per vertex");
  for (size_t i = 0; i < frame.instances.size(); ++i)
    if (frame.instances[i].mesh >= assets.meshes.size())
      throw std::runtime_error("PRT: instance " + std::to_string(i) +
                               " refers to a mesh that does not exist");
  if (settings.sun_directions.size() > kPrtMaxSuns)
    throw std::invalid_argument("PRT: " + std::to_string(settings.sun_directions.size()) +
                                " suns (at most " + std::to_string(kPrtMaxSuns) + ")");
  for (const glm::vec3& d : settings.sun_directions)
    if (!(glm::length(d) > 1e-6f))
      throw std::invalid_argument("PRT: a sun without a direction");
  if (settings.glow_cells.size() > scene::kMaxGlowCells)
    throw std::invalid_argument("PRT: " + std::to_string(settings.glow_cells.size()) +
                                " glow cells (at most " + std::to_string(scene::kMaxGlowCells) +
                                ")");
  for (const scene::GlowCell& c : settings.glow_cells)
    if (!(glm::length(c.direction) > 1e-6f))
      throw std::invalid_argument("PRT: a glow cell without a direction");
  const TraceAssets trace(assets);  // validates meshes, materials, textures
  const InstanceScene scene(trace, frame);

  PrtTransfer out;
  out.bands = settings.bands;
  out.kind = settings.kind;
  out.bounces = settings.kind == PrtKind::kInterreflected ? settings.bounces : 0;
  out.samples = settings.kind == PrtKind::kUnshadowed ? 0 : settings.samples;
  out.channels = settings.kind == PrtKind::kInterreflected ? 3 : 1;
  const std::vector<PrtVertex> verts = build_vertices(assets, frame, out);
  const uint32_t nv = uint32_t(verts.size());
  const size_t nc = size_t(shading::sh_count(settings.bands));
  const unsigned threads =
      settings.threads ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
  const bool bouncing = settings.kind == PrtKind::kInterreflected && settings.bounces > 0;
  // The suns ride along as extra columns after the SH coefficients: column nc + j starts as
  // sun j's direct irradiance (cosine, shadow ray) and bounces through the same rows.
  if (bouncing)
    for (const glm::vec3& d : settings.sun_directions)
      out.sun_directions.push_back(glm::normalize(d));
  // The glow rides along as one more column (RGB: it starts as each channel's own direct light)
  // where it bounces; without bounces its direct light is all there is.
  if (settings.kind != PrtKind::kUnshadowed)
    for (const scene::GlowCell& c : settings.glow_cells)
      out.glow_cells.push_back({glm::normalize(c.direction), c.irradiance});
  const bool glowing = !out.glow_cells.empty();
  const size_t suns = out.sun_directions.size(), glow_column = nc + suns;
  const size_t nt = glow_column + (bouncing && glowing ? 1 : 0);
  // Keep every vertex's bounce row (bounces then cost a sparse product) when the worst case,
  // 3 entries per ray, fits the budget; else rebuild each row by tracing again per bounce.
  const bool keep_rows =
      bouncing && double(nv) * 3.0 * settings.samples * sizeof(RowEntry) <=
                      double(settings.bounce_matrix_mb) * 1024.0 * 1024.0;
  // Progress: kept rows make the bounces cheap (the last 5 %); rebuilt rows cost a trace each.
  const double trace_share = !bouncing ? 1.0 : keep_rows ? 0.95 : 1.0 / (1.0 + settings.bounces);
  auto report = [&](double lo, double span) {
    return std::function<void(double)>([&progress, lo, span](double f) {
      if (progress) progress(lo + span * f);
    });
  };

  std::vector<double> zonal;
  for (int l = 0; l < settings.bands; ++l) zonal.push_back(shading::sh_cosine_lobe_zonal(l));
  const std::vector<glm::dvec3> local = cosine_hammersley(settings.samples);
  const double n_inv = 1.0 / double(settings.samples);
  const std::vector<TraceMesh>& meshes = trace.meshes();

  // Traces vertex v's rays. t != nullptr: subtracts the blocked directions' share from t (the
  // control variate, header). row != nullptr: fills v's bounce row, merged and sorted by target.
  auto trace_vertex = [&](uint32_t v, double* t, std::vector<RowEntry>* row) {
    const PrtVertex& pv = verts[v];
    std::vector<HitEntry> hits;
    double y[shading::kShMaxCount];
    RTCIntersectContext context;
    for (const glm::dvec3& d : local) {
      const glm::dvec3 w = glm::normalize(to_world(pv.n, d));
      const glm::vec3 wf(w);
      bool blocked = false;
      rtcInitIntersectContext(&context);
      if (row == nullptr) {
        RTCRay ray = make_ray(pv.origin, wf, std::numeric_limits<float>::infinity());
        rtcOccluded1(scene.get(), &context, &ray);
        blocked = ray.tfar < 0.0f;
      } else {
        RTCRayHit rh{};
        rh.ray = make_ray(pv.origin, wf, std::numeric_limits<float>::infinity());
        rh.hit.geomID = kInvalid;
        rh.hit.instID[0] = kInvalid;
        rtcIntersect1(scene.get(), &context, &rh);
        blocked = rh.hit.geomID != kInvalid;
        if (blocked && rh.hit.instID[0] != kInvalid) {
          const uint32_t inst = rh.hit.instID[0], prim = rh.hit.primID;
          const TraceMesh& m = meshes[frame.instances[inst].mesh];
          const uint32_t first = out.instances[inst].first;
          const uint32_t idx[3] = {first + m.indices[3 * prim], first + m.indices[3 * prim + 1],
                                   first + m.indices[3 * prim + 2]};
          const double b[3] = {1.0 - double(rh.hit.u) - double(rh.hit.v), double(rh.hit.u),
                               double(rh.hit.v)};
          const glm::dvec3 ns = b[0] * verts[idx[0]].n + b[1] * verts[idx[1]].n +
                                b[2] * verts[idx[2]].n;
          if (glm::dot(ns, w) < 0.0) {  // a front face: its vertices' transfer is for this side
            const scene::Material& mat = trace.materials()[m.materials[prim]];
            glm::dvec3 albedo(mat.albedo);
            if (mat.texture >= 0)
              albedo *= glm::dvec3(trace.textures()[size_t(mat.texture)].sample(
                  m.uv_at(prim, rh.hit.u, rh.hit.v)));
            for (int k = 0; k < 3; ++k) hits.push_back({idx[k], albedo * (b[k] * n_inv)});
          }
        }
      }
      if (!blocked || t == nullptr) continue;
      shading::sh_eval(w, settings.bands, y);
      for (size_t i = 0; i < nc; ++i) t[i] -= kPiD * n_inv * y[i];
    }
    if (row == nullptr) return;
    // Merge the hits of one target (stable sort: the sum's order is the rays' order).
    std::stable_sort(hits.begin(), hits.end(),
                     [](const HitEntry& a, const HitEntry& b) { return a.target < b.target; });
    row->clear();
    for (size_t i = 0; i < hits.size();) {
      glm::dvec3 w(0.0);
      size_t j = i;
      for (; j < hits.size() && hits[j].target == hits[i].target; ++j) w += hits[j].w;
      row->push_back({hits[i].target, {float(w.x), float(w.y), float(w.z)}});
      i = j;
    }
  };

  // the shadowed (or unshadowed) transfer, then the suns' direct irradiance: nt per vertex
  std::vector<double> t0(size_t(nv) * nt, 0.0);
  std::vector<glm::dvec3> glow0(glowing ? nv : 0, glm::dvec3(0.0));  // the glow's direct light
  std::vector<std::vector<RowEntry>> rows(keep_rows ? nv : 0);
  // True where the ray from vertex v towards unit direction l leaves the scene.
  auto sees = [&](uint32_t v, const glm::dvec3& l) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = make_ray(verts[v].origin, glm::vec3(l), std::numeric_limits<float>::infinity());
    rtcOccluded1(scene.get(), &context, &ray);
    return ray.tfar >= 0.0f;
  };
  auto first_pass = [&](uint32_t v) {
    if (verts[v].n == glm::dvec3(0.0)) return;  // degenerate: no transfer
    const std::vector<double> lobe = shading::sh_rotate_zonal(zonal, verts[v].n, settings.bands);
    double* t = t0.data() + size_t(v) * nt;
    std::copy(lobe.begin(), lobe.end(), t);
    if (settings.kind != PrtKind::kUnshadowed) trace_vertex(v, t, keep_rows ? &rows[v] : nullptr);
    for (size_t j = 0; j < suns; ++j) {
      const glm::dvec3 l(out.sun_directions[j]);
      const double cosine = glm::dot(verts[v].n, l);
      if (cosine > 0.0 && sees(v, l)) t[nc + j] = cosine;
    }
    if (!glowing) return;
    for (const scene::GlowCell& c : out.glow_cells) {
      const glm::dvec3 l(c.direction);
      const double cosine = glm::dot(verts[v].n, l);
      if (cosine > 0.0 && sees(v, l)) glow0[v] += glm::dvec3(c.irradiance) * cosine;
    }
  };
  if (settings.kind == PrtKind::kUnshadowed)
    for (uint32_t v = 0; v < nv; ++v) first_pass(v);  // closed form: no rays, no threads
  else
    run_parallel(nv, threads, first_pass, report(0.0, trace_share), cancel);

  const uint32_t channels = out.channels;
  std::vector<double> total(size_t(nv) * channels * nt);
  for (uint32_t v = 0; v < nv; ++v)
    for (uint32_t c = 0; c < channels; ++c)
      std::copy_n(t0.begin() + std::ptrdiff_t(size_t(v) * nt), nt,
                  total.begin() + std::ptrdiff_t((size_t(v) * channels + c) * nt));
  if (bouncing && glowing)
    for (uint32_t v = 0; v < nv; ++v)
      for (uint32_t c = 0; c < 3; ++c) total[(size_t(v) * 3 + c) * nt + glow_column] = glow0[v][c];
  if (bouncing) {
    // T_k = M T_{k-1} per channel, T_0 the shadowed transfer; total = sum over k <= bounces.
    std::vector<double> prev = total, next(total.size());
    for (uint32_t bounce = 0; bounce < settings.bounces; ++bounce) {
      auto row_fn = [&](uint32_t v) {
        double* dst = next.data() + size_t(v) * 3 * nt;
        std::fill_n(dst, 3 * nt, 0.0);
        if (verts[v].n == glm::dvec3(0.0)) return;
        std::vector<RowEntry> rebuilt;
        if (!keep_rows) trace_vertex(v, nullptr, &rebuilt);
        for (const RowEntry& e : keep_rows ? rows[v] : rebuilt)
          for (uint32_t c = 0; c < 3; ++c) {
            const double* src = prev.data() + (size_t(e.target) * 3 + c) * nt;
            for (size_t i = 0; i < nt; ++i) dst[c * nt + i] += double(e.w[c]) * src[i];
          }
      };
      const double span = (1.0 - trace_share) / double(settings.bounces);
      run_parallel(nv, threads, row_fn, report(trace_share + span * bounce, span), cancel);
      for (size_t i = 0; i < total.size(); ++i) total[i] += next[i];
      std::swap(prev, next);
    }
  }
  out.coefficients.resize(size_t(nv) * channels * nc);
  for (size_t row = 0; row < size_t(nv) * channels; ++row)
    std::copy_n(total.begin() + std::ptrdiff_t(row * nt), nc,
                out.coefficients.begin() + std::ptrdiff_t(row * nc));
  if (bouncing) {
    out.shadowed.resize(size_t(nv) * nc);
    out.sun_bounce.resize(size_t(nv) * suns * 3);
    for (uint32_t v = 0; v < nv; ++v) {
      std::copy_n(t0.begin() + std::ptrdiff_t(size_t(v) * nt), nc,
                  out.shadowed.begin() + std::ptrdiff_t(size_t(v) * nc));
      for (size_t j = 0; j < suns; ++j)  // the bounces alone: the total less the direct column
        for (uint32_t c = 0; c < 3; ++c)
          out.sun_bounce[(size_t(v) * suns + j) * 3 + c] =
              float(total[(size_t(v) * 3 + c) * nt + nc + j] - t0[size_t(v) * nt + nc + j]);
    }
  }
  if (glowing) {
    out.glow.resize(size_t(nv) * 3);
    for (uint32_t v = 0; v < nv; ++v)
      for (uint32_t c = 0; c < 3; ++c)
        out.glow[size_t(v) * 3 + c] =
            float(bouncing ? total[(size_t(v) * 3 + c) * nt + glow_column] : glow0[v][c]);
  }
  if (progress) progress(1.0);
  return out;
}

}  // namespace rp::truth
