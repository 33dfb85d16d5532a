// Embree visibility backend (see embree_visibility.h for the conventions and scene layout).
#include "passes/embree_visibility.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "cl/error.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"
#include "scene/alpha_mask.h"

namespace rp::passes {
namespace {

constexpr uint32_t kTile = 4;  // rtcIntersect16 packet = 4x4 pixels
constexpr uint32_t kNone = 0xFFFFFFFFu;

// Runs job(context, item) for item in [0, count) on `threads` threads (the caller is one of
// them); items are taken from an atomic counter, so which thread runs an item varies, and each
// item must write only its own outputs. Workers live as long as the pool (no per-run spawning).
class TilePool {
 public:
  using Job = void (*)(void* context, uint32_t item);

  explicit TilePool(unsigned threads) {
    for (unsigned i = 1; i < threads; ++i) workers_.emplace_back([this] { work(); });
  }
  ~TilePool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    start_.notify_all();
    for (std::thread& t : workers_) t.join();
  }
  TilePool(const TilePool&) = delete;
  TilePool& operator=(const TilePool&) = delete;

  unsigned threads() const { return static_cast<unsigned>(workers_.size()) + 1; }

  void run(uint32_t count, Job job, void* context) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      job_ = job;
      context_ = context;
      count_ = count;
      next_.store(0);
      busy_ = workers_.size();
      ++generation_;
    }
    start_.notify_all();
    drain();
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return busy_ == 0; });
  }

 private:
  void drain() {
    for (uint32_t i = next_.fetch_add(1); i < count_; i = next_.fetch_add(1)) job_(context_, i);
  }
  void work() {
    uint64_t seen = 0;
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(mutex_);
        start_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
      }
      drain();
      std::lock_guard<std::mutex> lock(mutex_);
      if (--busy_ == 0) done_.notify_one();
    }
  }

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  bool stop_ = false;
  uint64_t generation_ = 0;
  size_t busy_ = 0;
  Job job_ = nullptr;
  void* context_ = nullptr;
  uint32_t count_ = 0;  // written under the mutex before the workers are woken
  std::atomic<uint32_t> next_{0};
};

bool is_identity(const gpu::rp_mat4& m) {
  const float* f = &m.c[0].x;
  for (int i = 0; i < 16; ++i)
    if (f[i] != ((i % 5 == 0) ? 1.0f : 0.0f)) return false;
  return true;
}

// A mesh as Embree reads it: positions as float4 (x, y, z, 0) so every vertex can be loaded with
// 16-byte SSE loads (Embree's padding rule), indices uint3 in the mesh's own vertex order.
struct MeshData {
  std::vector<float> positions;
  std::vector<uint32_t> indices;
  uint32_t triangle_count = 0;
  RTCScene scene = nullptr;  // HIGH quality BVH over this mesh alone (nullptr when empty)
  // Meshes with alpha-masked materials: per-vertex uv and per-triangle material, read by the
  // Embree filter that lets rays through the holes (scene/alpha_mask.h); empty otherwise.
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> materials;
  const scene::AlphaMasks* masks = nullptr;
  // Per triangle: 1 where its material is single-sided (the camera does not see its back).
  std::vector<uint8_t> single_sided;

  // Embree filter (intersect and occluded) of a masked mesh: rejects hits in holes.
  static void alpha_filter(const RTCFilterFunctionNArguments* args) {
    const auto* m = static_cast<const MeshData*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
      if (args->valid[i] != -1) continue;
      const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
      const float b1 = RTCHitN_u(args->hit, args->N, i), b2 = RTCHitN_v(args->hit, args->N, i);
      const uint32_t* t = &m->indices[3 * size_t(prim)];
      const glm::vec2 uv = (1.0f - b1 - b2) * m->uvs[t[0]] + b1 * m->uvs[t[1]] + b2 * m->uvs[t[2]];
      if (!m->masks->solid(m->materials[prim], uv)) args->valid[i] = 0;
    }
  }
};

}  // namespace

struct EmbreeVisibilityPass::Impl {
  const rp::cl::Context* context = nullptr;
  RTCDevice device = nullptr;
  std::mutex error_mutex;
  std::string last_error;  // set by Embree's error callback

  std::vector<MeshData> meshes;
  RTCScene top = nullptr;
  // Static scene: identity-model instances, one triangle geometry each (geomID g is instance
  // static_instance_of[g]); instanced once into `top` as geometry static_top_id.
  RTCScene static_scene = nullptr;
  RTCGeometry static_instance = nullptr;
  unsigned static_top_id = RTC_INVALID_GEOMETRY_ID;
  bool static_enabled = false;
  std::vector<uint32_t> static_key;  // (instance index, mesh index) pairs of the static scene
  std::vector<uint32_t> static_instance_of;
  // Moving instances: pool of instance geometries in `top`, mover k currently instancing mesh
  // mover_mesh[k] (kNone when disabled); top-level geomID -> instance index in instance_of_top.
  std::vector<RTCGeometry> movers;
  std::vector<unsigned> mover_ids;
  std::vector<uint32_t> mover_mesh;
  std::vector<uint32_t> instance_of_top;
  std::vector<uint32_t> mesh_of_instance;  // the frame's instance -> its mesh (mesh_of)
  // Spheres: float4 (centre, radius) per sphere, plus one float4 of padding.
  RTCGeometry spheres = nullptr;
  unsigned sphere_top_id = RTC_INVALID_GEOMETRY_ID;
  std::vector<float> sphere_points;
  uint32_t sphere_items = 0;  // item count the shared buffer was last set with ...
  const float* shared_sphere_data = nullptr;  // ... and the address
  bool spheres_enabled = false;

  // Host copy of the visibility buffer (layouts of render::VisibilityBuffer).
  std::vector<float> depth;
  std::vector<uint32_t> ids;
  std::vector<float> bary;
  std::array<::cl::Event, 3> uploads;
  bool uploads_pending = false;

  // Per frame, read by the tracing threads.
  const render::GpuScene* scene = nullptr;
  uint32_t width = 0, height = 0, tiles_x = 0;

  std::unique_ptr<TilePool> pool;
  std::unique_ptr<scene::AlphaMasks> masks;  // what masked meshes' filters ask

  ~Impl() {
    for (RTCGeometry g : movers) rtcReleaseGeometry(g);
    if (spheres) rtcReleaseGeometry(spheres);
    if (static_instance) rtcReleaseGeometry(static_instance);
    if (static_scene) rtcReleaseScene(static_scene);
    if (top) rtcReleaseScene(top);
    for (MeshData& m : meshes)
      if (m.scene) rtcReleaseScene(m.scene);
    if (device) rtcReleaseDevice(device);
  }

  // Throws when Embree reported an error since the last check.
  void check(const char* what) {
    RTCError code = rtcGetDeviceError(device);
    if (code == RTC_ERROR_NONE) return;
    std::lock_guard<std::mutex> lock(error_mutex);
    throw rp::cl::Error(std::string("Embree visibility: ") + what + " failed: " +
                        (last_error.empty() ? "error code " + std::to_string(int(code))
                                            : last_error));
  }

  void build_meshes(const scene::SceneAssets& assets) {
    masks = std::make_unique<scene::AlphaMasks>(assets);
    for (const scene::Mesh& mesh : assets.meshes) {
      MeshData m;
      m.triangle_count = static_cast<uint32_t>(mesh.triangles.size());
      m.positions.reserve(4 * mesh.vertices.size() + 4);
      for (const scene::Vertex& v : mesh.vertices)
        m.positions.insert(m.positions.end(), {v.position.x, v.position.y, v.position.z, 0.0f});
      m.positions.insert(m.positions.end(), 4, 0.0f);
      for (const glm::uvec3& t : mesh.triangles) {
        if (t.x >= mesh.vertices.size() || t.y >= mesh.vertices.size() ||
            t.z >= mesh.vertices.size())
          throw rp::cl::Error("Embree visibility: mesh '" + mesh.name +
                              "' refers to a vertex that does not exist");
        m.indices.insert(m.indices.end(), {t.x, t.y, t.z});
      }
      m.single_sided.resize(mesh.triangles.size());
      for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const uint32_t material = t < mesh.materials.size() ? mesh.materials[t] : 0u;
        m.single_sided[t] =
            material < assets.materials.size() && !assets.materials[material].double_sided;
      }
      bool masked = false;
      for (uint32_t material : mesh.materials) masked = masked || masks->masked(material);
      if (masked && mesh.materials.size() == mesh.triangles.size()) {
        for (const scene::Vertex& v : mesh.vertices) m.uvs.push_back(v.uv);
        m.materials = mesh.materials;
        m.masks = masks.get();
      }
      meshes.push_back(std::move(m));
    }
    for (size_t i = 0; i < meshes.size(); ++i) {
      MeshData& m = meshes[i];
      if (m.triangle_count == 0) continue;
      m.scene = rtcNewScene(device);
      rtcSetSceneBuildQuality(m.scene, RTC_BUILD_QUALITY_HIGH);
      RTCGeometry g = new_triangles(m);
      rtcAttachGeometry(m.scene, g);
      rtcReleaseGeometry(g);
      rtcCommitScene(m.scene);
      check(("building the BVH of mesh '" + assets.meshes[i].name + "'").c_str());
    }
  }

  // A triangle geometry reading `m`'s arrays in place (they live as long as the pass).
  RTCGeometry new_triangles(const MeshData& m) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                               m.positions.data(), 0, 4 * sizeof(float),
                               m.positions.size() / 4 - 1);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.indices.data(), 0,
                               3 * sizeof(uint32_t), m.triangle_count);
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
    if (m.masks != nullptr) {  // `m` stays in place: `meshes` is complete before any geometry
      rtcSetGeometryUserData(g, const_cast<MeshData*>(&m));
      rtcSetGeometryIntersectFilterFunction(g, &MeshData::alpha_filter);
      rtcSetGeometryOccludedFilterFunction(g, &MeshData::alpha_filter);
    }
    rtcCommitGeometry(g);
    check("creating a triangle geometry");
    return g;
  }

  void build_top() {
    top = rtcNewScene(device);
    rtcSetSceneBuildQuality(top, RTC_BUILD_QUALITY_LOW);
    rtcSetSceneFlags(top, RTC_SCENE_FLAG_DYNAMIC);
    static_instance = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    static_top_id = rtcAttachGeometry(top, static_instance);
    rtcDisableGeometry(static_instance);
    spheres = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    sphere_top_id = rtcAttachGeometry(top, spheres);
    rtcDisableGeometry(spheres);
    check("creating the top-level scene");
  }

  // Mesh index of an instance from its triangle range (GpuScene lays meshes out in asset order).
  uint32_t mesh_of(const render::GpuScene& s, const gpu::Instance& inst, size_t index) const {
    for (size_t m = 0; m < s.meshes.size(); ++m)
      if (s.meshes[m].first_triangle == inst.first_triangle &&
          s.meshes[m].triangle_count == inst.triangle_count)
        return static_cast<uint32_t>(m);
    throw rp::cl::Error("Embree visibility: instance " + std::to_string(index) +
                        " does not cover exactly one mesh of the scene");
  }

  void update_scene(const render::GpuScene& s) {
    if (s.meshes.size() != meshes.size())
      throw rp::cl::Error("Embree visibility: the GpuScene was built from other assets (" +
                          std::to_string(s.meshes.size()) + " meshes, not " +
                          std::to_string(meshes.size()) + ")");
    const std::vector<gpu::Instance>& instances = s.host_instances;
    mesh_of_instance.assign(instances.size(), kNone);
    for (size_t i = 0; i < instances.size(); ++i)
      if (instances[i].triangle_count != 0) mesh_of_instance[i] = mesh_of(s, instances[i], i);
    // (the static set, the movers and the back-face test read it: one search per instance)

    // Static set: rebuild the static scene only when it changes.
    bool same = true;
    size_t k = 0;
    for (size_t i = 0; i < instances.size(); ++i) {
      if (instances[i].triangle_count == 0 || !is_identity(instances[i].model)) continue;
      const uint32_t m = mesh_of_instance[i];
      same = same && k + 2 <= static_key.size() && static_key[k] == i && static_key[k + 1] == m;
      k += 2;
    }
    if (!same || k != static_key.size()) rebuild_static(s);

    // Moving instances.
    size_t used = 0;
    for (size_t i = 0; i < instances.size(); ++i) {
      const gpu::Instance& inst = instances[i];
      if (inst.triangle_count == 0 || is_identity(inst.model)) continue;
      const uint32_t m = mesh_of_instance[i];
      if (used == movers.size()) {
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryTimeStepCount(g, 1);
        movers.push_back(g);
        mover_ids.push_back(rtcAttachGeometry(top, g));
        mover_mesh.push_back(kNone);
        if (instance_of_top.size() <= mover_ids.back()) instance_of_top.resize(mover_ids.back() + 1);
        check("creating an instance geometry");
      }
      RTCGeometry g = movers[used];
      if (mover_mesh[used] == kNone) rtcEnableGeometry(g);
      if (mover_mesh[used] != m) rtcSetGeometryInstancedScene(g, meshes[m].scene);
      mover_mesh[used] = m;
      rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &inst.model.c[0].x);
      rtcCommitGeometry(g);
      instance_of_top[mover_ids[used]] = static_cast<uint32_t>(i);
      ++used;
    }
    for (size_t j = used; j < movers.size(); ++j) {
      if (mover_mesh[j] == kNone) continue;
      rtcDisableGeometry(movers[j]);
      mover_mesh[j] = kNone;
    }

    // Spheres (radius <= 0 is never drawn by the rasterizer: a radius-0 point is never hit).
    const uint32_t n = s.sphere_count;
    if (sphere_points.size() < 4 * size_t(n) + 4) sphere_points.resize(4 * size_t(n) + 4);
    for (uint32_t i = 0; i < n; ++i) {
      const gpu::rp_float4& c = s.host_spheres[i].center_radius;
      float* p = &sphere_points[4 * size_t(i)];
      p[0] = c.x;
      p[1] = c.y;
      p[2] = c.z;
      p[3] = std::max(c.w, 0.0f);
    }
    if (n > 0) {
      // Re-set after a resize (the vector may have moved) or a count change, else mark updated.
      if (n != sphere_items || sphere_points.data() != shared_sphere_data) {
        rtcSetSharedGeometryBuffer(spheres, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                   sphere_points.data(), 0, 4 * sizeof(float), n);
        sphere_items = n;
        shared_sphere_data = sphere_points.data();
      } else {
        rtcUpdateGeometryBuffer(spheres, RTC_BUFFER_TYPE_VERTEX, 0);
      }
      if (!spheres_enabled) rtcEnableGeometry(spheres);
      spheres_enabled = true;
      rtcCommitGeometry(spheres);
    } else if (spheres_enabled) {
      rtcDisableGeometry(spheres);
      spheres_enabled = false;
    }
    rtcCommitScene(top);
    check("updating the scene");
  }
  void rebuild_static(const render::GpuScene& s) {
    if (static_scene) rtcReleaseScene(static_scene);
    static_scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(static_scene, RTC_BUILD_QUALITY_HIGH);
    static_key.clear();
    static_instance_of.clear();
    for (size_t i = 0; i < s.host_instances.size(); ++i) {
      const gpu::Instance& inst = s.host_instances[i];
      if (inst.triangle_count == 0 || !is_identity(inst.model)) continue;
      const uint32_t m = mesh_of_instance[i];
      static_key.push_back(static_cast<uint32_t>(i));
      static_key.push_back(m);
      RTCGeometry g = new_triangles(meshes[m]);
      const unsigned id = rtcAttachGeometry(static_scene, g);
      rtcReleaseGeometry(g);
      if (static_instance_of.size() <= id) static_instance_of.resize(id + 1, kNone);
      static_instance_of[id] = static_cast<uint32_t>(i);
    }
    rtcCommitScene(static_scene);
    rtcSetGeometryInstancedScene(static_instance, static_scene);
    const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    rtcSetGeometryTimeStepCount(static_instance, 1);
    rtcSetGeometryTransform(static_instance, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, identity);
    const bool any = !static_key.empty();
    if (any && !static_enabled) rtcEnableGeometry(static_instance);
    if (!any && static_enabled) rtcDisableGeometry(static_instance);
    static_enabled = any;
    rtcCommitGeometry(static_instance);
    check("building the static scene");
  }

  static void on_error(void* user, RTCError code, const char* message) {
    Impl* impl = static_cast<Impl*>(user);
    std::lock_guard<std::mutex> lock(impl->error_mutex);
    impl->last_error = std::string(message ? message : "unknown") + " (code " +
                       std::to_string(int(code)) + ")";
  }

  static void trace_row_job(void* self, uint32_t row) { static_cast<Impl*>(self)->trace_row(row); }

  // Traces the 4x4 tiles of tile row `ty` and writes their pixels.
  void trace_row(uint32_t ty) {
    const gpu::FrameConstants& c = scene->constants;
    const gpu::rp_mat4& inv = c.inv_view_proj;
    const gpu::rp_mat4& vp = c.view_proj;
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[16];
    // Per lane: clip z, w at the ray origin and their change per unit t (z_ndc along the ray).
    float z_o[16], w_o[16], z_d[16], w_d[16];
    float far_t[16];  // the far plane's t
    RTCIntersectContext ictx;
    rtcInitIntersectContext(&ictx);
    ictx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    const float sx = 2.0f / float(width), sy = 2.0f / float(height);
    for (uint32_t tx = 0; tx < tiles_x; ++tx) {
      for (uint32_t l = 0; l < 16; ++l) {
        const uint32_t x = tx * kTile + l % kTile, y = ty * kTile + l / kTile;
        valid[l] = (x < width && y < height) ? -1 : 0;
        // The rasterizer's sphere rays (visibility.cl), operation for operation, in float.
        const float nx = (float(x) + 0.5f) * sx - 1.0f;
        const float ny = 1.0f - (float(y) + 0.5f) * sy;
#define RP_UNPROJECT(comp, zn) \
  (((inv.c[0].comp * nx + inv.c[1].comp * ny) + inv.c[2].comp * (zn)) + inv.c[3].comp)
        const float near_w = RP_UNPROJECT(w, -1.0f), far_w = RP_UNPROJECT(w, 1.0f);
        const float ox = RP_UNPROJECT(x, -1.0f) / near_w, oy = RP_UNPROJECT(y, -1.0f) / near_w,
                    oz = RP_UNPROJECT(z, -1.0f) / near_w;
        float rx = RP_UNPROJECT(x, 1.0f) / far_w - ox, ry = RP_UNPROJECT(y, 1.0f) / far_w - oy,
              rz = RP_UNPROJECT(z, 1.0f) / far_w - oz;
#undef RP_UNPROJECT
        const float len = std::sqrt((rx * rx + ry * ry) + rz * rz);
        rx = rx / len;
        ry = ry / len;
        rz = rz / len;
        z_o[l] = ((vp.c[0].z * ox + vp.c[1].z * oy) + vp.c[2].z * oz) + vp.c[3].z;
        w_o[l] = ((vp.c[0].w * ox + vp.c[1].w * oy) + vp.c[2].w * oz) + vp.c[3].w;
        z_d[l] = (vp.c[0].z * rx + vp.c[1].z * ry) + vp.c[2].z * rz;
        w_d[l] = (vp.c[0].w * rx + vp.c[1].w * ry) + vp.c[2].w * rz;
        rh.ray.org_x[l] = ox;
        rh.ray.org_y[l] = oy;
        rh.ray.org_z[l] = oz;
        rh.ray.dir_x[l] = rx;
        rh.ray.dir_y[l] = ry;
        rh.ray.dir_z[l] = rz;
        rh.ray.tnear[l] = 0.0f;  // the near plane, as the rasterizer's z_ndc >= -1
        rh.ray.tfar[l] = std::isfinite(len) ? len : 0.0f;  // the far plane
        far_t[l] = rh.ray.tfar[l];
        rh.ray.time[l] = 0.0f;
        rh.ray.mask[l] = 0xFFFFFFFFu;
        rh.ray.id[l] = l;
        rh.ray.flags[l] = 0;
        rh.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][l] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect16(valid, top, &ictx, &rh);
      // The back faces of single-sided materials are not seen (the rasterizer culls them): such
      // lanes go on from just beyond the hit (bounded, for a stack of coplanar faces).
      for (int pass = 0; pass < 64; ++pass) {
        alignas(64) int again[16];
        bool any = false;
        for (uint32_t l = 0; l < 16; ++l) {
          again[l] = 0;
          if (!valid[l] || rh.hit.geomID[l] == RTC_INVALID_GEOMETRY_ID ||
              rh.hit.instID[0][l] == RTC_INVALID_GEOMETRY_ID ||
              !back_of_single_sided(rh, l))
            continue;
          again[l] = -1;
          any = true;
          rh.ray.tnear[l] = std::nextafter(rh.ray.tfar[l], far_t[l]);
          rh.ray.tfar[l] = far_t[l];
          rh.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
          rh.hit.instID[0][l] = RTC_INVALID_GEOMETRY_ID;
        }
        if (!any) break;
        rtcIntersect16(again, top, &ictx, &rh);
      }
      for (uint32_t l = 0; l < 16; ++l) {
        if (!valid[l]) continue;
        const uint32_t x = tx * kTile + l % kTile, y = ty * kTile + l / kTile;
        const size_t p = size_t(y) * width + x;
        uint32_t instance = RP_ID_NONE, primitive = RP_ID_NONE;
        float b1 = 0.0f, b2 = 0.0f, z = 1.0f;
        const unsigned geom = rh.hit.geomID[l], inst = rh.hit.instID[0][l];
        if (geom != RTC_INVALID_GEOMETRY_ID) {
          float t = rh.ray.tfar[l];
          if (inst == RTC_INVALID_GEOMETRY_ID) {  // a sphere (the only non-instanced geometry)
            const uint32_t index = rh.hit.primID[l];
            instance = RP_ID_SPHERE_BIT | index;
            primitive = 0;
            t = sphere_t(index, rh.ray, l, t);
          } else {
            instance = inst == static_top_id ? static_instance_of[geom] : instance_of_top[inst];
            primitive = rh.hit.primID[l];
            b1 = rh.hit.u[l];
            b2 = rh.hit.v[l];
          }
          z = (z_o[l] + t * z_d[l]) / (w_o[l] + t * w_d[l]);
        }
        depth[p] = z * 0.5f + 0.5f;
        ids[2 * p] = instance;
        ids[2 * p + 1] = primitive;
        bary[2 * p] = b1;
        bary[2 * p + 1] = b2;
      }
    }
  }

  // True when lane l hit the back of a single-sided material's triangle: counter-clockwise in
  // the mesh's space is the front, its normal taken through the instance's normal matrix
  // (which keeps that side for mirroring models too) against the ray.
  bool back_of_single_sided(const RTCRayHit16& rh, uint32_t l) const {
    const unsigned geom = rh.hit.geomID[l], inst = rh.hit.instID[0][l];
    const bool is_static = inst == static_top_id;
    const uint32_t instance = is_static ? static_instance_of[geom] : instance_of_top[inst];
    const MeshData& m = meshes[mesh_of_instance[instance]];
    const uint32_t prim = rh.hit.primID[l];
    if (!m.single_sided[prim]) return false;
    auto pos = [&](uint32_t k) {
      const float* p = &m.positions[4 * size_t(m.indices[3 * size_t(prim) + k])];
      return glm::vec3(p[0], p[1], p[2]);
    };
    const glm::vec3 p0 = pos(0), n = glm::cross(pos(1) - p0, pos(2) - p0);
    const gpu::rp_mat4& nm = scene->host_instances[instance].normal_matrix;
    const glm::vec3 front = glm::vec3(nm.c[0].x, nm.c[0].y, nm.c[0].z) * n.x +
                            glm::vec3(nm.c[1].x, nm.c[1].y, nm.c[1].z) * n.y +
                            glm::vec3(nm.c[2].x, nm.c[2].y, nm.c[2].z) * n.z;
    return front.x * rh.ray.dir_x[l] + front.y * rh.ray.dir_y[l] + front.z * rh.ray.dir_z[l] >
           0.0f;
  }

  // The rasterizer's sphere hit (visibility.cl) for the sphere Embree found, in the same float
  // operations, so both backends give the same depth; Embree's t where that formula misses
  // (a silhouette pixel the two decide differently).
  float sphere_t(uint32_t index, const RTCRay16& ray, uint32_t l, float embree_t) const {
    const gpu::rp_float4 s = scene->host_spheres[index].center_radius;
    const float rx = ray.dir_x[l], ry = ray.dir_y[l], rz = ray.dir_z[l];
    const float cx = ray.org_x[l] - s.x, cy = ray.org_y[l] - s.y, cz = ray.org_z[l] - s.z;
    const float b = (cx * rx + cy * ry) + cz * rz;
    const float px = cx - b * rx, py = cy - b * ry, pz = cz - b * rz;
    const float disc = s.w * s.w - ((px * px + py * py) + pz * pz);
    const float root = std::sqrt(std::max(disc, 0.0f));
    const float t0 = -b - root;
    const float t = t0 >= 0.0f ? t0 : -b + root;
    return (disc >= 0.0f && t >= 0.0f) ? t : embree_t;
  }
};

EmbreeVisibilityPass::EmbreeVisibilityPass(const rp::cl::Context& context,
                                           const scene::SceneAssets& assets, unsigned threads)
    : impl_(std::make_unique<Impl>()) {
  impl_->context = &context;
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device)
    throw rp::cl::Error("Embree visibility: could not create an Embree device (error code " +
                        std::to_string(int(rtcGetDeviceError(nullptr))) +
                        "); is the CPU supported by this Embree build? Use --visibility raster");
  rtcSetDeviceErrorFunction(impl_->device, &Impl::on_error, impl_.get());
  impl_->build_meshes(assets);
  impl_->build_top();
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  impl_->pool = std::make_unique<TilePool>(threads);
}

EmbreeVisibilityPass::~EmbreeVisibilityPass() = default;

unsigned EmbreeVisibilityPass::threads() const { return impl_->pool->threads(); }

double EmbreeVisibilityPass::render(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                                    render::VisibilityBuffer& out) {
  if (out.width != scene.constants.width || out.height != scene.constants.height)
    throw rp::cl::Error("Embree visibility: the visibility buffer is " +
                        std::to_string(out.width) + "x" + std::to_string(out.height) +
                        " but the frame was set up for " + std::to_string(scene.constants.width) +
                        "x" + std::to_string(scene.constants.height));
  if (out.width == 0 || out.height == 0) return 0.0;
  Impl& s = *impl_;
  // The previous frame's uploads read the host planes: they must be done before we overwrite.
  if (s.uploads_pending)
    for (::cl::Event& e : s.uploads) e.wait();
  s.uploads_pending = false;

  const auto start = std::chrono::steady_clock::now();
  s.update_scene(scene);
  const size_t n = size_t(out.width) * out.height;
  if (s.depth.size() != n) {  // only on a size change
    s.depth.resize(n);
    s.ids.resize(2 * n);
    s.bary.resize(2 * n);
  }
  s.scene = &scene;
  s.width = out.width;
  s.height = out.height;
  s.tiles_x = (out.width + kTile - 1) / kTile;
  const uint32_t rows = (out.height + kTile - 1) / kTile;
  s.pool->run(rows, &Impl::trace_row_job, &s);
  const double host_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  ::cl::CommandQueue& queue = profiler.queue();
  queue.enqueueWriteBuffer(out.depth, CL_FALSE, 0, n * sizeof(float), s.depth.data(), nullptr,
                           &s.uploads[0]);
  queue.enqueueWriteBuffer(out.ids, CL_FALSE, 0, 2 * n * sizeof(uint32_t), s.ids.data(), nullptr,
                           &s.uploads[1]);
  queue.enqueueWriteBuffer(out.bary, CL_FALSE, 0, 2 * n * sizeof(float), s.bary.data(), nullptr,
                           &s.uploads[2]);
  s.uploads_pending = true;
  for (const ::cl::Event& e : s.uploads) profiler.record(pass_name::kVisibility, e);
  return host_ms;
}

}  // namespace rp::passes
