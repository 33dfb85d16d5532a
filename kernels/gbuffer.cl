/* GBuffer resolve (SPEC 6.1): visibility buffer -> per-pixel surface attributes.
 * Host side: src/passes/gbuffer.cpp.
 *
 * Inputs and outputs are planar, row-major, top row first (src/render/frame_buffers.h):
 *   ids      uint2  (instance, primitive); RP_ID_NONE background, RP_ID_SPHERE_BIT spheres
 *   bary     float2 (b1, b2) perspective-correct, b0 = 1 - b1 - b2
 *   albedo   float4 linear rgb, a = 1 covered / 0 background
 *   normal_depth float4 world unit normal, w linear view depth (-z_view; far plane if background)
 *   position float4 world position, w = 1 covered / 0 background
 *   emission float4 rgb emitted radiance, w the surface's gloss code (shared/brdf_layout.h; 0 =
 *            matte), copied from Material.emission.w / Sphere.emission.w
 *   velocity float2 pixels, this frame minus previous, unjittered, +y down; 0 for background
 *
 * gbuffer_resolve: one work-item per span of RP_SPAN pixels of a row (common/span.h: 16 on
 * CPUs, 1 on GPUs), a 1D range over the spans in row-major order. Neighbouring pixels mostly
 * show the same primitive (a Cornell box wall quad is 45 pixels wide at 720x720), so a span is
 * resolved per distinct (instance, primitive) in it: the
 * primitive's data (instance matrices, vertices, material; or the sphere) is loaded once as
 * scalars and evaluated for all lanes with vector arithmetic, the lanes showing it keep the
 * result. A span showing one primitive costs one evaluation for RP_SPAN pixels. Velocity and
 * depth are computed once per span from the selected positions. Textures are sampled per lane
 * from the packed RGBA8 sRGB texels of every mip level, each tap decoded through the exact
 * sRGB table (common/span_texture.h), filtered as `texture_filter` says (shared/types.h
 * RP_TEXTURE_FILTER_*): bilinear in level 0; trilinear or anisotropic from the pixel's
 * analytic footprint ("texture footprint" below).
 *
 * Test variant -DRP_GBUFFER_LOD_OUT (tests/passes/texture_filter_test.cpp): position.w =
 * log2 |dT/dx|, velocity.x = log2 |dT/dy| (T: level-0 texel coordinates, the footprint's two
 * axes), emission.w = the level of detail the filter used (before clamping); 0 where untextured.
 *
 * Maths per pixel (unchanged from the per-pixel version): mesh: object-space position, normal
 * and uv interpolated with (b0, b1, b2), position through model and prev_model, normal through
 * normal_matrix and normalised (and turned to the side the camera sees, as the path tracer
 * does), albedo = material albedo * texture (wrap), emission =
 * material emission. Sphere: the camera ray through the pixel centre (unprojected with the
 * jittered inv_view_proj the rasterizer used) hits the sphere, the discriminant clamped at 0 so
 * a rasterized silhouette pixel whose exact ray just misses takes the closest point; the
 * previous position moves with the centre. Velocity = screen(view_proj_unjittered * p) -
 * screen(prev_view_proj_unjittered * prev_p); depth = -(view * p).z.
 */
#include "shared/types.h"
#include "shared/pass_params.h"
#include "common/colour.h"
#include "common/math.h"
#include "common/span.h"
#include "common/span_texture.h"
#include "common/random.h"


/* Clip coordinates -> pixel coordinates (rp_clip_to_screen), per lane. */
#define GB_SCREEN_X(cx, inv_w, size_x) (((cx) * (inv_w) * 0.5f + 0.5f) * (size_x))
#define GB_SCREEN_Y(cy, inv_w, size_y) ((0.5f - (cy) * (inv_w) * 0.5f) * (size_y))
/* Albedo and emission (float4: rgb, emission.w the gloss code) into the span's ar..ab / er..ew
 * lanes selected by `group`. */
#define GB_SELECT_ALBEDO_EMISSION(alb4, emi4, group)         \
  do {                                                       \
    const float4 alb_ = (alb4), emi_ = (emi4);               \
    ar = select(ar, (rp_spanf)(alb_.x), group);              \
    ag = select(ag, (rp_spanf)(alb_.y), group);              \
    ab = select(ab, (rp_spanf)(alb_.z), group);              \
    er = select(er, (rp_spanf)(emi_.x), group);              \
    eg = select(eg, (rp_spanf)(emi_.y), group);              \
    eb = select(eb, (rp_spanf)(emi_.z), group);              \
    ew = select(ew, (rp_spanf)(emi_.w), group);              \
  } while (0)

/* ---- texture footprint (filtered modes) ----
 *
 * The footprint of a pixel is the texture-coordinate change of one pixel step right and one
 * down, taken analytically from the primitive (no differences between neighbouring pixels,
 * which fail at edges): the ray through the pixel, cam + t d with d = f0 + x fx + y fy linear
 * in the pixel position, meets the triangle's plane n . (p - w0) = 0 at t = n.(w0 - cam) / n.d,
 * so (ray differentials) dp/dx = t (fx - d (n.fx) / (n.d)), likewise for y; texel coordinates
 * are linear on the plane, (u W, v H) = grad . p + const, with the gradients of the
 * barycentrics b1 = ((d11 e1 - d01 e2) . q) / D, b2 = ((d00 e2 - d01 e1) . q) / D (q = p - w0,
 * e1, e2 the world edges, dij = ei . ej, D = d00 d11 - d01^2). The jittered matrix the
 * visibility buffer was made with gives the rays; the jitter moves the pixel centre, not its
 * size, so the footprint stays one pixel. Spheres have no texture (Sphere has no texture
 * field), so only triangles need it. */

/* Camera position, the far-plane point of lane 0's pixel centre minus the camera, and the
 * far-plane steps of one pixel right and down. On the far plane (NDC z = 1) the inverse
 * perspective's w does not depend on x or y (its first two columns have w = 0, jitter
 * included), so the point is linear in the pixel position. */
inline void gb_footprint_rays(__global const FrameConstants* frame, uint x0, uint y,
                              float3* cam, float3* f0, float3* fx, float3* fy) {
  const rp_mat4 inv = frame->inv_view_proj;
  const float w = (float)frame->width, h = (float)frame->height;
  const float ndc_x = ((float)x0 + 0.5f) / w * 2.0f - 1.0f;
  const float ndc_y = 1.0f - ((float)y + 0.5f) / h * 2.0f;
  const float4 far = inv.c[0] * ndc_x + inv.c[1] * ndc_y + inv.c[2] + inv.c[3];
  const float inv_w = 1.0f / far.w;
  *cam = frame->camera_pos.xyz;
  *f0 = far.xyz * inv_w - *cam;
  *fx = inv.c[0].xyz * (2.0f / w * inv_w);
  *fy = inv.c[1].xyz * (-2.0f / h * inv_w);
}

/* Texel-coordinate derivatives per pixel (level-0 texels: u * tw, v * th) of the span's lanes
 * on the triangle (object vertices p0..p2 with u in .w, v0..v2, model matrix m). */
inline void gb_uv_derivatives(rp_mat4 m, float4 p0, float4 p1, float4 p2, float v0, float v1,
                              float v2, float tw, float th, float3 cam, float3 f0, float3 fx,
                              float3 fy, rp_spanf* dudx, rp_spanf* dvdx, rp_spanf* dudy,
                              rp_spanf* dvdy) {
  const float3 w0 = m.c[0].xyz * p0.x + m.c[1].xyz * p0.y + m.c[2].xyz * p0.z + m.c[3].xyz;
  const float3 w1 = m.c[0].xyz * p1.x + m.c[1].xyz * p1.y + m.c[2].xyz * p1.z + m.c[3].xyz;
  const float3 w2 = m.c[0].xyz * p2.x + m.c[1].xyz * p2.y + m.c[2].xyz * p2.z + m.c[3].xyz;
  const float3 e1 = w1 - w0, e2 = w2 - w0, nrm = cross(e1, e2);
  const float d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2);
  const float inv_den = 1.0f / (d00 * d11 - d01 * d01);
  const float3 gb1 = (e1 * d11 - e2 * d01) * inv_den, gb2 = (e2 * d00 - e1 * d01) * inv_den;
  const float3 gu = (gb1 * (p1.w - p0.w) + gb2 * (p2.w - p0.w)) * tw;
  const float3 gv = (gb1 * (v1 - v0) + gb2 * (v2 - v0)) * th;
  const float k = dot(nrm, w0 - cam);
  const float n_fx = dot(nrm, fx), n_fy = dot(nrm, fy);
  const float u_fx = dot(gu, fx), u_fy = dot(gu, fy), v_fx = dot(gv, fx), v_fy = dot(gv, fy);
  const rp_spanf nd = dot(nrm, f0) + RP_LANES * n_fx;  /* n . d per lane */
  const rp_spanf inv_nd = 1.0f / nd; /* one division, not three (a vector division is slow) */
  const rp_spanf t = k * inv_nd;
  const rp_spanf ud = dot(gu, f0) + RP_LANES * u_fx, vd = dot(gv, f0) + RP_LANES * v_fx;
  const rp_spanf sx = n_fx * inv_nd, sy = n_fy * inv_nd;
  *dudx = t * (u_fx - ud * sx);
  *dvdx = t * (v_fx - vd * sx);
  *dudy = t * (u_fy - ud * sy);
  *dvdy = t * (v_fy - vd * sy);
}

/* lod_bias (kernel argument, levels) is added to every filtered level of detail: 0 = the
 * standard rule. The renderer passes -1 while TAA jitters the camera (Renderer::render): TAA
 * then averages frames whose sample points move over the whole pixel, so each frame's texture
 * footprint should be narrower than the pixel or the average blurs twice. Measured against the
 * path tracer's pixel-averaged albedo (360, demo frame, anisotropic, 16 jittered frames
 * averaged): floor 36.7 dB at bias 0, 46.2 dB at -1 (bench --accuracy). */

/* Most taps of the anisotropic filter (the footprint's axis ratio is capped there). */
#ifndef RP_TEXTURE_MAX_ANISO
#define RP_TEXTURE_MAX_ANISO 4
#endif

/* Filtered texture lookup of the textured lanes, multiplied into (r, g, b):
 *   trilinear:   lod = log2(max(|d/dx|, |d/dy|)) in level-0 texels (the larger axis: no
 *                aliasing, blurs along the minor axis when the footprint is stretched);
 *   anisotropic: N taps along the major axis at offsets ((i + 0.5) / N - 0.5) * major, each
 *                trilinear at lod = log2(max(minor, major / N)), averaged; N is the largest
 *                ceil(major / minor) of the span's textured lanes, at most RP_TEXTURE_MAX_ANISO
 *                (one loop for the span: lanes needing fewer taps get overlapping ones). */
inline void gb_texture_filtered(__global const uint* texels,
                                __global const TextureInfo* textures, uint filter, float lod_bias,
                                int stochastic, rp_spanf pick,
                                rp_spani textured, rp_spanu index, rp_spani w0, rp_spani h0,
                                rp_spani levels, rp_spanf u, rp_spanf v, rp_spanf dudx,
                                rp_spanf dvdx, rp_spanf dudy, rp_spanf dvdy, int n, rp_spanf* r,
                                rp_spanf* g, rp_spanf* b, rp_spanf* lod_used) {
  const rp_spanf lx2 = dudx * dudx + dvdx * dvdx, ly2 = dudy * dudy + dvdy * dvdy;
  const rp_spanf major2 = fmax(lx2, ly2);
  rp_spanf cr, cg, cb;
  if (filter != RP_TEXTURE_FILTER_ANISOTROPIC) {
    *lod_used = 0.5f * log2(major2) + lod_bias;
    rp_span_texture_trilinear(texels, textures, textured, index, w0, h0, levels,
                              *lod_used, u, v, n, stochastic, pick, &cr, &cg, &cb);
  } else {
    const rp_spanf minor2 = fmin(lx2, ly2);
    /* ceil(major / minor) capped (a zero minor axis or NaN gives the cap) */
    const rp_spanf want = ceil(fmin(sqrt(major2 / minor2), (float)RP_TEXTURE_MAX_ANISO));
    float lw[RP_SPAN];
    int on[RP_SPAN];
    RP_SPAN_TO_ARRAY(want, lw);
    RP_SPAN_TO_ARRAY(textured, on);
    float taps = 1.0f;
    for (int i = 0; i < n; ++i)
      if (on[i]) taps = fmax(taps, lw[i]);
    const rp_spanf lod =
        0.5f * log2(fmax(minor2, major2 / (taps * taps))) + lod_bias;
    *lod_used = lod;
    /* the major axis in uv units (texel derivatives over the level-0 size) */
    const rp_spani along_y = ly2 > lx2;
    const rp_spanf au = select(dudx, dudy, along_y) / rp_span_convert_float(w0);
    const rp_spanf av = select(dvdx, dvdy, along_y) / rp_span_convert_float(h0);
    cr = cg = cb = 0.0f;
    /* Stochastic (under TAA): half the taps (rounded up), each jittered within its stratum of
     * the major axis per pixel and frame: the same box along the axis in expectation. */
    const int count = stochastic ? (int)ceil(0.5f * taps) : (int)taps;
    const rp_spanf jitter = stochastic ? pick * 16.0f - floor(pick * 16.0f) : (rp_spanf)(0.5f);
    for (int i = 0; i < count; ++i) {
      const rp_spanf o = ((float)i + jitter) / (float)count - 0.5f;
      rp_spanf tr, tg, tb;
      /* each tap its own level pick (golden-ratio steps from the pixel's) */
      const rp_spanf tap_pick = pick + 0.618034f * (float)i;
      rp_span_texture_trilinear(texels, textures, textured, index, w0, h0, levels, lod,
                                u + o * au, v + o * av, n, stochastic,
                                tap_pick - floor(tap_pick), &tr, &tg, &tb);
      cr += tr;
      cg += tg;
      cb += tb;
    }
    const float inv_taps = 1.0f / (float)count;
    cr *= inv_taps;
    cg *= inv_taps;
    cb *= inv_taps;
  }
  *r = select(*r, *r * cr, textured);
  *g = select(*g, *g * cg, textured);
  *b = select(*b, *b * cb, textured);
}

__kernel void gbuffer_resolve(__global const FrameConstants* frame,
                              __global const uint* ids,
                              __global const float* bary,
                              __global const Instance* instances,
                              __global const Sphere* spheres,
                              __global const Vertex* vertices,
                              __global const Triangle* triangles,
                              __global const Material* materials,
                              __global const TextureInfo* textures,
                              __global const uint* texels,
                              __global float* out_albedo,
                              __global float* out_normal_depth,
                              __global float* out_position,
                              __global float* out_emission,
                              __global float* out_velocity, const GBufferParams params) {
  uint texture_filter = params.texture_filter; /* a constant with RP_TEXTURE_FILTER_FIXED */
  const uint stochastic_levels = params.stochastic_levels;
  const float lod_bias = params.lod_bias;
  const uint width = frame->width, height = frame->height;
  /* 1D range over the spans in row-major order, so consecutive work-items read and write
   * consecutive memory. */
  const uint spans_per_row = (width + RP_SPAN - 1) / RP_SPAN;
  const uint gid = (uint)get_global_id(0);
  const uint y = gid / spans_per_row, x0 = (gid - y * spans_per_row) * RP_SPAN;
  if (y >= height) return;
  const int n = (int)min((uint)RP_SPAN, width - x0);
  const uint pixel = y * width + x0;
  const uint instance_count = frame->instance_count, sphere_count = frame->sphere_count;

  rp_spanu id_x, id_y;
  rp_load_span_pairs_u(ids + 2 * pixel, n, &id_x, &id_y);
  rp_spanf b1, b2;
  rp_load_span_pairs_f(bary + 2 * pixel, n, &b1, &b2);
  const rp_spanf b0 = 1.0f - b1 - b2;

  /* Per-lane surface (background until a primitive claims the lane). */
  rp_spanf px = 0.0f, py = 0.0f, pz = 0.0f;    /* world position */
  rp_spanf qx = 0.0f, qy = 0.0f, qz = 0.0f;    /* previous world position */
  rp_spanf nx = 0.0f, ny = 0.0f, nz = 0.0f;    /* world normal */
  rp_spanf ar = 0.0f, ag = 0.0f, ab = 0.0f;    /* albedo before texture */
  rp_spanf er = 0.0f, eg = 0.0f, eb = 0.0f;    /* emission */
  rp_spanf ew = 0.0f;                          /* gloss code (0: matte, background) */
  rp_spanf tu = 0.0f, tv = 0.0f;               /* texture coordinates */
  rp_spani textured = (rp_spani)(0);          /* lanes with a texture: its size and offset */
  rp_spanf tex_w = 1.0f, tex_h = 1.0f;
  rp_spanu tex_offset = (rp_spanu)(0u);
  rp_spanu tex_wrap = (rp_spanu)(RP_WRAP_REPEAT);
  rp_spanu tex_index = (rp_spanu)(0u);         /* TextureInfo of the lane (mip levels) */
  rp_spani tex_levels = (rp_spani)(1);
  /* Texture-coordinate derivatives per pixel step (texels of level 0; "v" texels = v * height):
   * (du/dx, dv/dx), (du/dy, dv/dy), the pixel's footprint (filtered modes only). */
  rp_spanf dudx = 0.0f, dvdx = 0.0f, dudy = 0.0f, dvdy = 0.0f;
  bool any_texture = false;
#ifdef RP_TEXTURE_FILTER_FIXED
  /* The host builds one program per filter (passes/gbuffer.cpp): with the filter a constant the
   * compiler drops the other paths; one kernel holding all three measured 5.0 against 3.0 ms
   * for bilinear at 720 busy (register pressure of the unused footprint state). */
  texture_filter = RP_TEXTURE_FILTER_FIXED;
#endif
  const bool mipmapped = texture_filter != RP_TEXTURE_FILTER_BILINEAR;
  /* Camera rays for the footprint, set up at the span's first textured primitive: the ray
   * through lane i's pixel centre is cam + t (f0 + i fx) (f0: lane 0's point on the far plane
   * minus the camera, fx / fy: the far-plane step of one pixel right / down). */
  bool have_footprint = false;
  float3 cam = (float3)(0.0f), f0 = cam, fx = cam, fy = cam;
  rp_spani covered = (rp_spani)(0);

  /* Camera rays through the lane centres, set up when the span has a sphere. */
  bool have_ray = false;
  rp_spanf ox = 0.0f, oy = 0.0f, oz = 0.0f, dx = 0.0f, dy = 0.0f, dz = 0.0f;

  uint lane_x[RP_SPAN], lane_y[RP_SPAN];
  RP_SPAN_TO_ARRAY(id_x, lane_x);
  RP_SPAN_TO_ARRAY(id_y, lane_y);
  /* Lanes resolved so far (vector and array copy: the array is read per lane). */
  rp_spani done = (rp_spani)(0);
  int lane_done[RP_SPAN];
  RP_SPAN_TO_ARRAY(done, lane_done);

  for (int lane = 0; lane < n; ++lane) {
    if (lane_done[lane]) continue;
    const uint a = lane_x[lane], p = lane_y[lane];
    const rp_spani group = (id_x == a) & (id_y == p);
    done |= group;
    RP_SPAN_TO_ARRAY(done, lane_done);
    if (a < instance_count && p < instances[a].triangle_count) {
      __global const Instance* inst = instances + a;
      const Triangle tri = triangles[inst->first_triangle + p];
      const float4 p0 = vertices[tri.x].position_u, n0 = vertices[tri.x].normal_v;
      const float4 p1 = vertices[tri.y].position_u, n1 = vertices[tri.y].normal_v;
      const float4 p2 = vertices[tri.z].position_u, n2 = vertices[tri.z].normal_v;
      const rp_spanf obx = p0.x * b0 + p1.x * b1 + p2.x * b2;
      const rp_spanf oby = p0.y * b0 + p1.y * b1 + p2.y * b2;
      const rp_spanf obz = p0.z * b0 + p1.z * b1 + p2.z * b2;
      const rp_spanf onx = n0.x * b0 + n1.x * b1 + n2.x * b2;
      const rp_spanf ony = n0.y * b0 + n1.y * b1 + n2.y * b2;
      const rp_spanf onz = n0.z * b0 + n1.z * b1 + n2.z * b2;
      const rp_mat4 m = inst->model, pm = inst->prev_model, nm = inst->normal_matrix;
      px = select(px, RP_MAT4_ROW_POINT(m, x, obx, oby, obz), group);
      py = select(py, RP_MAT4_ROW_POINT(m, y, obx, oby, obz), group);
      pz = select(pz, RP_MAT4_ROW_POINT(m, z, obx, oby, obz), group);
      qx = select(qx, RP_MAT4_ROW_POINT(pm, x, obx, oby, obz), group);
      qy = select(qy, RP_MAT4_ROW_POINT(pm, y, obx, oby, obz), group);
      qz = select(qz, RP_MAT4_ROW_POINT(pm, z, obx, oby, obz), group);
      const rp_spanf wnx = RP_MAT4_ROW_DIR(nm, x, onx, ony, onz);
      const rp_spanf wny = RP_MAT4_ROW_DIR(nm, y, onx, ony, onz);
      const rp_spanf wnz = RP_MAT4_ROW_DIR(nm, z, onx, ony, onz);
      /* Seen from its back (thin double-sided surfaces: leaves, cloth), a surface faces the
       * camera: its geometric normal turned towards the camera, the shading normal into that
       * side (the path tracer's rule, truth/trace_scene.cpp), so lights and cones behind it
       * do not reach the side seen. */
      const float3 go = cross(p1.xyz - p0.xyz, p2.xyz - p0.xyz);
      const float gx = RP_MAT4_ROW_DIR(nm, x, go.x, go.y, go.z);
      const float gy = RP_MAT4_ROW_DIR(nm, y, go.x, go.y, go.z);
      const float gz = RP_MAT4_ROW_DIR(nm, z, go.x, go.y, go.z);
      const float4 eye = frame->camera_pos;
      const rp_spanf towards = gx * (eye.x - RP_MAT4_ROW_POINT(m, x, obx, oby, obz)) +
                               gy * (eye.y - RP_MAT4_ROW_POINT(m, y, obx, oby, obz)) +
                               gz * (eye.z - RP_MAT4_ROW_POINT(m, z, obx, oby, obz));
      const rp_spanf side = select((rp_spanf)(1.0f), (rp_spanf)(-1.0f), towards < 0.0f);
      const rp_spanf shading_side = (wnx * gx + wny * gy + wnz * gz) * side;
      const rp_spanf inv_len = rsqrt(wnx * wnx + wny * wny + wnz * wnz) *
                               select((rp_spanf)(1.0f), (rp_spanf)(-1.0f), shading_side < 0.0f);
      nx = select(nx, wnx * inv_len, group);
      ny = select(ny, wny * inv_len, group);
      nz = select(nz, wnz * inv_len, group);
      __global const Material* mat = materials + tri.w;
      GB_SELECT_ALBEDO_EMISSION(mat->albedo, mat->emission, group);
      const uint texture = mat->texture;
      if (texture != RP_TEXTURE_NONE) {
        __global const TextureInfo* info = textures + texture;
        tu = select(tu, p0.w * b0 + p1.w * b1 + p2.w * b2, group);
        tv = select(tv, n0.w * b0 + n1.w * b1 + n2.w * b2, group);
        tex_w = select(tex_w, (rp_spanf)((float)info->width), group);
        tex_h = select(tex_h, (rp_spanf)((float)info->height), group);
        tex_offset = select(tex_offset, (rp_spanu)(info->offset), group);
        tex_wrap = select(tex_wrap, (rp_spanu)(info->wrap), group);
        tex_index = select(tex_index, (rp_spanu)(texture), group);
        tex_levels = select(tex_levels, (rp_spani)((int)info->levels), group);
        textured |= group;
        any_texture = true;
        if (mipmapped) {
          if (!have_footprint) {
            gb_footprint_rays(frame, x0, y, &cam, &f0, &fx, &fy);
            have_footprint = true;
          }
          rp_spanf ddx_u, ddx_v, ddy_u, ddy_v;
          gb_uv_derivatives(m, p0, p1, p2, n0.w, n1.w, n2.w, (float)info->width,
                            (float)info->height, cam, f0, fx, fy, &ddx_u, &ddx_v, &ddy_u,
                            &ddy_v);
          dudx = select(dudx, ddx_u, group);
          dvdx = select(dvdx, ddx_v, group);
          dudy = select(dudy, ddy_u, group);
          dvdy = select(dvdy, ddy_v, group);
        }
      }
      covered |= group;
    } else if (a != RP_ID_NONE && (a & RP_ID_SPHERE_BIT) != 0u &&
               (a & ~RP_ID_SPHERE_BIT) < sphere_count) {
      if (!have_ray) {
        /* Camera ray through each lane's pixel centre, unprojected with the jittered matrix
         * the rasterizer used, from the near to the far plane. */
        const rp_mat4 inv = frame->inv_view_proj;
        const rp_spanf ndc_x = ((float)x0 + 0.5f + RP_LANES) / (float)width * 2.0f - 1.0f;
        const float ndc_y = 1.0f - ((float)y + 0.5f) / (float)height * 2.0f;
#define GB_UNPROJECT(row, zn) \
  (inv.c[0].row * ndc_x + inv.c[1].row * ndc_y + inv.c[2].row * (zn) + inv.c[3].row)
        const rp_spanf near_w = GB_UNPROJECT(w, -1.0f), far_w = GB_UNPROJECT(w, 1.0f);
        ox = GB_UNPROJECT(x, -1.0f) / near_w;
        oy = GB_UNPROJECT(y, -1.0f) / near_w;
        oz = GB_UNPROJECT(z, -1.0f) / near_w;
        dx = GB_UNPROJECT(x, 1.0f) / far_w - ox;
        dy = GB_UNPROJECT(y, 1.0f) / far_w - oy;
        dz = GB_UNPROJECT(z, 1.0f) / far_w - oz;
#undef GB_UNPROJECT
        const rp_spanf inv_len = rsqrt(dx * dx + dy * dy + dz * dz);
        dx *= inv_len;
        dy *= inv_len;
        dz *= inv_len;
        have_ray = true;
      }
      __global const Sphere* s = spheres + (a & ~RP_ID_SPHERE_BIT);
      const float4 cr = s->center_radius, prev = s->prev_center;
      const rp_spanf cx = ox - cr.x, cy = oy - cr.y, cz = oz - cr.z;
      const rp_spanf bq = cx * dx + cy * dy + cz * dz;
      /* r^2 - squared distance of the centre from the ray: unlike b^2 - (|oc|^2 - r^2) it does
       * not cancel for small spheres far away (particles). */
      const rp_spanf ex = cx - bq * dx, ey = cy - bq * dy, ez = cz - bq * dz;
      const rp_spanf disc = fmax(cr.w * cr.w - (ex * ex + ey * ey + ez * ez), 0.0f);
      const rp_spanf root = sqrt(disc);
      const rp_spanf t_near = -bq - root;
      const rp_spanf t = select(-bq + root, t_near, t_near > 0.0f); /* near plane inside */
      const rp_spanf hx = ox + dx * t, hy = oy + dy * t, hz = oz + dz * t;
      const rp_spanf rx = hx - cr.x, ry = hy - cr.y, rz = hz - cr.z;
      const rp_spanf inv_len = rsqrt(rx * rx + ry * ry + rz * rz);
      px = select(px, hx, group);
      py = select(py, hy, group);
      pz = select(pz, hz, group);
      qx = select(qx, rx + prev.x, group);
      qy = select(qy, ry + prev.y, group);
      qz = select(qz, rz + prev.z, group);
      nx = select(nx, rx * inv_len, group);
      ny = select(ny, ry * inv_len, group);
      nz = select(nz, rz * inv_len, group);
      GB_SELECT_ALBEDO_EMISSION(s->albedo, s->emission, group);
      covered |= group;
    }
  }

  rp_spanf lod_used = 0.0f;
  if (any_texture) {
    if (!mipmapped)
      rp_span_texture_linear(texels, textured, tex_w, tex_h, tex_offset, tex_wrap, tu, tv, n, &ar,
                             &ag, &ab);
    else {
      /* per-lane level picks for stochastic trilinear (pixel and frame hashed) */
      float pk[RP_SPAN] = {0.0f};
      if (stochastic_levels)  /* under TAA only: no hashing otherwise */
        for (int i = 0; i < RP_SPAN; ++i)
          pk[i] = rp_hash_to_unit(rp_hash_pixel(x0 + (uint)i, y, frame->frame_index));
      gb_texture_filtered(texels, textures, texture_filter, lod_bias,
                          (int)stochastic_levels, RP_SPAN_FROM_ARRAY(pk), textured, tex_index,
                          rp_span_convert_int(tex_w), rp_span_convert_int(tex_h), tex_levels,
                          tu, tv, dudx, dvdx, dudy, dvdy, n, &ar, &ag, &ab, &lod_used);
    }
  }


  /* Velocity and linear depth of the covered lanes. */
  const float fw = (float)width, fh = (float)height;
  const rp_mat4 vp = frame->view_proj_unjittered, pvp = frame->prev_view_proj_unjittered;
  const rp_mat4 view = frame->view;
  const rp_spanf inv_w = 1.0f / RP_MAT4_ROW_POINT(vp, w, px, py, pz);
  const rp_spanf prev_inv_w = 1.0f / RP_MAT4_ROW_POINT(pvp, w, qx, qy, qz);
  rp_spanf vx = GB_SCREEN_X(RP_MAT4_ROW_POINT(vp, x, px, py, pz), inv_w, fw) -
                GB_SCREEN_X(RP_MAT4_ROW_POINT(pvp, x, qx, qy, qz), prev_inv_w, fw);
  rp_spanf vy = GB_SCREEN_Y(RP_MAT4_ROW_POINT(vp, y, px, py, pz), inv_w, fh) -
                GB_SCREEN_Y(RP_MAT4_ROW_POINT(pvp, y, qx, qy, qz), prev_inv_w, fh);
  vx = select((rp_spanf)(0.0f), vx, covered);
  vy = select((rp_spanf)(0.0f), vy, covered);
  const rp_spanf depth =
      select((rp_spanf)(frame->clip.y), -RP_MAT4_ROW_POINT(view, z, px, py, pz), covered);
  const rp_spanf one = select((rp_spanf)(0.0f), (rp_spanf)(1.0f), covered);

  rp_store_span_quads_f(ar, ag, ab, one, out_albedo + 4 * pixel, n);
  rp_store_span_quads_f(nx, ny, nz, depth, out_normal_depth + 4 * pixel, n);
#ifdef RP_GBUFFER_LOD_OUT
  const rp_spanf log_x = 0.5f * log2(dudx * dudx + dvdx * dvdx);
  const rp_spanf log_y = 0.5f * log2(dudy * dudy + dvdy * dvdy);
  rp_store_span_quads_f(px, py, pz, select((rp_spanf)(0.0f), log_x, textured),
                        out_position + 4 * pixel, n);
  rp_store_span_quads_f(er, eg, eb, select((rp_spanf)(0.0f), lod_used, textured),
                        out_emission + 4 * pixel, n);
  rp_store_span_pairs_f(select((rp_spanf)(0.0f), log_y, textured), vy, out_velocity + 2 * pixel,
                        n);
#else
  rp_store_span_quads_f(px, py, pz, one, out_position + 4 * pixel, n);
  rp_store_span_quads_f(er, eg, eb, ew, out_emission + 4 * pixel, n);
#endif
#ifndef RP_GBUFFER_LOD_OUT
  rp_store_span_pairs_f(vx, vy, out_velocity + 2 * pixel, n);
#endif
}
