#include "render/gpu_scene.h"

#include "shading/brdf_tables.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <glm/gtc/matrix_inverse.hpp>

#include "cl/buffer.h"
#include "cl/error.h"
#include "render/sky_texture.h"
#include "render/texture_mips.h"

namespace rp::render {
namespace {

// A read-only buffer holding `data`; `what` names it in an allocation failure ("the scene's
// 2000000 triangles").
template <typename T>
::cl::Buffer upload(const ::cl::Context& context, ::cl::CommandQueue& queue,
                    const std::vector<T>& data, const std::string& what) {
  return rp::cl::upload_buffer(context, queue, data, what, "a smaller scene needs less");
}

std::string mib(uint64_t bytes) {
  return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

// Texels of `texture`'s mip chain (every level).
uint64_t chain_texels(const scene::Texture& texture) {
  uint64_t texels = 0;
  const uint32_t w = uint32_t(std::max(texture.width, 1));
  const uint32_t h = uint32_t(std::max(texture.height, 1));
  for (uint32_t k = 0; k < mip_level_count(w, h); ++k)
    texels += uint64_t(std::max(1u, w >> k)) * std::max(1u, h >> k);
  return texels;
}

uint32_t gpu_wrap(scene::TextureWrap wrap) {
  switch (wrap) {
    case scene::TextureWrap::kClampToEdge: return RP_WRAP_CLAMP;
    case scene::TextureWrap::kMirroredRepeat: return RP_WRAP_MIRROR;
    case scene::TextureWrap::kRepeat: break;
  }
  return RP_WRAP_REPEAT;
}

// The box around mesh `m`'s bounds placed by `model` (its 8 corners transformed); lo > hi for
// an empty mesh.
std::pair<glm::vec3, glm::vec3> world_box(const MeshRange& m, const glm::mat4& model) {
  if (m.lo.x > m.hi.x) return {glm::vec3(1.0f), glm::vec3(-1.0f)};
  std::pair<glm::vec3, glm::vec3> box{glm::vec3(std::numeric_limits<float>::infinity()),
                                      glm::vec3(-std::numeric_limits<float>::infinity())};
  for (int k = 0; k < 8; ++k) {
    const glm::vec3 corner(k & 1 ? m.hi.x : m.lo.x, k & 2 ? m.hi.y : m.lo.y,
                           k & 4 ? m.hi.z : m.lo.z);
    const glm::vec3 p = glm::vec3(model * glm::vec4(corner, 1.0f));
    box.first = glm::min(box.first, p);
    box.second = glm::max(box.second, p);
  }
  return box;
}

}  // namespace

// On the device every texel of every mip level takes 4 bytes (packed sRGB, one buffer for all
// textures, which the gbuffer and voxelize kernels read directly, decoding per tap). A texture
// too large for that failed only at clCreateBuffer, after 45 s and 12 GiB of host memory spent
// on mip chains, and the renderer's out-of-memory message then named the frame size ("a 16x16
// image"). (Both passes once also kept a linear float4 copy, 16 bytes a
// texel each.)
void check_texture_memory(const std::vector<scene::Texture>& textures, uint64_t max_alloc,
                          uint64_t global) {
  constexpr uint64_t kPacked = 4;  // bytes per texel
  uint64_t texels = 0;
  const scene::Texture* largest = nullptr;
  for (const scene::Texture& t : textures) {
    texels += chain_texels(t);
    if (!largest || chain_texels(t) > chain_texels(*largest)) largest = &t;
  }
  if (!largest) return;
  const uint64_t need = texels * kPacked;
  const bool buffer_too_big = max_alloc > 0 && need > max_alloc;
  if (!buffer_too_big && (global == 0 || need <= global)) return;  // 0: the driver did not say
  std::string message = "the textures need " + mib(need) +
                        " of device memory with their mipmaps (texture '" + largest->name +
                        "' is " + std::to_string(largest->width) + "x" +
                        std::to_string(largest->height) + " texels; " +
                        std::to_string(kPacked) + " bytes per texel), ";
  if (buffer_too_big)
    message += "one buffer of " + mib(need) + ", but the device allows at most " +
               mib(max_alloc) + " per buffer";
  else
    message += "but the device has " + mib(global);
  throw rp::cl::Error(message + "; use smaller textures");
}

float halton(uint32_t index, uint32_t base) {
  // Exact in double for the indices used (< 2^20), one rounding to float at the end.
  double result = 0.0, scale = 1.0;
  while (index > 0) {
    scale /= double(base);
    result += scale * double(index % base);
    index /= base;
  }
  return float(result);
}

glm::vec2 taa_jitter_px(uint32_t frame_index, uint32_t jitter_frames) {
  if (jitter_frames == 0) return glm::vec2(0.0f);
  const uint32_t i = frame_index % jitter_frames + 1;
  return {halton(i, 2) - 0.5f, halton(i, 3) - 0.5f};
}

glm::mat4 jittered_view_proj(const glm::mat4& view_proj, glm::vec2 jitter_px, uint32_t width,
                             uint32_t height) {
  // screen x = (x_ndc + 1) / 2 * width, screen y = (1 - y_ndc) / 2 * height: a shift of
  // (jx, jy) pixels is (2 jx / width, -2 jy / height) in NDC, i.e. that times w in clip space.
  glm::mat4 shift(1.0f);
  shift[3][0] = 2.0f * jitter_px.x / float(width);
  shift[3][1] = -2.0f * jitter_px.y / float(height);
  return shift * view_proj;
}

uint32_t GpuScene::voxel_mesh(uint32_t mesh, uint32_t voxel_resolution) const {
  const MeshRange& m = meshes.at(mesh);
  if (m.proxy < 0 || voxel_resolution > m.proxy_max_voxels) return mesh;
  return static_cast<uint32_t>(m.proxy);
}

uint32_t GpuScene::shadow_mesh(uint32_t mesh, uint32_t shadow_size) const {
  const MeshRange& m = meshes.at(mesh);
  if (m.proxy < 0 || shadow_size > m.proxy_max_shadow_texels) return mesh;
  return static_cast<uint32_t>(m.proxy);
}

GpuScene::GpuScene(const ::cl::Context& context, const ::cl::CommandQueue& queue,
                   const scene::SceneAssets& assets)
    : context_(context), queue_(queue) {
  std::vector<gpu::Vertex> verts;
  std::vector<gpu::rp_float4> tangents_host;  // parallel to verts (zero: no tangent)
  std::vector<gpu::Triangle> tris;
  for (const scene::Mesh& mesh : assets.meshes) {
    if (mesh.materials.size() != mesh.triangles.size())
      throw rp::cl::Error("mesh '" + mesh.name + "': one material per triangle expected");
    if (mesh.proxy >= static_cast<int>(assets.meshes.size()))
      throw rp::cl::Error("mesh '" + mesh.name + "': its proxy " + std::to_string(mesh.proxy) +
                          " does not exist");
    MeshRange range{static_cast<uint32_t>(tris.size()),
                    static_cast<uint32_t>(mesh.triangles.size()), mesh.proxy,
                    mesh.proxy_max_voxels, mesh.proxy_max_shadow_texels};
    uint32_t base = static_cast<uint32_t>(verts.size());
    range.first_vertex = base;
    range.vertex_count = static_cast<uint32_t>(mesh.vertices.size());
    for (const scene::Vertex& v : mesh.vertices) {
      verts.push_back({gpu::to_gpu(v.position, v.uv.x), gpu::to_gpu(v.normal, v.uv.y)});
      range.lo = verts.size() == base + 1u ? v.position : glm::min(range.lo, v.position);
      range.hi = verts.size() == base + 1u ? v.position : glm::max(range.hi, v.position);
    }
    if (!mesh.tangents.empty() && mesh.tangents.size() != mesh.vertices.size())
      throw rp::cl::Error("mesh '" + mesh.name + "': one tangent per vertex expected");
    for (size_t i = 0; i < mesh.vertices.size(); ++i)
      tangents_host.push_back(mesh.tangents.empty() ? gpu::rp_float4{0.0f, 0.0f, 0.0f, 0.0f}
                                                    : gpu::to_gpu(mesh.tangents[i]));
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      const glm::uvec3& tri = mesh.triangles[t];
      if (tri.x >= mesh.vertices.size() || tri.y >= mesh.vertices.size() ||
          tri.z >= mesh.vertices.size() || mesh.materials[t] >= assets.materials.size())
        throw rp::cl::Error("mesh '" + mesh.name + "': triangle " + std::to_string(t) +
                            " refers to a vertex or material that does not exist");
      tris.push_back({base + tri.x, base + tri.y, base + tri.z, mesh.materials[t]});
    }
    meshes.push_back(range);
  }
  vertex_count = static_cast<uint32_t>(verts.size());
  triangle_count = static_cast<uint32_t>(tris.size());

  std::vector<gpu::Material> mats;
  for (const scene::Material& m : assets.materials) {
    gpu::Material g{};
    const float code = shading::gloss_code(m.specular);
    // w: the voxelizer's base weight (shading::voxel_base_weight)
    g.albedo = gpu::to_gpu(m.albedo, shading::voxel_base_weight(code, shading::BrdfTables::get()));
    g.emission = gpu::to_gpu(m.emission, code);  // w: brdf_layout.h
    const auto texture_index = [&](int t) {
      if (t >= static_cast<int>(assets.textures.size()))
        throw rp::cl::Error("material '" + m.name + "' refers to a texture that does not exist");
      return t < 0 ? RP_TEXTURE_NONE : static_cast<uint32_t>(t);
    };
    g.texture = texture_index(m.texture);
    g.normal_texture = texture_index(m.normal_texture);
    g.metallic_roughness_texture = texture_index(m.metallic_roughness_texture);
    g.emission_texture = texture_index(m.emission_texture);
    g.factors = {m.normal_scale, m.specular.roughness, m.metallic, m.specular.f0};
    // A cutoff of 0 cuts nothing (alpha >= 0): opaque materials need no test.
    const bool masked = m.alpha_mode == scene::AlphaMode::kMask && m.alpha_cutoff > 0.0f;
    g.coverage = {m.opacity, masked ? m.alpha_cutoff : 0.0f, m.double_sided ? 0.0f : 1.0f, 0.0f};
    if (masked) has_alpha_masks = true;
    if (g.normal_texture != RP_TEXTURE_NONE || g.metallic_roughness_texture != RP_TEXTURE_NONE ||
        g.emission_texture != RP_TEXTURE_NONE)
      has_material_maps = true;
    mats.push_back(g);
  }

  {  // before the mip chains: they cost seconds and gigabytes for a texture that cannot fit
    const ::cl::Device device = context.getInfo<CL_CONTEXT_DEVICES>().front();
    check_texture_memory(assets.textures, device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>(),
                         device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>());
  }
  std::vector<uint32_t> texel_data;
  std::vector<gpu::TextureInfo> infos;
  const auto mips_start = std::chrono::steady_clock::now();
  for (const scene::Texture& t : assets.textures) {
    // Each texture with its mip chain (render/texture_mips.h), levels back to back.
    MipChain chain;
    try {
      chain = build_mip_chain(t);
    } catch (const std::invalid_argument& e) {
      throw rp::cl::Error(e.what());
    }
    gpu::TextureInfo info{};
    const uint32_t base = static_cast<uint32_t>(texel_data.size());
    info.offset = base;
    info.width = static_cast<uint32_t>(t.width);
    info.height = static_cast<uint32_t>(t.height);
    info.levels = static_cast<uint32_t>(chain.levels.size());
    info.wrap = RP_WRAP_PACK(gpu_wrap(t.wrap_u), gpu_wrap(t.wrap_v));
    for (size_t k = 0; k < chain.levels.size(); ++k)
      info.level_offset[k] = base + chain.levels[k].offset;
    infos.push_back(info);
    texel_data.insert(texel_data.end(), chain.texels.begin(), chain.texels.end());
  }
  mips_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() -
                                                      mips_start)
                .count();

  const auto count = [](size_t n, const char* what) {
    return "the scene's " + std::to_string(n) + " " + what;
  };
  vertices = upload(context, queue_, verts, count(verts.size(), "vertices"));
  // Only scenes with normal, metallic-roughness or emission maps read the tangents (the
  // material pass); the others keep one unused element.
  if (!has_material_maps) tangents_host.assign(1, gpu::rp_float4{0.0f, 0.0f, 0.0f, 0.0f});
  tangents = upload(context, queue_, tangents_host, count(tangents_host.size(), "tangents"));
  triangles = upload(context, queue_, tris, count(tris.size(), "triangles"));
  materials = upload(context, queue_, mats, count(mats.size(), "materials"));
  texels = upload(context, queue_, texel_data,
                  count(infos.size(), "textures") + " with their mipmaps");
  textures = upload(context, queue_, infos, count(infos.size(), "texture records"));
  {  // the surface model's tables (shared/brdf_layout.h), integrated once per process
    const auto& cells = shading::BrdfTables::get().cells();
    std::vector<gpu::rp_float4> table;
    for (const glm::vec4& c : cells) table.push_back(gpu::to_gpu(c));
    brdf_table = upload(context, queue_, table, "the surface model's tables");
  }
  frame = ::cl::Buffer(context, CL_MEM_READ_ONLY, sizeof(gpu::FrameConstants));
  sky = upload(context, queue_, std::vector<gpu::rp_float4>(1, gpu::rp_float4{}), "no sky");
  sky_seen = sky;
}

void GpuScene::update_sky(const scene::Environment& environment) {
  if (environment.enabled() &&
      (environment.gathered_map() != sky_map_ || environment.map != sky_seen_map_)) {
    const SkyTexture texture = build_sky_texture(*environment.gathered_map());
    sky = upload(context_, queue_, texture.texels,
                 "the environment map's " + std::to_string(texture.info.levels) + " levels (" +
                     std::to_string(texture.info.width) + "x" +
                     std::to_string(texture.info.height) + " and halvings)");
    sky_map_ = environment.gathered_map();
    sky_info_ = texture.info;
    sky_seen = sky;
    if (environment.residual) {  // the whole map's level 0 (level_offset[0] is 0)
      const std::vector<gpu::rp_float4> level0 = build_sky_level0(*environment.map);
      sky_seen = upload(context_, queue_, level0,
                        "the environment map with its suns (" +
                            std::to_string(texture.info.width) + "x" +
                            std::to_string(texture.info.height) + ")");
    }
    sky_seen_map_ = environment.map;
  }
  constants.sky = sky_record(sky_info_, environment);
  if (!sky_diffuse_cones_) constants.sky.diffuse_cones = 0;
}

void GpuScene::hash_lights_and_objects(io::Fnv1a& h) const {
  const gpu::FrameConstants& c = constants;
  h.value(c.light_view_proj);
  h.value(c.light_pos);
  h.value(c.light_intensity);
  h.value(c.clip.z);
  h.value(c.clip.w);
  h.value(c.shadow_size);
  h.value(c.punctual_count);
  h.bytes(c.punctual, std::min<size_t>(c.punctual_count, RP_MAX_PUNCTUAL_LIGHTS) *
                          sizeof(c.punctual[0]));
  h.value(c.shadow_view_count);
  h.bytes(c.shadow_views, std::min<size_t>(c.shadow_view_count, RP_MAX_SHADOW_VIEWS) *
                              sizeof(c.shadow_views[0]));
  h.value(uint64_t(host_instances.size()));
  h.bytes(host_instances.data(), host_instances.size() * sizeof(gpu::Instance));
  h.value(uint64_t(host_spheres.size()));
  h.bytes(host_spheres.data(), host_spheres.size() * sizeof(gpu::Sphere));
}

ShadowBounds GpuScene::frame_bounds(const scene::FrameScene& f) const {
  ShadowBounds b;
  for (const scene::MeshInstance& inst : f.instances) {
    if (inst.mesh >= meshes.size()) continue;  // update() reports it
    const auto [lo, hi] = world_box(meshes[inst.mesh], inst.model);
    if (lo.x <= hi.x) b.add(lo, hi);
  }
  for (const scene::Sphere& s : f.spheres) b.add(s.center - s.radius, s.center + s.radius);
  return b;
}

void GpuScene::update(const scene::FrameScene& f, uint32_t width, uint32_t height,
                      uint32_t shadow_size, uint32_t voxel_resolution, uint32_t jitter_frames) {
  float aspect = float(width) / float(height);
  glm::mat4 view = f.camera.view();
  glm::mat4 view_proj = f.camera.projection(aspect) * view;
  glm::mat4 prev_view_proj = f.prev_camera.projection(aspect) * f.prev_camera.view();
  // TAA: only the matrices the rasterizer and the sphere rays use are jittered; velocity is
  // computed with the unjittered pair so it carries motion only.
  const glm::vec2 jitter = taa_jitter_px(f.frame_index, jitter_frames);
  const glm::mat4 view_proj_jittered =
      jitter_frames == 0 ? view_proj : jittered_view_proj(view_proj, jitter, width, height);

  gpu::FrameConstants& c = constants;
  c.view_proj = gpu::to_gpu(view_proj_jittered);
  c.inv_view_proj = gpu::to_gpu(glm::inverse(view_proj_jittered));
  c.view_proj_unjittered = gpu::to_gpu(view_proj);
  c.prev_view_proj_unjittered = gpu::to_gpu(prev_view_proj);
  c.view = gpu::to_gpu(view);
  c.light_view_proj = gpu::to_gpu(f.light.view_proj());
  c.camera_pos = gpu::to_gpu(f.camera.position, 1.0f);
  c.jitter = {jitter.x, jitter.y, last_jitter_px_.x, last_jitter_px_.y};
  last_jitter_px_ = jitter;
  c.light_pos = gpu::to_gpu(f.light.position, f.light.lamp_radius);
  c.light_intensity = gpu::to_gpu(f.light.intensity, 0.0f);
  c.clip = {f.camera.near_plane, f.camera.far_plane, f.light.shadow_near, f.light.shadow_far};
  c.width = width;
  c.height = height;
  c.shadow_size = shadow_size;
  c.frame_index = f.frame_index;
  c.voxel_resolution = voxel_resolution;
  c.voxel_levels = 1;
  while ((voxel_resolution >> c.voxel_levels) > 0) ++c.voxel_levels;  // log2(R) + 1
  // A file scene's lights; their shadow views follow the lamp's two planes.
  punctual = setup_punctual_lights(f.lights, shadow_size, 2 * uint64_t(shadow_size) * shadow_size,
                                   frame_bounds(f));
  for (size_t i = 0; i < punctual.lights.size(); ++i)
    if (!suns_in_voxels_ &&
        (f.lights[i].in_environment || f.lights[i].type == scene::LightType::kDirectional))
      punctual.lights[i].flags |= RP_LIGHT_NOT_IN_VOXELS;
  c.punctual_count = uint32_t(punctual.lights.size());
  c.shadow_view_count = uint32_t(punctual.views.size());
  std::copy(punctual.lights.begin(), punctual.lights.end(), c.punctual);
  std::copy(punctual.views.begin(), punctual.views.end(), c.shadow_views);
  update_sky(f.environment);

  host_instances.clear();
  host_instance_bounds.clear();
  instance_triangle_count = 0;
  voxel_triangle_count = 0;
  for (const scene::MeshInstance& inst : f.instances) {
    if (inst.mesh >= meshes.size())
      throw rp::cl::Error("instance refers to mesh " + std::to_string(inst.mesh) +
                          " which does not exist");
    gpu::Instance g{};
    g.model = gpu::to_gpu(inst.model);
    g.prev_model = gpu::to_gpu(inst.prev_model);
    g.normal_matrix = gpu::to_gpu(glm::inverseTranspose(inst.model));
    g.first_triangle = meshes[inst.mesh].first_triangle;
    g.triangle_count = meshes[inst.mesh].triangle_count;
    g.casts_shadow = (inst.casts_shadow ? RP_CASTS_LAMP_SHADOW : 0u) |
                     (inst.casts_shadow || inst.casts_light_shadow ? RP_CASTS_LIGHT_SHADOW : 0u);
    g.voxelize = inst.voxelize ? 1u : 0u;
    const MeshRange& voxel = meshes[voxel_mesh(inst.mesh, voxel_resolution)];
    g.voxel_first_triangle = voxel.first_triangle;
    g.voxel_triangle_count = voxel.triangle_count;
    const MeshRange& shadow = meshes[shadow_mesh(inst.mesh, shadow_size)];
    g.shadow_first_triangle = shadow.first_triangle;
    g.shadow_triangle_count = shadow.triangle_count;
    host_instances.push_back(g);
    host_instance_bounds.push_back(world_box(meshes[inst.mesh], inst.model));
    instance_triangle_count += g.triangle_count;
    voxel_triangle_count += g.voxel_triangle_count;
  }
  host_spheres.clear();
  for (const scene::Sphere& s : f.spheres) {
    gpu::Sphere g{};
    g.center_radius = gpu::to_gpu(s.center, s.radius);
    g.prev_center = gpu::to_gpu(s.prev_center, s.casts_shadow ? 1.0f : 0.0f);
    const float code = shading::gloss_code(s.specular);
    g.albedo = gpu::to_gpu(s.albedo, shading::voxel_base_weight(code, shading::BrdfTables::get()));
    g.emission = gpu::to_gpu(s.emission, code);
    host_spheres.push_back(g);
  }
  instance_count = static_cast<uint32_t>(host_instances.size());
  sphere_count = static_cast<uint32_t>(host_spheres.size());
  c.instance_count = instance_count;
  c.sphere_count = sphere_count;

  // Buffers only grow (doubling), so steady-state frames allocate nothing.
  auto ensure = [&](::cl::Buffer& buf, size_t& capacity, size_t needed, size_t elem) {
    needed = std::max<size_t>(needed, 1);
    if (capacity >= needed) return;
    capacity = std::max(needed, capacity * 2);
    buf = rp::cl::make_buffer(context_, CL_MEM_READ_ONLY, capacity * elem,
                              "the frame's list of " + std::to_string(needed) +
                                  " instances or spheres");
  };
  ensure(instances, instance_capacity_, host_instances.size(), sizeof(gpu::Instance));
  ensure(spheres, sphere_capacity_, std::max<size_t>(host_spheres.size(), 64), sizeof(gpu::Sphere));

  // Blocking writes: the sources are members that the next update() rewrites and that die with
  // this object, and OpenCL reads a non-blocking write's host memory whenever the command runs
  // (AddressSanitizer caught PoCL reading `constants` after the GpuScene was destroyed).
  queue_.enqueueWriteBuffer(frame, CL_TRUE, 0, sizeof(c), &c);
  if (!host_instances.empty())
    queue_.enqueueWriteBuffer(instances, CL_TRUE, 0,
                              host_instances.size() * sizeof(gpu::Instance), host_instances.data());
  if (!host_spheres.empty())
    queue_.enqueueWriteBuffer(spheres, CL_TRUE, 0, host_spheres.size() * sizeof(gpu::Sphere),
                              host_spheres.data());
}

}  // namespace rp::render
