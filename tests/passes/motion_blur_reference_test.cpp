// Motion blur kernels (kernels/motion_blur.cl) against a straightforward single-precision C++
// reference of the same steps: tile max (exact, ties included), 3x3 neighbourhood max (exact),
// the depth/speed half2 plane (exact against a round-to-nearest-even conversion, and within half
// precision of the float values), and the reconstruction filter (1e-5 relative) with its sample
// count from the neighbourhood max (min(2 ceil(|V_max|) + 1, 15)) and its quiet blocks (copied).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "cl/error.h"
#include "passes/motion_blur.h"
#include "passes/pass_names.h"
#include "render/frame_buffers.h"
#include "support/cl_fixture.h"

namespace {

using rp::passes::MotionBlurPass;
constexpr uint32_t kTile = MotionBlurPass::kTileSize;
constexpr float kMaxRadius = MotionBlurPass::kMaxBlurRadius;

struct V2 {
  float x = 0, y = 0;
  bool operator==(const V2& o) const { return x == o.x && y == o.y; }
};
struct V4 {
  float x = 0, y = 0, z = 0, w = 0;
};

struct Inputs {
  uint32_t w = 0, h = 0;
  std::vector<V2> velocity;
  std::vector<float> depth;
  std::vector<V4> hdr;
};

// --- reference -------------------------------------------------------------------------------

float len2(V2 v) {
  const float a = v.x * v.x;
  const float b = v.y * v.y;
  return a + b;
}

V2 half_vector(V2 velocity, float shutter) {
  const float s = shutter * 0.5f;
  V2 v{velocity.x * s, velocity.y * s};
  return std::isfinite(v.x) && std::isfinite(v.y) ? v : V2{};
}

V2 clamp_radius(V2 v) {
  const float l2 = len2(v);
  if (l2 > kMaxRadius * kMaxRadius) {
    const float k = kMaxRadius / std::sqrt(l2);
    v = {v.x * k, v.y * k};
  }
  return v;
}

// Max |V| per tile; ties: the lower pixel index wins (row-major scan with a strict ">").
std::vector<V2> ref_tile_max(const std::vector<V2>& velocity, uint32_t w, uint32_t h,
                             float shutter) {
  const uint32_t tx = (w + kTile - 1) / kTile, ty = (h + kTile - 1) / kTile;
  std::vector<V2> out(size_t(tx) * ty);
  for (uint32_t t = 0; t < tx * ty; ++t) {
    V2 best;
    float best_l2 = -1.0f;
    for (uint32_t y = (t / tx) * kTile; y < std::min(h, (t / tx + 1) * kTile); ++y)
      for (uint32_t x = (t % tx) * kTile; x < std::min(w, (t % tx + 1) * kTile); ++x) {
        const V2 v = half_vector(velocity[y * w + x], shutter);
        if (len2(v) > best_l2) {
          best = v;
          best_l2 = len2(v);
        }
      }
    out[t] = clamp_radius(best);
  }
  return out;
}

// Max |V| over the 3x3 tiles; ties: the first in row-major order of the neighbourhood wins.
std::vector<V2> ref_neighbour_max(const std::vector<V2>& tiles, uint32_t tx, uint32_t ty) {
  std::vector<V2> out(tiles.size());
  for (int y = 0; y < int(ty); ++y)
    for (int x = 0; x < int(tx); ++x) {
      V2 best;
      float best_l2 = -1.0f;
      for (int ny = std::max(0, y - 1); ny <= std::min(int(ty) - 1, y + 1); ++ny)
        for (int nx = std::max(0, x - 1); nx <= std::min(int(tx) - 1, x + 1); ++nx) {
          const V2 v = tiles[size_t(ny) * tx + size_t(nx)];
          if (len2(v) > best_l2) {
            best = v;
            best_l2 = len2(v);
          }
        }
      out[size_t(y) * tx + size_t(x)] = best;
    }
  return out;
}

// IEEE binary16, round to nearest even (what vstore_half2 does by default).
uint16_t float_to_half(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  const uint32_t sign = (u >> 16) & 0x8000u, mag = u & 0x7FFFFFFFu;
  if (mag >= 0x7F800000u) return uint16_t(sign | 0x7C00u | (mag > 0x7F800000u ? 0x200u : 0u));
  if (mag >= 0x477FF000u) return uint16_t(sign | 0x7C00u);  // >= 65520 rounds to infinity
  if (mag < 0x38800000u) {                                   // below 2^-14: subnormal half
    float a;
    std::memcpy(&a, &mag, 4);
    return uint16_t(sign | uint32_t(std::nearbyint(a * 16777216.0f)));  // units of 2^-24
  }
  uint32_t h = ((((mag >> 23) - 127u + 15u) << 10) | ((mag & 0x7FFFFFu) >> 13));
  const uint32_t rest = mag & 0x1FFFu;
  if (rest > 0x1000u || (rest == 0x1000u && (h & 1u))) ++h;  // carry into the exponent is right
  return uint16_t(sign | h);
}

float half_to_float(uint16_t h) {
  const uint32_t sign = uint32_t(h & 0x8000u) << 16, e = (h >> 10) & 0x1Fu, m = h & 0x3FFu;
  float mag;
  if (e == 0) {
    mag = float(m) / 16777216.0f;
  } else if (e == 31) {
    mag = m ? NAN : INFINITY;
  } else {
    mag = std::ldexp(float(1024u + m), int(e) - 25);
  }
  uint32_t u;
  std::memcpy(&u, &mag, 4);
  u |= sign;
  std::memcpy(&mag, &u, 4);
  return mag;
}

// The per-pixel jitter hash of kernels/common/random.h.
uint32_t hash_u32(uint32_t v) {
  const uint32_t state = v * 747796405u + 2891336453u;
  const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
float jitter(uint32_t x, uint32_t y) {
  const uint32_t h = hash_u32(x ^ hash_u32(y ^ hash_u32(0u)));
  return float(h >> 8) * (1.0f / 16777216.0f) - 0.5f;
}

float clamp01(float v) { return std::min(std::max(v, 0.0f), 1.0f); }
float soft_depth(float za, float zb) {
  return clamp01(1.0f - (za - zb) * (1.0f / MotionBlurPass::kSoftDepth));
}
// Speed terms from q = dist / speed: the cone 1 - q and the cylinder, a smooth step from 1 to 0
// over q in [0.95, 1.05].
float cone(float q) { return clamp01(1.0f - q); }
float cylinder(float q) {
  const float t = clamp01((q - 0.95f) * 10.0f);
  return 1.0f - t * t * (3.0f - 2.0f * t);
}

// Samples for a neighbourhood max |V| of sqrt(l2) pixels: about one per pixel of the streak.
int sample_count(float l2) {
  return std::min(2 * int(std::ceil(std::sqrt(l2))) + 1, MotionBlurPass::kSamples);
}

// The depth/speed plane (2 halves per pixel) of the whole image.
std::vector<uint16_t> ref_depth_speed(const Inputs& in, float shutter);

// Quiet blocks: a 4x4 pixel block whose blocks within reach (ceil(|V_max|) + 1 px, inside the
// tile's 3x3 neighbourhood) all have blur radii <= 0.95 px is copied (the filter would return
// the pixels themselves up to rounding: every sample 1 px or more away gets weight 0).
bool quiet_block(const std::vector<uint16_t>& zs, V2 vn, uint32_t w, uint32_t h, uint32_t x,
                 uint32_t y) {
  auto block_speed = [&](int bx, int by) {
    float m = 0.0f;
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const int px = std::min(4 * bx + i, int(w) - 1), py = std::min(4 * by + j, int(h) - 1);
        m = std::max(m, half_to_float(zs[2 * (size_t(py) * w + size_t(px)) + 1]));
      }
    return m;
  };
  const int x0 = int(x / 4 * 4), y0 = int(y / 4 * 4);
  const int tx = x0 / int(kTile), ty = y0 / int(kTile);
  const int reach = int(std::ceil(std::sqrt(len2(vn)))) + 1;
  const int bx_lo = std::max(std::max(x0 - reach, 0) / 4, 5 * (tx - 1));
  const int bx_hi = std::min(std::min(x0 + 3 + reach, int(w) - 1) / 4, 5 * (tx + 2) - 1);
  const int by_lo = std::max(std::max(y0 - reach, 0) / 4, 5 * (ty - 1));
  const int by_hi = std::min(std::min(y0 + 3 + reach, int(h) - 1) / 4, 5 * (ty + 2) - 1);
  float m = 0.0f;
  for (int by = by_lo; by <= by_hi; ++by)
    for (int bx = bx_lo; bx <= bx_hi; ++bx) m = std::max(m, block_speed(bx, by));
  return m <= 0.95f;
}

// The reconstruction filter over the neighbourhood max `nmax` (the device's, checked exactly by
// the tests above) and the reference depth/speed plane `zs`.
std::vector<V4> ref_reconstruct(const std::vector<V4>& hdr, const std::vector<uint16_t>& zs,
                                const std::vector<V2>& nmax, uint32_t w, uint32_t h) {
  const uint32_t tx = (w + kTile - 1) / kTile;
  std::vector<V4> out(hdr.size());
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const uint32_t i = y * w + x;
      const V2 vn = nmax[(y / kTile) * tx + x / kTile];
      if (len2(vn) <= 0.25f || quiet_block(zs, vn, w, h, x, y)) {
        out[i] = hdr[i];
        continue;
      }
      const float zx = half_to_float(zs[2 * i]), speed_x = std::max(half_to_float(zs[2 * i + 1]), 0.5f);
      float weight = 1.0f / speed_x;
      V4 sum{hdr[i].x * weight, hdr[i].y * weight, hdr[i].z * weight, hdr[i].w * weight};
      const float j = jitter(x, y);
      const float px = float(x) + 0.5f, py = float(y) + 0.5f;
      const int n = sample_count(len2(vn));
      const float step = 2.0f / float(n + 1);
      for (int s = 0; s < n; ++s) {
        if (s == (n - 1) / 2) continue;
        const float t = (float(s) + 1.0f + j) * step - 1.0f;
        const float ox = vn.x * t, oy = vn.y * t;
        const int sx = std::clamp(int(std::floor(px + ox)), 0, int(w) - 1);
        const int sy = std::clamp(int(std::floor(py + oy)), 0, int(h) - 1);
        const uint32_t k = uint32_t(sy) * w + uint32_t(sx);
        const float zy = half_to_float(zs[2 * k]), speed_y = std::max(half_to_float(zs[2 * k + 1]), 0.5f);
        const float ddx = float(sx) - float(x), ddy = float(sy) - float(y);
        const float dist = std::sqrt(ddx * ddx + ddy * ddy);
        const float q_y = dist / speed_y, q_x = dist / speed_x;
        const float alpha = soft_depth(zy, zx) * cone(q_y) + soft_depth(zx, zy) * cone(q_x) +
                            cylinder(q_y) * cylinder(q_x) * 2.0f;
        weight += alpha;
        sum = {sum.x + hdr[k].x * alpha, sum.y + hdr[k].y * alpha, sum.z + hdr[k].z * alpha,
               sum.w + hdr[k].w * alpha};
      }
      out[i] = {sum.x / weight, sum.y / weight, sum.z / weight, sum.w / weight};
    }
  return out;
}

std::vector<uint16_t> ref_depth_speed(const Inputs& in, float shutter) {
  std::vector<uint16_t> zs(2 * in.depth.size());
  for (size_t i = 0; i < in.depth.size(); ++i) {
    zs[2 * i] = float_to_half(std::min(std::max(in.depth[i], 0.0f), 60000.0f));
    zs[2 * i + 1] = float_to_half(std::sqrt(len2(clamp_radius(half_vector(in.velocity[i], shutter)))));
  }
  return zs;
}

// --- device ----------------------------------------------------------------------------------

struct Outputs {
  std::vector<V2> tile_max, neighbour_max;
  std::vector<uint16_t> depth_speed;
  std::vector<V4> hdr;
};

// Runs the pass on `in`. With `prime` (same size), runs it on `prime` first with the same pass
// object, so its intermediate buffers hold another frame's values (stale data must not leak).
Outputs run_device(const Inputs& in, float shutter, const Inputs* prime = nullptr) {
  auto& ctx = rp::test::context();
  const size_t n = size_t(in.w) * in.h;
  rp::render::GBuffer g;
  g.resize(ctx.context, in.w, in.h);
  ::cl::Buffer hdr_in(ctx.context, CL_MEM_READ_WRITE, n * 16), hdr_out(ctx.context, CL_MEM_READ_WRITE, n * 16);
  auto upload = [&](const Inputs& frame) {
    std::vector<V4> nd(n);
    for (size_t i = 0; i < n; ++i) nd[i] = {0.0f, 0.0f, 1.0f, frame.depth[i]};
    ctx.queue.enqueueWriteBuffer(g.velocity, CL_TRUE, 0, n * 8, frame.velocity.data());
    ctx.queue.enqueueWriteBuffer(g.normal_depth, CL_TRUE, 0, n * 16, nd.data());
    ctx.queue.enqueueWriteBuffer(hdr_in, CL_TRUE, 0, n * 16, frame.hdr.data());
  };
  rp::cl::Profiler profiler(ctx.queue);
  MotionBlurPass pass(ctx, rp::test::programs());
  if (prime) {
    upload(*prime);
    pass.run(profiler, hdr_in, g, in.w, in.h, shutter, hdr_out);
  }
  upload(in);
  pass.run(profiler, hdr_in, g, in.w, in.h, shutter, hdr_out);
  EXPECT_EQ(profiler.collect().count(rp::passes::pass_name::kMotionBlur), 1u);
  Outputs out;
  const size_t tiles = size_t(pass.tiles_x()) * pass.tiles_y();
  out.tile_max.resize(tiles);
  out.neighbour_max.resize(tiles);
  out.depth_speed.resize(2 * n);
  out.hdr.resize(n);
  ctx.queue.enqueueReadBuffer(pass.tile_max(), CL_TRUE, 0, tiles * 8, out.tile_max.data());
  ctx.queue.enqueueReadBuffer(pass.neighbour_max(), CL_TRUE, 0, tiles * 8, out.neighbour_max.data());
  ctx.queue.enqueueReadBuffer(pass.depth_speed(), CL_TRUE, 0, n * 4, out.depth_speed.data());
  ctx.queue.enqueueReadBuffer(hdr_out, CL_TRUE, 0, n * 16, out.hdr.data());
  return out;
}

// Deterministic pseudo-random inputs. Velocity components are integers in [-range, range], so
// with shutter 1 the half vectors are exact and many magnitudes tie ((3,4), (5,0), (0,-5), ...).
Inputs make_inputs(uint32_t w, uint32_t h, int range, uint32_t seed) {
  Inputs in;
  in.w = w;
  in.h = h;
  const size_t n = size_t(w) * h;
  uint32_t state = seed;
  auto next = [&state] { return state = hash_u32(state + 0x9E3779B9u); };
  for (size_t i = 0; i < n; ++i) {
    const int vx = int(next() % uint32_t(2 * range + 1)) - range;
    const int vy = int(next() % uint32_t(2 * range + 1)) - range;
    in.velocity.push_back({float(vx), float(vy)});
    in.depth.push_back(2.0f + float(next() % 4096u) / 1024.0f);
    in.hdr.push_back({float(next() % 1000u) / 250.0f, float(next() % 1000u) / 500.0f,
                      float(next() % 1000u) / 1000.0f, 1.0f});
  }
  return in;
}

TEST(MotionBlurKernels, TileMaxExactWithTies) {
  // 67x45: partial tiles on the right and bottom; |V| <= 6 * sqrt(2) / 2 * 2 (no clamp).
  Inputs in = make_inputs(67, 45, 6, 1u);
  // Explicit ties inside tile (1, 0): (6,8) at a higher index than (-10,0) and (0,10): the
  // lowest index (the (0,10) at row 2) must win over the later ones.
  auto at = [&](uint32_t x, uint32_t y) -> V2& { return in.velocity[y * in.w + x]; };
  at(30, 2) = {0.0f, 10.0f};
  at(25, 7) = {-10.0f, 0.0f};
  at(21, 15) = {6.0f, 8.0f};
  const Outputs out = run_device(in, 1.0f);
  const auto ref = ref_tile_max(in.velocity, in.w, in.h, 1.0f);
  ASSERT_EQ(out.tile_max.size(), ref.size());
  EXPECT_EQ(ref[1].x, 0.0f);
  EXPECT_EQ(ref[1].y, 5.0f);
  int ties = 0;
  for (size_t t = 0; t < ref.size(); ++t) {
    EXPECT_TRUE(out.tile_max[t] == ref[t]) << "tile " << t << ": got (" << out.tile_max[t].x << ", "
                                           << out.tile_max[t].y << ") want (" << ref[t].x << ", "
                                           << ref[t].y << ")";
    ties += len2(ref[t]) == 25.0f;
  }
  EXPECT_GT(ties, 0);  // the inputs do exercise ties
}

TEST(MotionBlurKernels, TileMaxClampsToTwentyPixels) {
  Inputs in = make_inputs(45, 41, 70, 2u);  // half vectors up to 35 px per axis
  const Outputs out = run_device(in, 1.0f);
  const auto ref = ref_tile_max(in.velocity, in.w, in.h, 1.0f);
  for (size_t t = 0; t < ref.size(); ++t) {
    // sqrt and division may be a few ulp off on some devices: 1e-6 relative.
    EXPECT_NEAR(out.tile_max[t].x, ref[t].x, 1e-6f * kMaxRadius) << "tile " << t;
    EXPECT_NEAR(out.tile_max[t].y, ref[t].y, 1e-6f * kMaxRadius) << "tile " << t;
    EXPECT_LE(std::sqrt(len2(out.tile_max[t])), kMaxRadius * (1.0f + 1e-6f));
  }
}

TEST(MotionBlurKernels, NeighbourMaxExactWithTies) {
  // Constant velocity per tile from a set with equal magnitudes (ties across tiles).
  const uint32_t w = 7 * kTile - 3, h = 5 * kTile - 9;
  const V2 set[] = {{0, 0}, {6, 8}, {-10, 0}, {0, 10}, {8, -6}, {2, 2}, {-8, 6}, {12, 0}};
  Inputs in = make_inputs(w, h, 1, 3u);
  uint32_t state = 77u;
  std::vector<V2> per_tile(7 * 5);
  for (auto& v : per_tile) v = set[(state = hash_u32(state)) % 8u];
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) in.velocity[y * w + x] = per_tile[(y / kTile) * 7 + x / kTile];
  const Outputs out = run_device(in, 1.0f);
  const auto tiles = ref_tile_max(in.velocity, w, h, 1.0f);
  const auto ref = ref_neighbour_max(tiles, 7, 5);
  for (size_t t = 0; t < ref.size(); ++t) {
    EXPECT_TRUE(out.tile_max[t] == tiles[t]) << "tile " << t;
    EXPECT_TRUE(out.neighbour_max[t] == ref[t])
        << "tile " << t << ": got (" << out.neighbour_max[t].x << ", " << out.neighbour_max[t].y
        << ") want (" << ref[t].x << ", " << ref[t].y << ")";
  }
}

TEST(MotionBlurKernels, DepthSpeedPlaneRoundTrip) {
  Inputs in = make_inputs(53, 37, 50, 4u);
  in.depth[0] = 1e9f;  // beyond half range: stored as the clamp depth, not infinity
  const float shutter = 0.37f;
  const Outputs out = run_device(in, shutter);
  const auto ref = ref_depth_speed(in, shutter);
  for (size_t i = 0; i < in.depth.size(); ++i) {
    const float depth = std::min(in.depth[i], 60000.0f);
    const float speed = std::sqrt(len2(clamp_radius(half_vector(in.velocity[i], shutter))));
    EXPECT_EQ(out.depth_speed[2 * i], ref[2 * i]) << "pixel " << i;
    EXPECT_NEAR(half_to_float(out.depth_speed[2 * i]), depth, depth * (1.0f / 2048.0f));
    EXPECT_NEAR(half_to_float(out.depth_speed[2 * i + 1]), speed, speed * (1.0f / 2048.0f) + 1e-6f)
        << "pixel " << i;
  }
}

// A depth/speed plane brought with the inputs (temporal upsampling makes one) is read as the
// pass's own: the pass's plane handed to a second pass gives the same image, bit for bit, and
// the second pass makes none.
TEST(MotionBlurKernels, APlaneBroughtAlongIsReadAsItsOwn) {
  const Inputs in = make_inputs(61, 43, 12, 9u);
  const float shutter = 0.7f;
  const Outputs own = run_device(in, shutter);
  auto& ctx = rp::test::context();
  const size_t n = size_t(in.w) * in.h;
  ::cl::Buffer velocity(ctx.context, CL_MEM_READ_WRITE, n * 8);
  ::cl::Buffer plane(ctx.context, CL_MEM_READ_WRITE, n * 4);
  ::cl::Buffer hdr_in(ctx.context, CL_MEM_READ_WRITE, n * 16);
  ::cl::Buffer hdr_out(ctx.context, CL_MEM_READ_WRITE, n * 16);
  ctx.queue.enqueueWriteBuffer(velocity, CL_TRUE, 0, n * 8, in.velocity.data());
  ctx.queue.enqueueWriteBuffer(plane, CL_TRUE, 0, n * 4, own.depth_speed.data());
  ctx.queue.enqueueWriteBuffer(hdr_in, CL_TRUE, 0, n * 16, in.hdr.data());
  rp::passes::MotionInputs motion;
  motion.width = in.w;
  motion.height = in.h;
  motion.velocity = &velocity;
  motion.depth_speed = &plane;
  motion.plane_shutter = shutter;
  MotionBlurPass pass(ctx, rp::test::programs());
  rp::cl::Profiler profiler(ctx.queue);
  pass.run(profiler, hdr_in, motion, in.w, in.h, shutter, hdr_out);
  profiler.collect();
  std::vector<V4> hdr(n);
  ctx.queue.enqueueReadBuffer(hdr_out, CL_TRUE, 0, n * 16, hdr.data());
  size_t moved = 0;
  for (size_t i = 0; i < n; ++i) {
    EXPECT_EQ(std::memcmp(&hdr[i], &own.hdr[i], sizeof(V4)), 0) << "pixel " << i;
    moved += std::memcmp(&hdr[i], &in.hdr[i], sizeof(V4)) != 0;
  }
  EXPECT_GT(moved, n / 2);  // the blur did run
  EXPECT_EQ(pass.frame_device_bytes(), MotionBlurPass::frame_bytes(in.w, in.h, false));
  // a plane made for another shutter, or no depth at all: refused
  motion.plane_shutter = 0.5f;
  EXPECT_THROW(pass.run(profiler, hdr_in, motion, in.w, in.h, shutter, hdr_out), rp::cl::Error);
  motion.depth_speed = nullptr;
  EXPECT_THROW(pass.run(profiler, hdr_in, motion, in.w, in.h, shutter, hdr_out), rp::cl::Error);
  profiler.collect();
}

TEST(MotionBlurKernels, HalfConversionReferenceIsRoundToNearestEven) {
  // The reference converter itself, on values with known encodings.
  EXPECT_EQ(float_to_half(1.0f), 0x3C00u);
  EXPECT_EQ(float_to_half(65504.0f), 0x7BFFu);
  EXPECT_EQ(float_to_half(1.0f + 1.0f / 2048.0f), 0x3C00u);          // tie -> even (down)
  EXPECT_EQ(float_to_half(1.0f + 3.0f / 2048.0f), 0x3C02u);          // tie -> even (up)
  EXPECT_EQ(float_to_half(std::ldexp(1.0f, -24)), 0x0001u);          // smallest subnormal
  EXPECT_EQ(half_to_float(0x3555u), 0.333251953125f);
}

TEST(MotionBlurKernels, SampleCountFollowsTheStreakLength) {
  EXPECT_EQ(sample_count(0.2601f), 3);   // 0.51 px
  EXPECT_EQ(sample_count(1.0f), 3);      // 1 px
  EXPECT_EQ(sample_count(1.0201f), 5);   // 1.01 px
  EXPECT_EQ(sample_count(12.25f), 9);    // 3.5 px
  EXPECT_EQ(sample_count(49.0f), 15);    // 7 px
  EXPECT_EQ(sample_count(400.0f), 15);   // the clamp
}

TEST(MotionBlurKernels, ReconstructionMatchesReference) {
  // Random colours and depths, still background, moving blocks at different depths and speeds
  // (sample counts 3 .. 15), one partly outside the image.
  const uint32_t w = 143, h = 101;
  Inputs in = make_inputs(w, h, 0, 5u);
  struct Block {
    uint32_t x0, y0, x1, y1;
    V2 v;
    float depth;
  };
  const Block blocks[] = {{10, 10, 25, 22, {14, 3}, 1.5f},
                          {40, 30, 52, 50, {-5, 20}, 2.5f},
                          {60, 5, 70, 15, {90, -40}, 1.0f},  // clamped to 20 px
                          {95, 10, 105, 18, {2, 1}, 2.0f},   // 0.9 px: 3 samples
                          {90, 60, 112, 75, {-4, 3}, 1.2f},  // 2 px: 5 samples
                          {125, 80, 143, 101, {7, 7}, 3.0f}};  // at the corner
  for (const Block& b : blocks)
    for (uint32_t y = b.y0; y < b.y1; ++y)
      for (uint32_t x = b.x0; x < b.x1; ++x) {
        in.velocity[y * w + x] = b.v;
        in.depth[y * w + x] = b.depth;
      }
  // Primed with a frame of other depths and motion everywhere: the pass must rewrite every part
  // of its depth/speed plane that this frame's reconstruction reads.
  // Its pixels are nearer and fast, so a stale sample would count as a blurred foreground.
  Inputs other = make_inputs(w, h, 30, 6u);
  for (float& d : other.depth) d = 0.5f;
  const Outputs out = run_device(in, 0.8f, &other);
  const auto ref = ref_reconstruct(in.hdr, ref_depth_speed(in, 0.8f), out.neighbour_max, w, h);
  int changed = 0, copied = 0;
  for (size_t i = 0; i < ref.size(); ++i) {
    const float* got = &out.hdr[i].x;
    const float* want = &ref[i].x;
    for (int c = 0; c < 4; ++c)
      ASSERT_NEAR(got[c], want[c], 1e-5f * std::max(1.0f, std::fabs(want[c])))
          << "pixel " << i % w << "," << i / w << " channel " << c;
    const bool same = std::memcmp(&out.hdr[i], &in.hdr[i], 16) == 0;
    changed += !same;
    copied += same;
  }
  EXPECT_GT(changed, 500);  // the filter did run ...
  EXPECT_GT(copied, 500);   // ... and skipped the still tiles
  // Quiet blocks inside moving tiles are copied bit for bit too.
  const uint32_t tx = (w + kTile - 1) / kTile;
  const std::vector<uint16_t> zs = ref_depth_speed(in, 0.8f);
  int quiet = 0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const V2 vn = out.neighbour_max[(y / kTile) * tx + x / kTile];
      if (len2(vn) > 0.25f && quiet_block(zs, vn, w, h, x, y)) {
        ++quiet;
        ASSERT_EQ(std::memcmp(&out.hdr[y * w + x], &in.hdr[y * w + x], 16), 0) << x << "," << y;
      }
    }
  EXPECT_GT(quiet, 500);
}

}  // namespace
