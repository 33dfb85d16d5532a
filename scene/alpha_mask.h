// Alpha masks (AlphaMode::kMask) as the host sees them: the path tracer's ray filter, the Embree
// visibility backend and the rasterizer's test reference all ask AlphaMasks::solid, so every
// renderer cuts the same holes. The kernels' side is kernels/common/alpha_mask.h (same rule,
// same bilinear arithmetic on the same bytes).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/frame_scene.h"

namespace rp::scene {

// The four texels of a bilinear lookup at uv of a width x height texture (rows top to bottom,
// texel centres at +0.5, v up) folded by the wrap modes, and the fractions between them.
struct BilinearTaps {
  size_t i00, i10, i01, i11;  // texel indices (row * width + column)
  float fx, fy;
};
BilinearTaps bilinear_taps(int width, int height, TextureWrap wrap_u, TextureWrap wrap_v,
                           glm::vec2 uv);

class AlphaMasks {
 public:
  // Keeps the alpha (byte / 255) of the textures that masked materials read.
  explicit AlphaMasks(const SceneAssets& assets);

  bool any() const { return any_; }
  bool masked(uint32_t material) const {
    return material < materials_.size() && materials_[material].cutoff > 0.0f;
  }
  // False where masked material `material` has a hole at uv: its opacity factor times the
  // texture's bilinear alpha is below the cutoff. True for every other material.
  bool solid(uint32_t material, glm::vec2 uv) const;

 private:
  struct Plane {
    int width = 0, height = 0;
    TextureWrap wrap_u = TextureWrap::kRepeat, wrap_v = TextureWrap::kRepeat;
    std::vector<float> alpha;  // empty: opaque texture (or one no masked material reads)
  };
  struct Mask {
    float opacity = 1.0f;
    float cutoff = 0.0f;  // 0: not masked
    int texture = -1;
  };
  std::vector<Plane> planes_;  // per texture
  std::vector<Mask> materials_;
  bool any_ = false;
};

}  // namespace rp::scene
