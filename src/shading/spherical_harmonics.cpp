#include "shading/spherical_harmonics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace rp::shading {
namespace {

constexpr double kPi = 3.14159265358979323846;

void check_bands(int bands) {
  if (bands < 1 || bands > kShMaxBands)
    throw std::invalid_argument("spherical harmonics: " + std::to_string(bands) +
                                " bands (1 to " + std::to_string(kShMaxBands) + ")");
}

// Nodes and weights of the n-point Gauss-Legendre rule on [-1, 1] (Newton on P_n from the
// Chebyshev guesses; converges to rounding in a few steps for n <= 64).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.assign(size_t(n), 0.0);
  weights.assign(size_t(n), 0.0);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (double(i) + 0.75) / (double(n) + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;  // P_0, P_1, then the recurrence up to P_n
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / dp;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    nodes[size_t(i)] = x;
    weights[size_t(i)] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
}

// Solves M X = Y for X (M: n x n, Y: n x k, both row-major; overwritten) by Gaussian
// elimination with partial pivoting.
std::vector<double> solve(std::vector<double> m, std::vector<double> y, int n, int k) {
  for (int c = 0; c < n; ++c) {
    int pivot = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(m[size_t(r * n + c)]) > std::abs(m[size_t(pivot * n + c)])) pivot = r;
    if (std::abs(m[size_t(pivot * n + c)]) < 1e-300)
      throw std::runtime_error("spherical harmonics: singular system");
    if (pivot != c) {
      for (int j = 0; j < n; ++j) std::swap(m[size_t(c * n + j)], m[size_t(pivot * n + j)]);
      for (int j = 0; j < k; ++j) std::swap(y[size_t(c * k + j)], y[size_t(pivot * k + j)]);
    }
    for (int r = 0; r < n; ++r) {
      if (r == c) continue;
      const double f = m[size_t(r * n + c)] / m[size_t(c * n + c)];
      if (f == 0.0) continue;
      for (int j = c; j < n; ++j) m[size_t(r * n + j)] -= f * m[size_t(c * n + j)];
      for (int j = 0; j < k; ++j) y[size_t(r * k + j)] -= f * y[size_t(c * k + j)];
    }
  }
  for (int r = 0; r < n; ++r)
    for (int j = 0; j < k; ++j) y[size_t(r * k + j)] /= m[size_t(r * n + r)];
  return y;
}

}  // namespace

void sh_eval(glm::dvec3 d, int bands, double* out) {
  check_bands(bands);
  const double x = d.x, y = d.y, z = d.z;
  out[0] = 0.282094791773878143;  // 1 / (2 sqrt(pi))
  if (bands < 2) return;
  out[1] = 0.488602511902919921 * y;  // sqrt(3 / (4 pi))
  out[2] = 0.488602511902919921 * z;
  out[3] = 0.488602511902919921 * x;
  if (bands < 3) return;
  out[4] = 1.092548430592079070 * x * y;  // sqrt(15 / (4 pi))
  out[5] = 1.092548430592079070 * y * z;
  out[6] = 0.315391565252520006 * (3.0 * z * z - 1.0);  // sqrt(5 / (16 pi))
  out[7] = 1.092548430592079070 * x * z;
  out[8] = 0.546274215296039535 * (x * x - y * y);  // sqrt(15 / (16 pi))
  if (bands < 4) return;
  out[9] = 0.590043589926643510 * y * (3.0 * x * x - y * y);  // sqrt(35 / (32 pi))
  out[10] = 2.890611442640554055 * x * y * z;                // sqrt(105 / (4 pi))
  out[11] = 0.457045799464465737 * y * (5.0 * z * z - 1.0);  // sqrt(21 / (32 pi))
  out[12] = 0.373176332590115391 * z * (5.0 * z * z - 3.0);  // sqrt(7 / (16 pi))
  out[13] = 0.457045799464465737 * x * (5.0 * z * z - 1.0);
  out[14] = 1.445305721320277027 * z * (x * x - y * y);  // sqrt(105 / (16 pi))
  out[15] = 0.590043589926643510 * x * (x * x - 3.0 * y * y);
  if (bands < 5) return;
  const double x2 = x * x, y2 = y * y, z2 = z * z;
  out[16] = 2.503342941796704539 * x * y * (x2 - y2);           // 3 sqrt(35 / pi) / 4
  out[17] = 1.770130769779930531 * y * z * (3.0 * x2 - y2);     // 3 sqrt(35 / (2 pi)) / 4
  out[18] = 0.946174695757560014 * x * y * (7.0 * z2 - 1.0);    // 3 sqrt(5 / pi) / 4
  out[19] = 0.669046543557289159 * y * z * (7.0 * z2 - 3.0);    // 3 sqrt(5 / (2 pi)) / 4
  out[20] = 0.105785546915204322 * (35.0 * z2 * z2 - 30.0 * z2 + 3.0);  // 3 / (16 sqrt(pi))
  out[21] = 0.669046543557289159 * x * z * (7.0 * z2 - 3.0);
  out[22] = 0.473087347878780007 * (x2 - y2) * (7.0 * z2 - 1.0);  // 3 sqrt(5 / pi) / 8
  out[23] = 1.770130769779930531 * x * z * (x2 - 3.0 * y2);
  out[24] = 0.625835735449176135 * (x2 * (x2 - 3.0 * y2) - y2 * (3.0 * x2 - y2));
}

std::vector<double> sh_project(const std::function<double(glm::dvec3)>& f, int bands, int rings,
                               int segments) {
  check_bands(bands);
  std::vector<double> nodes, weights;
  gauss_legendre(rings, nodes, weights);
  std::vector<double> c(size_t(sh_count(bands)), 0.0);
  double y[kShMaxCount];
  const double dphi = 2.0 * kPi / segments;
  for (int i = 0; i < rings; ++i) {
    const double z = nodes[size_t(i)], r = std::sqrt(std::max(0.0, 1.0 - z * z));
    for (int j = 0; j < segments; ++j) {
      const double phi = (double(j) + 0.5) * dphi;
      const glm::dvec3 d(r * std::cos(phi), r * std::sin(phi), z);
      const double w = weights[size_t(i)] * dphi * f(d);
      sh_eval(d, bands, y);
      for (size_t k = 0; k < c.size(); ++k) c[k] += w * y[k];
    }
  }
  return c;
}

double sh_cosine_lobe_zonal(int l) {
  switch (l) {
    case 0: return std::sqrt(kPi) / 2.0;
    case 1: return std::sqrt(kPi / 3.0);
    case 2: return std::sqrt(5.0 * kPi) / 8.0;
    case 3: return 0.0;
    case 4: return -std::sqrt(kPi) / 16.0;
    default: break;
  }
  throw std::invalid_argument("spherical harmonics: band " + std::to_string(l) + " (0 to 4)");
}

std::vector<double> sh_rotate_zonal(const std::vector<double>& zonal, glm::dvec3 n, int bands) {
  check_bands(bands);
  double y[kShMaxCount];
  sh_eval(n, bands, y);
  std::vector<double> c(size_t(sh_count(bands)), 0.0);
  for (int l = 0; l < bands && size_t(l) < zonal.size(); ++l)
    for (int m = -l; m <= l; ++m)
      c[size_t(sh_index(l, m))] =
          zonal[size_t(l)] * std::sqrt(4.0 * kPi / (2.0 * l + 1.0)) * y[sh_index(l, m)];
  return c;
}

namespace {

// Calls f(world direction, radiance, solid angle) for every texel of the enabled environment
// (its turn and strength applied): the texel's exact solid angle, (2 pi / width)
// (cos theta0 - cos theta1), and its centre's direction.
template <class F>
void for_each_texel(const scene::Environment& environment, F f) {
  const scene::EnvironmentMap& map = *environment.map;
  const int w = map.width, h = map.height;
  const double turn = double(environment.rotate_deg) * kPi / 180.0;
  const double ct = std::cos(turn), st = std::sin(turn);
  for (int row = 0; row < h; ++row) {
    const double t0 = kPi * row / h, t1 = kPi * (row + 1) / h;
    const double omega = (2.0 * kPi / w) * (std::cos(t0) - std::cos(t1));
    for (int col = 0; col < w; ++col) {
      const glm::dvec3 m(scene::environment_direction((float(col) + 0.5f) / float(w),
                                                      (float(row) + 0.5f) / float(h)));
      // the map's frame turned about +y into the world's (truth/environment.cpp to_world)
      const glm::dvec3 d(ct * m.x + st * m.z, m.y, -st * m.x + ct * m.z);
      const float* t = &map.rgb[3 * (size_t(row) * size_t(w) + size_t(col))];
      f(glm::normalize(d), glm::dvec3(t[0], t[1], t[2]) * double(environment.strength), omega);
    }
  }
}

}  // namespace

std::vector<glm::dvec3> sh_project_environment(const scene::Environment& environment,
                                               int bands) {
  check_bands(bands);
  std::vector<glm::dvec3> c(size_t(sh_count(bands)), glm::dvec3(0.0));
  if (!environment.enabled()) return c;
  double y[kShMaxCount];
  for_each_texel(environment, [&](glm::dvec3 d, glm::dvec3 radiance, double omega) {
    sh_eval(d, bands, y);
    for (size_t i = 0; i < c.size(); ++i) c[i] += radiance * (omega * y[i]);
  });
  return c;
}

std::vector<glm::dvec3> sh_project_glow(const scene::EnvironmentGlow& glow, int bands) {
  check_bands(bands);
  std::vector<glm::dvec3> c(size_t(sh_count(bands)), glm::dvec3(0.0));
  const int w = glow.width, h = glow.height;
  double y[kShMaxCount];
  for (size_t k = 0; k < glow.texels.size(); ++k) {
    const int row = int(glow.texels[k] / uint32_t(w)), col = int(glow.texels[k] % uint32_t(w));
    // for_each_texel's solid angle and direction, unturned
    const double t0 = kPi * row / h, t1 = kPi * (row + 1) / h;
    const double omega = (2.0 * kPi / w) * (std::cos(t0) - std::cos(t1));
    const glm::dvec3 d(scene::environment_direction((float(col) + 0.5f) / float(w),
                                                    (float(row) + 0.5f) / float(h)));
    sh_eval(glm::normalize(d), bands, y);
    const glm::dvec3 radiance(glow.radiance[k]);
    for (size_t i = 0; i < c.size(); ++i) c[i] += radiance * (omega * y[i]);
  }
  return c;
}

glm::dvec3 sh_irradiance(const std::vector<glm::dvec3>& coefficients, glm::dvec3 n, int bands) {
  std::vector<double> zonal;
  for (int l = 0; l < bands; ++l) zonal.push_back(sh_cosine_lobe_zonal(l));
  const std::vector<double> lobe = sh_rotate_zonal(zonal, n, bands);
  glm::dvec3 e(0.0);
  for (size_t i = 0; i < lobe.size() && i < coefficients.size(); ++i) e += coefficients[i] * lobe[i];
  return e;
}

double sh_irradiance_error(const scene::Environment& environment, int bands, int normals) {
  check_bands(bands);
  if (!environment.enabled() || normals < 1) return 0.0;
  const std::vector<glm::dvec3> c = sh_project_environment(environment, bands);
  // The texels as (world direction, luminance x solid angle): what the exact sums need.
  std::vector<glm::dvec4> texels;
  texels.reserve(size_t(environment.map->width) * size_t(environment.map->height));
  for_each_texel(environment, [&](glm::dvec3 d, glm::dvec3 radiance, double omega) {
    const double lum = 0.2126 * radiance.x + 0.7152 * radiance.y + 0.0722 * radiance.z;
    texels.emplace_back(d, lum * omega);
  });
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  double diff = 0.0, sum = 0.0;
  for (int k = 0; k < normals; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / normals, r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const glm::dvec3 n(r * std::cos(golden * k), z, r * std::sin(golden * k));
    double exact = 0.0;
    for (const glm::dvec4& t : texels)
      exact += t.w * std::max(0.0, n.x * t.x + n.y * t.y + n.z * t.z);
    const glm::dvec3 e = sh_irradiance(c, n, bands);
    diff += std::abs(0.2126 * e.x + 0.7152 * e.y + 0.0722 * e.z - exact);
    sum += exact;
  }
  return sum > 0.0 ? diff / sum : 0.0;
}

std::vector<glm::dvec3> sh_turn_environment(const std::vector<glm::dvec3>& unturned,
                                            float rotate_deg, float strength) {
  int bands = 0;
  while (sh_count(bands) < int(unturned.size())) ++bands;
  if (sh_count(bands) != int(unturned.size()))
    throw std::invalid_argument("sh_turn_environment: " + std::to_string(unturned.size()) +
                                " coefficients are not a whole number of bands");
  // The map's frame turned into the world's (sh_project_environment): columns R e_x, e_y, R e_z.
  const double turn = double(rotate_deg) * kPi / 180.0;
  const double ct = std::cos(turn), st = std::sin(turn);
  const glm::dmat3 r(glm::dvec3(ct, 0.0, -st), glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(st, 0.0, ct));
  const ShRotation rotation(r, bands);
  std::vector<glm::dvec3> out(unturned.size());
  double in_c[kShMaxCount], out_c[kShMaxCount];
  for (int c = 0; c < 3; ++c) {
    for (size_t i = 0; i < unturned.size(); ++i) in_c[i] = unturned[i][c];
    rotation.apply(in_c, out_c);
    for (size_t i = 0; i < unturned.size(); ++i) out[i][c] = out_c[i] * double(strength);
  }
  return out;
}

ShRotation::ShRotation(const glm::dmat3& rotation, int bands) : bands_(bands) {
  check_bands(bands);
  const glm::dmat3 inverse = glm::transpose(rotation);  // a rotation's inverse
  double ya[kShMaxCount], yb[kShMaxCount];
  for (int l = 0; l < bands; ++l) {
    const int w = 2 * l + 1, points = 2 * w;
    // A (points x w): band l at the points; B: band l at the points turned back by R^-1.
    std::vector<double> a(size_t(points * w)), b(size_t(points * w));
    for (int k = 0; k < points; ++k) {
      const double z = 1.0 - (2.0 * k + 1.0) / points;
      const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double phi = k * 2.39996322972865332;  // the golden angle
      const glm::dvec3 d(r * std::cos(phi), r * std::sin(phi), z);
      sh_eval(d, bands, ya);
      sh_eval(inverse * d, bands, yb);
      for (int m = 0; m < w; ++m) {
        a[size_t(k * w + m)] = ya[l * l + m];
        b[size_t(k * w + m)] = yb[l * l + m];
      }
    }
    // Least squares: (A^T A) D = A^T B; the band's coefficients turn as c' = D c.
    std::vector<double> ata(size_t(w * w), 0.0), atb(size_t(w * w), 0.0);
    for (int i = 0; i < w; ++i)
      for (int j = 0; j < w; ++j)
        for (int k = 0; k < points; ++k) {
          ata[size_t(i * w + j)] += a[size_t(k * w + i)] * a[size_t(k * w + j)];
          atb[size_t(i * w + j)] += a[size_t(k * w + i)] * b[size_t(k * w + j)];
        }
    const std::vector<double> d = solve(std::move(ata), std::move(atb), w, w);
    blocks_.insert(blocks_.end(), d.begin(), d.end());
  }
}

void ShRotation::apply(const double* in, double* out) const {
  size_t block = 0;
  for (int l = 0; l < bands_; ++l) {
    const int w = 2 * l + 1, first = l * l;
    for (int i = 0; i < w; ++i) {
      double s = 0.0;
      for (int j = 0; j < w; ++j) s += blocks_[block + size_t(i * w + j)] * in[first + j];
      out[first + i] = s;
    }
    block += size_t(w * w);
  }
}

}  // namespace rp::shading
