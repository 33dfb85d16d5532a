/* GBuffer resolve (SPEC 6.1): visibility buffer -> per-pixel surface attributes.
 * Host side: src/passes/gbuffer.cpp.
 *
 * Inputs and outputs are planar, row-major, top row first (src/render/frame_buffers.h):
 *   ids      uint2  (instance, primitive); RP_ID_NONE background, RP_ID_SPHERE_BIT spheres
 *   bary     float2 (b1, b2) perspective-correct, b0 = 1 - b1 - b2
 *   albedo   float4 linear rgb, a = 1 covered / 0 background
 *   normal_depth float4 world unit normal, w linear view depth (-z_view; far plane if background)
 *   position float4 world position, w = 1 covered / 0 background
 *   emission float4 rgb emitted radiance
 *   velocity float2 pixels, this frame minus previous, unjittered, +y down; 0 for background
 *
 * gbuffer_resolve: one work-item per span of RP_SPAN pixels of a row (common/span.h: 8 on
 * CPUs, 1 on GPUs), a 1D range over the spans in row-major order. Neighbouring pixels mostly
 * show the same primitive (a Cornell box wall quad is 45 pixels wide at 720x720), so a span is
 * resolved per distinct (instance, primitive) in it: the
 * primitive's data (instance matrices, vertices, material; or the sphere) is loaded once as
 * scalars and evaluated for all lanes with vector arithmetic, the lanes showing it keep the
 * result. A span showing one primitive costs one evaluation for RP_SPAN pixels. Velocity and
 * depth are computed once per span from the selected positions. Textures are sampled per lane
 * from linear float4 texels (gbuffer_decode_texels; the same values as the RGBA8 sRGB table
 * decode, so filtering is unchanged).
 *
 * Maths per pixel (unchanged from the per-pixel version): mesh: object-space position, normal
 * and uv interpolated with (b0, b1, b2), position through model and prev_model, normal through
 * normal_matrix and normalised, albedo = material albedo * bilinear texture (wrap), emission =
 * material emission. Sphere: the camera ray through the pixel centre (unprojected with the
 * jittered inv_view_proj the rasterizer used) hits the sphere, the discriminant clamped at 0 so
 * a rasterized silhouette pixel whose exact ray just misses takes the closest point; the
 * previous position moves with the centre. Velocity = screen(view_proj_unjittered * p) -
 * screen(prev_view_proj_unjittered * prev_p); depth = -(view * p).z.
 */
#include "shared/types.h"
#include "common/colour.h"
#include "common/span.h"
#include "common/span_texture.h"

/* Linear float4 copy of the RGBA8 sRGB texel buffer (one work-item per texel): rgb through the
 * exact sRGB table, alpha linear (code / 255), as common/colour.h's rp_unpack_rgba8_srgb. */
__kernel void gbuffer_decode_texels(__global const uint* texels, __global float4* linear_out,
                                    uint count) {
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  linear_out[i] = rp_unpack_rgba8_srgb(texels[i]);
}

/* M * (x, y, z, 1), one row: ((c0 x + c1 y) + c2 z) + c3. */
#define GB_ROW_POINT(m, row, x, y, z) \
  (m.c[0].row * (x) + m.c[1].row * (y) + m.c[2].row * (z) + m.c[3].row)
#define GB_ROW_DIR(m, row, x, y, z) (m.c[0].row * (x) + m.c[1].row * (y) + m.c[2].row * (z))

/* Clip coordinates -> pixel coordinates (rp_clip_to_screen), per lane. */
#define GB_SCREEN_X(cx, inv_w, size_x) (((cx) * (inv_w) * 0.5f + 0.5f) * (size_x))
#define GB_SCREEN_Y(cy, inv_w, size_y) ((0.5f - (cy) * (inv_w) * 0.5f) * (size_y))
/* Albedo and emission (float4 rgb) into the span's ar..ab / er..eb lanes selected by `group`. */
#define GB_SELECT_ALBEDO_EMISSION(alb4, emi4, group)         \
  do {                                                       \
    const float4 alb_ = (alb4), emi_ = (emi4);               \
    ar = select(ar, (rp_spanf)(alb_.x), group);              \
    ag = select(ag, (rp_spanf)(alb_.y), group);              \
    ab = select(ab, (rp_spanf)(alb_.z), group);              \
    er = select(er, (rp_spanf)(emi_.x), group);              \
    eg = select(eg, (rp_spanf)(emi_.y), group);              \
    eb = select(eb, (rp_spanf)(emi_.z), group);              \
  } while (0)

__kernel void gbuffer_resolve(__global const FrameConstants* frame,
                              __global const uint* ids,
                              __global const float* bary,
                              __global const Instance* instances,
                              __global const Sphere* spheres,
                              __global const Vertex* vertices,
                              __global const Triangle* triangles,
                              __global const Material* materials,
                              __global const TextureInfo* textures,
                              __global const float4* linear_texels,
                              __global float* out_albedo,
                              __global float* out_normal_depth,
                              __global float* out_position,
                              __global float* out_emission,
                              __global float* out_velocity) {
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
  rp_spanf tu = 0.0f, tv = 0.0f;               /* texture coordinates */
  rp_spani textured = (rp_spani)(0);          /* lanes with a texture: its size and offset */
  rp_spanf tex_w = 1.0f, tex_h = 1.0f;
  rp_spanu tex_offset = (rp_spanu)(0u);
  bool any_texture = false;
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
      px = select(px, GB_ROW_POINT(m, x, obx, oby, obz), group);
      py = select(py, GB_ROW_POINT(m, y, obx, oby, obz), group);
      pz = select(pz, GB_ROW_POINT(m, z, obx, oby, obz), group);
      qx = select(qx, GB_ROW_POINT(pm, x, obx, oby, obz), group);
      qy = select(qy, GB_ROW_POINT(pm, y, obx, oby, obz), group);
      qz = select(qz, GB_ROW_POINT(pm, z, obx, oby, obz), group);
      const rp_spanf wnx = GB_ROW_DIR(nm, x, onx, ony, onz);
      const rp_spanf wny = GB_ROW_DIR(nm, y, onx, ony, onz);
      const rp_spanf wnz = GB_ROW_DIR(nm, z, onx, ony, onz);
      const rp_spanf inv_len = rsqrt(wnx * wnx + wny * wny + wnz * wnz);
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
        textured |= group;
        any_texture = true;
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

  if (any_texture)
    rp_span_texture_linear(linear_texels, textured, tex_w, tex_h, tex_offset, tu, tv, n, &ar,
                           &ag, &ab);

  /* Velocity and linear depth of the covered lanes. */
  const float fw = (float)width, fh = (float)height;
  const rp_mat4 vp = frame->view_proj_unjittered, pvp = frame->prev_view_proj_unjittered;
  const rp_mat4 view = frame->view;
  const rp_spanf inv_w = 1.0f / GB_ROW_POINT(vp, w, px, py, pz);
  const rp_spanf prev_inv_w = 1.0f / GB_ROW_POINT(pvp, w, qx, qy, qz);
  rp_spanf vx = GB_SCREEN_X(GB_ROW_POINT(vp, x, px, py, pz), inv_w, fw) -
                GB_SCREEN_X(GB_ROW_POINT(pvp, x, qx, qy, qz), prev_inv_w, fw);
  rp_spanf vy = GB_SCREEN_Y(GB_ROW_POINT(vp, y, px, py, pz), inv_w, fh) -
                GB_SCREEN_Y(GB_ROW_POINT(pvp, y, qx, qy, qz), prev_inv_w, fh);
  vx = select((rp_spanf)(0.0f), vx, covered);
  vy = select((rp_spanf)(0.0f), vy, covered);
  const rp_spanf depth =
      select((rp_spanf)(frame->clip.y), -GB_ROW_POINT(view, z, px, py, pz), covered);
  const rp_spanf one = select((rp_spanf)(0.0f), (rp_spanf)(1.0f), covered);

  rp_store_span_quads_f(ar, ag, ab, one, out_albedo + 4 * pixel, n);
  rp_store_span_quads_f(nx, ny, nz, depth, out_normal_depth + 4 * pixel, n);
  rp_store_span_quads_f(px, py, pz, one, out_position + 4 * pixel, n);
  rp_store_span_quads_f(er, eg, eb, (rp_spanf)(0.0f), out_emission + 4 * pixel, n);
  rp_store_span_pairs_f(vx, vy, out_velocity + 2 * pixel, n);
}
