// Measures of the accuracy report (see accuracy_metrics.h).
#include "bench/src/accuracy_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "app/host_tone_map.h"
#include "scene/demo_scene.h"

namespace rp::bench {

using app::tone_map_srgb;

namespace {

uint16_t bit(Region r) { return uint16_t(1u << unsigned(r)); }

double luma(const std::vector<float>& rgb, size_t pixel) {
  return 0.2126 * rgb[3 * pixel] + 0.7152 * rgb[3 * pixel + 1] + 0.0722 * rgb[3 * pixel + 2];
}

void check_sizes(const std::vector<float>& a, const std::vector<float>& b,
                 const std::vector<uint16_t>& labels) {
  if (a.size() != b.size() || a.size() != 3 * labels.size())
    throw std::invalid_argument("accuracy: images and region labels differ in size");
}

constexpr float kFloorY = -1.0f;  // the box's floor (scene/cornell_box.h: the box [-1, 1]^3)

// Whether floor point p (y = -1) lies within kMarbleContactRadii radii of a marble's contact
// point; marbles are the spheres that do not emit, resting on the floor.
bool beside_marble(glm::vec3 p, const std::vector<scene::Sphere>& spheres) {
  for (const scene::Sphere& s : spheres) {
    if (s.emission != glm::vec3(0.0f)) continue;
    if (std::abs(s.center.y - s.radius - kFloorY) > 0.01f * s.radius) continue;
    const glm::vec2 d(p.x - s.center.x, p.z - s.center.z);
    if (glm::dot(d, d) < (kMarbleContactRadii * s.radius) * (kMarbleContactRadii * s.radius))
      return true;
  }
  return false;
}

// The label a primary hit gives (without the erosion): one named region or none (kImage).
Region label_of(const truth::PrimaryHit& h, const std::vector<scene::Sphere>& spheres) {
  namespace demo = scene::demo;
  if (h.sphere != truth::PrimaryHit::kNone)
    return h.sphere < spheres.size() && spheres[h.sphere].emission == glm::vec3(0.0f)
               ? Region::kMarble
               : Region::kImage;  // fireballs, particles, or no sphere list given
  if (h.material == demo::kFloorMaterial && beside_marble(h.position, spheres))
    return Region::kFloorByMarbles;
  switch (h.material) {
    case demo::kCeilingMaterial: return Region::kCeiling;
    case demo::kBackMaterial: return Region::kBackWall;
    case demo::kLeftMaterial: return Region::kLeftWall;
    case demo::kRightMaterial: return Region::kRightWall;
    case demo::kFloorMaterial:
      return h.lamp_visible && h.lamp_cos > 0.0f ? Region::kFloorLit : Region::kFloorShadow;
    case demo::kTumblerMaterial:
      return h.lamp_visible && h.lamp_cos > 0.0f ? Region::kTumblerLit : Region::kTumblerShadowed;
    default: return Region::kImage;  // lamp cap, spheres: counted in the whole image only
  }
}

}  // namespace

const char* region_name(Region r) {
  switch (r) {
    case Region::kImage: return "image";
    case Region::kCeiling: return "ceiling";
    case Region::kFloorLit: return "floor_lit";
    case Region::kFloorShadow: return "floor_in_shadow";
    case Region::kBackWall: return "back_wall";
    case Region::kLeftWall: return "left_wall";
    case Region::kRightWall: return "right_wall";
    case Region::kTumblerLit: return "tumblers_lit";
    case Region::kTumblerShadowed: return "tumblers_shadowed";
    case Region::kMarble: return "marbles";
    case Region::kFloorByMarbles: return "floor_by_marbles";
    case Region::kCount: break;
  }
  return "?";
}

std::vector<uint16_t> classify_regions(const std::vector<truth::PrimaryHit>& hits, uint32_t width,
                                       uint32_t height, const std::vector<scene::Sphere>& spheres) {
  if (hits.size() != size_t(width) * height)
    throw std::invalid_argument("accuracy: primary hits do not match the image size");
  std::vector<Region> raw(hits.size(), Region::kCount);  // kCount = background
  for (size_t i = 0; i < hits.size(); ++i)
    if (hits[i].hit()) raw[i] = label_of(hits[i], spheres);
  std::vector<uint16_t> labels(hits.size(), 0);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const size_t i = size_t(y) * width + x;
      if (raw[i] == Region::kCount) continue;
      labels[i] = bit(Region::kImage);
      if (raw[i] == Region::kImage) continue;
      const bool same = x > 0 && x + 1 < width && y > 0 && y + 1 < height &&
                        raw[i - 1] == raw[i] && raw[i + 1] == raw[i] &&
                        raw[i - width] == raw[i] && raw[i + width] == raw[i];
      if (same) labels[i] |= bit(raw[i]);
    }
  return labels;
}

ErrorStats compare_region(const std::vector<float>& a, const std::vector<float>& truth,
                          const std::vector<uint16_t>& labels, Region region) {
  check_sizes(a, truth, labels);
  double abs_sum = 0.0, a_sum = 0.0, t_sum = 0.0;
  ErrorStats s;
  for (size_t i = 0; i < labels.size(); ++i) {
    if (!(labels[i] & bit(region))) continue;
    ++s.pixels;
    for (size_t c = 0; c < 3; ++c) {
      abs_sum += std::abs(double(a[3 * i + c]) - double(truth[3 * i + c]));
      a_sum += a[3 * i + c];
      t_sum += truth[3 * i + c];
    }
  }
  s.sum_truth = t_sum;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  s.rel_l1 = t_sum > 0.0 ? abs_sum / t_sum : nan;
  s.bias = t_sum > 0.0 ? a_sum / t_sum - 1.0 : nan;
  return s;
}

IncomingLight incoming_indirect(const std::vector<float>& indirect,
                                const std::vector<float>& albedo,
                                const std::vector<uint16_t>& labels, Region region) {
  check_sizes(indirect, albedo, labels);
  IncomingLight in;
  std::array<uint64_t, 3> n{};
  for (size_t i = 0; i < labels.size(); ++i) {
    if (!(labels[i] & bit(region))) continue;
    for (size_t c = 0; c < 3; ++c)
      if (albedo[3 * i + c] > 1.0e-3f) {  // a channel the surface reflects
        in.rgb[c] += double(indirect[3 * i + c]) / double(albedo[3 * i + c]);
        ++n[c];
      }
  }
  for (size_t c = 0; c < 3; ++c) in.rgb[c] = n[c] ? in.rgb[c] / double(n[c]) : 0.0;
  return in;
}

LeakStats leaks_and_misses(const std::vector<float>& a, const std::vector<float>& truth,
                           const std::vector<uint16_t>& labels, Region in) {
  check_sizes(a, truth, labels);
  LeakStats s;
  double sum = 0.0;
  uint64_t covered = 0;
  for (size_t i = 0; i < labels.size(); ++i)
    if (labels[i] & bit(Region::kImage)) {
      sum += luma(truth, i);
      ++covered;
    }
  s.epsilon = covered ? 0.05 * sum / double(covered) : 0.0;
  for (size_t i = 0; i < labels.size(); ++i) {
    if (!(labels[i] & bit(in))) continue;
    ++s.covered_pixels;
    const double v = luma(a, i), t = luma(truth, i);
    if (v > 1.5 * t + s.epsilon) ++s.leak_pixels;
    if (v < (t - s.epsilon) / 1.5) ++s.missing_pixels;
  }
  return s;
}

double tone_mapped_psnr(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size() || a.empty())
    throw std::invalid_argument("accuracy: PSNR of images of different sizes");
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double d = tone_map_srgb(a[i]) - tone_map_srgb(b[i]);
    sum += d * d;
  }
  if (sum == 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(1.0 / (sum / double(a.size())));
}

double rgba8_psnr(const std::vector<uint8_t>& rgba, const std::vector<float>& radiance) {
  if (rgba.size() / 4 != radiance.size() / 3 || rgba.size() % 4 || radiance.size() % 3 ||
      rgba.empty())
    throw std::invalid_argument("accuracy: PSNR of images of different sizes");
  double sum = 0.0;
  for (size_t p = 0; p < rgba.size() / 4; ++p)
    for (size_t c = 0; c < 3; ++c) {
      const double d = rgba[4 * p + c] / 255.0 - tone_map_srgb(radiance[3 * p + c]);
      sum += d * d;
    }
  if (sum == 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(1.0 / (sum / double(radiance.size())));
}

namespace {
double nan_value() { return std::numeric_limits<double>::quiet_NaN(); }
double srgb_encode(double v) {
  v = std::clamp(v, 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}
template <class Value>
double psnr_over(const std::vector<float>& a, const std::vector<float>& truth,
                 const std::vector<uint8_t>& mask, Value value) {
  if (a.size() != truth.size() || a.size() != 3 * mask.size())
    throw std::invalid_argument("accuracy: images and mask differ in size");
  double sum = 0.0;
  uint64_t n = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    for (size_t c = 0; c < 3; ++c) {
      const double d = value(a[3 * i + c]) - value(truth[3 * i + c]);
      sum += d * d;
    }
    n += 3;
  }
  if (n == 0) return nan_value();
  if (sum == 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(double(n) / sum);
}
}  // namespace

double masked_psnr(const std::vector<float>& a, const std::vector<float>& truth,
                   const std::vector<uint8_t>& mask, double scale) {
  return psnr_over(a, truth, mask, [scale](float v) { return double(v) * scale; });
}

double masked_tone_mapped_psnr(const std::vector<float>& a, const std::vector<float>& truth,
                               const std::vector<uint8_t>& mask) {
  return psnr_over(a, truth, mask, [](float v) { return tone_map_srgb(v); });
}

std::vector<ErrorBin> tone_mapped_error_by_key(const std::vector<float>& a,
                                               const std::vector<float>& truth,
                                               const std::vector<uint8_t>& mask,
                                               const std::vector<float>& key, int bins) {
  if (a.size() != truth.size() || a.size() != 3 * mask.size() || key.size() != mask.size())
    throw std::invalid_argument("accuracy: images, mask and key differ in size");
  if (bins < 1) throw std::invalid_argument("accuracy: error bins must be at least 1");
  std::vector<ErrorBin> out(static_cast<size_t>(bins));
  std::vector<double> sum(static_cast<size_t>(bins), 0.0);
  for (size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    const int b = std::clamp(int(std::floor(double(key[i]) * bins)), 0, bins - 1);
    ErrorBin& e = out[size_t(b)];
    ++e.pixels;
    for (size_t c = 0; c < 3; ++c) {
      const double d = tone_map_srgb(a[3 * i + c]) - tone_map_srgb(truth[3 * i + c]);
      sum[size_t(b)] += d;
      e.squared_sum += d * d;
    }
  }
  for (size_t b = 0; b < out.size(); ++b) {
    if (out[b].pixels == 0) continue;
    const double n = 3.0 * double(out[b].pixels);
    out[b].mean = sum[b] / n;
    out[b].rms = std::sqrt(out[b].squared_sum / n);
  }
  return out;
}

double srgb_psnr(const std::vector<float>& a, const std::vector<float>& truth,
                 const std::vector<uint8_t>& mask) {
  return psnr_over(a, truth, mask, [](float v) { return srgb_encode(v); });
}

std::vector<uint8_t> dilate(const std::vector<uint8_t>& mask, uint32_t width, uint32_t height,
                            int radius) {
  if (mask.size() != size_t(width) * height)
    throw std::invalid_argument("accuracy: mask does not match the image size");
  std::vector<uint8_t> out(mask.size(), 0);
  for (int y = 0; y < int(height); ++y)
    for (int x = 0; x < int(width); ++x) {
      if (!mask[size_t(y) * width + size_t(x)]) continue;
      for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u >= 0 && v >= 0 && u < int(width) && v < int(height))
            out[size_t(v) * width + size_t(u)] = 1;
        }
    }
  return out;
}

double bilinear_luma(const std::vector<float>& rgb, uint32_t width, uint32_t height, double x,
                     double y) {
  const double fx = std::clamp(x - 0.5, 0.0, double(width - 1));
  const double fy = std::clamp(y - 0.5, 0.0, double(height - 1));
  const auto x0 = uint32_t(fx), y0 = uint32_t(fy);
  const uint32_t x1 = std::min(x0 + 1, width - 1), y1 = std::min(y0 + 1, height - 1);
  const double tx = fx - x0, ty = fy - y0;
  auto at = [&](uint32_t u, uint32_t v) { return luma(rgb, size_t(v) * width + u); };
  return (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x1, y0)) +
         ty * ((1 - tx) * at(x0, y1) + tx * at(x1, y1));
}

double transition_width(const std::vector<ProfileSample>& p, double lo, double hi) {
  auto cross = [&](size_t i, double level) {  // between samples i - 1 and i
    const double dv = p[i].v - p[i - 1].v;
    const double t = dv != 0.0 ? (level - p[i - 1].v) / dv : 1.0;
    return p[i - 1].s + std::clamp(t, 0.0, 1.0) * (p[i].s - p[i - 1].s);
  };
  size_t i90 = 0;
  while (i90 < p.size() && !(p[i90].v >= hi)) ++i90;
  if (i90 == 0 || i90 == p.size()) return nan_value();
  size_t i10 = i90;  // the last sample at or below lo before i90
  while (i10 > 0 && !(p[i10 - 1].v <= lo)) --i10;
  if (i10 == 0) return nan_value();
  return cross(i90, hi) - cross(i10, lo);
}

void signed_heat_map(const std::vector<float>& a, const std::vector<float>& truth,
                     const std::vector<uint16_t>& labels, double eps, std::vector<uint8_t>& rgba) {
  check_sizes(a, truth, labels);
  rgba.assign(labels.size() * 4, 0);
  for (size_t i = 0; i < labels.size(); ++i) {
    uint8_t* p = &rgba[4 * i];
    p[3] = 255;
    if (!(labels[i] & bit(Region::kImage))) continue;
    const double rel = std::clamp((luma(a, i) - luma(truth, i)) / (luma(truth, i) + eps), -1.0, 1.0);
    // white at 0, towards red (too bright) or blue (too dark)
    const auto fade = uint8_t(std::lround(255.0 * (1.0 - std::abs(rel))));
    p[0] = rel >= 0.0 ? 255 : fade;
    p[1] = fade;
    p[2] = rel <= 0.0 ? 255 : fade;
  }
}

std::vector<uint8_t> tile_rgba8(const std::vector<std::vector<uint8_t>>& images, uint32_t w,
                                uint32_t h, uint32_t columns) {
  const uint32_t rows = uint32_t((images.size() + columns - 1) / columns);
  std::vector<uint8_t> out(size_t(w) * columns * h * rows * 4, 0);
  for (size_t k = 0; k < images.size(); ++k) {
    const size_t ox = (k % columns) * w, oy = (k / columns) * h;
    for (uint32_t y = 0; y < h; ++y)
      std::copy_n(&images[k][size_t(y) * w * 4], size_t(w) * 4,
                  &out[((oy + y) * size_t(w) * columns + ox) * 4]);
  }
  return out;
}

}  // namespace rp::bench
