/* Struct layouts shared by the host (C++) and the kernels (OpenCL C).
 *
 * Rules (DESIGN.md): only 4-byte scalars and 4-vectors, explicit padding, every struct a multiple
 * of 16 bytes; the host side static_asserts each size (src/render/gpu_types.h).
 * Matrices are column-major like GLM: c[k] is column k, so a glm::mat4 is copied byte for byte.
 *
 * Coordinate conventions
 *   world:   Cornell box spans [-1,1]^3, y up, the open side faces +z (the camera).
 *   NDC:     OpenGL style, x,y,z in [-1,1] after the divide by w.
 *   depth:   the visibility buffer stores z_ndc * 0.5 + 0.5 in [0,1]; cleared to 1.0 (far plane)
 *            and "no hit" is marked by the id RP_ID_NONE, not by depth.
 *   pixels:  (0,0) is the top-left pixel, its centre at (0.5, 0.5); pixel y grows downwards,
 *            so screen y = (1 - y_ndc) * 0.5 * height.
 */
#ifndef ROLYPOLY_SHARED_TYPES_H
#define ROLYPOLY_SHARED_TYPES_H

#ifdef __OPENCL_VERSION__
typedef float4 rp_float4;
typedef uint4 rp_uint4;
typedef uint rp_uint;
typedef int rp_int;
typedef float rp_float;
#else
#include <cstdint>
namespace rp::gpu {
struct alignas(16) rp_float4 { float x, y, z, w; };
struct alignas(16) rp_uint4 { uint32_t x, y, z, w; };
typedef uint32_t rp_uint;
typedef int32_t rp_int;
typedef float rp_float;
#endif

/* Column-major 4x4 matrix (GLM layout). */
typedef struct {
  rp_float4 c[4];
} rp_mat4;

/* Ids in the visibility buffer. instance < RP_ID_SPHERE_BIT: a mesh instance, primitive = the
 * triangle index within its mesh. instance has RP_ID_SPHERE_BIT set: analytic sphere number
 * (instance & ~RP_ID_SPHERE_BIT), primitive = 0. RP_ID_NONE: background. */
#define RP_ID_NONE 0xFFFFFFFFu
#define RP_ID_SPHERE_BIT 0x80000000u

/* Texture index meaning "no texture" in Material.texture. */
#define RP_TEXTURE_NONE 0xFFFFFFFFu

/* A loaded scene's punctual lights (scene/frame_scene.h PunctualLight, in render space) and
 * the shadow views they are seen from. Their shadow maps lie in the ShadowMap's depth buffer
 * after the lamp's two planes: view v has two planes of size^2 floats at `offset` (nearest
 * occluder, z_ndc * 0.5 + 0.5, 1.0 empty; then the farthest), drawn by the same rasterizer.
 * A point light has six views (cube faces +x, -x, +y, -y, +z, -z, 90 degrees), a spot one
 * perspective view along its axis, a directional light one orthographic view over the GI
 * volume. Light units and attenuation: scene/punctual_light.h (common/punctual_light.h). */
#define RP_MAX_PUNCTUAL_LIGHTS 8u
#define RP_MAX_SHADOW_VIEWS 48u
#define RP_LIGHT_DIRECTIONAL 0u
#define RP_LIGHT_POINT 1u
#define RP_LIGHT_SPOT 2u
/* PunctualLightGpu.flags: a sun (an environment's, or a directional light) whose bounces
 * precomputed radiance transfer gathers (src/passes/prt_sky.h): lit directly, not voxelized. */
#define RP_LIGHT_NOT_IN_VOXELS 1u

/* 80 bytes. */
typedef struct {
  rp_float4 position_range; /* xyz position (point, spot), w range (0: none) */
  rp_float4 direction;      /* xyz unit direction the light travels (directional, spot) */
  rp_float4 intensity;      /* rgb: direct radiance = albedo * intensity * cos * attenuation */
  rp_float4 cone;           /* spot: x cos(outer), y 1 / (cos inner - cos outer), 0: hard edge */
  rp_uint type;             /* RP_LIGHT_* */
  rp_uint first_view;       /* its shadow views in FrameConstants.shadow_views */
  rp_uint view_count;       /* 0: no shadow */
  rp_uint flags;            /* RP_LIGHT_NOT_IN_VOXELS: the GI volume leaves its light out */
} PunctualLightGpu;

/* The environment light as the real-time modes see it (scene/environment.h; host:
 * src/render/sky_texture.h): an equirectangular map and its mip chain in one float4 buffer
 * (rgb radiance, w unused), level l of width >> l by height >> l texels (at least 1) at
 * texel level_offset[l], rows top to bottom as in the map. Directions turn into the map's frame
 * by (x, z) -> (c x - s z, s x + c z) with (c, s) = turn.xy (the path tracer's rotation);
 * radiance is texel x turn.z (the strength). levels == 0: no environment (black). */
#define RP_SKY_MAX_LEVELS 12u
/* The diffuse cones' sky table after the chain, at texel cell_offset: for each normal of an
 * RP_SKY_CELL_SIDE^2 octahedral grid in the map's frame (row j, column i: the normal whose
 * octahedral coordinates are (i, j) * 2 / (side - 1) - 1, so the six axes are grid points), 16
 * texels, the map averaged over each diffuse cone's cell of the cosine-weighted hemisphere
 * (src/render/sky_cells.h; kernels/common/sky.h: rp_sky_cells). */
#define RP_SKY_CELL_SIDE 33u
typedef struct {
  rp_float4 turn;  /* x cos, y sin of the turn about +y, z strength, w unused */
  rp_uint width, height, levels;
  rp_uint diffuse_cones; /* 1: diffuse cones (and the bounce grid) add the sky; 0: PRT does */
  rp_uint level_offset[RP_SKY_MAX_LEVELS];
  rp_uint cell_offset;   /* first texel of the diffuse cones' table */
  rp_uint pad0, pad1, pad2;
} SkyGpu;

/* 96 bytes. */
typedef struct {
  rp_mat4 view_proj;        /* render space -> this view's clip space */
  rp_float4 depth;          /* x near, y far, z 1: orthographic (linear z01), 0: perspective;
                               w world size of a texel at clip w = 1 (2 / (size |row 0|)) */
  rp_uint offset;           /* first float of its nearest-occluder plane in the depth buffer */
  rp_uint size;             /* texels per side */
  rp_uint pad0, pad1;
} ShadowViewGpu;

/* Per-frame constants, one copy per frame (uploaded once). */
typedef struct {
  rp_mat4 view_proj;            /* world -> clip, including the sub-pixel jitter (rasterize with it) */
  rp_mat4 inv_view_proj;        /* inverse of view_proj (camera rays for analytic spheres) */
  rp_mat4 view_proj_unjittered; /* world -> clip without jitter (velocity) */
  rp_mat4 prev_view_proj_unjittered; /* the previous frame's, without jitter (velocity) */
  rp_mat4 view;                 /* world -> view space (linear depth = -z_view) */
  rp_mat4 light_view_proj;      /* world -> shadow-map clip space */
  rp_float4 camera_pos;         /* xyz world position, w unused */
  rp_float4 jitter;             /* xy: this frame's jitter in pixels, zw: previous frame's */
  rp_float4 light_pos;          /* xyz lamp centre (the point light), w lamp radius */
  rp_float4 light_intensity;    /* rgb radiant intensity of the point light, w unused */
  rp_float4 clip;               /* x camera near, y camera far, z light near, w light far */
  rp_uint width, height;        /* output size in pixels */
  rp_uint shadow_size;          /* shadow map is shadow_size x shadow_size */
  rp_uint frame_index;          /* frames since start (drives per-frame noise rotation) */
  rp_uint instance_count, sphere_count;
  rp_uint voxel_resolution;     /* voxels per side of level 0 (32, 64 or 128) over [-1,1]^3 */
  rp_uint voxel_levels;         /* mip levels incl. level 0: log2(voxel_resolution) + 1 */
  rp_uint punctual_count;       /* lights in `punctual` (0: the demo) */
  rp_uint shadow_view_count;
  rp_uint pad_punctual0, pad_punctual1;
  PunctualLightGpu punctual[RP_MAX_PUNCTUAL_LIGHTS];
  ShadowViewGpu shadow_views[RP_MAX_SHADOW_VIEWS];
  SkyGpu sky;
} FrameConstants;

/* Instance.casts_shadow bits: drawn into the punctual lights' shadow views (scene::MeshInstance
 * casts_shadow or casts_light_shadow), into the demo lamp's map (casts_shadow). The demo's box
 * has only the first: it hides the sky's sun, but the lamp hangs inside its ceiling. */
#define RP_CASTS_LIGHT_SHADOW 1u
#define RP_CASTS_LAMP_SHADOW 2u

/* One vertex of a mesh in object space. 32 bytes. */
typedef struct {
  rp_float4 position_u; /* xyz position, w texture u */
  rp_float4 normal_v;   /* xyz unit normal, w texture v */
} Vertex;

/* One triangle: x,y,z global vertex indices (into the shared vertex buffer), w material index. */
typedef rp_uint4 Triangle;

/* One placed copy of a mesh. 224 bytes. */
typedef struct {
  rp_mat4 model;         /* object -> world, this frame */
  rp_mat4 prev_model;    /* object -> world, previous frame */
  rp_mat4 normal_matrix; /* inverse transpose of model (upper 3x3 used) */
  rp_uint first_triangle; /* the mesh's first triangle in the shared triangle buffer */
  rp_uint triangle_count;
  rp_uint casts_shadow;  /* RP_CASTS_* bits: the shadow maps it is drawn into */
  rp_uint voxelize;      /* 1: part of the GI voxel volume (0 for the lamp cap: its light
                            already comes from the analytic point light) */
  rp_uint voxel_first_triangle; /* the triangles the voxelizer takes instead: the mesh's proxy */
  rp_uint voxel_triangle_count; /* at this frame's voxel resolution, or the mesh itself */
  rp_uint shadow_first_triangle; /* and those the shadow map draws (the draw list is built on */
  rp_uint shadow_triangle_count; /* the host from these: kernels read the list) */
} Instance;

/* An analytic sphere (marble, fireball, particle). 64 bytes. */
typedef struct {
  rp_float4 center_radius; /* xyz world centre, w radius */
  rp_float4 prev_center;   /* xyz previous frame's centre, w casts_shadow (1.0 or 0.0) */
  rp_float4 albedo;        /* rgb diffuse albedo, w the voxelizer's base weight (1 - E_spec_avg
                              of the coat, 1 without one: shading::voxel_base_weight) */
  rp_float4 emission;      /* rgb emitted radiance, w gloss code (shared/brdf_layout.h) */
} Sphere;

/* Surface material. 80 bytes. */
typedef struct {
  rp_float4 albedo;   /* rgb, multiplied with the texture when there is one; w the voxelizer's
                         base weight (1 - E_spec_avg of the coat, 1 without one:
                         shading::voxel_base_weight) */
  rp_float4 emission; /* rgb emitted radiance, w gloss code (shared/brdf_layout.h) */
  rp_uint texture;    /* base colour: index into TextureInfo, or RP_TEXTURE_NONE */
  /* A file's per-texel maps (scene/frame_scene.h Material), or RP_TEXTURE_NONE; resolved by
   * gbuffer_material (kernels/gbuffer_material.cl) */
  rp_uint normal_texture;             /* tangent-space normal map (linear rgb) */
  rp_uint metallic_roughness_texture; /* G scales the roughness, B the metallic factor */
  rp_uint emission_texture;           /* sRGB, multiplies emission.rgb */
  rp_float4 factors;  /* x normal scale, y roughness factor, z metallic factor, w dielectric f0 */
  /* Alpha masks (scene/frame_scene.h AlphaMode::kMask): x the base colour alpha factor, y the
   * cutoff below which (factor x the base colour texture's alpha) is a hole, 0 for an opaque
   * material (nothing is cut). The rasterizer, the shadow maps and the voxelizer test it
   * (kernels/common/alpha_mask.h). z: 1 for a single-sided material (glTF doubleSided false):
   * the camera does not see its back faces (the rasterizer culls them; the path tracer's and
   * Embree's camera rays pass through them), 0 for a double-sided one; w unused. Shadows,
   * voxels and every other ray see both sides. */
  rp_float4 coverage;
} Material;

/* A material that cuts holes (Material.coverage.y > 0). */
#define RP_MATERIAL_MASKED(m) ((m).coverage.y > 0.0f)
/* A material whose back faces the camera does not see (Material.coverage.z). */
#define RP_MATERIAL_SINGLE_SIDED(m) ((m).coverage.z != 0.0f)

/* gbuffer_resolve's texture filter (render::TextureFilter, --texture-filter). */
#define RP_TEXTURE_FILTER_BILINEAR 0u
#define RP_TEXTURE_FILTER_TRILINEAR 1u
#define RP_TEXTURE_FILTER_ANISOTROPIC 2u

/* Most mip levels of a texture (up to 32768 texels a side). */
#define RP_TEXTURE_MAX_LEVELS 16

/* Where a texture and its mip chain live in the shared RGBA8 texel buffer (one uint per texel,
 * R in the low byte, sRGB-encoded rgb, linear alpha; rows top to bottom, u right, v up so texel
 * row = (1 - v) * height). Level k is max(1, width >> k) x max(1, height >> k) texels at
 * level_offset[k] (absolute texel index; the levels of a texture lie back to back, level 0 at
 * `offset`), k < levels = floor(log2(max(width, height))) + 1; unused entries are 0. Built on
 * the host (src/render/texture_mips.h). 96 bytes. */
typedef struct {
  rp_uint offset; /* first texel of level 0 (= level_offset[0]) */
  rp_uint width, height; /* level 0 */
  rp_uint levels;
  rp_uint level_offset[RP_TEXTURE_MAX_LEVELS];
  rp_uint wrap; /* how u and v outside [0, 1] fold back: RP_WRAP_U(wrap), RP_WRAP_V(wrap) */
  rp_uint unused[3];
} TextureInfo;

/* Texture wrap modes (scene/frame_scene.h TextureWrap, glTF wrapS / wrapT), 2 bits per axis. */
#define RP_WRAP_REPEAT 0u
#define RP_WRAP_CLAMP 1u
#define RP_WRAP_MIRROR 2u
#define RP_WRAP_PACK(u, v) ((u) | ((v) << 2))
#define RP_WRAP_U(w) ((w) & 3u)
#define RP_WRAP_V(w) (((w) >> 2) & 3u)

#ifndef __OPENCL_VERSION__
}  // namespace rp::gpu
#endif

#endif
