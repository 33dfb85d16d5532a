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

float tone(float x) {
  x = std::min(std::max(x, 0.0f), 1.0e30f);
  return x / (1.0f + x);
}
float tone_inverse(float y) {
  y = std::clamp(y, 0.0f, 65535.0f / 65536.0f);
  return y / (1.0f - y);
}
glm::vec3 tone(glm::vec3 c) { return {tone(c.x), tone(c.y), tone(c.z)}; }

glm::vec3 to_ycocg(glm::vec3 c) {
  return {0.25f * c.x + 0.5f * c.y + 0.25f * c.z, 0.5f * c.x - 0.5f * c.z,
          -0.25f * c.x + 0.5f * c.y - 0.25f * c.z};
}
glm::vec3 from_ycocg(glm::vec3 c) {
  const float y = c.x, co = c.y, cg = c.z;
  return {y + co - cg, y + cg, y - co - cg};
}

glm::vec3 clip_to_box(glm::vec3 q, glm::vec3 centre, glm::vec3 extent) {
  // Scale the offset from the centre down until its largest normalised component is 1.
  glm::vec3 d = q - centre;
  float largest = 0.0f;
  for (int c = 0; c < 3; ++c)
    largest = std::max(largest, std::abs(d[c]) / std::max(extent[c], 1.0e-6f));
  if (largest <= 1.0f) return q;
  return centre + d / largest;
}

glm::vec3 bilinear(const std::vector<glm::vec3>& plane, uint32_t w, uint32_t h, glm::vec2 pos) {
  const float x = std::clamp(pos.x - 0.5f, 0.0f, float(w - 1));
  const float y = std::clamp(pos.y - 0.5f, 0.0f, float(h - 1));
  const uint32_t x0 = uint32_t(x), y0 = uint32_t(y);
  const uint32_t x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
  const float fx = x - float(x0), fy = y - float(y0);
  auto at = [&](uint32_t px, uint32_t py) { return plane[size_t(py) * w + px]; };
  return (at(x0, y0) * (1 - fx) + at(x1, y0) * fx) * (1 - fy) +
         (at(x0, y1) * (1 - fx) + at(x1, y1) * fx) * fy;
}

std::vector<glm::vec3> Reference::resolve(const Frame& f) {
  const uint32_t w = f.width, h = f.height;
  if (w != width_ || h != height_) history_.clear();
  width_ = w;
  height_ = h;
  std::vector<glm::vec3> mapped(size_t(w) * h), raw(mapped.size());
  for (size_t i = 0; i < mapped.size(); ++i) {
    raw[i] = glm::vec3(f.hdr[i]);
    mapped[i] = tone(raw[i]);
  }

  std::vector<glm::vec3> out(mapped.size());
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      // Centre, left, right, up, down, clamped at the borders.
      const size_t taps[5] = {i, size_t(y) * w + (x > 0 ? x - 1 : 0),
                              size_t(y) * w + std::min(x + 1, w - 1),
                              size_t(y > 0 ? y - 1 : 0) * w + x,
                              size_t(std::min(y + 1, h - 1)) * w + x};
      glm::vec3 mean(0.0f), mean_sq(0.0f);
      for (size_t t : taps) {
        glm::vec3 v = to_ycocg(mapped[t]);
        mean += v;
        mean_sq += v * v;
      }
      mean /= 5.0f;
      mean_sq /= 5.0f;
      glm::vec3 stddev = glm::sqrt(glm::max(mean_sq - mean * mean, glm::vec3(0.0f)));

      const glm::vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
      glm::vec3 current = mapped[i];
      // Unjittered: bilinear in HDR, then tone mapped (as documented in kernels/taa.cl).
      if (settings_.unjitter_current) current = tone(bilinear(raw, w, h, centre + f.jitter));
      size_t nearest = i;
      for (size_t t : taps)
        if (f.depth[t] < f.depth[nearest]) nearest = t;
      const glm::vec2 prev = centre - f.velocity[nearest];
      const bool on_screen =
          prev.x >= 0.0f && prev.y >= 0.0f && prev.x <= float(w) && prev.y <= float(h);
      glm::vec3 result = current;
      if (!history_.empty() && on_screen) {
        glm::vec3 hist = bilinear(history_, w, h, prev);
        hist = from_ycocg(clip_to_box(to_ycocg(hist), mean, settings_.gamma * stddev));
        result = glm::clamp(hist * settings_.history_weight +
                                current * (1.0f - settings_.history_weight),
                            0.0f, 1.0f);
      }
      out[i] = result;
    }
  }
  history_ = out;
  return out;
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
  }
  std::vector<glm::vec4> normal_depth(n);
  for (size_t i = 0; i < n; ++i) normal_depth[i] = glm::vec4(0.0f, 0.0f, 1.0f, f.depth[i]);
  ctx.queue.enqueueWriteBuffer(hdr_in_, CL_TRUE, 0, n * 16, f.hdr.data());
  ctx.queue.enqueueWriteBuffer(gbuffer_.velocity, CL_TRUE, 0, n * 8, f.velocity.data());
  ctx.queue.enqueueWriteBuffer(gbuffer_.normal_depth, CL_TRUE, 0, n * 16, normal_depth.data());
  scene_->constants.width = f.width;
  scene_->constants.height = f.height;
  scene_->constants.jitter = {f.jitter.x, f.jitter.y, 0.0f, 0.0f};
  rp::cl::Profiler profiler(ctx.queue);
  pass_->run(profiler, *scene_, hdr_in_, gbuffer_, hdr_out_);
  rp::cl::PassTimes times = profiler.collect();
  last_ms_ = times.count("taa") ? times.at("taa") : -1.0;
  std::vector<glm::vec4> out(n);
  ctx.queue.enqueueReadBuffer(hdr_out_, CL_TRUE, 0, n * 16, out.data());
  return out;
}

}  // namespace rp::test::taa
