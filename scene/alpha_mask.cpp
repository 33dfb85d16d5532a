#include "scene/alpha_mask.h"

#include <algorithm>
#include <cmath>

namespace rp::scene {
namespace {

// Texel coordinate i (any integer) folded into [0, n) by `mode`.
int fold(int i, int n, TextureWrap mode) {
  switch (mode) {
    case TextureWrap::kClampToEdge: return std::clamp(i, 0, n - 1);
    case TextureWrap::kMirroredRepeat: {
      int k = i % (2 * n);
      if (k < 0) k += 2 * n;
      return k < n ? k : 2 * n - 1 - k;
    }
    case TextureWrap::kRepeat: break;
  }
  int k = i % n;
  return k < 0 ? k + n : k;
}

// Columns (or rows) c0 = floor(x) and c0 + 1 folded into [0, n).
void fold_pair(float c0, int n, TextureWrap mode, int& i0, int& i1) {
  const float size = float(n);
  if (mode == TextureWrap::kRepeat) {
    c0 -= std::floor(c0 / size) * size;  // wrap in float (exact for integers below 2^24)
    i0 = int(c0);
    if (i0 >= n) i0 -= n;
    if (i0 < 0) i0 += n;
    i1 = i0 + 1 == n ? 0 : i0 + 1;
    return;
  }
  const float c = std::clamp(c0, -4.0f * size, 4.0f * size);  // far outside: any fold is the same
  i0 = fold(int(c), n, mode);
  i1 = fold(int(c) + 1, n, mode);
}

}  // namespace

BilinearTaps bilinear_taps(int width, int height, TextureWrap wrap_u, TextureWrap wrap_v,
                           glm::vec2 uv) {
  const float x = uv.x * float(width) - 0.5f, y = (1.0f - uv.y) * float(height) - 0.5f;
  const float x0f = std::floor(x), y0f = std::floor(y);
  int x0, x1, y0, y1;
  fold_pair(x0f, width, wrap_u, x0, x1);
  fold_pair(y0f, height, wrap_v, y0, y1);
  const size_t row0 = size_t(y0) * size_t(width), row1 = size_t(y1) * size_t(width);
  return {row0 + size_t(x0), row0 + size_t(x1), row1 + size_t(x0), row1 + size_t(x1),
          x - x0f, y - y0f};
}

AlphaMasks::AlphaMasks(const SceneAssets& assets) {
  planes_.resize(assets.textures.size());
  for (const Material& m : assets.materials) {
    Mask mask;
    if (m.alpha_mode == AlphaMode::kMask && m.alpha_cutoff > 0.0f) {
      mask.opacity = m.opacity;
      mask.cutoff = m.alpha_cutoff;
      if (m.texture >= 0 && size_t(m.texture) < assets.textures.size()) mask.texture = m.texture;
      any_ = true;
    }
    materials_.push_back(mask);
    if (mask.texture < 0 || !planes_[size_t(mask.texture)].alpha.empty()) continue;
    const Texture& t = assets.textures[size_t(mask.texture)];
    const size_t texels = size_t(std::max(t.width, 0)) * size_t(std::max(t.height, 0));
    if (texels == 0 || t.rgba.size() != texels * 4) continue;  // the renderers refuse it
    bool opaque = true;
    for (size_t i = 0; i < texels && opaque; ++i) opaque = t.rgba[4 * i + 3] == 255;
    if (opaque) continue;
    Plane& plane = planes_[size_t(mask.texture)];
    plane.width = t.width;
    plane.height = t.height;
    plane.wrap_u = t.wrap_u;
    plane.wrap_v = t.wrap_v;
    plane.alpha.resize(texels);
    for (size_t i = 0; i < texels; ++i) plane.alpha[i] = float(t.rgba[4 * i + 3]) / 255.0f;
  }
}

bool AlphaMasks::solid(uint32_t material, glm::vec2 uv) const {
  if (!masked(material)) return true;
  const Mask& m = materials_[material];
  float alpha = m.opacity;
  if (m.texture >= 0) {
    const Plane& p = planes_[size_t(m.texture)];
    if (!p.alpha.empty()) {
      const BilinearTaps f = bilinear_taps(p.width, p.height, p.wrap_u, p.wrap_v, uv);
      const float top = p.alpha[f.i00] + (p.alpha[f.i10] - p.alpha[f.i00]) * f.fx;
      const float bottom = p.alpha[f.i01] + (p.alpha[f.i11] - p.alpha[f.i01]) * f.fx;
      alpha *= top + (bottom - top) * f.fy;
    }
  }
  return alpha >= m.cutoff;
}

}  // namespace rp::scene
