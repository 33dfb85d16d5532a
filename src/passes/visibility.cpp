// Host side of the compute rasterizer (kernels/visibility.cl). Per view (camera, lamp):
// clear -> setup (triangles, spheres) -> count -> scan -> bin -> raster, then an asynchronous
// read of the tile-list total that the next frame of the view waits for (long finished by
// then) to grow the list if it overflowed (the raster kernel stays correct on overflow, only
// slower). The view parameters
// go to the kernels by value, so a view writes nothing to the device and never waits for it.
// Device memory is sized by the triangle count, sphere count, view size and list total, and
// only ever grows; host-side state lives in ViewState/Impl members: a steady frame allocates
// nothing of its own.
#include "passes/visibility.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cl/buffer.h"
#include "cl/error.h"
#include "cl/kernel_args.h"
#include "passes/pass_names.h"
#include "render/gpu_types.h"  // before raster_types.h, which builds on its types
#include "kernels/shared/raster_types.h"

namespace rp::passes {
namespace {

static_assert(sizeof(gpu::RasterView) == 160);
static_assert(sizeof(gpu::RasterTriangle) == 64);

constexpr size_t kTile = RP_RASTER_TILE;
constexpr size_t kItemGroup = 64;  // RP_ITEM_GROUP in visibility.cl
constexpr size_t kScanGroup = 128; // RP_SCAN_GROUP in visibility.cl
constexpr size_t kSetupGroup = 16;  // RP_SETUP_GROUP in visibility.cl
constexpr size_t kTilesPerGroup = 4;  // work-group of the one-tile-per-work-item raster layout
constexpr size_t kRasterEdgesBytes = 64;  // RasterEdges (kernels/common/raster.h): 4 x 16 bytes

// Pixels per raster work-item: SIMD-wide spans on CPUs (PoCL vectorizes float16 code, not the
// loop over a tile's triangles): the native float vector width (rp::cl::cpu_span_lanes; 16
// measured faster than 8 on the 2-core AVX-512 EPYC, the two within noise on AVX2), one
// pixel per work-item on GPUs. ROLYPOLY_RASTER_SPAN (1, 4, 8 or 16) overrides the choice
// (tests use it to compare the variants). CPUs with spans of 8 or 16 use the one-tile-per-
// work-item raster layout (kernels/visibility.cl RP_TILE_LAYOUT).
int choose_span(const rp::cl::Context& context) {
  if (const char* env = std::getenv("ROLYPOLY_RASTER_SPAN"); env && *env) {
    std::string s = env;
    if (s == "1" || s == "4" || s == "8" || s == "16") return std::stoi(s);
    throw rp::cl::Error("ROLYPOLY_RASTER_SPAN must be 1, 4, 8 or 16, not '" + s + "'");
  }
  // Mesa's llvmpipe (rusticl, Mesa 22.3) runs the 8-wide tile layout nondeterministically
  // across its threads: whole work-groups' tiles come out as garbage in about half the runs of
  // the demo at 64x64, never with LP_NUM_THREADS=1, while oclgrind --data-races finds nothing
  // in the kernel; spans of 4 and 16 matched PoCL bit for bit in 20 of 20 runs. 16 keeps the
  // tile layout the CPU runs elsewhere.
  if (context.info.is_cpu && context.info.platform_name == "rusticl") return 16;
  if (context.info.is_cpu) return rp::cl::cpu_span_lanes(context.info);
  // One pixel per work-item needs 16x16 work-groups and 28 KiB of local memory (256 RasterItems).
  if (context.info.max_work_group_size < 256 || context.info.local_mem_bytes < 32 * 1024) return 4;
  return 1;
}

glm::mat4 to_glm(const gpu::rp_mat4& m) {
  glm::mat4 out;
  for (int c = 0; c < 4; ++c) out[c] = glm::vec4(m.c[c].x, m.c[c].y, m.c[c].z, m.c[c].w);
  return out;
}

// A buffer of at least `needed` elements of `elem` bytes that only grows (by 1.5x, so a slowly
// growing count does not reallocate every frame). Returns true when it was (re)allocated.
bool ensure(const ::cl::Context& context, ::cl::Buffer& buffer, size_t& capacity, size_t needed,
            size_t elem) {
  needed = std::max<size_t>(needed, 1);
  if (capacity >= needed) return false;
  capacity = std::max(needed, capacity + capacity / 2);
  // Lists that grow with the scene's triangles and the image's tiles.
  buffer = rp::cl::make_buffer(context, CL_MEM_READ_WRITE, capacity * elem,
                               "the rasterizer's triangle lists (" + std::to_string(needed) +
                                   " entries)");
  return true;
}

}  // namespace

// Kernels and scratch memory of one view. Layouts: tris RasterTriangle[triangle items];
// bounds int4[all items] (pixel x0, y0, x1, y1); edges RasterEdges[triangle items] (the
// triangle in the frame of its bounds' first pixel); counts/start/cursor uint[2 * tiles]
// (triangles of tile t at t, spheres at tiles + t); list uint[list_capacity] item indices.
struct ViewState {
  std::string pass;
  bool depth_only = false;
  ::cl::Kernel clear, setup, setup_spheres, count, scan, bin, raster;
  gpu::RasterView params{};
  ::cl::Buffer tris, bounds, edges, counts, start, cursor, list, total;
  ::cl::Buffer unused;  // stands in for the ids / bary planes the depth-only variant lacks
  size_t tris_cap = 0, bounds_cap = 0, edges_cap = 0, tiles_cap = 0, list_cap = 0;
  // The previous frame's list total, read back without blocking; total_event completes it.
  uint32_t total_host = 0;
  ::cl::Event total_event;
  bool total_pending = false;
  // Draw items uint2 (instance, global triangle index), instance-major so the item index
  // orders like (instance id, primitive id). The camera draws every instance's mesh; the
  // shadow map the casters' shadow triangles (Instance.shadow_*: a mesh's proxy where it has
  // one for the map's size). Rebuilt only when those ranges change.
  ::cl::Buffer draw_items;
  size_t draw_cap = 0;
  uint32_t draw_count = 0;
  std::vector<uint32_t> draw_key;  // (first triangle, count) per instance
  std::vector<uint32_t> draw_host;
};

// Whether the box `bounds` (world space; lo > hi: empty) lies wholly outside one plane of
// view_proj's clip volume (-w <= x, y, z <= w), widened by (mx, my) in NDC units across x and
// y: then none of its triangles can cover a pixel centre or the depth range, and the
// rasterizer need not set them up. Conservative: a box straddling the planes' corners is kept.
bool outside_frustum(const glm::mat4& view_proj, const std::pair<glm::vec3, glm::vec3>& bounds,
                     float mx, float my) {
  const auto& [lo, hi] = bounds;
  if (lo.x > hi.x) return true;
  // per plane, whether every corner is beyond it (a small relative margin: rounding)
  bool beyond[6] = {true, true, true, true, true, true};
  for (int k = 0; k < 8; ++k) {
    const glm::vec4 c = view_proj * glm::vec4(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y,
                                             k & 4 ? hi.z : lo.z, 1.0f);
    const float a = std::abs(c.w);
    const float wx = c.w + (1.0e-4f + mx) * a, wy = c.w + (1.0e-4f + my) * a;
    const float wz = c.w + 1.0e-4f * a;
    beyond[0] = beyond[0] && c.x < -wx;
    beyond[1] = beyond[1] && c.x > wx;
    beyond[2] = beyond[2] && c.y < -wy;
    beyond[3] = beyond[3] && c.y > wy;
    beyond[4] = beyond[4] && c.z < -wz;
    beyond[5] = beyond[5] && c.z > wz;
  }
  for (bool b : beyond)
    if (b) return true;
  return false;
}

struct VisibilityPass::Impl {
  const rp::cl::Context* context = nullptr;
  int span = 1;
  bool tile_layout = false;  // raster: one work-item per tile (CPUs), else a group per tile
  ViewState camera, shadow;
  ViewState lights;  // the punctual lights' shadow views, one after the other
  // Sub-buffers of the shadow depth buffer, one per punctual view (offset, size), rebuilt
  // when the buffer or the views change.
  ::cl::Buffer light_maps_of;
  std::vector<std::pair<uint64_t, uint32_t>> light_map_keys;
  std::vector<::cl::Buffer> light_maps;
  // What the light maps were drawn from (views, instances, spheres as bytes): a static scene
  // under fixed lights draws them once.
  std::vector<unsigned char> light_maps_key, light_maps_key_scratch;

  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  // A pending read of a list total writes into its ViewState: let it land first.
  ~Impl() {
    for (ViewState* v : {&camera, &shadow, &lights})
      if (v->total_pending) v->total_event.wait();
  }

  void init_view(ViewState& v, rp::cl::ProgramCache& programs, const std::string& pass,
                 bool depth_only) {
    v.pass = pass;
    v.depth_only = depth_only;
    std::string options = "-DRP_SPAN=" + std::to_string(span);
    if (tile_layout) options += " -DRP_TILE_LAYOUT=1";
    if (depth_only) options += " -DRP_DEPTH_ONLY=1";
    v.clear = programs.kernel("visibility.cl", "visibility_clear", options);
    v.setup = programs.kernel("visibility.cl", "visibility_setup", options);
    v.setup_spheres = programs.kernel("visibility.cl", "visibility_setup_spheres", options);
    v.count = programs.kernel("visibility.cl", "visibility_count", options);
    v.scan = programs.kernel("visibility.cl", "visibility_scan", options);
    v.bin = programs.kernel("visibility.cl", "visibility_bin", options);
    v.raster = programs.kernel("visibility.cl", "visibility_raster", options);
    const ::cl::Context& ctx = context->context;
    v.total = ::cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(uint32_t));
    v.unused = ::cl::Buffer(ctx, CL_MEM_READ_WRITE, 2 * sizeof(uint32_t));
  }

  // The camera view culls the instances outside its frustum: the unjittered one widened by two
  // pixels (the jitter moves it by at most half a pixel), so the draw list changes only when
  // the camera or an object moves, not with the jitter. Depth-only views draw every caster.
  void update_draw_items(ViewState& v, const render::GpuScene& scene, uint32_t width,
                         uint32_t height) {
    const glm::mat4 view_proj = to_glm(scene.constants.view_proj_unjittered);
    const float mx = 4.0f / float(std::max(width, 1u)), my = 4.0f / float(std::max(height, 1u));
    const std::vector<gpu::Instance>& instances = scene.host_instances;
    ensure(context->context, v.draw_items, v.draw_cap, 1, 2 * sizeof(uint32_t));  // never unset
    // the triangles this view draws of instance i (none: a depth-only view's non-caster, an
    // instance outside the camera's frustum)
    auto range = [&](size_t i) -> std::pair<uint32_t, uint32_t> {
      const gpu::Instance& inst = instances[i];
      if (!v.depth_only) {
        if (i < scene.host_instance_bounds.size() &&
            outside_frustum(view_proj, scene.host_instance_bounds[i], mx, my))
          return {0u, 0u};
        return {inst.first_triangle, inst.triangle_count};
      }
      if ((inst.casts_shadow & v.params.caster_mask) == 0u) return {0u, 0u};
      return {inst.shadow_first_triangle, inst.shadow_triangle_count};
    };
    bool same = v.draw_key.size() == 2 * instances.size();
    for (size_t i = 0; same && i < instances.size(); ++i) {
      const auto [first, count] = range(i);
      same = v.draw_key[2 * i] == first && v.draw_key[2 * i + 1] == count;
    }
    if (same) return;
    v.draw_key.clear();
    v.draw_host.clear();
    for (uint32_t i = 0; i < instances.size(); ++i) {
      const auto [first, count] = range(i);
      v.draw_key.push_back(first);
      v.draw_key.push_back(count);
      if (uint64_t(first) + count > scene.triangle_count)
        throw rp::cl::Error("visibility pass: instance " + std::to_string(i) +
                            " refers to triangles beyond the scene's triangle buffer");
      for (uint32_t t = 0; t < count; ++t) {
        v.draw_host.push_back(i);
        v.draw_host.push_back(first + t);
      }
    }
    v.draw_count = static_cast<uint32_t>(v.draw_host.size() / 2);
    ensure(context->context, v.draw_items, v.draw_cap, v.draw_count, 2 * sizeof(uint32_t));
    if (v.draw_count > 0)
      context->queue.enqueueWriteBuffer(v.draw_items, CL_TRUE, 0,
                                        v.draw_host.size() * sizeof(uint32_t),
                                        v.draw_host.data());
  }

  void run_view(rp::cl::Profiler& profiler, ViewState& v, const render::GpuScene& scene,
                const glm::mat4& view_proj, const glm::mat4& inv_view_proj, uint32_t width,
                uint32_t height, const ::cl::Buffer& depth_out, const ::cl::Buffer& ids_out,
                const ::cl::Buffer& bary_out) {
    const ::cl::Context& ctx = context->context;
    ::cl::CommandQueue& queue = profiler.queue();
    update_draw_items(v, scene, width, height);
    const uint32_t tiles_x = static_cast<uint32_t>((width + kTile - 1) / kTile);
    const uint32_t tiles_y = static_cast<uint32_t>((height + kTile - 1) / kTile);
    const uint32_t tiles = tiles_x * tiles_y;
    const uint32_t spheres = scene.sphere_count;
    const uint32_t items = v.draw_count + spheres;

    ensure(ctx, v.tris, v.tris_cap, v.draw_count, sizeof(gpu::RasterTriangle));
    ensure(ctx, v.edges, v.edges_cap, v.draw_count, kRasterEdgesBytes);
    ensure(ctx, v.bounds, v.bounds_cap, items, 4 * sizeof(int32_t));
    if (v.tiles_cap < size_t(2) * tiles) {  // only when the view size grows
      v.tiles_cap = size_t(2) * tiles;
      v.counts = ::cl::Buffer(ctx, CL_MEM_READ_WRITE, v.tiles_cap * sizeof(uint32_t));
      v.start = ::cl::Buffer(ctx, CL_MEM_READ_WRITE, v.tiles_cap * sizeof(uint32_t));
      v.cursor = ::cl::Buffer(ctx, CL_MEM_READ_WRITE, v.tiles_cap * sizeof(uint32_t));
    }
    // First guess for the list: every item in about four tiles. Later frames grow it from
    // the totals read back: the previous frame's (long complete) is checked here.
    ensure(ctx, v.list, v.list_cap, size_t(4) * items + tiles, sizeof(uint32_t));
    if (v.total_pending) {
      v.total_event.wait();
      v.total_pending = false;
      if (v.total_host > v.list_cap)
        ensure(ctx, v.list, v.list_cap, size_t(v.total_host) + v.total_host / 4,
               sizeof(uint32_t));
    }

    gpu::RasterView& p = v.params;
    p.view_proj = gpu::to_gpu(view_proj);
    p.inv_view_proj = gpu::to_gpu(inv_view_proj);
    p.width = width;
    p.height = height;
    p.tiles_x = tiles_x;
    p.tiles_y = tiles_y;
    p.triangle_items = v.draw_count;
    p.sphere_count = spheres;
    p.list_capacity = static_cast<uint32_t>(v.list_cap);

    const uint32_t count_n = 2 * tiles;
    rp::cl::bind_args(v.clear, v.counts, cl_uint(count_n));
    profiler.enqueue(v.pass, v.clear, ::cl::NDRange(rp::cl::round_up(count_n, kItemGroup)),
                     ::cl::NDRange(kItemGroup));

    if (items > 0) {
      if (v.draw_count > 0) {
        rp::cl::bind_args(v.setup, p, v.draw_items, scene.instances, scene.triangles,
                          scene.vertices, scene.materials, v.tris, v.bounds, v.edges);
        const size_t lanes = static_cast<size_t>(span);
        const size_t spans = (v.draw_count + lanes - 1) / lanes;
        profiler.enqueue(v.pass, v.setup, ::cl::NDRange(rp::cl::round_up(spans, kSetupGroup)),
                         ::cl::NDRange(kSetupGroup));
      }
      if (spheres > 0) {
        rp::cl::bind_args(v.setup_spheres, p, scene.spheres, v.bounds);
        profiler.enqueue(v.pass, v.setup_spheres,
                         ::cl::NDRange(rp::cl::round_up(spheres, kItemGroup)),
                         ::cl::NDRange(kItemGroup));
      }
      rp::cl::bind_args(v.count, p, v.bounds, v.edges, v.counts);
      profiler.enqueue(v.pass, v.count, ::cl::NDRange(rp::cl::round_up(items, kItemGroup)),
                       ::cl::NDRange(kItemGroup));
    }

    rp::cl::bind_args(v.scan, v.counts, cl_uint(count_n), v.start, v.cursor, v.total);
    profiler.enqueue(v.pass, v.scan, ::cl::NDRange(kScanGroup), ::cl::NDRange(kScanGroup));

    if (items > 0) {
      rp::cl::bind_args(v.bin, p, v.bounds, v.edges, v.cursor, v.list);
      profiler.enqueue(v.pass, v.bin, ::cl::NDRange(rp::cl::round_up(items, kItemGroup)),
                       ::cl::NDRange(kItemGroup));
    }

    // the last five: what the alpha test of masked materials reads (kernels/common/alpha_mask.h)
    rp::cl::bind_args(v.raster, p, v.tris, v.bounds, scene.spheres, v.start, v.cursor, v.list,
                      depth_out, ids_out, bary_out, scene.triangles, scene.vertices,
                      scene.materials, scene.textures, scene.texels);
    if (tile_layout) {  // CPU layout: one work-item per tile
      profiler.enqueue(v.pass, v.raster,
                       ::cl::NDRange(rp::cl::round_up(tiles, kTilesPerGroup)),
                       ::cl::NDRange(kTilesPerGroup));
    } else {  // one work-group per tile, a work-item per span of a row
      const size_t group_w = kTile / static_cast<size_t>(span);
      profiler.enqueue(v.pass, v.raster, ::cl::NDRange(tiles_x * group_w, tiles_y * kTile),
                       ::cl::NDRange(group_w, kTile));
    }

    // The total for the next frame's list size; nothing waits for it now.
    queue.enqueueReadBuffer(v.total, CL_FALSE, 0, sizeof(uint32_t), &v.total_host, nullptr,
                            &v.total_event);
    profiler.record(v.pass, v.total_event);
    v.total_pending = true;
  }
};

VisibilityPass::VisibilityPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs)
    : impl_(std::make_shared<Impl>()) {
  impl_->context = &context;
  impl_->span = choose_span(context);
  impl_->tile_layout = context.info.is_cpu && impl_->span >= 8;
  impl_->init_view(impl_->camera, programs, pass_name::kVisibility, false);
  impl_->init_view(impl_->shadow, programs, pass_name::kShadowMap, true);
  impl_->init_view(impl_->lights, programs, pass_name::kShadowMapLights, true);
  impl_->shadow.params.caster_mask = RP_CASTS_LAMP_SHADOW;
  impl_->lights.params.caster_mask = RP_CASTS_LIGHT_SHADOW;
}

uint64_t VisibilityPass::tile_list_bytes(uint32_t width, uint32_t height) {
  const uint64_t tiles = uint64_t((width + kTile - 1) / kTile) * ((height + kTile - 1) / kTile);
  return 3 * 2 * tiles * sizeof(uint32_t);
}

uint32_t VisibilityPass::camera_triangles() const { return impl_->camera.draw_count; }

uint64_t VisibilityPass::camera_tile_bytes() const {
  const ViewState& v = impl_->camera;
  return buffer_bytes({&v.counts, &v.start, &v.cursor});
}

uint64_t VisibilityPass::lamp_tile_bytes() const {
  const ViewState& v = impl_->shadow;
  return buffer_bytes({&v.counts, &v.start, &v.cursor});
}

void VisibilityPass::render(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                            render::VisibilityBuffer& out) {
  if (out.width != scene.constants.width || out.height != scene.constants.height)
    throw rp::cl::Error("visibility pass: the visibility buffer is " + std::to_string(out.width) +
                        "x" + std::to_string(out.height) + " but the frame was set up for " +
                        std::to_string(scene.constants.width) + "x" +
                        std::to_string(scene.constants.height));
  if (out.width == 0 || out.height == 0) return;
  impl_->run_view(profiler, impl_->camera, scene, to_glm(scene.constants.view_proj),
                  to_glm(scene.constants.inv_view_proj), out.width, out.height, out.depth, out.ids,
                  out.bary);
}

void VisibilityPass::render_shadow(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                                   render::ShadowMap& out) {
  if (out.size != scene.constants.shadow_size)
    throw rp::cl::Error("shadow map pass: the shadow map is " + std::to_string(out.size) +
                        " texels wide but the frame was set up for " +
                        std::to_string(scene.constants.shadow_size));
  if (out.size == 0) return;
  glm::mat4 light = to_glm(scene.constants.light_view_proj);
  ViewState& v = impl_->shadow;
  impl_->run_view(profiler, v, scene, light, glm::inverse(light), out.size, out.size, out.depth,
                  v.unused, v.unused);
}

void VisibilityPass::render_light_shadows(rp::cl::Profiler& profiler,
                                          const render::GpuScene& scene,
                                          render::ShadowMap& out) {
  const std::vector<gpu::ShadowViewGpu>& views = scene.punctual.views;
  if (views.empty()) return;
  const uint64_t needed = views.back().offset + 2 * uint64_t(views.back().size) * views.back().size;
  out.ensure_floats(impl_->context->context, needed);
  std::vector<std::pair<uint64_t, uint32_t>> keys;
  keys.reserve(views.size());
  for (const gpu::ShadowViewGpu& v : views) keys.emplace_back(v.offset, v.size);
  if (impl_->light_maps_of() != out.depth() || impl_->light_map_keys != keys) {
    impl_->light_maps.clear();
    for (const auto& [offset, size] : keys) {
      const cl_buffer_region region{size_t(offset) * sizeof(float),
                                    2 * size_t(size) * size * sizeof(float)};
      impl_->light_maps.push_back(
          out.depth.createSubBuffer(CL_MEM_READ_WRITE, CL_BUFFER_CREATE_TYPE_REGION, &region));
    }
    impl_->light_maps_of = out.depth;
    impl_->light_map_keys = std::move(keys);
    impl_->light_maps_key.clear();  // new storage: draw every view again
  }
  // Skip the views when nothing they draw or see changed since they were drawn.
  std::vector<unsigned char>& key = impl_->light_maps_key_scratch;
  key.clear();
  const auto append = [&key](const void* data, size_t bytes) {
    const auto* b = static_cast<const unsigned char*>(data);
    key.insert(key.end(), b, b + bytes);
  };
  append(views.data(), views.size() * sizeof(views[0]));
  append(scene.host_instances.data(), scene.host_instances.size() * sizeof(gpu::Instance));
  append(scene.host_spheres.data(), scene.host_spheres.size() * sizeof(gpu::Sphere));
  if (key == impl_->light_maps_key) return;
  std::swap(impl_->light_maps_key, key);
  ViewState& v = impl_->lights;
  for (size_t i = 0; i < views.size(); ++i) {
    const glm::mat4 vp = to_glm(views[i].view_proj);
    impl_->run_view(profiler, v, scene, vp, glm::inverse(vp), views[i].size, views[i].size,
                    impl_->light_maps[i], v.unused, v.unused);
  }
}

}  // namespace rp::passes
