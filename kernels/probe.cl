/* Device peak probe (bench/src/peak_probe.cpp), in the spirit of clpeak: the bench divides each
 * pass's modelled bytes and flops (bench/src/pass_work.cpp) by these measured peaks.
 *
 * probe_fill: src[i] = (i & 0xFFFFFF, 1, 2, 3) as floats (exact), the copy's known input.
 * probe_copy: dst[i] = src[i], one float4 per work-item: 32 B of global traffic per item
 *   (16 read + 16 written), unit stride, the streaming bandwidth a well-behaved pass can reach.
 * probe_copy_wrap: dst[i & mask] = src[i & mask] for i over many times the buffer's length:
 *   the same 32 B per work-item, but the working set (src + dst = 32 * (mask + 1) bytes) stays
 *   small enough to live in one cache level while a launch is long enough to time (the
 *   cache-aware ceilings of the bench's efficiency columns). mask + 1 is a power of two.
 * probe_compute: 8 independent chains of float8 mads per work-item (64 lanes, enough
 *   independent work to hide mad latency on CPUs and GPUs), RP_PROBE_UNROLL mads per chain per
 *   loop iteration. With a = 1 and b = 1 from the host (unknown to the compiler, so nothing
 *   folds) every mad adds exactly 1: lane j starts at (gid & 255) + j and ends at that +
 *   iterations * RP_PROBE_UNROLL, all integers below 2^24, so the per-item sum of the 64 lanes
 *   written to out[gid] is exact and the host checks it. Flops per item:
 *   iterations * RP_PROBE_UNROLL * 64 lanes * 2 (a mad is 2 flops).
 */
#define RP_PROBE_UNROLL 8

__kernel void probe_fill(__global float4* restrict src, uint n) {
  const uint i = (uint)get_global_id(0);
  if (i >= n) return;
  src[i] = (float4)((float)(i & 0xFFFFFFu), 1.0f, 2.0f, 3.0f);
}

__kernel void probe_copy(__global const float4* restrict src, __global float4* restrict dst) {
  const size_t i = get_global_id(0);
  dst[i] = src[i];
}

__kernel void probe_copy_wrap(__global const float4* restrict src, __global float4* restrict dst,
                              uint mask) {
  const uint i = (uint)get_global_id(0) & mask;
  dst[i] = src[i];
}

#define RP_PROBE_MAD8(x) x = mad(x, a, b)
#define RP_PROBE_STEP                                                                    \
  RP_PROBE_MAD8(x0); RP_PROBE_MAD8(x1); RP_PROBE_MAD8(x2); RP_PROBE_MAD8(x3);            \
  RP_PROBE_MAD8(x4); RP_PROBE_MAD8(x5); RP_PROBE_MAD8(x6); RP_PROBE_MAD8(x7)

__kernel void probe_compute(__global float* restrict out, float a_in, float b_in, uint iterations) {
  const uint gid = (uint)get_global_id(0);
  const float8 a = (float8)(a_in), b = (float8)(b_in);
  const float8 lane = (float8)(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f);
  const float8 base = (float8)((float)(gid & 255u)) + lane;
  float8 x0 = base, x1 = base + 8.0f, x2 = base + 16.0f, x3 = base + 24.0f;
  float8 x4 = base + 32.0f, x5 = base + 40.0f, x6 = base + 48.0f, x7 = base + 56.0f;
  for (uint k = 0; k < iterations; ++k) {
    RP_PROBE_STEP; RP_PROBE_STEP; RP_PROBE_STEP; RP_PROBE_STEP;
    RP_PROBE_STEP; RP_PROBE_STEP; RP_PROBE_STEP; RP_PROBE_STEP;
  }
  const float8 s = ((x0 + x1) + (x2 + x3)) + ((x4 + x5) + (x6 + x7));
  out[gid] = ((s.s0 + s.s1) + (s.s2 + s.s3)) + ((s.s4 + s.s5) + (s.s6 + s.s7));
}
