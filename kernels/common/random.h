/* Deterministic per-pixel randomness (OpenCL C only): integer hashes and a Poisson disk.
 * Everything depends only on its integer inputs (pixel, frame index), never on timing, so a
 * frame renders bit-identically every run (DESIGN.md). */
#ifndef ROLYPOLY_COMMON_RANDOM_H
#define ROLYPOLY_COMMON_RANDOM_H

/* 32-bit integer hash: a permuted-congruential step followed by an xorshift-multiply output
 * mix (the PCG "RXS-M-XS" permutation). Good avalanche for consecutive inputs, integer only,
 * vectorizes (variable shifts exist on AVX2/AVX-512). */
inline uint rp_hash_u32(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

/* Hash of a pixel and a frame index (chained so that (x, y, f) permutations differ). */
inline uint rp_hash_pixel(uint x, uint y, uint frame) {
  return rp_hash_u32(x ^ rp_hash_u32(y ^ rp_hash_u32(frame)));
}

/* Top 24 bits of a hash as a float in [0, 1). */
inline float rp_hash_to_unit(uint h) { return (float)(h >> 8) * (1.0f / 16777216.0f); }

/* 16 points in the unit disk with pairwise distance >= 0.436 (dart throwing, best of 200 seeded
 * trials, generated once offline; fixed data, not regenerated at run time). */
#define RP_POISSON_DISK_COUNT 16
__constant float2 RP_POISSON_DISK[RP_POISSON_DISK_COUNT] = {
    (float2)(0.3972f, 0.6871f),   (float2)(0.9056f, -0.0336f),  (float2)(-0.7300f, -0.2740f),
    (float2)(-0.0751f, -0.5619f), (float2)(-0.4080f, 0.8898f),  (float2)(-0.3577f, 0.4519f),
    (float2)(0.5044f, 0.2503f),   (float2)(0.4689f, -0.8088f),  (float2)(0.1092f, -0.0942f),
    (float2)(0.8308f, 0.5409f),   (float2)(-0.7750f, 0.2014f),  (float2)(-0.4490f, -0.8619f),
    (float2)(-0.0158f, -0.9943f), (float2)(0.0188f, 0.9827f),   (float2)(0.5436f, -0.2779f),
    (float2)(-0.3392f, -0.0255f)};

/* One Poisson-disk point chosen and rotated by hash h: the top 4 bits pick the point, the low
 * 24 bits give the rotation angle. native_sin/native_cos are cheap on PoCL (DESIGN.md) and
 * deterministic on a given device. Result lies in the unit disk. */
inline float2 rp_poisson_rotated(uint h) {
  float2 p = RP_POISSON_DISK[h >> 28];
  float angle = (float)(h & 0xFFFFFFu) * (6.28318530718f / 16777216.0f);
  float c = native_cos(angle), s = native_sin(angle);
  return (float2)(c * p.x - s * p.y, s * p.x + c * p.y);
}

#endif
