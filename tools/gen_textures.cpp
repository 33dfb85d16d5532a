// Writes the procedural textures of scene/assets (our own, no third-party images):
//   wood.png          512x512  floor planks: growth rings and grain from value noise
//   tumbler_face.png  512x256  the tumbler's paint, in the UV layout of make_tumbler_mesh
// Usage: gen_textures [output_dir]   (default: the source tree's scene/assets)
// Deterministic: integer hashing only, so the committed PNGs can be regenerated bit for bit.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <stb/stb_image_write.h>

#include "scene/tumbler_shape.h"

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
using Rgb = glm::vec3;  // sRGB-encoded components in [0, 1] (we paint in display space)

// ---- value noise ----

uint32_t hash2(int32_t x, int32_t y, uint32_t seed) {
  uint32_t h = static_cast<uint32_t>(x) * 0x8da6b343u ^ static_cast<uint32_t>(y) * 0xd8163841u ^
               seed * 0xcb1ab31fu;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return h;
}

float lattice(int32_t x, int32_t y, uint32_t seed) {
  return static_cast<float>(hash2(x, y, seed) & 0xFFFFFFu) / static_cast<float>(0xFFFFFF);
}

// Smoothly interpolated random values on the integer lattice, in [0, 1].
float value_noise(float x, float y, uint32_t seed) {
  const float fx = std::floor(x), fy = std::floor(y);
  const int32_t ix = static_cast<int32_t>(fx), iy = static_cast<int32_t>(fy);
  const float tx = x - fx, ty = y - fy;
  const float sx = tx * tx * (3.0f - 2.0f * tx), sy = ty * ty * (3.0f - 2.0f * ty);
  const float a = lattice(ix, iy, seed), b = lattice(ix + 1, iy, seed);
  const float c = lattice(ix, iy + 1, seed), d = lattice(ix + 1, iy + 1, seed);
  return glm::mix(glm::mix(a, b, sx), glm::mix(c, d, sx), sy);
}

// Four octaves, result in about [0, 1].
float fbm(float x, float y, uint32_t seed) {
  float sum = 0.0f, amplitude = 0.5f, norm = 0.0f;
  for (int octave = 0; octave < 4; ++octave) {
    sum += amplitude * value_noise(x, y, seed + static_cast<uint32_t>(octave));
    norm += amplitude;
    x *= 2.0f;
    y *= 2.0f;
    amplitude *= 0.5f;
  }
  return sum / norm;
}

// ---- image helpers ----

struct Image {
  int width, height;
  std::vector<uint8_t> rgb;  // rows top to bottom
};

uint8_t to_byte(float c) {
  return static_cast<uint8_t>(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f));
}

// Fills the image with paint(u, v), u right and v up in [0,1] (the renderer's texture
// convention: row = (1 - v) * height), averaging an n x n grid of samples per pixel.
template <typename Paint>
Image render(int width, int height, int n, Paint paint) {
  Image image{width, height, std::vector<uint8_t>(static_cast<size_t>(width) * height * 3)};
  for (int py = 0; py < height; ++py) {
    for (int px = 0; px < width; ++px) {
      Rgb sum(0.0f);
      for (int sy = 0; sy < n; ++sy) {
        for (int sx = 0; sx < n; ++sx) {
          const float u = (static_cast<float>(px) + (static_cast<float>(sx) + 0.5f) / static_cast<float>(n)) /
                          static_cast<float>(width);
          const float v = 1.0f - (static_cast<float>(py) + (static_cast<float>(sy) + 0.5f) / static_cast<float>(n)) /
                                     static_cast<float>(height);
          sum += paint(u, v);
        }
      }
      sum /= static_cast<float>(n * n);
      const size_t i = (static_cast<size_t>(py) * width + px) * 3;
      image.rgb[i] = to_byte(sum.x);
      image.rgb[i + 1] = to_byte(sum.y);
      image.rgb[i + 2] = to_byte(sum.z);
    }
  }
  return image;
}

bool write_png(const std::string& path, const Image& image) {
  if (stbi_write_png(path.c_str(), image.width, image.height, 3, image.rgb.data(),
                     image.width * 3) == 0) {
    std::fprintf(stderr, "gen_textures: cannot write %s\n", path.c_str());
    return false;
  }
  std::printf("wrote %s (%dx%d)\n", path.c_str(), image.width, image.height);
  return true;
}

// ---- wood planks ----
// 8 planks across u (0.25 world units each on the 2x2 floor), running along v. Each plank is cut
// into boards of varying length; every board has its own tint and its own log: growth rings are
// stripes across the board, bent by low-frequency noise, with fine grain along the board.
Rgb paint_wood(float u, float v) {
  constexpr int kPlanks = 8;
  const float across = u * kPlanks;
  const int plank = static_cast<int>(std::floor(across));
  const float x = across - static_cast<float>(plank);  // position across the plank, [0,1)
  // Board joints: boards half the texture long, joints staggered per plank.
  const float offset = lattice(plank, 7, 11u);
  const float along = v + offset;
  const float board_len = 0.5f;
  const float board_f = along / board_len;
  const int board = static_cast<int>(std::floor(board_f));
  const float y = board_f - static_cast<float>(board);  // position along the board, [0,1)

  const uint32_t board_seed = hash2(plank, board, 3u);
  const float tint = static_cast<float>(board_seed & 0xFFu) / 255.0f;
  const Rgb light = glm::mix(Rgb(0.80f, 0.58f, 0.36f), Rgb(0.86f, 0.66f, 0.44f), tint);
  const Rgb dark = glm::mix(Rgb(0.55f, 0.34f, 0.18f), Rgb(0.62f, 0.40f, 0.22f), tint);

  // Growth rings: distance from the log's pith (off to one side of the board), warped.
  const float pith = -0.6f + 1.4f * static_cast<float>((board_seed >> 8) & 0xFFu) / 255.0f;
  const float warp = fbm(x * 2.0f, along * 6.0f, board_seed) - 0.5f;
  const float rings = std::fabs(x - pith + 0.35f * warp) * 9.0f + 0.3f * std::sin(along * 11.0f);
  const float ring = 0.5f + 0.5f * std::cos(2.0f * kPi * rings);
  const float ring_dark = std::pow(ring, 3.0f);
  // Fine grain: stretched noise along the board.
  const float grain = fbm(x * 40.0f + 13.0f * static_cast<float>(plank), along * 3.0f, 5u);
  Rgb colour = glm::mix(light, dark, 0.65f * ring_dark + 0.35f * grain);

  // Dark gaps between planks and at board ends, slightly soft.
  const float gap_u = std::min(x, 1.0f - x) * static_cast<float>(512 / kPlanks);  // pixels
  const float gap_v = std::min(y, 1.0f - y) * board_len * 512.0f;
  const float edge = std::min(gap_u, gap_v);
  if (edge < 1.0f) colour *= 0.35f;
  else if (edge < 2.0f) colour *= 0.75f;
  return colour;
}

// ---- tumbler paint ----
// Painted in the tumbler's local space: each texel is mapped back to its surface point, and the
// face, eyes, cheeks and mouth are shapes in the front view (x, y) of points with z > 0, so they
// look round on the model. A red hood and body, a gold collar band, a cream medallion with a
// gold flower on the belly.
const Rgb kRed(0.78f, 0.10f, 0.12f), kDarkRed(0.55f, 0.05f, 0.07f), kGold(0.93f, 0.72f, 0.25f),
    kSkin(0.99f, 0.90f, 0.80f), kCream(0.98f, 0.94f, 0.82f), kBlack(0.08f, 0.06f, 0.06f),
    kPink(0.97f, 0.55f, 0.58f), kWhite(1.0f), kMouth(0.80f, 0.12f, 0.18f);

// 1 inside an ellipse centred at c with radii r, 0 outside (hard edge; supersampling smooths).
float in_ellipse(glm::vec2 p, glm::vec2 c, glm::vec2 r) {
  const glm::vec2 d = (p - c) / r;
  return glm::dot(d, d) <= 1.0f ? 1.0f : 0.0f;
}

Rgb paint_tumbler(const rp::scene::TumblerShape& shape, float u, float v) {
  const float y = shape.y_bottom() + v * shape.height();
  const float r = shape.radius(y);
  const float theta = 2.0f * kPi * u;  // the mesh's azimuth: (x, z) = r * (-sin, -cos)
  const glm::vec3 p(-r * std::sin(theta), y, -r * std::cos(theta));
  const glm::vec2 front(p.x, p.y);     // front-view coordinates
  const bool facing = p.z > 0.0f;

  Rgb colour = kRed;
  // Darker red towards the bottom, as if lacquered in two layers.
  colour = glm::mix(kDarkRed, colour, std::clamp((y + 0.2f) / 0.12f, 0.0f, 1.0f));

  // Collar band all the way round, with dark red pin stripes.
  if (y > 0.158f && y < 0.182f) colour = kGold;
  if (std::fabs(y - 0.158f) < 0.002f || std::fabs(y - 0.182f) < 0.002f) colour = kDarkRed;
  // A ring of gold dots around the lower body.
  {
    const float cell = u * 24.0f;
    const float du = (cell - std::floor(cell) - 0.5f) * (2.0f * kPi * r / 24.0f);
    if (glm::length(glm::vec2(du, y + 0.10f)) < 0.012f) colour = kGold;
  }
  if (!facing) return colour;

  // Belly medallion: cream disk, gold rim, five-petal gold flower, red heart.
  const glm::vec2 belly(0.0f, 0.03f);
  const float rho = glm::length(front - belly);
  if (rho < 0.085f) {
    colour = rho > 0.075f ? kGold : kCream;
    const float phi = std::atan2(front.y - belly.y, front.x - belly.x);
    const float petal = 0.058f * (0.45f + 0.55f * std::fabs(std::cos(2.5f * phi)));
    if (rho < petal) colour = kGold;
    if (rho < 0.014f) colour = kRed;
  }

  // Face: a skin-coloured oval with a gold rim on the front of the head.
  const glm::vec2 face(0.0f, 0.268f), face_r(0.070f, 0.066f);
  if (in_ellipse(front, face, face_r + glm::vec2(0.008f)) > 0.0f) colour = kGold;
  if (in_ellipse(front, face, face_r) > 0.0f) {
    colour = kSkin;
    for (const float side : {-1.0f, 1.0f}) {
      // Cheeks.
      if (in_ellipse(front, {side * 0.042f, 0.246f}, {0.014f, 0.011f}) > 0.0f) colour = kPink;
      // Eyes with a highlight.
      const glm::vec2 eye(side * 0.025f, 0.278f);
      if (in_ellipse(front, eye, {0.0095f, 0.0135f}) > 0.0f) {
        colour = kBlack;
        if (in_ellipse(front, eye + glm::vec2(0.003f, 0.005f), {0.0035f, 0.0035f}) > 0.0f) {
          colour = kWhite;
        }
      }
      // Eyebrows: thin arcs above the eyes.
      const float brow = glm::length((front - (eye + glm::vec2(0.0f, 0.004f))) / glm::vec2(1.0f, 0.9f));
      if (std::fabs(brow - 0.024f) < 0.0018f && front.y > eye.y + 0.017f) colour = kBlack;
    }
    // Smile: the lower part of a circle.
    const float smile = glm::length(front - glm::vec2(0.0f, 0.258f));
    if (std::fabs(smile - 0.020f) < 0.0022f && front.y < 0.248f) colour = kMouth;
  }
  return colour;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : ROLYPOLY_ASSET_DIR;
  const rp::scene::TumblerShape shape;
  const Image wood = render(512, 512, 3, paint_wood);
  const Image face = render(512, 256, 4, [&](float u, float v) { return paint_tumbler(shape, u, v); });
  const bool ok = write_png(dir + "/wood.png", wood) && write_png(dir + "/tumbler_face.png", face);
  return ok ? 0 : 1;
}
