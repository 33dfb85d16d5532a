// Temporal upsampling (kernels/taa_upsample.cl, passes/taa_upsample.h) against a plain C++
// reference written from the kernel's header comment (double precision, one output pixel at a
// time), and what it is for: jittered frames rendered at half size converge to the full-size
// picture, closer than any single frame's upscale; and the motion blur's depth/speed plane it
// writes beside its velocity.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "cl/error.h"
#include "passes/motion_blur.h"
#include "passes/taa_upsample.h"
#include "render/gpu_scene.h"
#include "support/cl_fixture.h"
#include "taa_reference.h"

namespace rp::test {
namespace {

namespace taa = rp::test::taa;

// One frame at the render size.
struct LowFrame {
  uint32_t width = 0, height = 0;
  std::vector<glm::vec4> hdr;
  std::vector<glm::vec2> velocity;  // render pixels
  std::vector<float> depth;         // linear depth (normal_depth.w)
  glm::vec2 jitter{0.0f};           // render pixels
};

double weight(double d2) {
  const double t = std::max(0.0, 1.0 - 0.7 * d2);
  return t * t;
}

// The algorithm of kernels/taa_upsample.cl, step by step; history in tone-mapped rgb.
class Reference {
 public:
  Reference(uint32_t ow, uint32_t oh, passes::TaaSettings s) : ow_(ow), oh_(oh), s_(s) {}

  std::vector<glm::vec3> resolve(const LowFrame& f) {
    const int rw = int(f.width), rh = int(f.height), ow = int(ow_), oh = int(oh_);
    const double sx = double(rw) / ow, sy = double(rh) / oh;
    std::vector<glm::vec3> out(size_t(ow) * oh);
    for (int oy = 0; oy < oh; ++oy)
      for (int ox = 0; ox < ow; ++ox) {
        const double px = (ox + 0.5) * sx, py = (oy + 0.5) * sy;
        const int cx = std::clamp(int(std::floor(px + f.jitter.x)), 0, rw - 1);
        const int cy = std::clamp(int(std::floor(py + f.jitter.y)), 0, rh - 1);
        // the samples within reach: the 2x2 around p where the weight's reach, sqrt(1 / 0.7)
        // output pixels, is under a render pixel, else the 3x3 around the nearest
        const bool two = sx * std::sqrt(1.0 / 0.7) < 1.0 && sy * std::sqrt(1.0 / 0.7) < 1.0;
        const int bx = two ? int(std::floor(px + f.jitter.x - 0.5)) : cx - 1;
        const int by = two ? int(std::floor(py + f.jitter.y - 0.5)) : cy - 1;
        const int taps = two ? 2 : 3;
        glm::dvec3 sum(0.0), m1(0.0), m2(0.0);
        double sum_w = 0.0, max_w = 0.0, near = INFINITY;
        glm::dvec2 v(0.0);
        for (int dy = 0; dy < taps; ++dy)
          for (int dx = 0; dx < taps; ++dx) {
            const int x = std::clamp(bx + dx, 0, rw - 1), y = std::clamp(by + dy, 0, rh - 1);
            const size_t i = size_t(y) * rw + x;
            const glm::dvec3 c = glm::dvec3(taa::tone(glm::vec3(f.hdr[i])));
            const double ddx = (x + 0.5 - f.jitter.x - px) / sx;
            const double ddy = (y + 0.5 - f.jitter.y - py) / sy;
            const double w = weight(ddx * ddx + ddy * ddy);
            sum_w += w;
            max_w = std::max(max_w, w);
            sum += w * c;
          }
        // the neighbourhood box and the nearest surface's velocity: the 3x3 around the nearest
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int x = std::clamp(cx + dx, 0, rw - 1), y = std::clamp(cy + dy, 0, rh - 1);
            const size_t i = size_t(y) * rw + x;
            const glm::dvec3 c = glm::dvec3(taa::tone(glm::vec3(f.hdr[i])));
            const glm::dvec3 ycc = glm::dvec3(taa::to_ycocg(glm::vec3(c)));
            m1 += ycc;
            m2 += ycc * ycc;
            if (f.depth[i] < near) {
              near = f.depth[i];
              v = glm::dvec2(f.velocity[i]);
            }
          }
        const size_t nearest = size_t(cy) * rw + cx;
        const glm::dvec3 current =
            sum_w > 1e-6 ? sum / sum_w : glm::dvec3(taa::tone(glm::vec3(f.hdr[nearest])));
        const glm::dvec2 motion(v.x / sx, v.y / sy);
        const glm::dvec2 h(ox + 0.5 - motion.x, oy + 0.5 - motion.y);
        glm::dvec3 result = current;
        if (!history_.empty() && h.x >= 0 && h.y >= 0 && h.x <= ow && h.y <= oh) {
          glm::dvec3 mean = m1 / 9.0;
          const glm::dvec3 var = glm::max(m2 / 9.0 - mean * mean, glm::dvec3(0.0));
          glm::dvec3 extent = double(s_.gamma) * glm::sqrt(var);
          // grown to hold the current colour
          const glm::dvec3 c = glm::dvec3(taa::to_ycocg(glm::vec3(current)));
          const glm::dvec3 lo = glm::min(mean - extent, c), hi = glm::max(mean + extent, c);
          mean = 0.5 * (lo + hi);
          extent = 0.5 * (hi - lo);
          const glm::vec3 hist = taa::bilinear(history_, ow_, oh_, glm::vec2(h));
          const glm::dvec3 q = glm::dvec3(taa::from_ycocg(
              taa::clip_to_box(taa::to_ycocg(hist), glm::vec3(mean), glm::vec3(extent))));
          const double k = (1.0 - s_.history_weight) * max_w;
          result = glm::clamp(q + (current - q) * k, glm::dvec3(0.0), glm::dvec3(1.0));
        }
        out[size_t(oy) * ow + ox] = glm::vec3(result);
      }
    history_ = out;
    return out;
  }

 private:
  uint32_t ow_, oh_;
  passes::TaaSettings s_;
  std::vector<glm::vec3> history_;
};

// Runs the real pass on host frames.
class Harness {
 public:
  Harness(uint32_t ow, uint32_t oh) : ow_(ow), oh_(oh) {
    auto& ctx = context();
    scene_ = std::make_unique<render::GpuScene>(ctx.context, ctx.queue, scene::SceneAssets{});
    pass_ = std::make_unique<passes::TaaUpsamplePass>(ctx, programs());
    out_ = ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, size_t(ow) * oh * 16);
  }
  passes::TaaUpsamplePass& pass() { return *pass_; }

  std::vector<glm::vec4> run(const LowFrame& f) {
    auto& ctx = context();
    const size_t n = size_t(f.width) * f.height;
    if (gbuffer_.width != f.width || gbuffer_.height != f.height) {
      gbuffer_.resize(ctx.context, f.width, f.height);
      hdr_ = ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16);
    }
    std::vector<glm::vec4> nd(n, glm::vec4(0.0f));
    for (size_t i = 0; i < n; ++i) nd[i].w = f.depth[i];
    ctx.queue.enqueueWriteBuffer(hdr_, CL_TRUE, 0, n * 16, f.hdr.data());
    ctx.queue.enqueueWriteBuffer(gbuffer_.velocity, CL_TRUE, 0, n * 8, f.velocity.data());
    ctx.queue.enqueueWriteBuffer(gbuffer_.normal_depth, CL_TRUE, 0, n * 16, nd.data());
    scene_->constants.width = f.width;
    scene_->constants.height = f.height;
    scene_->constants.jitter = {f.jitter.x, f.jitter.y, 0.0f, 0.0f};
    rp::cl::Profiler profiler(ctx.queue);
    pass_->run(profiler, *scene_, hdr_, gbuffer_, ow_, oh_, out_);
    profiler.collect();
    std::vector<glm::vec4> out(size_t(ow_) * oh_);
    ctx.queue.enqueueReadBuffer(out_, CL_TRUE, 0, out.size() * 16, out.data());
    return out;
  }

 private:
  uint32_t ow_, oh_;
  std::unique_ptr<render::GpuScene> scene_;
  std::unique_ptr<passes::TaaUpsamplePass> pass_;
  render::GBuffer gbuffer_;
  ::cl::Buffer hdr_, out_;
};

LowFrame random_frame(uint32_t w, uint32_t h, std::mt19937& rng, float max_velocity) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  LowFrame f;
  f.width = w;
  f.height = h;
  const size_t n = size_t(w) * h;
  f.hdr.resize(n);
  f.velocity.resize(n);
  f.depth.resize(n);
  for (size_t i = 0; i < n; ++i) {
    f.hdr[i] = {4.0f * u(rng), 4.0f * u(rng), 4.0f * u(rng), u(rng)};
    f.velocity[i] = {max_velocity * (2.0f * u(rng) - 1.0f), max_velocity * (2.0f * u(rng) - 1.0f)};
    f.depth[i] = 1.0f + 9.0f * u(rng);
  }
  f.jitter = {u(rng) - 0.5f, u(rng) - 0.5f};
  return f;
}

// Worst difference of tone-mapped values (the pass's hdr_out mapped back) from the reference.
float worst_difference(const std::vector<glm::vec4>& out, const std::vector<glm::vec3>& ref) {
  float worst = 0.0f;
  for (size_t i = 0; i < out.size(); ++i)
    worst = std::max(worst, glm::length(taa::tone(glm::vec3(out[i])) - ref[i]));
  return worst;
}

// Tone-mapped values in [0, 1); float against double through 9 weighted taps, a clip and the
// history's bilinear tap at float positions (the random histories have steps of up to 1 between
// pixels): measured worst 4.7e-5 on PoCL with motion, 1e-6 without.
constexpr float kTolerance = 1e-4f;

void check_against_reference(uint32_t rw, uint32_t rh, uint32_t ow, uint32_t oh,
                             float max_velocity) {
  std::mt19937 rng(rw * 131 + ow);
  Harness pass(ow, oh);
  Reference ref(ow, oh, pass.pass().settings());
  for (int frame = 0; frame < 4; ++frame) {
    const LowFrame f = random_frame(rw, rh, rng, max_velocity);
    const std::vector<glm::vec4> out = pass.run(f);
    const std::vector<glm::vec3> expected = ref.resolve(f);
    EXPECT_LT(worst_difference(out, expected), kTolerance)
        << rw << "x" << rh << " -> " << ow << "x" << oh << ", frame " << frame;
  }
}

TEST(TaaUpsample, MatchesReferenceAtHalfSize) { check_against_reference(20, 12, 40, 24, 0.0f); }
TEST(TaaUpsample, MatchesReferenceWithMotionAndPartialBlocks) {
  check_against_reference(29, 17, 41, 30, 3.0f);  // scale ~0.7, a last block of 1 pixel
}
TEST(TaaUpsample, MatchesReferenceAtFullSize) { check_against_reference(19, 9, 19, 9, 1.5f); }
TEST(TaaUpsample, MatchesReferenceAboveTheTwoByTwoScale) {
  check_against_reference(36, 18, 40, 20, 2.0f);  // scale 0.9: the 3x3 of samples within reach
}

// A sharp pattern (finer than the render pixels) seen through half-size jittered frames: the
// accumulated output must approach the full-size picture (the pattern box-filtered over each
// output pixel) far better than the first frame, which only has a quarter of the samples.
TEST(TaaUpsample, HalfSizeFramesConvergeToTheFullSizePicture) {
  const uint32_t ow = 64, oh = 48, rw = 32, rh = 24;
  // radiance at a point in output pixels: stripes and a disc
  const auto scene = [](double x, double y) {
    const bool stripe = int(std::floor(x / 3.0)) % 2 == 0;
    const bool disc = (x - 40) * (x - 40) + (y - 20) * (y - 20) < 150;
    return disc ? 2.0 : stripe ? 0.8 : 0.1;
  };
  // the pixels' mean of tone-mapped radiance, 8x8 samples each (TAA averages tone-mapped
  // values)
  std::vector<double> truth(size_t(ow) * oh);
  for (uint32_t y = 0; y < oh; ++y)
    for (uint32_t x = 0; x < ow; ++x) {
      double s = 0.0;
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) s += taa::tone(float(scene(x + (i + 0.5) / 8, y + (j + 0.5) / 8)));
      truth[size_t(y) * ow + x] = s / 64.0;
    }
  Harness pass(ow, oh);
  const uint32_t phases = passes::upsample_jitter_frames(0.5f);
  const auto error = [&](const std::vector<glm::vec4>& out) {  // RMS of the tone-mapped red
    double e = 0.0;
    for (size_t i = 0; i < out.size(); ++i) {
      const double d = taa::tone(out[i].x) - truth[i];
      e += d * d;
    }
    return std::sqrt(e / double(out.size()));
  };
  double first = 0.0, last = 0.0;
  for (uint32_t frame = 0; frame < 4 * phases; ++frame) {
    LowFrame f;
    f.width = rw;
    f.height = rh;
    f.hdr.resize(size_t(rw) * rh);
    f.velocity.assign(f.hdr.size(), glm::vec2(0.0f));
    f.depth.assign(f.hdr.size(), 1.0f);
    // the Halton jitter the renderer uses (render pixels in [-0.5, 0.5))
    const auto halton = [](uint32_t i, uint32_t b) {
      double r = 0.0, s = 1.0;
      for (; i > 0; i /= b) r += (s /= b) * (i % b);
      return r;
    };
    const uint32_t k = frame % phases + 1;
    f.jitter = {float(halton(k, 2) - 0.5), float(halton(k, 3) - 0.5)};
    for (uint32_t y = 0; y < rh; ++y)
      for (uint32_t x = 0; x < rw; ++x) {  // sample at q = i + 0.5 - jitter (render px)
        const double v = scene((x + 0.5 - f.jitter.x) * 2.0, (y + 0.5 - f.jitter.y) * 2.0);
        f.hdr[size_t(y) * rw + x] = glm::vec4(float(v), float(v), float(v), 1.0f);
      }
    const std::vector<glm::vec4> out = pass.run(f);
    if (frame == 0) first = error(out);
    last = error(out);
  }
  std::printf("half-size frames: RMS error of the first %.4f, after %u frames %.4f\n", first,
              4 * phases, last);
  // measured 0.141 -> 0.0665 on PoCL: what remains is the reconstruction's footprint at the
  // stripes' edges (the interior converges to the truth)
  EXPECT_LT(last, 0.55 * first);
  EXPECT_LT(last, 0.08);
}

// With a motion blur shutter set, the pass writes the depth/speed plane (common/depth_speed.h)
// the motion blur pass would make from the pass's output velocity and the depth of the render
// pixel nearest each output pixel: the same bits, halves included.
TEST(TaaUpsample, WritesTheMotionBlurPlaneOfItsVelocity) {
  const uint32_t rw = 29, rh = 17, ow = 41, oh = 30;
  const float shutter = 0.6f;
  std::mt19937 rng(7);
  LowFrame f = random_frame(rw, rh, rng, 3.0f);
  // every output pixel's blur radius over half a pixel, so that the motion blur pass makes its
  // plane in every tile (it skips still ones)
  for (glm::vec2& v : f.velocity) v.x = 2.0f + std::abs(v.x) * (2.0f / 3.0f);
  f.depth[3] = 1e9f;  // beyond the half range: the clamp depth
  Harness pass(ow, oh);
  pass.pass().set_motion_blur_shutter(shutter);
  pass.run(f);
  const passes::MotionInputs motion = pass.pass().motion();
  ASSERT_NE(motion.depth_speed, nullptr);
  EXPECT_EQ(motion.plane_shutter, shutter);
  auto& ctx = context();
  const size_t n = size_t(ow) * oh;
  std::vector<uint32_t> plane(n);
  std::vector<glm::vec2> velocity(n);
  ctx.queue.enqueueReadBuffer(*motion.depth_speed, CL_TRUE, 0, n * 4, plane.data());
  ctx.queue.enqueueReadBuffer(*motion.velocity, CL_TRUE, 0, n * 8, velocity.data());

  // The same velocity and the nearest render pixel's depth through the motion blur pass.
  // Output pixels whose centre lies within 1e-3 render pixels of a render pixel boundary
  // (after the jitter) are left out: float and double may pick different neighbours there.
  render::GBuffer g;
  g.resize(ctx.context, ow, oh);
  std::vector<glm::vec4> nd(n, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
  std::vector<bool> decided(n, true);
  for (uint32_t oy = 0; oy < oh; ++oy)
    for (uint32_t ox = 0; ox < ow; ++ox) {
      const double px = (ox + 0.5) * rw / ow + f.jitter.x, py = (oy + 0.5) * rh / oh + f.jitter.y;
      const auto tie = [](double v) { return std::abs(v - std::round(v)) < 1e-3; };
      const int cx = std::clamp(int(std::floor(px)), 0, int(rw) - 1);
      const int cy = std::clamp(int(std::floor(py)), 0, int(rh) - 1);
      decided[size_t(oy) * ow + ox] = !tie(px) && !tie(py);
      nd[size_t(oy) * ow + ox].w = f.depth[size_t(cy) * rw + size_t(cx)];
    }
  ctx.queue.enqueueWriteBuffer(g.velocity, CL_TRUE, 0, n * 8, velocity.data());
  ctx.queue.enqueueWriteBuffer(g.normal_depth, CL_TRUE, 0, n * 16, nd.data());
  ::cl::Buffer hdr_in(ctx.context, CL_MEM_READ_WRITE, n * 16);
  ::cl::Buffer hdr_out(ctx.context, CL_MEM_READ_WRITE, n * 16);
  std::vector<glm::vec4> black(n, glm::vec4(0.0f));
  ctx.queue.enqueueWriteBuffer(hdr_in, CL_TRUE, 0, n * 16, black.data());
  passes::MotionBlurPass blur(ctx, programs());
  rp::cl::Profiler profiler(ctx.queue);
  blur.run(profiler, hdr_in, g, ow, oh, shutter, hdr_out);
  profiler.collect();
  std::vector<uint32_t> want(n);
  ctx.queue.enqueueReadBuffer(blur.depth_speed(), CL_TRUE, 0, n * 4, want.data());
  size_t compared = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!decided[i]) continue;
    ++compared;
    EXPECT_EQ(plane[i], want[i]) << "output pixel " << i;
  }
  EXPECT_GT(compared, n * 9 / 10);
  // the far render pixel's output pixels hold the clamp depth, 60000 (0x7B53 as a half)
  EXPECT_TRUE(std::any_of(plane.begin(), plane.end(),
                          [](uint32_t v) { return (v & 0xFFFFu) == 0x7B53u; }));

  // A motion blur with another shutter cannot use the plane; without a shutter there is none.
  EXPECT_THROW(blur.run(profiler, hdr_in, motion, ow, oh, 0.5f, hdr_out), rp::cl::Error);
  pass.pass().set_motion_blur_shutter(0.0f);
  pass.run(f);
  EXPECT_EQ(pass.pass().motion().depth_speed, nullptr);
  EXPECT_THROW(blur.run(profiler, hdr_in, pass.pass().motion(), ow, oh, shutter, hdr_out),
               rp::cl::Error);
  profiler.collect();
}

TEST(TaaUpsample, JitterPhasesGrowAsTheScaleFalls) {
  EXPECT_EQ(passes::upsample_jitter_frames(1.0f), 16u);
  EXPECT_EQ(passes::upsample_jitter_frames(0.5f), 32u);
  EXPECT_GE(passes::upsample_jitter_frames(0.7f), 16u);
}

}  // namespace
}  // namespace rp::test
