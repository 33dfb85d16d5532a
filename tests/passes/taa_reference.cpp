#include "passes/pass_names.h"
#include "taa_reference.h"

#include <algorithm>
#include <cmath>

#include "support/cl_fixture.h"

namespace rp::test::taa {

Frame still_frame(uint32_t width, uint32_t height, std::vector<glm::vec4> hdr) {
  Frame f;
  f.width = width;
  f.height = height;
  f.hdr = std::move(hdr);
  f.velocity.assign(size_t(width) * height, glm::vec2(0.0f));
  f.depth.assign(size_t(width) * height, 1.0f);
  return f;
}

// The helpers are templates so that Reference::resolve can run them in double precision (below)
// while the tests use the float versions declared in the header.
namespace {

namespace pass_name = rp::passes::pass_name;

template <class T>
T tone_t(T x) {
  x = std::min(std::max(x, T(0)), T(1.0e30));
  return x / (T(1) + x);
}

template <class V>
V to_ycocg_t(V c) {
  using T = typename V::value_type;
  return {T(0.25) * c.x + T(0.5) * c.y + T(0.25) * c.z, T(0.5) * c.x - T(0.5) * c.z,
          T(-0.25) * c.x + T(0.5) * c.y - T(0.25) * c.z};
}

template <class V>
V from_ycocg_t(V c) {
  const auto y = c.x, co = c.y, cg = c.z;
  return {y + co - cg, y + cg, y - co - cg};
}

template <class V>
V clip_to_box_t(V q, V centre, V extent) {
  using T = typename V::value_type;
  // Scale the offset from the centre down until its largest normalised component is 1.
  V d = q - centre;
  T largest = 0;
  for (int c = 0; c < 3; ++c)
    largest = std::max(largest, std::abs(d[c]) / std::max(extent[c], T(1.0e-6)));
  if (largest <= T(1)) return q;
  return centre + d / largest;
}

template <class V>
V bilinear_t(const std::vector<V>& plane, uint32_t w, uint32_t h, glm::vec2 pos) {
  using T = typename V::value_type;
  const float x = std::clamp(pos.x - 0.5f, 0.0f, float(w - 1));
  const float y = std::clamp(pos.y - 0.5f, 0.0f, float(h - 1));
  const uint32_t x0 = uint32_t(x), y0 = uint32_t(y);
  const uint32_t x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
  const T fx = T(x - float(x0)), fy = T(y - float(y0));
  auto at = [&](uint32_t px, uint32_t py) { return plane[size_t(py) * w + px]; };
  return (at(x0, y0) * (T(1) - fx) + at(x1, y0) * fx) * (T(1) - fy) +
         (at(x0, y1) * (T(1) - fx) + at(x1, y1) * fx) * fy;
}

}  // namespace

float tone(float x) { return tone_t(x); }
float tone_inverse(float y) {
  y = std::clamp(y, 0.0f, 65535.0f / 65536.0f);
  return y / (1.0f - y);
}
glm::vec3 tone(glm::vec3 c) { return {tone(c.x), tone(c.y), tone(c.z)}; }
glm::vec3 to_ycocg(glm::vec3 c) { return to_ycocg_t(c); }
glm::vec3 from_ycocg(glm::vec3 c) { return from_ycocg_t(c); }
glm::vec3 clip_to_box(glm::vec3 q, glm::vec3 centre, glm::vec3 extent) {
  return clip_to_box_t(q, centre, extent);
}
glm::vec3 bilinear(const std::vector<glm::vec3>& plane, uint32_t w, uint32_t h, glm::vec2 pos) {
  return bilinear_t(plane, w, h, pos);
}

// In double precision: the 5-tap variance E[v^2] - E[v]^2 cancels badly when the neighbours are
// alike, so two float evaluations in different operation orders (this and the kernel) can differ
// by more than either differs from the exact value (measured: 1.5e-5 apart, the kernel 4.5e-6
// from the exact value). Positions and weights stay float, as in the kernel.
std::vector<glm::vec3> Reference::resolve(const Frame& f) {
  using glm::dvec3;
  const uint32_t w = f.width, h = f.height;
  if (w != width_ || h != height_) history_.clear();
  width_ = w;
  height_ = h;
  std::vector<dvec3> mapped(size_t(w) * h), raw(mapped.size());
  for (size_t i = 0; i < mapped.size(); ++i) {
    raw[i] = dvec3(glm::vec3(f.hdr[i]));
    mapped[i] = {tone_t(raw[i].x), tone_t(raw[i].y), tone_t(raw[i].z)};
  }

  std::vector<dvec3> out(mapped.size());
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      // Centre, left, right, up, down, clamped at the borders.
      const size_t taps[5] = {i, size_t(y) * w + (x > 0 ? x - 1 : 0),
                              size_t(y) * w + std::min(x + 1, w - 1),
                              size_t(y > 0 ? y - 1 : 0) * w + x,
                              size_t(std::min(y + 1, h - 1)) * w + x};
      dvec3 mean(0.0), mean_sq(0.0);
      for (size_t t : taps) {
        dvec3 v = to_ycocg_t(mapped[t]);
        mean += v;
        mean_sq += v * v;
      }
      mean /= 5.0;
      mean_sq /= 5.0;
      dvec3 stddev = glm::sqrt(glm::max(mean_sq - mean * mean, dvec3(0.0)));

      const glm::vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
      dvec3 current = mapped[i];
      // Unjittered: bilinear in HDR, then tone mapped (as documented in kernels/taa.cl).
      if (settings_.unjitter_current) {
        const dvec3 s = bilinear_t(raw, w, h, centre + f.jitter);
        current = {tone_t(s.x), tone_t(s.y), tone_t(s.z)};
      }
      size_t nearest = i;
      for (size_t t : taps)
        if (f.depth[t] < f.depth[nearest]) nearest = t;
      const glm::vec2 prev = centre - f.velocity[nearest];
      const bool on_screen =
          prev.x >= 0.0f && prev.y >= 0.0f && prev.x <= float(w) && prev.y <= float(h);
      dvec3 result = current;
      if (!history_.empty() && on_screen) {
        dvec3 hist = bilinear_t(history_, w, h, prev);
        hist = from_ycocg_t(
            clip_to_box_t(to_ycocg_t(hist), mean, double(settings_.gamma) * stddev));
        const double weight = double(settings_.history_weight);
        result = glm::clamp(hist * weight + current * (1.0 - weight), 0.0, 1.0);
      }
      out[i] = result;
    }
  }
  history_ = out;
  std::vector<glm::vec3> result(out.size());
  for (size_t i = 0; i < out.size(); ++i) result[i] = glm::vec3(out[i]);
  return result;
}

Harness::Harness(passes::TaaSettings settings) {
  auto& ctx = rp::test::context();
  scene_ = std::make_unique<render::GpuScene>(ctx.context, ctx.queue, scene::SceneAssets{});
  pass_ = std::make_unique<passes::TaaPass>(ctx, rp::test::programs(), settings);
}

Harness::~Harness() = default;

std::vector<glm::vec4> Harness::run(const Frame& f) {
  auto& ctx = rp::test::context();
  const size_t n = size_t(f.width) * f.height;
  if (gbuffer_.width != f.width || gbuffer_.height != f.height) {
    gbuffer_.resize(ctx.context, f.width, f.height);
    hdr_in_ = ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16);
    hdr_out_ = ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 16);
    depth_ = ::cl::Buffer(ctx.context, CL_MEM_READ_WRITE, n * 4);
  }
  ctx.queue.enqueueWriteBuffer(hdr_in_, CL_TRUE, 0, n * 16, f.hdr.data());
  ctx.queue.enqueueWriteBuffer(gbuffer_.velocity, CL_TRUE, 0, n * 8, f.velocity.data());
  ctx.queue.enqueueWriteBuffer(depth_, CL_TRUE, 0, n * 4, f.depth.data());
  scene_->constants.width = f.width;
  scene_->constants.height = f.height;
  scene_->constants.jitter = {f.jitter.x, f.jitter.y, 0.0f, 0.0f};
  rp::cl::Profiler profiler(ctx.queue);
  pass_->run(profiler, *scene_, hdr_in_, gbuffer_, depth_, hdr_out_);
  rp::cl::PassTimes times = profiler.collect();
  last_ms_ = times.count(pass_name::kTaa) ? times.at(pass_name::kTaa) : -1.0;
  std::vector<glm::vec4> out(n);
  ctx.queue.enqueueReadBuffer(hdr_out_, CL_TRUE, 0, n * 16, out.data());
  return out;
}

}  // namespace rp::test::taa
