/* The scalar parameters of the kernels that take more than one, as one struct per kernel passed
 * by value (the kernel's last argument), shared by the host (C++) and the kernels: a kernel
 * reads them by name, and the host binds them with rp::cl::bind_args (src/cl/kernel_args.h)
 * in one call with the buffers, so a signature and its host call cannot drift apart.
 * Same rules as shared/types.h: 4-byte scalars only, explicit padding, sizes multiples of 16;
 * the host static_asserts each size (src/render/gpu_types.h). */
#ifndef ROLYPOLY_SHARED_PASS_PARAMS_H
#define ROLYPOLY_SHARED_PASS_PARAMS_H

/* Needs shared/types.h included first (rp_uint, rp_float): the kernel include expander and
 * C++ resolve relative paths differently, so this header includes nothing itself. */

#ifndef __OPENCL_VERSION__
namespace rp::gpu {
#endif

/* The indirect pass's low-resolution planes (common/indirect.h, src/passes/indirect.h):
 * width x height samples, rows `stride` floats apart, planes `plane` floats apart;
 * pixel_scale: the world size of one full-resolution pixel per unit of view depth. 32 bytes. */
typedef struct {
  rp_uint width, height, stride, plane;
  rp_float pixel_scale;
  rp_uint pad0, pad1, pad2;
} LowResPlanes;

/* indirect_trace (kernels/indirect.cl). 48 bytes. */
typedef struct {
  LowResPlanes planes;
  rp_uint voxel_resolution, voxel_levels; /* the GI volume's level-0 side and its levels */
  rp_uint ssr_top;     /* the min-Z pyramid's coarsest level (0: no screen-space reflections) */
  rp_uint ssr_history; /* 1: prev_hdr holds the previous frame's light output */
} IndirectTraceParams;

/* indirect_filter (kernels/indirect.cl). prev_planes: the previous frame's planes
 * (prev_geom, prev_history), of its render size prev_width x prev_height pixels: this frame's
 * unless the render size changed. 96 bytes. */
typedef struct {
  LowResPlanes planes;
  rp_uint history_valid;    /* 0: the previous frame's planes are not read */
  rp_float alpha_min;       /* the history blend's floor */
  rp_uint specular_history; /* 1: the reflections' history is blended (a still camera) */
  rp_uint pad;
  LowResPlanes prev_planes;
  rp_uint prev_width, prev_height;
  rp_uint pad1, pad2;
} IndirectFilterParams;

/* light_shade (kernels/light.cl). 16 bytes. */
typedef struct {
  rp_uint voxel_resolution, voxel_levels;
  rp_uint ssr_history; /* 1: the ssr_* buffers hold the previous frame (0: none is read) */
  rp_uint pad;
} LightShadeParams;

/* One level of ssr_min_z (kernels/ssr.cl): the source level at src_offset floats of src,
 * src_width x src_height, halved into dst at dst_offset, dst_width x dst_height. 32 bytes. */
typedef struct {
  rp_uint src_offset, src_width, src_height;
  rp_uint dst_offset, dst_width, dst_height;
  rp_uint pad0, pad1;
} MinZLevel;

/* The motion blur pass's kernels (kernels/motion_blur.cl): each reads the fields it needs.
 * The image is width x height pixels in tiles_x x tiles_y tiles; shutter the fraction of the
 * frame interval the shutter is open. The fused bloom (fuse_bloom 1; motion_blur_composite
 * always): its level 1 is bloom_width x bloom_height, and out = in * bloom_keep +
 * up(level 1) * bloom_scale. 48 bytes. */
typedef struct {
  rp_uint width, height, tiles_x, tiles_y;
  rp_float shutter;
  rp_uint fuse_bloom, bloom_width, bloom_height;
  rp_float bloom_keep, bloom_scale;
  rp_uint pad0, pad1;
} MotionBlurParams;

/* TAA (kernels/taa.cl taa_resolve) and temporal upsampling (kernels/taa_upsample.cl): the
 * frame is render_width x render_height (for taa_resolve also the output), the output
 * out_width x out_height; jitter in render pixels; out = hist * history_weight + c * (1 -
 * history_weight) with the clip box mean +- gamma * stddev; history_valid 0: the history is
 * not read. taa_resolve only: unjitter (resample the current frame at pixel centres) and
 * x_first (the first column of its grid: its border build runs the last columns). taa_upsample
 * only: blur_half, the motion blur's shutter / 2 (0: no depth/speed plane). 48 bytes. */
typedef struct {
  rp_uint render_width, render_height, out_width, out_height;
  rp_float jitter_x, jitter_y, history_weight, gamma;
  rp_uint history_valid, unjitter, x_first;
  rp_float blur_half;
} TaaParams;

/* One step of the bloom chain (kernels/bloom.cl): from a source of src_width x src_height
 * (the image, or a level) into a destination of dst_width x dst_height. bloom_downsample_first:
 * karis 1 takes the Karis average; bloom_mix: out = in * keep + up(level 1) * scale. 32 bytes. */
typedef struct {
  rp_int src_width, src_height, dst_width, dst_height;
  rp_int karis;
  rp_float keep, scale;
  rp_int pad;
} BloomStep;

/* gbuffer_resolve (kernels/gbuffer.cl): texture_filter RP_TEXTURE_FILTER_* (shared/types.h),
 * lod_bias added to the texture level (log2 texels), stochastic_levels 1: the level between
 * two mips picked per pixel by the frame's noise (TAA integrates it). 16 bytes. */
typedef struct {
  rp_uint texture_filter;
  rp_float lod_bias;
  rp_uint stochastic_levels;
  rp_uint pad;
} GBufferParams;

/* prt_vertex_irradiance (kernels/prt.cl): vertex_count vertices' transfer of `channels`
 * channels (1 or 3) and `coefficients` SH coefficients each (9 or 25); suns 1: subtract the
 * shadowed transfer's light of the suns' coefficients (their first vertex is lit elsewhere);
 * traced_suns > 0: add that many suns' traced bounces instead; glow_scale > 0: add the traced
 * glow times it (the environment's strength / pi). 32 bytes. */
typedef struct {
  rp_uint vertex_count, channels, coefficients, suns;
  rp_uint traced_suns;
  rp_float glow_scale;
  rp_uint pad0, pad1;
} PrtVertexParams;

/* One level of the shadow filter's mip chain (kernels/shadow_filter.cl, layout in
 * shared/shadow_mips.h): from the source level (src_size^2 texels at src_offset; for
 * shadow_filter_first the map itself) into dst_size^2 texels at dst_offset, planes `plane`
 * floats apart. 32 bytes. */
typedef struct {
  rp_uint src_offset, src_size, dst_offset, dst_size;
  rp_uint plane, pad0, pad1, pad2;
} ShadowMipStep;

/* The fast mode's bounce gather (one cone a face) refreshes one face in this many a frame:
 * a quarter, so that the 32^3 grid (common/bounce.h) costs about what 16^3 cells cost at a
 * half (busy demo 720x720: bounce pass about 1 ms). */
#define RP_BOUNCE_FACE_STRIDE 4u

/* bounce_gather (kernels/bounce.cl): the GI volume's level-0 side and levels, the frame
 * index (the cone set's rotation) and the cones gathered per face (1 or 16). 16 bytes. */
typedef struct {
  rp_uint resolution, levels, frame, cones;
} BounceParams;

/* tone_map_output (kernels/tone_map.cl): pixel_count pixels; dither 1 adds the frame's
 * blue-noise dither (frame: its index). 16 bytes. */
typedef struct {
  rp_uint pixel_count, dither, frame, pad;
} ToneMapParams;

/* voxel_mips_build (kernels/voxel_mips.cl): the chain's level-0 side and the level built.
 * 16 bytes. */
typedef struct {
  rp_uint resolution, level, pad0, pad1;
} VoxelMipsParams;

/* debug_view_voxels (kernels/debug_view.cl): the GI volume's level-0 side, the level shown and
 * its direction (0..5: +x, -x, +y, -y, +z, -z; 0 at level 0). 16 bytes. */
typedef struct {
  rp_uint voxel_resolution, level, dir, pad;
} VoxelViewParams;

/* The voxelizer's kernels (kernels/voxelize.cl: voxelize_triangles, _large, _cached,
 * _spheres; each reads the fields it needs). 48 bytes. */
typedef struct {
  rp_uint resolution;     /* the volume's side: the dense level 0, or the octree's */
  rp_uint instance_count; /* the frame's instances */
  rp_uint triangle_total; /* voxel triangles of the frame (the draw items) */
  rp_uint sphere_count;
  rp_uint bounce_cells;   /* the bounce grid's cells per side (0: no bounce light) */
  rp_uint slices;         /* work-items sharing one large triangle (or one sphere) */
  rp_uint record;         /* voxelize_triangles, _large: VX_ACCUMULATE, VX_COUNT, VX_RECORD */
  rp_uint cache_capacity; /* samples the static surface cache holds */
  rp_uint samples;        /* voxelize_cached: the samples in the cache */
  rp_uint refresh_stride, refresh_phase; /* voxelize_cached: the bounce light's refresh */
  rp_uint direct_fresh;   /* voxelize_cached: 1 reuses the samples' stored direct light */
} VoxelizeParams;

/* The octree builder's kernels (kernels/svo.cl; each reads the fields it needs). 96 bytes. */
typedef struct {
  rp_uint first, count;     /* the nodes [first, first + count) of the depth worked on */
  rp_uint depth;            /* that depth (0: the root) */
  rp_uint resolution_log2;  /* log2 of the octree's resolution: its number of depths */
  rp_uint fragment_count;   /* the frame's fragments */
  rp_uint chunk;            /* nodes per work-item of svo_count and svo_allocate */
  rp_uint chunks, slot;     /* svo_scan: the chunk sums and the totals' slot (the depth) */
  rp_uint child_first, brick_first, own_first; /* svo_allocate: where the depth's children,
                                                  bricks and own samples start */
  rp_uint directions;       /* svo_allocate: samples per occupied own voxel */
  rp_uint leaf;             /* svo_allocate: 1 at the last depth (no children) */
  rp_uint descend;          /* svo_flag: 1 descends from the occupancy bits' last depth */
  rp_uint level;            /* svo_occ_mark: the finest occupancy level */
  rp_uint offset;           /* svo_flag_bits: the occupancy level's first word */
  rp_uint src, dst, n;      /* svo_occ_reduce: source and destination level offsets (words),
                               the destination's side */
  rp_uint words;            /* svo_occ_clear: the occupancy words */
  rp_uint table_offset, brick_offset, alpha_offset; /* the pools' offsets (svo_layout.h) */
  rp_uint parent_brick_first; /* svo_leaves: the parents' first brick (RP_SVO_NO_BRICK: none) */
} SvoBuildParams;

#ifndef __OPENCL_VERSION__
}  // namespace rp::gpu
#endif

#endif
