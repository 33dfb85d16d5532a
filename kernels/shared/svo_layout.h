/* Layout of the sparse voxel octree (seed 001), shared by host and kernels. The
 * octree stores the SAME values as the dense chain of shared/voxel_layout.h (level 0
 * isotropic, levels >= 1 six directional volumes, x-fastest voxel coordinates, box [-1,1]^3),
 * but only where something is, in 3^3 bricks that a trilinear lookup reads without touching a
 * neighbour node.
 *
 * Resolution R = 2^D voxels per side at level 0 (R = 256 or 512 in the app, any power of two
 * from 2 to 1024 in tests). Levels as in the dense chain: level l has n_l = R >> l voxels per
 * side; the octree holds levels 0 .. D-1 (the dense chain's 1^3 level D is never sampled: the
 * cone tracer's top level is levels - 2 = D - 1).
 *
 * Nodes. A node at depth k (0 = root .. D-1 = leaves) with integer coordinate a (0 <= a <
 * 2^k per axis) stands for the region of level-(l+1) voxel a, l = D-1-k its "brick level":
 * its brick holds the level-l voxels 2a, 2a+1 (its own eight) and 2a+2 (the first voxel of
 * the next region along each axis: the border) per axis, 3^3 samples. A node's 8 children
 * (depth k+1, coordinates 2a + o, o in {0,1}^3) are stored together, child o at
 * child_block + (o.x | o.y << 1 | o.z << 2).
 *   A trilinear sample of level l at grid point u (level-l voxel units, centres at i + 0.5;
 *   taps x0 = floor(u - 0.5) and x0 + 1 per axis, as the dense sampler) reads node
 *   a = x0 >> 1 and its brick samples (x0 - 2a) and (x0 - 2a) + 1: both in the brick.
 *   A node exists (has a brick) iff one of its 27 samples is non-empty, i.e. a fragment lies
 *   in one of those level-l voxels. Own voxels make a node exist (the fragment's owner: "own"
 *   flag), and so does a non-empty own voxel of a neighbour a + e (e in {0,1}^3 \ 0) lying on
 *   that neighbour's low faces along e (the "face" flags, dilation). If a node exists its
 *   parent exists (its 27 samples lie inside the parent's region plus border), so this is an
 *   octree; and where no node exists, the dense volume is empty at all 8 taps: the octree
 *   lookup equals the dense lookup everywhere.
 *
 * One device buffer holds the whole octree ("the volume", passed to the cone tracer in place
 * of the dense chain as `__global const float4* voxels`), in float4 units:
 *   [0 .. RP_SVO_HEADER_FLOAT4S)   header, 32 uints (RP_SVO_HDR_*)
 *   node pool:  at float4 RP_SVO_HEADER_FLOAT4S, node i = 2 uints (8 bytes):
 *       word 0: child block index (first of 8 children; 0 = no children: the root is node 0,
 *               never a child) in bits 0-29 | RP_SVO_NODE_OWN (bit 30: own voxels non-empty)
 *               | RP_SVO_NODE_BRICK (bit 31: the node exists and has a brick)
 *       word 1: the brick's address (RP_SVO_NO_BRICK: none): brick b's address is
 *               b << RP_SVO_BRICK_SHIFT, and sample (i,j,k) of direction d of the brick (i, j, k
 *               in 0..2) is read at address + 27 d + (k*3 + j)*3 + i (rp_svo_sample): the
 *               cone tracer's view, a 3^3 brick per direction, 27 samples, own and border.
 *     nodes of one depth are contiguous, depth by depth: depth 0 is node 0, depth k+1 holds
 *     8 children per existing depth-k node, in the order of their parents (prefix sums).
 *   brick table: at uint header[RP_SVO_HDR_TABLE_OFFSET], RP_SVO_TABLE_WORDS = 4 uints per
 *     brick b (node a): word 0 the first own sample of the node in the sample pool
 *     (RP_SVO_NO_BRICK: it has none); words 1, 2, 3 in bits 0-23 (RP_SVO_LINK_MASK) the brick
 *     index of the face neighbour a + x, a + y, a + z at the same depth (RP_SVO_NO_LINK where
 *     it does not exist); word 1 bits 24-31: the node's own-voxel mask, bit o (o = ox | oy << 1
 *     | oz << 2) set when own voxel 2a + o holds a fragment (its samples are stored).
 *     Sample (i,j,k) of a brick is own sample (i & 1, j & 1, k & 1) of node a + e,
 *     e = (i >> 1, j >> 1, k >> 1) (rp_svo_locate): its borders (an index 2) are its
 *     neighbours' own samples, read through the table instead of stored a second time (the
 *     values of seed 001's border transfer, each stored once). An edge or corner neighbour
 *     a + e is reached by face links, x then y then z (rp_svo_load); where a link is missing
 *     the sample is 0, which is its value: a border sample v = 2(a + e) on the low faces of
 *     a + e along e is non-empty only if a fragment lies in v, and then the dilation (below:
 *     the "face" flags) made every node a + e - e' (e' a subset of e) exist, so every node on
 *     the path exists.
 *   sample pool: the samples of occupied own voxels only (an own voxel without a fragment is
 *     0 in every direction; nodes that exist only for a neighbour's border store none): with
 *     own-voxel mask m (n = popcount m), own voxel o of direction d at
 *     first + d n + popcount(m & ((1 << o) - 1)) (rp_svo_own_slot);
 *       brick level 0 (leaves):  1 direction (isotropic), n samples (at most 40 bytes packed)
 *       brick level >= 1:        6 directions (RP_DIR_* order), 6n samples (at most 240 bytes)
 *     samples of 5 bytes (header[RP_SVO_HDR_SAMPLE_BYTES] = 5): rgb (premultiplied
 *     radiance) as one uint in the shared-exponent format RGB9E5 (9-bit mantissas, 5-bit
 *     exponent, bias 15: values up to 65408, relative precision 2^-9 of the largest channel)
 *     at uint s of the plane starting at float4 header[RP_SVO_HDR_BRICK_OFFSET], and the opacity
 *     as one byte round(255 a) at byte header[RP_SVO_HDR_ALPHA_OFFSET] + s of the buffer; or,
 *     when header[RP_SVO_HDR_SAMPLE_BYTES] is 16 (kernels built with RP_SVO_FLOAT_SAMPLES=1,
 *     the tests' bit-exact comparison with the dense chain), float4 samples at that float4.
 *     (Bricks that stored their 27 samples per direction, borders copied from the
 *     neighbours, took 135 / 810 bytes: 167 MiB of bricks for the 512^3 demo. A table entry
 *     is 16 bytes; a brick's samples 5 bytes per occupied own voxel and direction.)
 *   solid grid (optional; header[RP_SVO_HDR_SOLID_OFFSET] != 0, 16-byte aligned, after the
 *     sample pool): for levels l = header[RP_SVO_HDR_SOLID_LEVEL] .. D-1, back to back, one byte
 *     per level-l cell (x fastest, (R >> l)^3 cells, dense: the grid is small): round(255 x the
 *     fraction of the cell inside a closed object), written per frame by the host
 *     (src/passes/svo_solid.h). Cone samples at those levels take at least
 *     RP_SVO_SOLID_WEIGHT x that opacity (common/svo.h rp_svo_solid_apply): the voxelized
 *     shells are hollow.
 *
 * Fragments (the voxelizer's output at the octree's resolution, kernels/voxelize.cl built
 * with RP_VOXEL_FRAGMENTS): RP_SVO_FRAGMENT_WORDS = 5 uints (20 bytes) per fragment, one
 * per (surface sample, voxel) pair, duplicates allowed:
 *   words 0-2  fixed-point radiance x opacity (r, g, b), as the dense voxelizer adds them
 *              (render/voxel_volume.h's format),
 *   word 3     the "cover" word: the contribution's fixed-point opacity and its facing
 *              coverage words x, y, z (voxel_layout.h), exactly (rp_svo_pack_cover). The
 *              voxelizer adds two kinds: a plane's (triangles) at opacity 1 with each axis's
 *              value (<= RP_VOXEL_FACING_UNIT = 128) in one half, packed 10 bits an axis
 *              (rp_svo_pack_facing: the value, which halves), bit 31 clear, the opacity
 *              implied; and a sphere's at any opacity <= 1 with the same value in both halves
 *              of every axis: bit 31 set, the opacity (<= 2^16: 17 bits) in bits 0-16 and the
 *              value in bits 17-24,
 *   word 4     the level-0 voxel (z * R + y) * R + x.
 * Their order in the list is whatever the atomics made it: nothing depends on it (flags are
 * ORed, sums are integers). (8 words, the facing words unpacked, put the 512^3 demo's list at
 * 59 MiB instead of 44: the difference between fitting the 256 MB budget or not; 6 words, the
 * opacity a word of its own, 10.4 MiB more on the busy scene at 512^3.)
 */
#ifndef ROLYPOLY_SHARED_SVO_LAYOUT_H
#define ROLYPOLY_SHARED_SVO_LAYOUT_H

#define RP_SVO_HEADER_FLOAT4S 8u  /* 32 uints */
#define RP_SVO_HDR_RESOLUTION 0u   /* R */
#define RP_SVO_HDR_DEPTHS 1u       /* D = log2 R: node depths 0 .. D-1 */
#define RP_SVO_HDR_NODES 2u        /* nodes in the pool */
#define RP_SVO_HDR_BRICK_OFFSET 3u /* first float4 of the brick pool */
#define RP_SVO_HDR_SAMPLES 4u      /* samples in the brick pool */
#define RP_SVO_HDR_SAMPLE_BYTES 5u /* 5 (packed RGB9E5 + alpha byte) or 16 (float) */
#define RP_SVO_HDR_FRAGMENTS 6u    /* fragments the pool was built from */
#define RP_SVO_HDR_LEVEL_START 7u  /* 7 .. 7+D: first node of each depth (+ the end) */
#define RP_SVO_HDR_SOLID_OFFSET 28u /* byte offset of the solid grid, 0: none (below) */
#define RP_SVO_HDR_SOLID_LEVEL 29u  /* its first level */
#define RP_SVO_HDR_ALPHA_OFFSET 30u /* byte offset of the opacity plane (packed samples) */
/* The opacity a cone sample takes from a fully solid cell: RP_SVO_SOLID_WEIGHT x the grid's
 * fraction (common/svo.h rp_svo_solid_apply says why it is below 1). */
#define RP_SVO_SOLID_WEIGHT 0.6f
#define RP_SVO_HDR_TABLE_OFFSET 18u /* first uint of the brick table (after LEVEL_START) */
#define RP_SVO_MAX_DEPTHS 10u      /* R <= 1024 (voxel keys: 10 bits per axis) */

#define RP_SVO_NODE_CHILD_MASK 0x3FFFFFFFu
#define RP_SVO_NODE_OWN 0x40000000u
#define RP_SVO_NODE_BRICK 0x80000000u
#define RP_SVO_NO_BRICK 0xFFFFFFFFu

#define RP_SVO_BRICK_SAMPLES 27u  /* one direction, as the cone tracer addresses them */
#define RP_SVO_BRICK_SHIFT 8u     /* brick address = brick index << 8 (27 x 6 = 162 < 256) */
#define RP_SVO_MAX_BRICKS 0xFFFFFEu /* brick indices: below RP_SVO_NO_LINK */
#define RP_SVO_TABLE_WORDS 4u     /* brick table words per brick: own samples, +x, +y, +z */
#define RP_SVO_OWN_SAMPLES 8u     /* own voxels per node */
#define RP_SVO_LINK_MASK 0x00FFFFFFu /* table words 1-3: the face link's bits */
#define RP_SVO_NO_LINK 0x00FFFFFFu   /* no face neighbour */
#define RP_SVO_MASK_SHIFT 24u        /* table word 1: the own-voxel mask's first bit */
#define RP_SVO_FRAGMENT_WORDS 5u
#define RP_SVO_FRAGMENT_COVER 3u  /* word holding the opacity and the facing words */
#define RP_SVO_FRAGMENT_KEY 4u    /* word holding the voxel index */
#define RP_SVO_COVER_SPHERE 0x80000000u

/* Build scratch per node (svo.cl), one uint: bit 0 own voxels non-empty; bit e (1..7, e = ex
 * | ey << 1 | ez << 2) own voxels non-empty on the low faces along e, so node a - e must
 * exist (svo_dilate marks it with RP_SVO_NODE_BRICK in its node word before svo_allocate
 * writes the word). The node exists iff bit 0 or that mark is set. */
#define RP_SVO_FLAG_OWN 1u
#define RP_SVO_FLAG_FACES 0xFEu
#define RP_SVO_FLAG_VOXELS_SHIFT 8u /* bits 8-15: own voxel o holds a fragment (bit 8 + o) */

#ifdef __OPENCL_VERSION__
#define RP_SVO_FN static inline
#define RP_SVO_UINT uint
#else
#include <cstdint>
#define RP_SVO_FN inline
#define RP_SVO_UINT uint32_t
namespace rp::gpu {
#endif

/* Samples of a brick at brick level l (1 direction at level 0, 6 above). */
RP_SVO_FN RP_SVO_UINT rp_svo_brick_size(RP_SVO_UINT level) {
  return level == 0u ? RP_SVO_BRICK_SAMPLES : 6u * RP_SVO_BRICK_SAMPLES;
}

/* Directions stored at brick level l: 1 at level 0, 6 above. */
RP_SVO_FN RP_SVO_UINT rp_svo_directions(RP_SVO_UINT level) { return level == 0u ? 1u : 6u; }

/* Set bits of an 8-bit mask. */
RP_SVO_FN RP_SVO_UINT rp_svo_popcount8(RP_SVO_UINT x) {
  x = x - ((x >> 1) & 0x55u);
  x = (x & 0x33u) + ((x >> 2) & 0x33u);
  return (x + (x >> 4)) & 0x0Fu;
}

/* Index, after a node's first own sample, of own sample `own` (8 d + o: direction d, own voxel
 * o) for own-voxel mask m; RP_SVO_NO_BRICK when voxel o is not stored (it is 0). */
RP_SVO_FN RP_SVO_UINT rp_svo_own_slot(RP_SVO_UINT mask, RP_SVO_UINT own) {
  const RP_SVO_UINT o = own & 7u;
  if (((mask >> o) & 1u) == 0u) return RP_SVO_NO_BRICK;
  return (own >> 3) * rp_svo_popcount8(mask) + rp_svo_popcount8(mask & ((1u << o) - 1u));
}

/* Where sample `slot` (27 d + rp_svo_sample(i, j, k), below 256) of a brick lies: returns the
 * offset e = ex | ey << 1 | ez << 2 of the node holding it (0: the brick's own node, else the
 * neighbour a + e) and sets *own to its index among that node's own samples (8 d + (i & 1) +
 * 2 (j & 1) + 4 (k & 1)). */
RP_SVO_FN RP_SVO_UINT rp_svo_locate(RP_SVO_UINT slot, RP_SVO_UINT* own) {
  const RP_SVO_UINT d = slot / 27u, t = slot - 27u * d;
  const RP_SVO_UINT k = t / 9u, j = (t - 9u * k) / 3u, i = t - 9u * k - 3u * j;
  *own = 8u * d + (i & 1u) + 2u * (j & 1u) + 4u * (k & 1u);
  return (i >> 1) | ((j >> 1) << 1) | ((k >> 1) << 2);
}

/* Sample index of brick coordinate (i, j, k) in 0..2 (one direction). */
RP_SVO_FN RP_SVO_UINT rp_svo_sample(RP_SVO_UINT i, RP_SVO_UINT j, RP_SVO_UINT k) {
  return (k * 3u + j) * 3u + i;
}

/* Facing coverage words (x, y, z; shared/voxel_layout.h) of ONE plane contribution -> fragment
 * word 3 (rp_svo_pack_cover): per axis i bits [10 i, 10 i + 8) the value, bit 10 i + 8 set
 * when the low half (+ facing) gets it, bit 10 i + 9 when the high half does. Exact for what
 * the voxelizer adds (see the header: a value <= 128 per half, both halves only with the same
 * value). */
RP_SVO_FN RP_SVO_UINT rp_svo_pack_facing_axis(RP_SVO_UINT w) {
  const RP_SVO_UINT lo = w & 0xFFFFu, hi = w >> 16;
  const RP_SVO_UINT q = lo > hi ? lo : hi;
  return (q & 255u) | (lo != 0u ? 256u : 0u) | (hi != 0u ? 512u : 0u);
}
RP_SVO_FN RP_SVO_UINT rp_svo_pack_facing(RP_SVO_UINT fx, RP_SVO_UINT fy, RP_SVO_UINT fz) {
  return rp_svo_pack_facing_axis(fx) | (rp_svo_pack_facing_axis(fy) << 10) |
         (rp_svo_pack_facing_axis(fz) << 20);
}
/* The facing word of `axis` (0..2) back from rp_svo_pack_facing's word. */
RP_SVO_FN RP_SVO_UINT rp_svo_unpack_facing(RP_SVO_UINT packed, RP_SVO_UINT axis) {
  const RP_SVO_UINT b = packed >> (10u * axis), q = b & 255u;
  return ((b & 256u) != 0u ? q : 0u) | ((b & 512u) != 0u ? q << 16 : 0u);
}

/* Fragment word 3 from one contribution's fixed-point opacity `a` and facing words: a
 * sphere's (every axis the same value v <= 255 in both halves) as RP_SVO_COVER_SPHERE | a
 * (a < 2^17) | v << 17, else a plane's (opacity 1 implied) as rp_svo_pack_facing. */
RP_SVO_FN RP_SVO_UINT rp_svo_pack_cover(RP_SVO_UINT a, RP_SVO_UINT fx, RP_SVO_UINT fy,
                                        RP_SVO_UINT fz) {
  const RP_SVO_UINT v = fx & 0xFFFFu;
  if (fx == fy && fy == fz && (fx >> 16) == v && v <= 255u)
    return RP_SVO_COVER_SPHERE | (a & 0x1FFFFu) | (v << 17);
  return rp_svo_pack_facing(fx, fy, fz);
}
/* The fixed-point opacity back from word 3 (`one`: the fixed-point 1.0, a plane's). */
RP_SVO_FN RP_SVO_UINT rp_svo_cover_opacity(RP_SVO_UINT cover, RP_SVO_UINT one) {
  return (cover & RP_SVO_COVER_SPHERE) != 0u ? cover & 0x1FFFFu : one;
}
/* The facing word of `axis` (0..2) back from word 3. */
RP_SVO_FN RP_SVO_UINT rp_svo_cover_facing(RP_SVO_UINT cover, RP_SVO_UINT axis) {
  if ((cover & RP_SVO_COVER_SPHERE) == 0u) return rp_svo_unpack_facing(cover, axis);
  const RP_SVO_UINT v = (cover >> 17) & 255u;
  return v | (v << 16);
}

/* log2 of a power of two. */
RP_SVO_FN RP_SVO_UINT rp_svo_log2(RP_SVO_UINT r) {
  RP_SVO_UINT d = 0u;
  while ((r >> d) > 1u) ++d;
  return d;
}

#ifndef __OPENCL_VERSION__
}  // namespace rp::gpu
#endif
#undef RP_SVO_FN
#undef RP_SVO_UINT
#endif
