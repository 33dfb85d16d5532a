/* Struct layouts of the compute rasterizer (kernels/visibility.cl, src/passes/visibility.cpp),
 * shared by the host and the kernels. Same rules as shared/types.h: 4-byte scalars and
 * 4-vectors only, sizes multiples of 16, host static_asserts in src/passes/visibility.cpp. */
#ifndef ROLYPOLY_SHARED_RASTER_TYPES_H
#define ROLYPOLY_SHARED_RASTER_TYPES_H

/* Needs shared/types.h included first (rp_mat4, rp_float4): the kernel include expander and
 * C++ resolve relative paths differently, so this header includes nothing itself. */

#ifndef __OPENCL_VERSION__
namespace rp::gpu {
#endif

/* Pixels per side of a binning tile; the raster kernel runs one work-group per tile. */
#define RP_RASTER_TILE 16

/* One rendered view (the camera, or the lamp for the shadow map), passed by value to the
 * view's kernels (a kernel argument). 160 bytes. */
typedef struct {
  rp_mat4 view_proj;      /* world -> clip */
  rp_mat4 inv_view_proj;  /* clip -> world: rays through pixel centres for analytic spheres */
  rp_uint width, height;  /* view size in pixels */
  rp_uint tiles_x, tiles_y; /* ceil(size / RP_RASTER_TILE) */
  rp_uint triangle_items; /* draw items [0, triangle_items) are triangles ... */
  rp_uint sphere_count;   /* ... items [triangle_items, triangle_items + sphere_count) spheres */
  rp_uint list_capacity;  /* entries in the tile list buffer (a tile whose range goes past it
                             rasterizes every item: kernels/visibility.cl) */
  rp_uint caster_mask;    /* depth-only views: the Instance.casts_shadow bits (RP_CASTS_*) that
                             draw an instance into this view */
} RasterView;

/* A triangle after vertex transform, one per triangle draw item. 64 bytes.
 * v[i] is vertex i in homogeneous pixel space: (x', y', z_clip, w_clip) with
 * x' = (x_clip + w_clip) * width / 2 and y' = (w_clip - y_clip) * height / 2, so the pixel
 * position is (x' / w, y' / w) and z_ndc = z_clip / w. Linear in clip space, so no divide is
 * needed and vertices behind the eye stay valid (homogeneous rasterization). */
typedef struct {
  rp_float4 v[3];
  rp_uint4 info; /* x instance id, y primitive id (triangle index in its mesh), zw unused */
} RasterTriangle;

#ifndef __OPENCL_VERSION__
}  // namespace rp::gpu
#endif

#endif
