// Embree scenes and surface resolution of the path tracer (see trace_scene.h).
#include "truth/trace_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rp::truth {
namespace {

constexpr unsigned kInvalid = RTC_INVALID_GEOMETRY_ID;

// Exact sRGB decode of an 8-bit code: the float nearest the double-precision curve (the same
// values as kernels/common/colour.h's table).
float srgb8_to_linear(uint8_t code) {
  const double c = double(code) / 255.0;
  return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

}  // namespace

RTCRay make_ray(glm::vec3 org, glm::vec3 dir, float t_max) {
  RTCRay r{};
  r.org_x = org.x;
  r.org_y = org.y;
  r.org_z = org.z;
  r.dir_x = dir.x;
  r.dir_y = dir.y;
  r.dir_z = dir.z;
  r.tnear = 0.0f;
  r.tfar = t_max;
  r.mask = 0xFFFFFFFFu;
  r.flags = 0;
  r.time = 0.0f;
  return r;
}

glm::vec3 LinearTexture::sample(glm::vec2 uv) const {
  const scene::BilinearTaps f = scene::bilinear_taps(width, height, wrap_u, wrap_v, uv);
  auto texel = [&](size_t i) { return glm::vec3(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]); };
  return glm::mix(glm::mix(texel(f.i00), texel(f.i10), f.fx),
                  glm::mix(texel(f.i01), texel(f.i11), f.fx), f.fy);
}

TraceAssets::TraceAssets(const scene::SceneAssets& assets)
    : materials_(assets.materials), masks_(assets) {
  meshes_.reserve(assets.meshes.size());  // the alpha filter's user data points into it
  device_ = rtcNewDevice(nullptr);
  if (device_ == nullptr)
    throw std::runtime_error("path tracer: Embree could not create a device (error " +
                             std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  for (const scene::Texture& t : assets.textures) {
    if (t.width <= 0 || t.height <= 0 || t.rgba.size() != size_t(t.width) * size_t(t.height) * 4)
      throw std::runtime_error("path tracer: texture '" + t.name + "' has no or wrong texels");
    LinearTexture lt;
    lt.width = t.width;
    lt.height = t.height;
    lt.wrap_u = t.wrap_u;
    lt.wrap_v = t.wrap_v;
    const size_t texels = size_t(t.width) * size_t(t.height);
    lt.rgb.resize(texels * 3);
    for (size_t i = 0; i < texels; ++i)
      for (size_t c = 0; c < 3; ++c)
        lt.rgb[3 * i + c] =
            t.srgb ? srgb8_to_linear(t.rgba[4 * i + c]) : float(t.rgba[4 * i + c]) / 255.0f;
    textures_.push_back(std::move(lt));
  }
  for (const scene::Material& m : materials_)
    for (int texture : {m.texture, m.metallic_roughness_texture, m.normal_texture,
                        m.emission_texture})
      if (texture >= int(textures_.size()))
        throw std::runtime_error("path tracer: material '" + m.name + "' refers to texture " +
                                 std::to_string(texture) + ", which does not exist");
  for (const scene::Mesh& mesh : assets.meshes) {
    TraceMesh m;
    m.owner = this;
    const size_t nv = mesh.vertices.size();
    for (const scene::Vertex& v : mesh.vertices) {
      m.positions.insert(m.positions.end(), {v.position.x, v.position.y, v.position.z, 0.0f});
      m.normals.push_back(v.normal);
      m.uvs.push_back(v.uv);
    }
    m.positions.insert(m.positions.end(), 4, 0.0f);
    if (mesh.materials.size() != mesh.triangles.size())
      throw std::runtime_error("path tracer: mesh '" + mesh.name + "' has " +
                               std::to_string(mesh.materials.size()) + " materials for " +
                               std::to_string(mesh.triangles.size()) + " triangles");
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      const glm::uvec3 tri = mesh.triangles[t];
      if (tri.x >= nv || tri.y >= nv || tri.z >= nv)
        throw std::runtime_error("path tracer: mesh '" + mesh.name +
                                 "' refers to a vertex that does not exist");
      if (mesh.materials[t] >= materials_.size())
        throw std::runtime_error("path tracer: mesh '" + mesh.name +
                                 "' refers to a material that does not exist");
      m.indices.insert(m.indices.end(), {tri.x, tri.y, tri.z});
    }
    m.materials = mesh.materials;
    if (!mesh.tangents.empty() && mesh.tangents.size() != nv)
      throw std::runtime_error("path tracer: mesh '" + mesh.name + "' has " +
                               std::to_string(mesh.tangents.size()) + " tangents for " +
                               std::to_string(nv) + " vertices");
    m.tangents = mesh.tangents;
    bool masked = false;
    for (uint32_t material : mesh.materials) masked = masked || masks_.masked(material);
    if (!mesh.triangles.empty()) {
      m.bvh = rtcNewScene(device_);
      rtcSetSceneBuildQuality(m.bvh, RTC_BUILD_QUALITY_HIGH);
      RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                 m.positions.data(), 0, 4 * sizeof(float), nv);
      rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.indices.data(),
                                 0, 3 * sizeof(uint32_t), mesh.triangles.size());
      rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
      if (masked) {
        // Cut-outs: every ray (camera, gathers, shadows) passes through a hole. The meshes_
        // element is the user data: its address is reserved below, so it does not move.
        rtcSetGeometryUserData(g, meshes_.data() + meshes_.size());
        rtcSetGeometryIntersectFilterFunction(g, &TraceAssets::alpha_filter);
        rtcSetGeometryOccludedFilterFunction(g, &TraceAssets::alpha_filter);
      }
      rtcCommitGeometry(g);
      rtcAttachGeometryByID(m.bvh, g, 0);
      rtcReleaseGeometry(g);
      rtcCommitScene(m.bvh);
    }
    meshes_.push_back(std::move(m));  // the vectors' buffers move with it (Embree keeps pointers)
    check(("building the BVH of mesh '" + mesh.name + "'").c_str());
  }
}

glm::vec2 TraceMesh::uv_at(uint32_t prim, float b1, float b2) const {
  const uint32_t i0 = indices[3 * prim], i1 = indices[3 * prim + 1], i2 = indices[3 * prim + 2];
  return (1.0f - b1 - b2) * uvs[i0] + b1 * uvs[i1] + b2 * uvs[i2];
}

void TraceAssets::alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* mesh = static_cast<const TraceMesh*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
    const glm::vec2 uv =
        mesh->uv_at(prim, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i));
    if (!mesh->owner->masks().solid(mesh->materials[prim], uv)) args->valid[i] = 0;
  }
}

TraceAssets::~TraceAssets() {
  for (TraceMesh& m : meshes_)
    if (m.bvh) rtcReleaseScene(m.bvh);
  if (device_) rtcReleaseDevice(device_);
}

void TraceAssets::check(const char* what) const {
  const RTCError code = rtcGetDeviceError(device_);
  if (code != RTC_ERROR_NONE)
    throw std::runtime_error(std::string("path tracer: Embree failed ") + what + " (error " +
                             std::to_string(int(code)) + ")");
}

TraceScene::TraceScene(const TraceAssets& assets, const scene::FrameScene& frame)
    : assets_(&assets), frame_(&frame) {
  for (size_t i = 0; i < frame.instances.size(); ++i) {
    if (frame.instances[i].mesh >= assets.meshes().size())
      throw std::runtime_error("path tracer: instance " + std::to_string(i) +
                               " refers to a mesh that does not exist");
    normal_matrices_.push_back(glm::transpose(glm::inverse(frame.instances[i].model)));
  }
  scene_ = rtcNewScene(assets.device());
  shadow_scene_ = rtcNewScene(assets.device());
  add_instances(scene_, Casters::kAll);
  add_instances(shadow_scene_, Casters::kLamp);
  if (std::any_of(frame.instances.begin(), frame.instances.end(),
                  [](const scene::MeshInstance& i) {
                    return i.casts_light_shadow && !i.casts_shadow;
                  })) {
    light_shadow_scene_ = rtcNewScene(assets.device());
    add_instances(light_shadow_scene_, Casters::kLight);
  }

  // Spheres: every one with a radius in the scene, the casters also in the shadow scene. The
  // geometry id after the instances' ids (instance i has id i).
  sphere_geometry_ = unsigned(frame.instances.size());
  std::vector<uint32_t> all;
  for (size_t i = 0; i < frame.spheres.size(); ++i) {
    const scene::Sphere& s = frame.spheres[i];
    if (!(s.radius > 0.0f)) continue;  // never drawn (the rasterizer's rule)
    all.push_back(uint32_t(i));
    if (s.casts_shadow) caster_spheres_.push_back(uint32_t(i));
  }
  auto add_spheres = [&](RTCScene top, const std::vector<uint32_t>& which,
                         std::vector<float>& points) {
    if (which.empty()) return;
    points.clear();
    for (uint32_t i : which) {
      const scene::Sphere& s = frame.spheres[i];
      points.insert(points.end(), {s.center.x, s.center.y, s.center.z, s.radius});
    }
    points.insert(points.end(), 4, 0.0f);
    RTCGeometry g = rtcNewGeometry(assets.device(), RTC_GEOMETRY_TYPE_SPHERE_POINT);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, points.data(), 0,
                               4 * sizeof(float), which.size());
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(top, g, sphere_geometry_);
    rtcReleaseGeometry(g);
  };
  // Index within `all` = Embree primID in scene_: keep the map for hits.
  sphere_index_ = all;
  add_spheres(scene_, all, sphere_points_);
  add_spheres(shadow_scene_, caster_spheres_, caster_points_);
  if (light_shadow_scene_) add_spheres(light_shadow_scene_, caster_spheres_, caster_points_);
  rtcCommitScene(scene_);
  rtcCommitScene(shadow_scene_);
  if (light_shadow_scene_) rtcCommitScene(light_shadow_scene_);
  assets.check("building the frame's scene");
}

TraceScene::~TraceScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (shadow_scene_) rtcReleaseScene(shadow_scene_);
  if (light_shadow_scene_) rtcReleaseScene(light_shadow_scene_);
}

void TraceScene::add_instances(RTCScene top, Casters which) {
  for (size_t i = 0; i < frame_->instances.size(); ++i) {
    const scene::MeshInstance& inst = frame_->instances[i];
    const TraceMesh& mesh = assets_->meshes()[inst.mesh];
    const bool in = which == Casters::kAll ||
                    (which == Casters::kLamp && inst.casts_shadow) ||
                    (which == Casters::kLight && (inst.casts_shadow || inst.casts_light_shadow));
    if (mesh.bvh == nullptr || !in) continue;
    RTCGeometry g = rtcNewGeometry(assets_->device(), RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, mesh.bvh);
    rtcSetGeometryTimeStepCount(g, 1);
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &inst.model[0][0]);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(top, g, unsigned(i));
    rtcReleaseGeometry(g);
  }
}

bool TraceScene::back_of_single_sided(const RTCRayHit& rh) const {
  if (rh.hit.instID[0] == kInvalid) return false;  // a sphere
  const scene::MeshInstance& inst = frame_->instances[rh.hit.instID[0]];
  const TraceMesh& m = assets_->meshes()[inst.mesh];
  const uint32_t prim = rh.hit.primID;
  if (assets_->materials()[m.materials[prim]].double_sided) return false;
  // Counter-clockwise in the object's space is the front: the winding's normal through the
  // normal matrix (which keeps that side for mirroring models too) against the ray.
  auto pos = [&](uint32_t k) {
    return glm::vec3(m.positions[4 * k], m.positions[4 * k + 1], m.positions[4 * k + 2]);
  };
  const glm::vec3 p0 = pos(m.indices[3 * prim]), p1 = pos(m.indices[3 * prim + 1]),
                  p2 = pos(m.indices[3 * prim + 2]);
  const glm::vec3 front = glm::mat3(normal_matrices_[rh.hit.instID[0]]) *
                          glm::cross(p1 - p0, p2 - p0);
  return glm::dot(front, glm::vec3(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z)) > 0.0f;
}

bool TraceScene::intersect(glm::vec3 org, glm::vec3 dir, float t_max, Surface& out,
                           Viewer viewer) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  float t_near = 0.0f;
  // The camera passes through back faces of single-sided materials (the rasterizer culls
  // them): past such a hit the ray goes on from just beyond it. Bounded, for a ray that
  // grazes a stack of coplanar faces.
  for (int pass = 0;; ++pass) {
    rh.ray = make_ray(org, dir, t_max);
    rh.ray.tnear = t_near;
    rh.hit.geomID = kInvalid;
    rh.hit.instID[0] = kInvalid;
    rtcIntersect1(scene_, &context, &rh);
    if (rh.hit.geomID == kInvalid) return false;
    if (viewer != Viewer::kCamera || pass == 64 || !back_of_single_sided(rh)) break;
    t_near = std::nextafter(rh.ray.tfar, t_max);
  }
  const float t = rh.ray.tfar;

  if (rh.hit.instID[0] != kInvalid) {
    const uint32_t i = rh.hit.instID[0];
    const scene::MeshInstance& inst = frame_->instances[i];
    const TraceMesh& m = assets_->meshes()[inst.mesh];
    const uint32_t prim = rh.hit.primID;
    const uint32_t i0 = m.indices[3 * prim], i1 = m.indices[3 * prim + 1],
                   i2 = m.indices[3 * prim + 2];
    const float b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1.0f - b1 - b2;
    auto pos = [&](uint32_t k) {
      return glm::vec3(m.positions[4 * k], m.positions[4 * k + 1], m.positions[4 * k + 2]);
    };
    const glm::mat3 nm(normal_matrices_[i]);
    const glm::vec3 p0 = pos(i0);
    out.ng = glm::normalize(nm * glm::cross(pos(i1) - p0, pos(i2) - p0));
    out.ns = glm::normalize(nm * (b0 * m.normals[i0] + b1 * m.normals[i1] + b2 * m.normals[i2]));
    const scene::Material& mat = assets_->materials()[m.materials[prim]];
    const glm::vec2 uv = b0 * m.uvs[i0] + b1 * m.uvs[i1] + b2 * m.uvs[i2];
    const auto& textures = assets_->textures();
    out.albedo = mat.albedo;
    if (mat.texture >= 0) out.albedo *= textures[size_t(mat.texture)].sample(uv);
    out.emission = mat.emission;
    if (mat.emission_texture >= 0)
      out.emission *= textures[size_t(mat.emission_texture)].sample(uv);
    out.specular = mat.specular;
    if (mat.metallic_roughness_texture >= 0) {
      // glTF: G scales the roughness, B the metallic factor; a texel is a metal at >= 0.5
      const glm::vec3 mr = textures[size_t(mat.metallic_roughness_texture)].sample(uv);
      out.specular.roughness = mat.specular.roughness * mr.y;
      out.specular.metal = mat.metallic * mr.z >= 0.5f;
    }
    if (mat.normal_texture >= 0 && !m.tangents.empty()) {
      // Tangent space (frame_scene.h Mesh::tangents): the tangent follows the model matrix,
      // the bitangent is w * cross(n, t) after orthogonalising t against the shading normal.
      const glm::vec4 t4 = b0 * m.tangents[i0] + b1 * m.tangents[i1] + b2 * m.tangents[i2];
      glm::vec3 tangent = glm::mat3(inst.model) * glm::vec3(t4);
      tangent -= out.ns * glm::dot(out.ns, tangent);
      const float len = glm::length(tangent);
      if (len > 1.0e-12f) {
        tangent /= len;
        const glm::vec3 b = (t4.w < 0.0f ? -1.0f : 1.0f) * glm::cross(out.ns, tangent);
        const glm::vec3 tex = textures[size_t(mat.normal_texture)].sample(uv) * 2.0f - 1.0f;
        const glm::vec3 n = tangent * (tex.x * mat.normal_scale) + b * (tex.y * mat.normal_scale) +
                            out.ns * tex.z;
        if (glm::dot(n, n) > 1.0e-12f) out.ns = glm::normalize(n);
      }
    }
    out.lights_scene = inst.voxelize;
    out.instance = i;
    out.sphere = 0xFFFFFFFFu;
    out.material = m.materials[prim];
    out.p = org + t * dir;
  } else {
    const uint32_t k = sphere_index_[rh.hit.primID];
    const scene::Sphere& s = frame_->spheres[k];
    glm::vec3 n = org + t * dir - s.center;
    const float len = glm::length(n);
    n = len > 0.0f ? n / len : -dir;
    out.p = s.center + n * s.radius;  // on the surface: offsets along n then leave it
    out.ng = out.ns = n;
    out.albedo = s.albedo;
    out.emission = s.emission;
    out.specular = s.specular;
    out.lights_scene = true;
    out.instance = 0xFFFFFFFFu;
    out.sphere = k;
    out.material = 0xFFFFFFFFu;
  }
  // Face the ray's origin (a ray can only reach a back face through a crack).
  if (glm::dot(out.ng, dir) > 0.0f) out.ng = -out.ng;
  if (glm::dot(out.ns, out.ng) < 0.0f) out.ns = -out.ns;
  return true;
}

namespace {

bool occluded(RTCScene scene, glm::vec3 org, glm::vec3 dir, float t_max) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = make_ray(org, dir, t_max);
  rtcOccluded1(scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf when something was hit
}

}  // namespace

bool TraceScene::shadowed(glm::vec3 org, glm::vec3 dir, float t_max) const {
  return occluded(shadow_scene_, org, dir, t_max);
}

bool TraceScene::light_shadowed(glm::vec3 org, glm::vec3 dir, float t_max) const {
  return occluded(light_shadow_scene_ ? light_shadow_scene_ : shadow_scene_, org, dir, t_max);
}

}  // namespace rp::truth
