#include "render/sky_cells.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace rp::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Unit direction through the centre of texel (x, y) of a width x height map.
glm::dvec3 texel_direction(int x, int y, int width, int height) {
  const double phi = 2.0 * kPi * (x + 0.5) / width, theta = kPi * (y + 0.5) / height;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

// The texel holding direction d.
size_t texel_of(const glm::dvec3& d, int width, int height) {
  double u = std::atan2(d.x, -d.z) / (2.0 * kPi);
  if (u < 0.0) u += 1.0;
  const double v = std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi;
  const int x = std::min(int(u * width), width - 1), y = std::min(int(v * height), height - 1);
  return size_t(y) * width + x;
}

// The cone directions in the local frame (cone_trace.h: RP_CONE_SET16).
glm::dvec3 cone_axis(int k) {
  if (k == 0) return {0.0, 0.0, 1.0};
  const bool inner = k <= 5;
  const double s2 = inner ? 3.5 / 16.0 : 11.0 / 16.0;
  const double azimuth = inner ? 72.0 * (k - 1) : 18.0 + 36.0 * (k - 6);
  const double r = std::sqrt(s2), a = azimuth * kPi / 180.0;
  return {r * std::cos(a), r * std::sin(a), std::sqrt(1.0 - s2)};
}

}  // namespace

glm::dvec3 sky_cell_normal(int i, int j, int side) {
  const double h = 0.5 * (side - 1);
  double px = i / h - 1.0, py = j / h - 1.0;
  const double z = 1.0 - std::fabs(px) - std::fabs(py);
  if (z < 0.0) {
    const double fx = (1.0 - std::fabs(py)) * (px < 0.0 ? -1.0 : 1.0);
    const double fy = (1.0 - std::fabs(px)) * (py < 0.0 ? -1.0 : 1.0);
    px = fx;
    py = fy;
  }
  return glm::normalize(glm::dvec3(px, py, z));
}

void sky_cell_basis(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b) {
  glm::dvec3 c = glm::cross(glm::dvec3(kSkyBasisAxis), n);
  if (glm::dot(c, c) < 1e-12) c = glm::cross(glm::dvec3(1.0, 0.0, 0.0), n);
  t = glm::normalize(c);
  b = glm::cross(n, t);
}

int sky_cone_cell(const glm::dvec3& local) {
  if (local.z <= 0.0) return -1;
  const double r2 = local.x * local.x + local.y * local.y;
  if (r2 < 1.0 / 16.0) return 0;
  double deg = std::atan2(local.y, local.x) * (180.0 / kPi);
  if (deg < 0.0) deg += 360.0;
  if (r2 < 6.0 / 16.0) return 1 + int(std::floor((deg + 36.0) / 72.0)) % 5;
  return 6 + int(std::floor(deg / 36.0)) % 10;
}

std::vector<gpu::rp_float4> sky_cell_table(const SkyCellSource& map, int side) {
  const int w = map.width, h = map.height;
  // texel directions and solid angles, once
  std::vector<glm::dvec3> dirs(size_t(w) * h);
  std::vector<double> omega(static_cast<size_t>(h));
  for (int y = 0; y < h; ++y) {
    omega[size_t(y)] = 2.0 * kPi / w * (std::cos(kPi * y / h) - std::cos(kPi * (y + 1) / h));
    for (int x = 0; x < w; ++x) dirs[size_t(y) * w + x] = texel_direction(x, y, w, h);
  }
  std::vector<gpu::rp_float4> table(size_t(side) * side * 16);
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const glm::dvec3 n = sky_cell_normal(i, j, side);
      glm::dvec3 t, b;
      sky_cell_basis(n, t, b);
      std::array<glm::dvec3, 16> sum{};
      std::array<double, 16> weight{};
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const size_t texel = size_t(y) * w + x;
          const glm::dvec3& d = dirs[texel];
          const double cos_theta = glm::dot(d, n);
          if (cos_theta <= 0.0) continue;
          const int k = sky_cone_cell({glm::dot(d, t), glm::dot(d, b), cos_theta});
          const double wt = cos_theta * omega[size_t(y)];
          sum[size_t(k)] += wt * glm::dvec3(map.rgb[3 * texel], map.rgb[3 * texel + 1],
                                            map.rgb[3 * texel + 2]);
          weight[size_t(k)] += wt;
        }
      // Each cell's mean, then all 16 scaled so that their mean is the hemisphere's
      // cosine-weighted mean (irradiance / pi; the cells' own weights differ from a 16th of the
      // hemisphere's by the texels their borders cut): unoccluded, the cones then bring the
      // map's irradiance, and a constant map its radiance exactly.
      std::array<glm::dvec3, 16> mean{};
      glm::dvec3 total(0.0), cells(0.0);
      double total_weight = 0.0;
      for (int k = 0; k < 16; ++k) {
        glm::dvec3& c = mean[size_t(k)];
        if (weight[size_t(k)] > 0.0) {
          c = sum[size_t(k)] / weight[size_t(k)];
        } else {
          const glm::dvec3 l = cone_axis(k);
          const size_t texel = texel_of(l.x * t + l.y * b + l.z * n, w, h);
          c = {map.rgb[3 * texel], map.rgb[3 * texel + 1], map.rgb[3 * texel + 2]};
        }
        total += sum[size_t(k)];
        total_weight += weight[size_t(k)];
        cells += c;
      }
      glm::dvec3 scale(1.0);
      for (int ch = 0; ch < 3; ++ch)
        if (cells[ch] > 0.0 && total_weight > 0.0)
          scale[ch] = total[ch] / total_weight / (cells[ch] / 16.0);
      for (int k = 0; k < 16; ++k) {
        const glm::dvec3 c = mean[size_t(k)] * scale;
        table[(size_t(j) * side + i) * 16 + size_t(k)] = {float(c.x), float(c.y), float(c.z),
                                                           0.0f};
      }
    }
  return table;
}

}  // namespace rp::render
