/* Physically based bloom (SPEC 6.6, after Jimenez, "Next Generation Post Processing in Call of
 * Duty: Advanced Warfare", SIGGRAPH 2014). Host side and the chain's bookkeeping:
 * src/passes/bloom.{h,cpp}.
 *
 * Images: float4 per texel (rgb linear HDR, a carried along), row-major, top row first, pixel
 * centres at +0.5. Level 0 is the input (W0 x H0); level k is ceil(W(k-1) / 2) x ceil(H(k-1) / 2).
 * Coarse texel m covers fine texels 2m and 2m+1 (the second one does not exist for the last
 * texel of an odd-sized level: clamp-to-edge repeats the edge), so a fine-level position p
 * (in pixels) is coarse position p / 2. All sampling is clamp-to-edge.
 *
 * Downsample (13 taps): destination texel (x, y) is centred on the source texel CORNER
 * (2x+1, 2y+1); the 13 bilinear taps sit at source offsets {-2, 0, 2}^2 and {-1, 1}^2 from it.
 * Every tap lands on a texel corner, so each is exactly the mean of a 2x2 texel box, and the 13
 * taps together read the 6x6 source texels 2x-2 .. 2x+3 (the 36-texel footprint). They form five
 * overlapping 2x2 groups of taps: the inner group (the four {-1, 1}^2 taps), weight 0.5, and the
 * four outer corner groups (e.g. offsets (-2,-2), (0,-2), (-2,0), (0,0)), weight 0.125 each.
 * Interior energy is conserved: every source texel's weights over all destination texels sum to
 * exactly 1/4 (= the area ratio).
 *
 * Karis average (first downsample only): each group's mean colour G is weighted by
 * 1 / (1 + luma(G)) (Rec. 709 luma, clamped at 0) on top of its 0.5 / 0.125, and the result is
 * divided by the sum of those weights. A single very bright texel then contributes a bounded
 * amount, so a particle moving by one pixel does not make the bloom flicker.
 *
 * Upsample (3x3 tent, radius 1 texel of the DESTINATION level = 0.5 texel of the coarse level):
 * nine bilinear taps of the coarse level at the destination texel centre + {-1, 0, 1}^2
 * destination texels, weights (1 2 1)/4 x (1 2 1)/4. The taps sit at fixed fractions (+-0.25 and
 * +-0.75 of a coarse texel from the coarse texel centres), so the nine taps collapse exactly
 * into a separable 3x3 texel stencil: destination texel i = 2m + p (parity p) reads coarse
 * texels m-1, m, m+1 with weights (5/16, 10/16, 1/16) for p = 0 and (1/16, 10/16, 5/16) for
 * p = 1 (clamping the texel index equals clamping the bilinear taps). Like the downsample it
 * conserves interior energy. tests/passes/bloom_test.cpp checks the kernel against the literal
 * nine bilinear taps.
 *
 * Accumulation, down levels D1 .. DN: UN = DN, Uk = Dk + up(U(k+1)), bloom = up(U1) / N.
 * Uk holds N-k+1 copies of the energy, so dividing by N makes the bloom's total energy equal the
 * input's (each level weighted 1/N).
 *
 * PoCL: every kernel except the Karis downsample runs one work-item per output FLOAT over the
 * flat index i = 4 * texel + channel, in straight-line scalar code (what PoCL vectorizes across
 * work-items, DESIGN.md). The Karis step needs all channels for luma: one work-item per texel.
 * Deterministic: gathers only, no atomics.
 */

/* Mean of the 2x2 box of taps / texels a, b, c, d. */
#define RP_BLOOM_BOX(a, b, c, d) (0.25f * (((a) + (b)) + ((c) + (d))))

/* The 6 clamped source rows (as element offsets row * width * 4) and columns (as element
 * offsets column * 4) of destination texel (x, y): 2x-2 .. 2x+3. */
#define RP_BLOOM_FOOTPRINT(x, y, src_w, src_h)                                      \
  const int r0 = clamp(2 * (y) - 2, 0, (src_h) - 1) * (src_w) * 4;                  \
  const int r1 = clamp(2 * (y) - 1, 0, (src_h) - 1) * (src_w) * 4;                  \
  const int r2 = min(2 * (y), (src_h) - 1) * (src_w) * 4;                           \
  const int r3 = min(2 * (y) + 1, (src_h) - 1) * (src_w) * 4;                       \
  const int r4 = min(2 * (y) + 2, (src_h) - 1) * (src_w) * 4;                       \
  const int r5 = min(2 * (y) + 3, (src_h) - 1) * (src_w) * 4;                       \
  const int c0 = clamp(2 * (x) - 2, 0, (src_w) - 1) * 4;                            \
  const int c1 = clamp(2 * (x) - 1, 0, (src_w) - 1) * 4;                            \
  const int c2 = min(2 * (x), (src_w) - 1) * 4;                                     \
  const int c3 = min(2 * (x) + 1, (src_w) - 1) * 4;                                 \
  const int c4 = min(2 * (x) + 2, (src_w) - 1) * 4;                                 \
  const int c5 = min(2 * (x) + 3, (src_w) - 1) * 4;

/* Plain 13-tap downsample of one channel: dst[i], i = 4 * (y * dst_w + x) + channel. */
__kernel void bloom_downsample(__global const float* restrict src, int src_w, int src_h,
                               __global float* restrict dst, int dst_w, int dst_h) {
  const int i = (int)get_global_id(0);
  if (i >= dst_w * dst_h * 4) return;
  const int ch = i & 3, texel = i >> 2;
  const int x = texel % dst_w, y = texel / dst_w;
  RP_BLOOM_FOOTPRINT(x, y, src_w, src_h)
  __global const float* s = src + ch;
#define T(r, c) s[r + c]
  /* The 13 taps row by row (source offsets -2, -1, 0, 1, 2 in y), named a .. n without i. */
  const float a = RP_BLOOM_BOX(T(r0, c0), T(r0, c1), T(r1, c0), T(r1, c1));
  const float b = RP_BLOOM_BOX(T(r0, c2), T(r0, c3), T(r1, c2), T(r1, c3));
  const float c = RP_BLOOM_BOX(T(r0, c4), T(r0, c5), T(r1, c4), T(r1, c5));
  const float d = RP_BLOOM_BOX(T(r1, c1), T(r1, c2), T(r2, c1), T(r2, c2));
  const float e = RP_BLOOM_BOX(T(r1, c3), T(r1, c4), T(r2, c3), T(r2, c4));
  const float f = RP_BLOOM_BOX(T(r2, c0), T(r2, c1), T(r3, c0), T(r3, c1));
  const float g = RP_BLOOM_BOX(T(r2, c2), T(r2, c3), T(r3, c2), T(r3, c3));
  const float h = RP_BLOOM_BOX(T(r2, c4), T(r2, c5), T(r3, c4), T(r3, c5));
  const float j = RP_BLOOM_BOX(T(r3, c1), T(r3, c2), T(r4, c1), T(r4, c2));
  const float k = RP_BLOOM_BOX(T(r3, c3), T(r3, c4), T(r4, c3), T(r4, c4));
  const float l = RP_BLOOM_BOX(T(r4, c0), T(r4, c1), T(r5, c0), T(r5, c1));
  const float m = RP_BLOOM_BOX(T(r4, c2), T(r4, c3), T(r5, c2), T(r5, c3));
  const float n = RP_BLOOM_BOX(T(r4, c4), T(r4, c5), T(r5, c4), T(r5, c5));
#undef T
  const float inner = RP_BLOOM_BOX(d, e, j, k);
  const float outer = RP_BLOOM_BOX(a, b, f, g) + RP_BLOOM_BOX(b, c, g, h) +
                      RP_BLOOM_BOX(f, g, l, m) + RP_BLOOM_BOX(g, h, m, n);
  dst[i] = 0.5f * inner + 0.125f * outer;
}

/* Karis weight of a group's mean colour: 1 / (1 + luma), luma Rec. 709, negative luma as 0. */
inline float rp_bloom_karis_weight(float4 g) {
  return 1.0f / (1.0f + fmax(0.2126f * g.x + 0.7152f * g.y + 0.0722f * g.z, 0.0f));
}

/* First downsample (full resolution -> level 1) with the Karis average: one work-item per
 * destination texel, same taps and groups as bloom_downsample. */
__kernel void bloom_downsample_karis(__global const float4* restrict src, int src_w, int src_h,
                                     __global float4* restrict dst, int dst_w, int dst_h) {
  const int texel = (int)get_global_id(0);
  if (texel >= dst_w * dst_h) return;
  const int x = texel % dst_w, y = texel / dst_w;
  RP_BLOOM_FOOTPRINT(x, y, src_w, src_h)
#define T(r, c) src[(r + c) >> 2]
  const float4 a = RP_BLOOM_BOX(T(r0, c0), T(r0, c1), T(r1, c0), T(r1, c1));
  const float4 b = RP_BLOOM_BOX(T(r0, c2), T(r0, c3), T(r1, c2), T(r1, c3));
  const float4 c = RP_BLOOM_BOX(T(r0, c4), T(r0, c5), T(r1, c4), T(r1, c5));
  const float4 d = RP_BLOOM_BOX(T(r1, c1), T(r1, c2), T(r2, c1), T(r2, c2));
  const float4 e = RP_BLOOM_BOX(T(r1, c3), T(r1, c4), T(r2, c3), T(r2, c4));
  const float4 f = RP_BLOOM_BOX(T(r2, c0), T(r2, c1), T(r3, c0), T(r3, c1));
  const float4 g = RP_BLOOM_BOX(T(r2, c2), T(r2, c3), T(r3, c2), T(r3, c3));
  const float4 h = RP_BLOOM_BOX(T(r2, c4), T(r2, c5), T(r3, c4), T(r3, c5));
  const float4 j = RP_BLOOM_BOX(T(r3, c1), T(r3, c2), T(r4, c1), T(r4, c2));
  const float4 k = RP_BLOOM_BOX(T(r3, c3), T(r3, c4), T(r4, c3), T(r4, c4));
  const float4 l = RP_BLOOM_BOX(T(r4, c0), T(r4, c1), T(r5, c0), T(r5, c1));
  const float4 m = RP_BLOOM_BOX(T(r4, c2), T(r4, c3), T(r5, c2), T(r5, c3));
  const float4 n = RP_BLOOM_BOX(T(r4, c4), T(r4, c5), T(r5, c4), T(r5, c5));
#undef T
  const float4 g_in = RP_BLOOM_BOX(d, e, j, k);
  const float4 g_tl = RP_BLOOM_BOX(a, b, f, g), g_tr = RP_BLOOM_BOX(b, c, g, h);
  const float4 g_bl = RP_BLOOM_BOX(f, g, l, m), g_br = RP_BLOOM_BOX(g, h, m, n);
  const float w_in = 0.5f * rp_bloom_karis_weight(g_in);
  const float w_tl = 0.125f * rp_bloom_karis_weight(g_tl);
  const float w_tr = 0.125f * rp_bloom_karis_weight(g_tr);
  const float w_bl = 0.125f * rp_bloom_karis_weight(g_bl);
  const float w_br = 0.125f * rp_bloom_karis_weight(g_br);
  const float4 sum = w_in * g_in + ((w_tl * g_tl + w_tr * g_tr) + (w_bl * g_bl + w_br * g_br));
  dst[texel] = sum / (w_in + ((w_tl + w_tr) + (w_bl + w_br)));
}

/* Tent upsample of one channel of the coarse level at destination texel (x, y), see the top
 * comment: separable stencil over coarse texels m-1, m, m+1 per axis. */
inline float rp_bloom_tent(__global const float* coarse, int coarse_w, int coarse_h, int x, int y,
                           int ch) {
  const int mx = x >> 1, my = y >> 1;
  /* Weight of texel m-1 (5/16 for even, 1/16 for odd); m+1 gets 6/16 minus that. */
  const float wx0 = (x & 1) ? 0.0625f : 0.3125f, wx2 = 0.375f - wx0;
  const float wy0 = (y & 1) ? 0.0625f : 0.3125f, wy2 = 0.375f - wy0;
  const int ca = max(mx - 1, 0) * 4 + ch, cb = min(mx, coarse_w - 1) * 4 + ch,
            cc = min(mx + 1, coarse_w - 1) * 4 + ch;
  const int ra = max(my - 1, 0) * coarse_w * 4, rb = min(my, coarse_h - 1) * coarse_w * 4,
            rc = min(my + 1, coarse_h - 1) * coarse_w * 4;
  const float row_a = wx0 * coarse[ra + ca] + 0.625f * coarse[ra + cb] + wx2 * coarse[ra + cc];
  const float row_b = wx0 * coarse[rb + ca] + 0.625f * coarse[rb + cb] + wx2 * coarse[rb + cc];
  const float row_c = wx0 * coarse[rc + ca] + 0.625f * coarse[rc + cb] + wx2 * coarse[rc + cc];
  return wy0 * row_a + 0.625f * row_b + wy2 * row_c;
}

/* U(k) = D(k) + up(U(k+1)): dst[i] for i = 4 * (y * dst_w + x) + channel. */
__kernel void bloom_upsample_add(__global const float* restrict coarse, int coarse_w,
                                 int coarse_h, __global const float* restrict level,
                                 __global float* restrict dst, int dst_w, int dst_h) {
  const int i = (int)get_global_id(0);
  if (i >= dst_w * dst_h * 4) return;
  const int texel = i >> 2;
  const int x = texel % dst_w, y = texel / dst_w;
  dst[i] = level[i] + rp_bloom_tent(coarse, coarse_w, coarse_h, x, y, i & 3);
}

/* Full resolution: out = in * (1 - f) + up(U1) * f / N; bloom_scale = f / N. out may be the
 * same buffer as in (each work-item reads and writes only its own element), hence no restrict. */
__kernel void bloom_mix(__global const float* hdr_in, __global const float* restrict coarse,
                        int coarse_w, int coarse_h, __global float* hdr_out, int width,
                        int height, float keep, float bloom_scale) {
  const int i = (int)get_global_id(0);
  if (i >= width * height * 4) return;
  const int texel = i >> 2;
  const int x = texel % width, y = texel / width;
  const float bloom = rp_bloom_tent(coarse, coarse_w, coarse_h, x, y, i & 3);
  hdr_out[i] = hdr_in[i] * keep + bloom * bloom_scale;
}
