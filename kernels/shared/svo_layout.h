/* Layout of the sparse voxel octree (issue 17, seed 001), shared by host and kernels. The
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
 *       word 1: the brick's first sample in the brick pool (RP_SVO_NO_BRICK: none)
 *     nodes of one depth are contiguous, depth by depth: depth 0 is node 0, depth k+1 holds
 *     8 children per existing depth-k node, in the order of their parents (prefix sums).
 *   brick pool: samples of 5 bytes (header[RP_SVO_HDR_SAMPLE_BYTES] = 5): rgb (premultiplied
 *     radiance) as one uint in the shared-exponent format RGB9E5 (9-bit mantissas, 5-bit
 *     exponent, bias 15: values up to 65408, relative precision 2^-9 of the largest channel)
 *     at uint s of the plane starting at float4 header[RP_SVO_HDR_BRICK_OFFSET], and the opacity
 *     as one byte round(255 a) at byte header[RP_SVO_HDR_ALPHA_OFFSET] + s of the buffer; or,
 *     when header[RP_SVO_HDR_SAMPLE_BYTES] is 16 (kernels built with RP_SVO_FLOAT_SAMPLES=1,
 *     the tests' bit-exact comparison with the dense chain), float4 samples at that float4.
 *     A brick is 27 samples per direction, sample (i,j,k) at (k*3 + j)*3 + i:
 *       brick level 0 (leaves):  1 direction (isotropic), 27 samples (135 bytes packed)
 *       brick level >= 1:        6 directions (RP_DIR_* order), 162 samples (810 bytes),
 *                                direction d's 27 samples at brick + 27 d
 *     (half floats, 8 bytes, would put 512^3 of the demo at 267 MiB of bricks: over the
 *     256 MB budget; 5 bytes: 167 MiB)
 *     samples with an index 2 along some axis are borders: copies of the neighbour node's own
 *     samples (the border transfer, svo.cl), 0 where that neighbour does not exist.
 *   solid grid (optional; header[RP_SVO_HDR_SOLID_OFFSET] != 0, 16-byte aligned, after the
 *     brick pool): for levels l = header[RP_SVO_HDR_SOLID_LEVEL] .. D-1, back to back, one byte
 *     per level-l cell (x fastest, (R >> l)^3 cells, dense: the grid is small): round(255 x the
 *     fraction of the cell inside a closed object), written per frame by the host
 *     (src/passes/svo_solid.h). Cone samples at those levels take at least that opacity
 *     (common/svo.h rp_svo_solid_apply): the voxelized shells are hollow.
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
#define RP_SVO_MAX_DEPTHS 10u      /* R <= 1024 (voxel keys: 10 bits per axis) */

#define RP_SVO_NODE_CHILD_MASK 0x3FFFFFFFu
#define RP_SVO_NODE_OWN 0x40000000u
#define RP_SVO_NODE_BRICK 0x80000000u
#define RP_SVO_NO_BRICK 0xFFFFFFFFu

#define RP_SVO_BRICK_SAMPLES 27u  /* one direction */
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
