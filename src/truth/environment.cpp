#include "truth/environment.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <stb/stb_image.h>

#include "truth/exr_io.h"
#include "truth/sampling.h"

namespace rp::truth {
namespace {

constexpr float kDegree = kPi / 180.0f;

// The index of the first entry of the inclusive CDF [first, first + n) above u, and u's place
// inside that entry's interval (0..1).
size_t invert(const std::vector<float>& cdf, size_t first, size_t n, float u, float* frac) {
  const auto begin = cdf.begin() + std::ptrdiff_t(first);
  size_t k = size_t(std::upper_bound(begin, begin + std::ptrdiff_t(n - 1), u) - begin);
  const float lo = k == 0 ? 0.0f : cdf[first + k - 1], hi = cdf[first + k];
  *frac = hi > lo ? std::clamp((u - lo) / (hi - lo), 0.0f, 0.99999994f) : 0.5f;
  return k;
}

}  // namespace

EnvironmentSampler::EnvironmentSampler(const scene::Environment& environment) {
  if (!environment.enabled() || !(environment.strength > 0.0f)) return;
  map_ = environment.map.get();
  if (environment.residual && environment.residual->rgb.size() == map_->rgb.size())
    residual_ = environment.residual.get();
  strength_ = environment.strength;
  cos_turn_ = std::cos(environment.rotate_deg * kDegree);
  sin_turn_ = std::sin(environment.rotate_deg * kDegree);
  const size_t w = size_t(map_->width), h = size_t(map_->height);
  if (map_->rgb.size() != w * h * 3)
    throw std::invalid_argument("environment map: " + std::to_string(map_->rgb.size()) +
                                " floats for " + std::to_string(w) + "x" + std::to_string(h));
  // Texel weights: luminance x sin(theta) at the row's centre (its share of the sphere).
  std::vector<double> row_sum(h, 0.0), weights(w * h);
  double total = 0.0;
  for (size_t y = 0; y < h; ++y) {
    const double s = std::sin(kPi * (double(y) + 0.5) / double(h));
    for (size_t x = 0; x < w; ++x) {
      const float* t = &map_->rgb[3 * (y * w + x)];
      const double weight = std::max(0.0, double(luminance({t[0], t[1], t[2]}))) * s;
      weights[y * w + x] = weight;
      row_sum[y] += weight;
    }
    total += row_sum[y];
  }
  if (!(total > 0.0)) return;  // a black map: nothing to sample, radiance() still answers
  row_cdf_.resize(h);
  texel_cdf_.resize(w * h);
  density_.resize(w * h);
  double running = 0.0;
  for (size_t y = 0; y < h; ++y) {
    running += row_sum[y];
    row_cdf_[y] = y + 1 == h ? 1.0f : float(running / total);
    double in_row = 0.0;
    for (size_t x = 0; x < w; ++x) {
      in_row += weights[y * w + x];
      texel_cdf_[y * w + x] =
          x + 1 == w ? 1.0f
                     : (row_sum[y] > 0.0 ? float(in_row / row_sum[y]) : float(x + 1) / float(w));
      density_[y * w + x] = float(weights[y * w + x] / total * double(w * h));
    }
  }
  enabled_ = true;
}

glm::vec3 EnvironmentSampler::to_map(glm::vec3 d) const {
  return {cos_turn_ * d.x - sin_turn_ * d.z, d.y, sin_turn_ * d.x + cos_turn_ * d.z};
}

glm::vec3 EnvironmentSampler::to_world(glm::vec3 d) const {
  return {cos_turn_ * d.x + sin_turn_ * d.z, d.y, -sin_turn_ * d.x + cos_turn_ * d.z};
}

size_t EnvironmentSampler::texel_of(glm::vec3 map_dir) const {
  const glm::vec2 uv = scene::environment_uv(map_dir);
  const size_t w = size_t(map_->width), h = size_t(map_->height);
  const size_t x = std::min(w - 1, size_t(uv.x * float(w)));
  const size_t y = std::min(h - 1, size_t(uv.y * float(h)));
  return y * w + x;
}

glm::vec3 EnvironmentSampler::radiance(glm::vec3 dir) const {
  if (map_ == nullptr) return glm::vec3(0.0f);
  const float* t = &map_->rgb[3 * texel_of(to_map(dir))];
  return glm::vec3(t[0], t[1], t[2]) * strength_;
}

glm::vec3 EnvironmentSampler::sun_part(size_t texel) const {
  if (residual_ == nullptr) return glm::vec3(0.0f);
  const float* t = &map_->rgb[3 * texel];
  const float* r = &residual_->rgb[3 * texel];
  return glm::vec3(t[0] - r[0], t[1] - r[1], t[2] - r[2]) * strength_;
}

glm::vec3 EnvironmentSampler::sun_radiance(glm::vec3 dir) const {
  if (map_ == nullptr) return glm::vec3(0.0f);
  return sun_part(texel_of(to_map(dir)));
}

EnvironmentSampler::Sample EnvironmentSampler::sample(float u1, float u2) const {
  Sample s;
  if (!enabled_) return s;
  const size_t w = size_t(map_->width), h = size_t(map_->height);
  float fy = 0.0f, fx = 0.0f;
  const size_t y = invert(row_cdf_, 0, h, u1, &fy);
  const size_t x = invert(texel_cdf_, y * w, w, u2, &fx);
  const float u = (float(x) + fx) / float(w), v = (float(y) + fy) / float(h);
  const glm::vec3 map_dir = scene::environment_direction(u, v);
  const float sin_theta = std::sin(kPi * v);
  if (!(sin_theta > 0.0f)) return s;
  s.dir = to_world(map_dir);
  const float* t = &map_->rgb[3 * (y * w + x)];
  s.radiance = glm::vec3(t[0], t[1], t[2]) * strength_;
  s.sun = sun_part(y * w + x);
  s.pdf = density_[y * w + x] / (2.0f * kPi * kPi * sin_theta);
  return s;
}

float EnvironmentSampler::pdf(glm::vec3 dir) const {
  if (!enabled_) return 0.0f;
  const glm::vec3 map_dir = to_map(dir);
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - map_dir.y * map_dir.y));
  if (!(sin_theta > 0.0f)) return 0.0f;
  return density_[texel_of(map_dir)] / (2.0f * kPi * kPi * sin_theta);
}

scene::EnvironmentMap load_environment_map(const std::filesystem::path& path) {
  scene::EnvironmentMap map;
  const std::string ext = path.extension().string();
  const std::string name = path.string();
  if (ext == ".exr" || ext == ".EXR") {
    uint32_t w = 0, h = 0;
    map.rgb = read_exr_layer(path, "", w, h);
    map.width = int(w);
    map.height = int(h);
  } else if (ext == ".hdr" || ext == ".HDR") {
    int w = 0, h = 0, channels = 0;
    float* data = stbi_loadf(name.c_str(), &w, &h, &channels, 3);
    if (data == nullptr)
      throw std::runtime_error("environment map " + name + ": cannot read it as Radiance HDR (" +
                               (stbi_failure_reason() ? stbi_failure_reason() : "unknown") + ")");
    map.width = w;
    map.height = h;
    map.rgb.assign(data, data + size_t(w) * size_t(h) * 3);
    stbi_image_free(data);
  } else {
    throw std::runtime_error("environment map " + name +
                             ": unknown kind (an equirectangular .exr or .hdr is expected)");
  }
  if (map.width < 2 || map.height < 1 || map.width != 2 * map.height)
    throw std::runtime_error("environment map " + name + ": " + std::to_string(map.width) + "x" +
                             std::to_string(map.height) +
                             " is not an equirectangular map (width = 2 x height)");
  // Lossy EXR codecs (DWAA/DWAB, as Blender's studio lights use) ring slightly below zero next
  // to bright texels: such values are read as 0 (no light), while NaN and infinity are refused.
  for (float& v : map.rgb) {
    if (!std::isfinite(v))
      throw std::runtime_error("environment map " + name + ": has non-finite radiance");
    v = std::max(v, 0.0f);
  }
  return map;
}

}  // namespace rp::truth
