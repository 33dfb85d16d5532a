// TAA behaviour on a static scene: a hard-edged disc rendered on the host with the
// pass's own Halton jitter sequence (pixel p of frame k sees the scene at p - jitter_k, as the
// jittered view_proj does), fed through the pass frame after frame. The output settles (the
// difference between consecutive frames drops well below that of the raw jittered input within
// 16 frames) and the edge is closer to a 64x supersampled ground truth than the unjittered
// one-sample image. Errors are measured on tone-mapped values (what TAA averages).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "render/gpu_scene.h"
#include "taa_reference.h"

namespace {

constexpr uint32_t kSize = 32;
constexpr float kInside = 4.0f, kOutside = 0.1f;  // HDR radiance; tone mapped 0.8 and 0.0909

// The scene at unjittered screen position s (pixels): a disc, hard edge.
float scene_at(glm::vec2 s) {
  const glm::vec2 d = s - glm::vec2(15.3f, 16.7f);
  return glm::dot(d, d) < 9.2f * 9.2f ? kInside : kOutside;
}

std::vector<glm::vec4> render(glm::vec2 jitter) {
  std::vector<glm::vec4> img(size_t(kSize) * kSize);
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      const float v = scene_at(glm::vec2(float(x) + 0.5f, float(y) + 0.5f) - jitter);
      img[size_t(y) * kSize + x] = {v, v, v, 1.0f};
    }
  return img;
}

// Mean over 8x8 stratified positions in each pixel of the tone-mapped scene.
std::vector<float> ground_truth() {
  std::vector<float> gt(size_t(kSize) * kSize);
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      double sum = 0.0;
      for (int sy = 0; sy < 8; ++sy)
        for (int sx = 0; sx < 8; ++sx)
          sum += rp::test::taa::tone(scene_at({float(x) + (float(sx) + 0.5f) / 8.0f,
                                               float(y) + (float(sy) + 0.5f) / 8.0f}));
      gt[size_t(y) * kSize + x] = float(sum / 64.0);
    }
  return gt;
}

std::vector<float> mapped_red(const std::vector<glm::vec4>& hdr) {
  std::vector<float> out(hdr.size());
  for (size_t i = 0; i < hdr.size(); ++i) out[i] = rp::test::taa::tone(hdr[i].x);
  return out;
}

float mean_abs_diff(const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) sum += std::abs(a[i] - b[i]);
  return float(sum / double(a.size()));
}

struct Sequence {
  std::vector<float> taa_change, raw_change;  // per frame k >= 1, mean |frame k - frame k-1|
  float taa_error = 0.0f;                     // last frame vs ground truth
};

Sequence run_frames(rp::passes::TaaSettings settings, uint32_t frames) {
  rp::test::taa::Harness gpu(settings);
  Sequence run;
  const std::vector<float> gt = ground_truth();
  std::vector<float> prev_out, prev_raw;
  for (uint32_t k = 0; k < frames; ++k) {
    rp::test::taa::Frame f = rp::test::taa::still_frame(kSize, kSize, {});
    f.jitter = rp::render::taa_jitter_px(k, 16);
    f.hdr = render(f.jitter);
    const std::vector<float> raw = mapped_red(f.hdr), out = mapped_red(gpu.run(f));
    if (k > 0) {
      run.taa_change.push_back(mean_abs_diff(out, prev_out));
      run.raw_change.push_back(mean_abs_diff(raw, prev_raw));
    }
    prev_out = out;
    prev_raw = raw;
    run.taa_error = mean_abs_diff(out, gt);
  }
  return run;
}

TEST(TaaConvergence, StaticEdgeSettlesAndIsSmootherThanOneSample) {
  const std::vector<float> gt = ground_truth();
  const float single_error = mean_abs_diff(mapped_red(render(glm::vec2(0.0f))), gt);
  for (bool unjitter : {false, true}) {
    rp::passes::TaaSettings settings;
    settings.unjitter_current = unjitter;
    const Sequence run = run_frames(settings, 33);
    float raw_mean = 0.0f;
    for (float r : run.raw_change) raw_mean += r / float(run.raw_change.size());
    std::printf("unjitter %d: one-sample error %.5f, TAA error %.5f; raw jittered change %.5f;"
                " TAA change per frame:",
                int(unjitter), double(single_error), double(run.taa_error), double(raw_mean));
    for (float c : run.taa_change) std::printf(" %.4f", double(c));
    std::printf("\n");
    // Settles within 16 frames: every change from frame 16 on is below a quarter of the raw
    // jittered input's mean change (measured: at most 0.19 of it).
    for (size_t k = 15; k < run.taa_change.size(); ++k)
      EXPECT_LT(run.taa_change[k], 0.25f * raw_mean) << "frame " << k + 1;
    // Smoother edge: closer to the supersampled image than the one-sample image. Measured on
    // PoCL: 0.24x with the jittered current sample (it integrates the pixel footprint), 0.65x
    // when the current frame is resampled bilinearly at the unjittered centre (that resampling
    // blurs every frame by up to a pixel-wide tent).
    EXPECT_LT(run.taa_error, (unjitter ? 0.8f : 0.4f) * single_error) << "unjitter " << unjitter;
  }
}

}  // namespace
