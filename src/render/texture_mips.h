// Mip chains of the scene's textures, built once at load on the host.
//
// Level k of a W x H texture is max(1, W >> k) x max(1, H >> k) texels (the OpenGL / D3D
// size rule, so a texel of every level covers the same uv rectangle fraction: level k's texel
// (i, j) covers uv [i / w_k, (i + 1) / w_k] x ..., whatever the parity). The chain runs down
// to 1 x 1: mip_level_count = floor(log2(max(W, H))) + 1 levels.
//
// Filtering, in linear light: the sRGB rgb codes are decoded (exact sRGB curve), alpha is
// code / 255 (alpha is linear, never sRGB), and so is the rgb of a data map (Texture::srgb
// false: normal and metallic-roughness maps, read as code / 255); level k + 1 is the
// AREA-WEIGHTED box filter of level k (kept in float, so the rounding to 8 bits happens once per
// level, not compounded):
// along an axis of n texels that halves to m = max(1, n / 2):
//   n even:        output i = mean of inputs 2i, 2i + 1 (the usual 2x2 box);
//   n odd, n > 1:  output i covers the input interval [i s, (i + 1) s], s = n / m (= 2 + 1/m),
//                  each input texel j weighted by its overlap with it, divided by s: for n = 5
//                  (m = 2): out0 = (t0 + t1 + t2 / 2) / 2.5, out1 = (t2 / 2 + t3 + t4) / 2.5,
//                  so the middle texel counts half in each and no texel is dropped (a plain
//                  2x2 box would drop the last column and shift the image by 1/(2n));
//   n = 1:         kept (the other axis may still halve).
// The 2D filter is the product of the two axes' weights (separable). Each level is then
// re-encoded to RGBA8 (sRGB, or linear for alpha and data maps; round to nearest code), the
// format of the shared texel buffer.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/frame_scene.h"

namespace rp::render {

// Most levels a texture may have (shared/types.h RP_TEXTURE_MAX_LEVELS): up to 32768 texels a
// side.
uint32_t mip_level_count(uint32_t width, uint32_t height);

struct MipLevel {
  uint32_t width = 0, height = 0;
  uint32_t offset = 0;  // first texel of the level, counted from level 0's first texel
};

// The chain of `texture`: levels[k] for k = 0 .. mip_level_count - 1, their texels back to back
// in `texels` (RGBA8 sRGB packed as one uint, R in the low byte; level 0 = the texture's own
// bytes unchanged). Throws std::invalid_argument for an empty, inconsistent or too large
// texture.
struct MipChain {
  std::vector<MipLevel> levels;
  std::vector<uint32_t> texels;
};
MipChain build_mip_chain(const scene::Texture& texture);

// The exact sRGB decode (code -> linear [0, 1]) and the encode (round to nearest code) used by
// the chain (encode(decode(c)) == c for every code).
float srgb8_decode(uint8_t code);
uint8_t srgb8_encode(float linear);

}  // namespace rp::render
