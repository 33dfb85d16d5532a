/* Sparse voxel octree build (seed 001). Host side: src/passes/svo.cpp. Layout,
 * node and brick meaning: shared/svo_layout.h; reading: common/svo.h.
 *
 * Input: the voxelizer's fragment list at resolution R = 2^D (kernels/voxelize.cl built with
 * RP_VOXEL_FRAGMENTS): per fragment the fixed-point sums it adds and its level-0 voxel.
 * Per frame, top-down, for depth k = 0 .. D-1 (brick level l = D-1-k):
 *   svo_clear_nodes   the depth's nodes (8 per existing parent, or the root) start empty
 *   svo_flag_bits     (depths whose brick level is >= the host's bits level, 3: the top
 *                     D - 3 depths) one work-item per node: the same flags from the level's
 *                     occupancy bits (svo_occ_mark: one pass over the fragments for the
 *                     finest such level, svo_occ_reduce: the coarser ones), instead of
 *   svo_flag          32 fragments a work-item: each one's owner node at depth k (the child of
 *                     its depth k-1 owner, kept in `cur`; found by descent at the first depth
 *                     after the bit depths), OR-ed flags: own voxels non-empty,
 *                     and which low faces hold the fragment's level-l voxel (bit e: node
 *                     a - e must exist too, its border holds that voxel)
 *   svo_dilate        one work-item per depth-k node with face bits: OR "exists" (bit 31 of
 *                     the node word, final after svo_allocate) into the nodes a - e (found by
 *                     descent)
 *   svo_count, svo_scan, svo_allocate
 *                     prefix sums over the depth's nodes in index order (fixed chunks, a
 *                     serial scan of the chunk sums; two counts: existing nodes and nodes
 *                     with own voxels): existing node i of rank r gets brick brick_first + r
 *                     (a brick-table entry) and, above the leaves, child block
 *                     child_first + 8 r; the samples of its occupied own voxels (the flags'
 *                     voxel bits) at own_first + directions * (occupied own voxels of the
 *                     nodes before it) (none for a node without: its own voxels are empty);
 *                     its children's coordinates 2a + o are recorded
 * Nothing here depends on the order of the fragments or of the work-items: flags are ORed,
 * ranks come from prefix sums over node indices, sums are integers. So the pools are
 * bit-identical run to run (DESIGN.md).
 Then bottom-up:
 *   svo_link          one work-item per fragment: pushes the fragment onto its leaf's list
 *                     (head per leaf in the flag words, which the leaf depth's svo_allocate
 *                     zeroed; "next" in the fragment's owner word `cur`, no longer needed):
 *                     the fragments grouped by leaf without per-voxel accumulators (those
 *                     took 8 voxels x 8 words = 256 bytes a leaf, 107 MiB at 512^3)
 *   svo_leaves        one work-item per leaf: walks its list summing its fragments' words
 *                     per own voxel in private memory (uint adds with the dense voxelizer's
 *                     overflow rule: the same integers whatever the list order), resolves
 *                     the 8 own samples (the dense resolve), and, being the only reader of
 *                     its facing sums, writes its parent's level-1 own sample for it (the
 *                     anisotropic mip step from the 8 samples and their facing coverage)
 *   svo_border        one work-item per node of a depth: brick-table words 1..3 = the bricks
 *                     of the face neighbours a + x, a + y, a + z (none where they do not
 *                     exist): the border samples (index 2 on some axis) are read through them
 *                     (seed 001's "value transfer" without the copies: every level-l voxel
 *                     is stored once)
 *   svo_mips          one work-item per node with own samples at brick level l >= 2: own
 *                     sample o (level-l voxel 2a + o) in the 6 directions =
 *                     common/voxel_composite.h over the own samples of child o, then
 *                     svo_border.
 * The values are those of the dense chain (voxelize.cl resolve, voxel_mips.cl), computed by
 * the same functions in the same order; with float samples bit-identical.
 */
#pragma OPENCL FP_CONTRACT OFF

#include "shared/types.h"
#include "shared/pass_params.h"
#include "shared/voxel_layout.h"
#include "shared/svo_layout.h"
#include "common/voxel_composite.h"
#include "common/voxel_resolve.h"
#include "common/svo.h"

#if !defined(RP_VOXEL_FIXED_BITS) || !defined(RP_VOXEL_SATURATED)
#error "svo.cl needs -DRP_VOXEL_FIXED_BITS, -DRP_VOXEL_SATURATED"
#endif

#define SVO_NODE_WORDS(svo) ((svo) + 4u * RP_SVO_HEADER_FLOAT4S)

inline uint3 svo_unpack(uint c) { return (uint3)(c & 1023u, (c >> 10) & 1023u, c >> 20); }
inline uint svo_pack(uint3 a) { return a.x | (a.y << 10) | (a.z << 20); }

/* rgb (clamped to [0, 65408]) -> RGB9E5 (the EXT_texture_shared_exponent rule: shared exponent
 * from the largest channel, mantissas rounded to nearest; the exponent from the float's bits
 * rather than log2). */
inline uint svo_pack_rgb(float3 c) {
  c = fmin(fmax(c, 0.0f), 65408.0f); /* NaN -> 0 */
  const float m = fmax(fmax(c.x, c.y), c.z);
  int e = (int)((as_uint(m) >> 23) & 255u) - 127;  /* floor(log2 m) for normal m */
  e = max(e, -16) + 16;                               /* biased shared exponent, 0 .. 31 */
  float inv = as_float((uint)(151 - e) << 23);        /* 2^(24 - e) */
  /* round to nearest: the conversion truncates, i.e. floors these non-negative values */
  if ((uint)(m * inv + 0.5f) == 512u) {
    ++e;
    inv *= 0.5f;
  }
  const uint r = (uint)(c.x * inv + 0.5f), g = (uint)(c.y * inv + 0.5f),
             b = (uint)(c.z * inv + 0.5f);
  return r | (g << 9) | (b << 18) | ((uint)e << 27);
}

/* The brick pool as written by the builder: pool = the rgb plane (uints, or float4s with
 * RP_SVO_FLOAT_SAMPLES), alpha = the opacity plane (bytes). */
inline void svo_store(__global uint* pool, __global uchar* alpha, uint s, float4 v) {
#if RP_SVO_FLOAT_SAMPLES
  (void)alpha;
  ((__global float4*)pool)[s] = v;
#else
  pool[s] = svo_pack_rgb(v.xyz);
  alpha[s] = (uchar)(clamp(v.w, 0.0f, 1.0f) * 255.0f + 0.5f);
#endif
}

/* Copies sample `from` to `to` as stored (the border transfer: no unpacking). */
inline void svo_copy(__global uint* pool, __global uchar* alpha, uint to, uint from) {
#if RP_SVO_FLOAT_SAMPLES
  (void)alpha;
  ((__global float4*)pool)[to] = ((__global const float4*)pool)[from];
#else
  pool[to] = pool[from];
  alpha[to] = alpha[from];
#endif
}

/* Stores the empty sample (rgb 0, opacity 0). */
inline void svo_clear_sample(__global uint* pool, __global uchar* alpha, uint s) {
#if RP_SVO_FLOAT_SAMPLES
  (void)alpha;
  ((__global float4*)pool)[s] = (float4)(0.0f);
#else
  pool[s] = 0u;
  alpha[s] = (uchar)0;
#endif
}

#define svo_pool_load rp_svo_pool_load
#define SVO_POOL(svo, brick_offset) ((svo) + 4u * (brick_offset))
#define SVO_ALPHA(svo, alpha_offset) ((__global uchar*)(svo) + (alpha_offset))
#define SVO_TABLE(svo, table_offset) ((svo) + (table_offset))
/* Brick table word 0 (the node's own samples) of the brick at address `brick`. */
#define SVO_OWN_FIRST(table, brick) \
  ((table)[RP_SVO_TABLE_WORDS * ((brick) >> RP_SVO_BRICK_SHIFT)])

__kernel void svo_clear_nodes(__global uint* svo, __global uint* own,
                              const SvoBuildParams params) {
  const uint first = params.first, count = params.count;
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  __global uint* nodes = SVO_NODE_WORDS(svo);
  nodes[2u * (first + i)] = 0u;
  nodes[2u * (first + i) + 1u] = RP_SVO_NO_BRICK;
  own[first + i] = 0u;
}

/* Fragments per work-item of svo_flag: consecutive fragments (written by the same voxelizer
 * work-item) mostly share their shallow owners, so a work-item ORs their bits locally and
 * issues one atomic per change of owner (contention on the top nodes otherwise). */
#define SVO_FLAG_CHUNK 32u

/* The owners at `depth` of fragments [SVO_FLAG_CHUNK g, + SVO_FLAG_CHUNK) (see the header).
 * resolution_log2 = D. */
__kernel void svo_flag(__global const uint* fragments, __global uint* svo, __global uint* cur,
                       volatile __global uint* own, const SvoBuildParams params) {
  const uint fragment_count = params.fragment_count, depth = params.depth;
  const uint resolution_log2 = params.resolution_log2, descend = params.descend;
  const uint begin = (uint)get_global_id(0) * SVO_FLAG_CHUNK;
  if (begin >= fragment_count) return;
  const uint end = min(begin + SVO_FLAG_CHUNK, fragment_count);
  const uint D = resolution_log2;
  const uint R = 1u << D;
  const uint level = D - 1u - depth;
  __global const uint* nodes = SVO_NODE_WORDS(svo);
  uint last = 0xFFFFFFFFu, pending = 0u;
  uint3 last_a = (uint3)(0xFFFFFFFFu);
  for (uint f = begin; f < end; ++f) {
    const uint key = fragments[RP_SVO_FRAGMENT_WORDS * f + RP_SVO_FRAGMENT_KEY];
    const uint3 v0 = (uint3)(key & (R - 1u), (key >> D) & (R - 1u), key >> (2u * D));
    const uint3 v = v0 >> level; /* level-l voxel */
    const uint3 a = v >> 1;      /* node coordinate at this depth */
    uint node = 0u;
    if (descend != 0u) { /* the depths above came from the occupancy bits: no owner yet */
      node = all(a == last_a) ? last : rp_svo_find(nodes, depth, a);
      last_a = a;
    } else if (depth > 0u) {
      const uint child = nodes[2u * cur[f]] & RP_SVO_NODE_CHILD_MASK;
      node = child + ((a.x & 1u) | ((a.y & 1u) << 1) | ((a.z & 1u) << 2));
    }
    cur[f] = node;
    /* low faces: v on the node's low side (v = 2a) with a neighbour a - e inside the grid */
    const uint m = ((v.x & 1u) == 0u && a.x > 0u ? 1u : 0u) |
                   ((v.y & 1u) == 0u && a.y > 0u ? 2u : 0u) |
                   ((v.z & 1u) == 0u && a.z > 0u ? 4u : 0u);
    uint bits = RP_SVO_FLAG_OWN |
                (1u << (RP_SVO_FLAG_VOXELS_SHIFT + ((v.x & 1u) | ((v.y & 1u) << 1) |
                                                    ((v.z & 1u) << 2))));
    for (uint e = 1u; e < 8u; ++e)
      if ((e & m) == e) bits |= 1u << e;
    if (node != last) {
      if (last != 0xFFFFFFFFu) atomic_or(own + last, pending);
      last = node;
      pending = 0u;
    }
    pending |= bits;
  }
  atomic_or(own + last, pending);
}

/* Occupancy bits (the top depths' flags without a pass over the fragments per depth): bit
 * (z n + y) n + x of level l's words (level l >= the host's bits level, n = R >> l) is set
 * when a fragment lies in level-l voxel (x, y, z). Level `level`'s words start at word
 * `offset`. */
__kernel void svo_occ_clear(__global uint* occ, const SvoBuildParams params) {
  const uint words = params.words;
  const uint i = (uint)get_global_id(0);
  if (i < words) occ[i] = 0u;
}

/* SVO_FLAG_CHUNK fragments a work-item: consecutive fragments mostly share a word. */
__kernel void svo_occ_mark(__global const uint* fragments, volatile __global uint* occ,
                           const SvoBuildParams params) {
  const uint fragment_count = params.fragment_count, level = params.level;
  const uint resolution_log2 = params.resolution_log2;
  const uint begin = (uint)get_global_id(0) * SVO_FLAG_CHUNK;
  if (begin >= fragment_count) return;
  const uint end = min(begin + SVO_FLAG_CHUNK, fragment_count);
  const uint D = resolution_log2, R = 1u << D, n = R >> level;
  uint last = 0xFFFFFFFFu, pending = 0u;
  for (uint f = begin; f < end; ++f) {
    const uint key = fragments[RP_SVO_FRAGMENT_WORDS * f + RP_SVO_FRAGMENT_KEY];
    const uint3 v = (uint3)(key & (R - 1u), (key >> D) & (R - 1u), key >> (2u * D)) >> level;
    const uint bit = (v.z * n + v.y) * n + v.x;
    if ((bit >> 5) != last) {
      if (last != 0xFFFFFFFFu) atomic_or(occ + last, pending);
      last = bit >> 5;
      pending = 0u;
    }
    pending |= 1u << (bit & 31u);
  }
  atomic_or(occ + last, pending);
}

/* Level l + 1's bits (n per side) from level l's (2n): one work-item per word. */
__kernel void svo_occ_reduce(__global uint* occ, const SvoBuildParams params) {
  const uint src = params.src, dst = params.dst, n = params.n;
  const uint w = (uint)get_global_id(0);
  const uint count = n * n * n;
  if (w * 32u >= count) return;
  const uint m = 2u * n;
  uint word = 0u;
  for (uint b = 0; b < 32u && w * 32u + b < count; ++b) {
    const uint j = w * 32u + b;
    const uint3 c = 2u * (uint3)(j % n, (j / n) % n, j / (n * n));
    uint any = 0u;
    for (uint o = 0; o < 8u; ++o) {
      const uint s = ((c.z + (o >> 2)) * m + c.y + ((o >> 1) & 1u)) * m + c.x + (o & 1u);
      any |= (occ[src + (s >> 5)] >> (s & 31u)) & 1u;
    }
    word |= any << b;
  }
  occ[dst + w] = word;
}

/* svo_flag's bits for the nodes of `depth` (brick level l = D-1-depth >= the bits level) from
 * level l's occupancy words (at `offset`): own = any own voxel 2a + o occupied; bit e = an
 * occupied own voxel on the low faces along e (o_i = 0 and a_i > 0 for every axis i of e). */
__kernel void svo_flag_bits(__global uint* own, __global const uint* coords,
                            __global const uint* occ, const SvoBuildParams params) {
  const uint offset = params.offset, first = params.first, count = params.count;
  const uint depth = params.depth;
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  const uint3 a = svo_unpack(coords[first + i]);
  const uint n = 2u << depth; /* level-l voxels per side */
  uint bits = 0u;
  for (uint o = 0; o < 8u; ++o) {
    const uint3 ov = (uint3)(o & 1u, (o >> 1) & 1u, o >> 2);
    const uint3 v = 2u * a + ov;
    const uint s = (v.z * n + v.y) * n + v.x;
    if (((occ[offset + (s >> 5)] >> (s & 31u)) & 1u) == 0u) continue;
    const uint m = (ov.x == 0u && a.x > 0u ? 1u : 0u) | (ov.y == 0u && a.y > 0u ? 2u : 0u) |
                   (ov.z == 0u && a.z > 0u ? 4u : 0u);
    bits |= RP_SVO_FLAG_OWN | (1u << (RP_SVO_FLAG_VOXELS_SHIFT + o));
    for (uint e = 1u; e < 8u; ++e)
      if ((e & m) == e) bits |= 1u << e;
  }
  own[first + i] = bits;
}

/* path[j] = the ancestor at depth j (0 .. depth-1) of the node at `depth` with coordinate a. */
inline void svo_path(__global const uint* nodes, uint depth, uint3 a, uint* path) {
  path[0] = 0u;
  for (uint j = 1u; j < depth; ++j) {
    const uint s = depth - j;
    path[j] = (nodes[2u * path[j - 1u]] & RP_SVO_NODE_CHILD_MASK) +
              (((a.x >> s) & 1u) | (((a.y >> s) & 1u) << 1) | (((a.z >> s) & 1u) << 2));
  }
}

/* The node at `depth` with coordinate b (!= a, inside the grid), descending from the deepest
 * ancestor it shares with a (path: svo_path of a) instead of the root; 0xFFFFFFFF when it is
 * not in the tree. The ancestors agree above depth - 1 - h, h = the highest differing bit. */
inline uint svo_find_near(__global const uint* nodes, const uint* path, uint depth, uint3 a,
                          uint3 b) {
  const uint h = 31u - clz((a.x ^ b.x) | (a.y ^ b.y) | (a.z ^ b.z));
  uint idx = path[depth - 1u - h];
  for (uint j = depth - h; j <= depth && idx != 0xFFFFFFFFu; ++j) {
    const uint child = nodes[2u * idx] & RP_SVO_NODE_CHILD_MASK;
    const uint s = depth - j;
    idx = child == 0u ? 0xFFFFFFFFu
                      : child + (((b.x >> s) & 1u) | (((b.y >> s) & 1u) << 1) |
                                 (((b.z >> s) & 1u) << 2));
  }
  return idx;
}

/* "Exists" goes into bit 31 of the target's node word 0 (cleared by svo_clear_nodes, final
 * only after svo_allocate): this kernel reads the flag words and the node words of depths < k
 * (the descent), and writes only depth k's node words, so nothing it reads is written. */
__kernel void svo_dilate(__global uint* svo, __global const uint* own,
                         __global const uint* coords, const SvoBuildParams params) {
  const uint first = params.first, count = params.count, depth = params.depth;
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  const uint bits = own[first + i] & RP_SVO_FLAG_FACES;
  if (bits == 0u) return;
  const uint3 a = svo_unpack(coords[first + i]);
  volatile __global uint* nodes = SVO_NODE_WORDS(svo);
  uint path[RP_SVO_MAX_DEPTHS];
  svo_path((__global const uint*)nodes, depth, a, path);
  for (uint e = 1u; e < 8u; ++e) {
    if ((bits & (1u << e)) == 0u) continue;
    const uint3 b = a - (uint3)(e & 1u, (e >> 1) & 1u, e >> 2);
    const uint t = svo_find_near((__global const uint*)nodes, path, depth, a, b);
    if (t != 0xFFFFFFFFu) atomic_or(nodes + 2u * t, RP_SVO_NODE_BRICK);
  }
}

/* Node i exists: own voxels, or a neighbour's border needs it (svo_dilate's mark). */
inline bool svo_exists(__global const uint* svo, __global const uint* own, uint i) {
  return (own[i] & RP_SVO_FLAG_OWN) != 0u || (SVO_NODE_WORDS(svo)[2u * i] & RP_SVO_NODE_BRICK) != 0u;
}

/* Existing nodes (sums[2g]) and occupied own voxels (sums[2g + 1]: the samples stored per
 * direction) in chunk g of [first, first + count). */
__kernel void svo_count(__global const uint* svo, __global const uint* own,
                        __global uint* sums, const SvoBuildParams params) {
  const uint first = params.first, count = params.count, chunk = params.chunk;
  const uint g = (uint)get_global_id(0);
  const uint begin = g * chunk;
  if (begin >= count) return;
  const uint end = min(begin + chunk, count);
  uint n = 0u, o = 0u;
  for (uint i = begin; i < end; ++i) {
    n += svo_exists(svo, own, first + i) ? 1u : 0u;
    o += rp_svo_popcount8((own[first + i] >> RP_SVO_FLAG_VOXELS_SHIFT) & 255u);
  }
  sums[2u * g] = n;
  sums[2u * g + 1u] = o;
}

/* Exclusive prefix sums over the chunk sums (both counts), in place; the totals into
 * totals[2 slot], totals[2 slot + 1]. One work-item: the chunks number nodes / chunk (a few
 * thousand). */
__kernel void svo_scan(__global uint* sums, __global uint* totals, const SvoBuildParams params) {
  const uint chunks = params.chunks, slot = params.slot;
  if (get_global_id(0) != 0) return;
  uint run = 0u, run_own = 0u;
  for (uint g = 0; g < chunks; ++g) {
    const uint s = sums[2u * g], o = sums[2u * g + 1u];
    sums[2u * g] = run;
    sums[2u * g + 1u] = run_own;
    run += s;
    run_own += o;
  }
  totals[2u * slot] = run;
  totals[2u * slot + 1u] = run_own;
}

/* At the leaf depth the flag words are then zeroed: they become the leaves' list heads
 * (svo_link). */
__kernel void svo_allocate(__global uint* svo, __global uint* own, __global uint* coords,
                           __global const uint* sums, const SvoBuildParams params) {
  const uint first = params.first, count = params.count, chunk = params.chunk;
  const uint child_first = params.child_first, brick_first = params.brick_first;
  const uint own_first = params.own_first, directions = params.directions, leaf = params.leaf;
  const uint table_offset = params.table_offset;
  const uint g = (uint)get_global_id(0);
  const uint begin = g * chunk;
  if (begin >= count) return;
  const uint end = min(begin + chunk, count);
  __global uint* nodes = SVO_NODE_WORDS(svo);
  __global uint* table = SVO_TABLE(svo, table_offset);
  uint rank = sums[2u * g], own_rank = sums[2u * g + 1u];
  for (uint k = begin; k < end; ++k) {
    const uint i = first + k;
    const uint flags = own[i];
    if (leaf != 0u) own[i] = 0u;
    if ((flags & RP_SVO_FLAG_OWN) == 0u && (nodes[2u * i] & RP_SVO_NODE_BRICK) == 0u)
      continue; /* does not exist: as svo_clear_nodes left it */
    const uint child = leaf != 0u ? 0u : child_first + 8u * rank;
    nodes[2u * i] = child | RP_SVO_NODE_BRICK | ((flags & RP_SVO_FLAG_OWN) ? RP_SVO_NODE_OWN : 0u);
    const uint b = brick_first + rank;
    nodes[2u * i + 1u] = b << RP_SVO_BRICK_SHIFT;
    __global uint* entry = table + RP_SVO_TABLE_WORDS * b;
    const uint mask = (flags >> RP_SVO_FLAG_VOXELS_SHIFT) & 255u;
    entry[0] = mask != 0u ? own_first + directions * own_rank : RP_SVO_NO_BRICK;
    own_rank += rp_svo_popcount8(mask);
    entry[1] = RP_SVO_NO_LINK | (mask << RP_SVO_MASK_SHIFT);
    entry[2] = RP_SVO_NO_LINK;
    entry[3] = RP_SVO_NO_LINK;
    if (leaf == 0u) {
      const uint3 a2 = 2u * svo_unpack(coords[i]);
      for (uint o = 0; o < 8u; ++o)
        coords[child + o] = svo_pack(a2 + (uint3)(o & 1u, (o >> 1) & 1u, o >> 2));
    }
    ++rank;
  }
}

/* Fragment f onto its leaf's list: heads[leaf] and next[] (= cur) hold fragment index + 1,
 * 0 ends a list. Each work-item rewrites only its own cur[f] (after reading it). */
__kernel void svo_link(__global uint* cur, volatile __global uint* heads,
                       const SvoBuildParams params) {
  const uint fragment_count = params.fragment_count;
  const uint f = (uint)get_global_id(0);
  if (f >= fragment_count) return;
  cur[f] = atomic_xchg(heads + cur[f], f + 1u);
}

/* Leaf slot i of the leaf depth (nodes [first, first + count), 8 per level-1 parent in the
 * order of the parents' bricks, see svo_allocate): own samples from its fragments' sums, as
 * voxelize_resolve; then, when there is a level 1 (parent_brick_first != RP_SVO_NO_BRICK), the
 * parent's own sample i & 7 in the six directions (svo_mips' step over this leaf's 8 samples,
 * seen through their facing sums: what voxel_mips.cl does for the dense level 1). A leaf slot
 * without a brick clears that parent sample (its 8 voxels are empty). */
__kernel void svo_leaves(__global const uint* fragments, __global const uint* next,
                         __global const uint* heads, __global uint* svo,
                         const SvoBuildParams params) {
  const uint first = params.first, count = params.count;
  const uint brick_offset = params.brick_offset, alpha_offset = params.alpha_offset;
  const uint parent_brick_first = params.parent_brick_first;
  const uint resolution_log2 = params.resolution_log2, table_offset = params.table_offset;
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  const uint D = resolution_log2;
  const uint brick = SVO_NODE_WORDS(svo)[2u * (first + i) + 1u];
  __global uint* pool = SVO_POOL(svo, brick_offset);
  __global uchar* alpha = SVO_ALPHA(svo, alpha_offset);
  __global const uint* table = SVO_TABLE(svo, table_offset);
  /* the parent's own voxel i & 7, stored when it is occupied (then this leaf has fragments) */
  uint pdst = RP_SVO_NO_BRICK, pstride = 0u;
  if (parent_brick_first != RP_SVO_NO_BRICK) {
    __global const uint* pe = table + RP_SVO_TABLE_WORDS * (parent_brick_first + (i >> 3));
    const uint pmask = pe[1] >> RP_SVO_MASK_SHIFT;
    const uint slot = rp_svo_own_slot(pmask, i & 7u);
    if (pe[0] != RP_SVO_NO_BRICK && slot != RP_SVO_NO_BRICK) {
      pdst = pe[0] + slot;
      pstride = rp_svo_popcount8(pmask);
    }
  }
  const bool parent = pdst != RP_SVO_NO_BRICK;
  const uint mine = brick == RP_SVO_NO_BRICK ? RP_SVO_NO_BRICK : SVO_OWN_FIRST(table, brick);
  if (mine == RP_SVO_NO_BRICK) { /* no fragments here: the parent's sample is empty */
    if (parent)
      for (uint d = 0; d < 6u; ++d) svo_clear_sample(pool, alpha, pdst + pstride * d);
    return;
  }
  const uint mask = table[RP_SVO_TABLE_WORDS * (brick >> RP_SVO_BRICK_SHIFT) + 1u] >>
                    RP_SVO_MASK_SHIFT;
  /* per own voxel o: sums r, g, b, a and facing x, y, z (the dense accumulator's words 0-6),
   * overflow bits (its word 7) */
  uint acc[8][7], over[8];
  for (uint o = 0; o < 8u; ++o) {
    over[o] = 0u;
    for (uint w = 0; w < 7u; ++w) acc[o][w] = 0u;
  }
  for (uint j = heads[first + i]; j != 0u; j = next[j - 1u]) {
    __global const uint* frag = fragments + RP_SVO_FRAGMENT_WORDS * (j - 1u);
    const uint key = frag[RP_SVO_FRAGMENT_KEY];
    const uint o = (key & 1u) | (((key >> D) & 1u) << 1) | (((key >> (2u * D)) & 1u) << 2);
    const uint cover = frag[RP_SVO_FRAGMENT_COVER];
    for (uint c = 0; c < 4u; ++c) {
      const uint q = c < 3u ? frag[c] : rp_svo_cover_opacity(cover, 1u << RP_VOXEL_FIXED_BITS);
      const uint old = acc[o][c];
      acc[o][c] = old + q;
      if (old > 0xFFFFFFFFu - q) over[o] |= 1u << c;
    }
    for (uint a = 0; a < 3u; ++a) acc[o][4u + a] += rp_svo_cover_facing(cover, a);
  }
  /* own voxel o: resolved as the dense voxelizer does; stored when occupied (else it is 0) */
  float4 iso[8];
  for (uint o = 0; o < 8u; ++o) {
    const uint slot = rp_svo_own_slot(mask, o);
    if (slot == RP_SVO_NO_BRICK) {
      iso[o] = (float4)(0.0f);
      continue;
    }
    svo_store(pool, alpha, mine + slot,
              rp_voxel_resolve((uint4)(acc[o][0], acc[o][1], acc[o][2], acc[o][3]), over[o]));
    iso[o] = svo_pool_load(pool, alpha, mine + slot);
  }
  if (!parent) return;
  /* level 1: the samples as stored (packed: rounded), as svo_mips reads its children */
  uint4 facing[8];
  for (uint c = 0; c < 8u; ++c) facing[c] = (uint4)(acc[c][4], acc[c][5], acc[c][6], over[c]);
  for (uint d = 0; d < 6u; ++d) {
    float4 c8[8];
    for (uint c = 0; c < 8u; ++c) c8[c] = mips_facing(iso[c], facing[c], d);
    svo_store(pool, alpha, pdst + pstride * d, mips_composite(c8, d));
  }
}

/* Brick-table words 1..3 of the nodes of `depth`: the brick index of the face neighbour a + x,
 * a + y, a + z (RP_SVO_NO_LINK where it does not exist or lies outside the grid). */
__kernel void svo_border(__global uint* svo, __global const uint* coords,
                         const SvoBuildParams params) {
  const uint first = params.first, count = params.count, depth = params.depth;
  const uint table_offset = params.table_offset;
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  __global const uint* nodes = SVO_NODE_WORDS(svo);
  const uint brick = nodes[2u * (first + i) + 1u];
  if (brick == RP_SVO_NO_BRICK) return;
  __global uint* table = SVO_TABLE(svo, table_offset);
  __global uint* entry = table + RP_SVO_TABLE_WORDS * (brick >> RP_SVO_BRICK_SHIFT);
  const uint3 a = svo_unpack(coords[first + i]);
  const uint side = 1u << depth;
  /* the node's ancestors, so that a neighbour's descent starts at the deepest ancestor they
   * share instead of the root (usually the parent) */
  uint path[RP_SVO_MAX_DEPTHS];
  svo_path(nodes, depth, a, path);
  for (uint axis = 0u; axis < 3u; ++axis) {
    const uint e = 1u << axis;
    const uint3 b = a + (uint3)(e & 1u, (e >> 1) & 1u, e >> 2);
    uint link = RP_SVO_NO_LINK;
    if (b.x < side && b.y < side && b.z < side) {
      const uint idx = svo_find_near(nodes, path, depth, a, b);
      if (idx != 0xFFFFFFFFu) {
        const uint nb = nodes[2u * idx + 1u];
        if (nb != RP_SVO_NO_BRICK) link = nb >> RP_SVO_BRICK_SHIFT;
      }
    }
    /* word 1 keeps its own-voxel mask (bits 24-31) */
    entry[1u + axis] = (entry[1u + axis] & ~RP_SVO_LINK_MASK) | link;
  }
}

/* Own samples of the nodes of `depth` (brick level `level` >= 2) from their children (level 1:
 * svo_leaves). */
__kernel void svo_mips(__global uint* svo, const SvoBuildParams params) {
  const uint first = params.first, count = params.count;
  const uint brick_offset = params.brick_offset, alpha_offset = params.alpha_offset;
  const uint table_offset = params.table_offset;
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  __global const uint* nodes = SVO_NODE_WORDS(svo);
  const uint brick = nodes[2u * (first + i) + 1u];
  if (brick == RP_SVO_NO_BRICK) return;
  __global const uint* table = SVO_TABLE(svo, table_offset);
  const uint mine = SVO_OWN_FIRST(table, brick);
  if (mine == RP_SVO_NO_BRICK) return; /* own voxels empty: nothing stored */
  const uint mask =
      table[RP_SVO_TABLE_WORDS * (brick >> RP_SVO_BRICK_SHIFT) + 1u] >> RP_SVO_MASK_SHIFT;
  const uint stride = rp_svo_popcount8(mask);
  __global uint* pool = SVO_POOL(svo, brick_offset);
  __global uchar* alpha = SVO_ALPHA(svo, alpha_offset);
  const uint children = nodes[2u * (first + i)] & RP_SVO_NODE_CHILD_MASK;
  for (uint o = 0; o < 8u; ++o) {
    const uint slot = rp_svo_own_slot(mask, o);
    if (slot == RP_SVO_NO_BRICK) continue; /* own voxel o empty: 0, not stored */
    const uint dst = mine + slot;
    const uint cb = children == 0u ? RP_SVO_NO_BRICK : nodes[2u * (children + o) + 1u];
    const uint src = cb == RP_SVO_NO_BRICK ? RP_SVO_NO_BRICK : SVO_OWN_FIRST(table, cb);
    if (src == RP_SVO_NO_BRICK) { /* child o's own voxels all empty: the composite is 0 */
      for (uint d = 0; d < 6u; ++d) svo_clear_sample(pool, alpha, dst + stride * d);
      continue;
    }
    const uint cmask =
        table[RP_SVO_TABLE_WORDS * (cb >> RP_SVO_BRICK_SHIFT) + 1u] >> RP_SVO_MASK_SHIFT;
    const uint cstride = rp_svo_popcount8(cmask);
    for (uint d = 0; d < 6u; ++d) {
      float4 c8[8];
      for (uint c = 0; c < 8u; ++c) {
        const uint cs = rp_svo_own_slot(cmask, c);
        c8[c] = cs == RP_SVO_NO_BRICK ? (float4)(0.0f)
                                      : svo_pool_load(pool, alpha, src + cstride * d + cs);
      }
      svo_store(pool, alpha, dst + stride * d, mips_composite(c8, d));
    }
  }
}
