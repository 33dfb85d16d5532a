// C++ reference of the TAA resolve (kernels/taa.cl, kernels/common/taa.h) and a harness that
// runs the real pass on host images. Written from SPEC 6.7, independently of the kernel code.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "passes/taa.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"

namespace rp::test::taa {

// One frame's inputs, planar row-major, top row first.
struct Frame {
  uint32_t width = 0, height = 0;
  std::vector<glm::vec4> hdr;       // linear HDR (w passed through)
  std::vector<glm::vec2> velocity;  // pixels, current - previous
  std::vector<float> depth;         // per pixel, ordered as the view depth (nearest = least)
  glm::vec2 jitter{0.0f};           // this frame's jitter in pixels
};

// A frame with zero velocity, depth 1 everywhere and no jitter.
Frame still_frame(uint32_t width, uint32_t height, std::vector<glm::vec4> hdr);

float tone(float x);          // x / (1 + x), negative -> 0
float tone_inverse(float y);  // y / (1 - y), y clamped to [0, 65535/65536]
glm::vec3 tone(glm::vec3 c);
glm::vec3 to_ycocg(glm::vec3 c);
glm::vec3 from_ycocg(glm::vec3 c);
glm::vec3 clip_to_box(glm::vec3 q, glm::vec3 centre, glm::vec3 extent);
// Bilinear, clamp to edge, pixel centres at +0.5.
glm::vec3 bilinear(const std::vector<glm::vec3>& plane, uint32_t w, uint32_t h, glm::vec2 pos);

// The resolve, frame after frame, computed in double precision; history in tone-mapped rgb.
class Reference {
 public:
  explicit Reference(passes::TaaSettings settings) : settings_(settings) {}
  // Returns the tone-mapped result of the frame (what the pass keeps as history).
  std::vector<glm::vec3> resolve(const Frame& frame);
  void reset() { history_.clear(); }

 private:
  passes::TaaSettings settings_;
  std::vector<glm::dvec3> history_;  // empty: no history
  uint32_t width_ = 0, height_ = 0;
};

// Runs the real TaaPass on host frames.
class Harness {
 public:
  explicit Harness(passes::TaaSettings settings = {});
  ~Harness();
  // Returns hdr_out (linear HDR float4 per pixel).
  std::vector<glm::vec4> run(const Frame& frame);
  passes::TaaPass& pass() { return *pass_; }
  double last_ms() const { return last_ms_; }

 private:
  std::unique_ptr<render::GpuScene> scene_;
  std::unique_ptr<passes::TaaPass> pass_;
  render::GBuffer gbuffer_;
  ::cl::Buffer hdr_in_, hdr_out_, depth_;  // depth_: a float per pixel (the pass's depth input)
  double last_ms_ = 0.0;
};

}  // namespace rp::test::taa
