#include "passes/voxelize_reference.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "passes/voxelize.h"
#include "render/frame_buffers.h"
#include "render/texture_mips.h"
#include "scene/alpha_mask.h"
#include "render/voxel_volume.h"
#include "shading/brdf_tables.h"
#include "support/cl_fixture.h"

namespace rp::test {
namespace {

// ---- float3 arithmetic, one IEEE operation per step like the kernel ----
RefF3 operator+(RefF3 a, RefF3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
RefF3 operator-(RefF3 a, RefF3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
RefF3 operator*(RefF3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
RefF3 operator*(RefF3 a, RefF3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
RefF3 operator-(RefF3 a) { return {-a.x, -a.y, -a.z}; }
RefF3 add_scalar(RefF3 a, float s) { return {a.x + s, a.y + s, a.z + s}; }
RefF3 f3(const gpu::rp_float4& v) { return {v.x, v.y, v.z}; }
RefF3 f3(const glm::vec3& v) { return {v.x, v.y, v.z}; }
RefF3 fmin3(RefF3 a, RefF3 b) { return {std::fmin(a.x, b.x), std::fmin(a.y, b.y), std::fmin(a.z, b.z)}; }
RefF3 fmax3(RefF3 a, RefF3 b) { return {std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z)}; }

// vx_cross / vx_dot
RefF3 cross(RefF3 a, RefF3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
float dot(RefF3 a, RefF3 b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
RefF3 normalize(RefF3 a) { return a * (1.0f / std::sqrt(dot(a, a))); }

// vx_transform: ((c0 x + c1 y) + c2 z) + c3
RefF3 transform(const gpu::rp_mat4& m, RefF3 p) {
  return ((f3(m.c[0]) * p.x + f3(m.c[1]) * p.y) + f3(m.c[2]) * p.z) + f3(m.c[3]);
}
gpu::rp_float4 mul_point4(const gpu::rp_mat4& m, RefF3 p) {
  auto comp = [&](int i) {
    const float* c0 = &m.c[0].x;
    const float* c1 = &m.c[1].x;
    const float* c2 = &m.c[2].x;
    const float* c3 = &m.c[3].x;
    return ((c0[i] * p.x + c1[i] * p.y) + c2[i] * p.z) + c3[i];
  };
  return {comp(0), comp(1), comp(2), comp(3)};
}

// ---- exact test (voxelize.cl VxTriangleAxes, vx_triangle_axes, vx_triangle_box) ----
RefF3 edge_projections(RefF3 e, RefF3 p) {
  return {e.z * p.y - e.y * p.z, e.x * p.z - e.z * p.x, e.y * p.x - e.x * p.y};
}

struct TriangleAxes {
  RefF3 n;
  float n_dist = 0.0f, n_radius = 0.0f;
  RefF3 e[3];
  float pmin[9], pmax[9], radius[9];
};

TriangleAxes triangle_axes(RefF3 A, RefF3 B, RefF3 C) {
  TriangleAxes t;
  t.e[0] = B - A;
  t.e[1] = C - B;
  t.e[2] = A - C;
  t.n = cross(t.e[0], t.e[1]);
  t.n_dist = dot(t.n, A);
  t.n_radius = 0.5f * ((std::fabs(t.n.x) + std::fabs(t.n.y)) + std::fabs(t.n.z));
  for (int i = 0; i < 3; ++i) {
    const RefF3 e = t.e[i];
    const RefF3 pa = edge_projections(e, A), pb = edge_projections(e, B),
                pc = edge_projections(e, C);
    const RefF3 lo = fmin3(fmin3(pa, pb), pc), hi = fmax3(fmax3(pa, pb), pc);
    const float ax = std::fabs(e.x), ay = std::fabs(e.y), az = std::fabs(e.z);
    t.pmin[3 * i + 0] = lo.x;
    t.pmin[3 * i + 1] = lo.y;
    t.pmin[3 * i + 2] = lo.z;
    t.pmax[3 * i + 0] = hi.x;
    t.pmax[3 * i + 1] = hi.y;
    t.pmax[3 * i + 2] = hi.z;
    t.radius[3 * i + 0] = 0.5f * (az + ay);
    t.radius[3 * i + 1] = 0.5f * (az + ax);
    t.radius[3 * i + 2] = 0.5f * (ay + ax);
  }
  return t;
}

bool axes_overlap(const TriangleAxes& t, RefF3 c) {
  if (std::fabs(t.n_dist - dot(t.n, c)) > t.n_radius) return false;
  for (int i = 0; i < 3; ++i) {
    const RefF3 s = edge_projections(t.e[i], c);
    const float sj[3] = {s.x, s.y, s.z};
    for (int j = 0; j < 3; ++j) {
      const int k = 3 * i + j;
      if (t.pmin[k] - sj[j] > t.radius[k] || t.pmax[k] - sj[j] < -t.radius[k]) return false;
    }
  }
  return true;
}

// ---- lighting (common/direct_light.h), agrees to rounding ----
float lamp_falloff(float s) {
  s = std::clamp(s, 0.0f, 1.0f);
  return s * (s * 0.204f + 0.446f) + 0.35f;
}

float shadow_linear_depth(float d, float near, float far) {
  const float z_ndc = d * 2.0f - 1.0f;
  const float lin = 2.0f * near * far / ((far + near) - z_ndc * (far - near));
  return d >= 1.0f ? 3.0e38f : lin;
}

// vx_direct: light (rgb, before albedo) at p with normal n, 4 shadow taps at (+-1.5, +-1.5)
// texels (RP_VOXEL_SHADOW_SPREAD), slope bias over a reach of 2.8 texels.
RefF3 direct(const VoxelRefInput& in, RefF3 p, RefF3 n) {
  const gpu::FrameConstants& k = in.constants;
  // direction to the lamp centre, distance to its disk's centre in the ceiling, plus a^2
  const RefF3 to_light = f3(k.light_pos) - p;
  const float ze = k.light_pos.y - 1.0f;
  const RefF3 to_disk = RefF3{to_light.x, to_light.y - ze, to_light.z};
  const float a2 = std::fmax(k.light_pos.w * k.light_pos.w - ze * ze, 0.0f);
  const float inv_d = 1.0f / std::sqrt(dot(to_light, to_light));
  const RefF3 l = to_light * inv_d;
  const float cos_theta = dot(n, l);
  if (!(cos_theta > 0.0f)) return {};
  const float scale = cos_theta * lamp_falloff(l.y) / (dot(to_disk, to_disk) + a2);

  const gpu::rp_mat4& lvp = k.light_view_proj;
  const int size = int(k.shadow_size);
  const float w0 = mul_point4(lvp, p).w;
  const RefF3 row0 = {lvp.c[0].x, lvp.c[1].x, lvp.c[2].x};
  const float texel = 2.0f * std::fabs(w0) / (float(size) * std::sqrt(dot(row0, row0)));
  const float c = std::max(cos_theta, 1.0e-4f);
  const float tan_theta = std::min(std::sqrt(std::max(1.0f - c * c, 0.0f)) / c, 8.0f);
  const RefF3 q = p + n * (texel * 1.0f);
  const gpu::rp_float4 clip = mul_point4(lvp, q);
  const RefF3 ndc = {clip.x / clip.w, clip.y / clip.w, clip.z / clip.w};
  float lit = 1.0f;
  if (!(clip.w <= 0.0f || std::fabs(ndc.x) > 1.0f || std::fabs(ndc.y) > 1.0f || ndc.z > 1.0f)) {
    const float receiver = clip.w - texel * (1.0f + 2.8f * tan_theta);
    const float sx = (ndc.x * 0.5f + 0.5f) * float(size);
    const float sy = (0.5f - ndc.y * 0.5f) * float(size);
    float taps = 0.0f;
    for (int t = 0; t < 4; ++t) {
      const float ox = (t & 1) ? 1.5f : -1.5f, oy = (t & 2) ? 1.5f : -1.5f;
      const int tx = std::clamp(int(std::floor(sx + ox)), 0, size - 1);
      const int ty = std::clamp(int(std::floor(sy + oy)), 0, size - 1);
      taps += receiver <= shadow_linear_depth(in.shadow.at(size_t(ty) * size + tx), k.clip.z,
                                              k.clip.w)
                  ? 1.0f
                  : 0.0f;
    }
    lit = taps * 0.25f;
  }
  return f3(k.light_intensity) * (scale * lit);
}

// ---- texture (common/sampling.h rp_texture_bilinear), agrees to rounding ----
float srgb8_to_linear(uint8_t code) {
  const double c = code / 255.0;
  return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

RefF3 texture_bilinear(const scene::Texture& t, float u, float v) {
  const int w = t.width, h = t.height;
  const float x = u * float(w) - 0.5f, y = (1.0f - v) * float(h) - 0.5f;
  float x0f = std::floor(x), y0f = std::floor(y);
  const float fx = x - x0f, fy = y - y0f;
  x0f -= std::floor(x0f / float(w)) * float(w);
  y0f -= std::floor(y0f / float(h)) * float(h);
  auto wrap = [](int i, int n) { return ((i % n) + n) % n; };
  const int x0 = wrap(int(x0f), w), y0 = wrap(int(y0f), h);
  const int x1 = x0 + 1 == w ? 0 : x0 + 1, y1 = y0 + 1 == h ? 0 : y0 + 1;
  auto texel = [&](int tx, int ty) {
    const uint8_t* p = &t.rgba[(size_t(ty) * w + tx) * 4];
    return RefF3{srgb8_to_linear(p[0]), srgb8_to_linear(p[1]), srgb8_to_linear(p[2])};
  };
  auto mix = [](RefF3 a, RefF3 b, float f) { return a + (b - a) * f; };
  return mix(mix(texel(x0, y0), texel(x1, y0), fx), mix(texel(x0, y1), texel(x1, y1), fx), fy);
}

// Bilinear in mip level `level` of `chain` (vx_texture_level's level fields + the sample).
RefF3 level_bilinear(const render::MipChain& chain, uint32_t level, float u, float v) {
  const render::MipLevel& l = chain.levels.at(level);
  scene::Texture t{"level", int(l.width), int(l.height), {}};
  for (uint32_t i = 0; i < l.width * l.height; ++i) {
    const uint32_t texel = chain.texels[l.offset + i];
    for (int c = 0; c < 4; ++c) t.rgba.push_back(uint8_t(texel >> (8 * c)));
  }
  return texture_bilinear(t, u, v);
}

// vx_texture_level + the trilinear mix of vx_albedo_span.
RefF3 texture_trilinear(const render::MipChain& chain, float lod, float u, float v) {
  const uint32_t levels = uint32_t(chain.levels.size());
  const float l0f = std::floor(lod);
  const uint32_t l0 = uint32_t(l0f), l1 = std::min(l0 + 1, levels - 1);
  const float frac = lod - l0f;
  const RefF3 a = level_bilinear(chain, l0, u, v), b = level_bilinear(chain, l1, u, v);
  return a + (b - a) * frac;
}

// ---- accumulation (vx_fixed, vx_accumulate) ----
uint32_t fixed(float value) {
  return uint32_t(std::fmin(std::fmax(value, 0.0f), render::kVoxelMaxContribution) *
                      render::kVoxelFixedScale +
                  0.5f);
}

void accumulate(VoxelSums& sums, uint32_t voxel, RefF3 radiance, float a) {
  const RefF3 premul = radiance * a;
  const uint32_t q[4] = {fixed(premul.x), fixed(premul.y), fixed(premul.z), fixed(a)};
  for (uint32_t c = 0; c < 4; ++c) {
    if (q[c] == 0u) continue;
    uint32_t& s = sums.accum[kAccumWords * size_t(voxel) + c];
    const uint32_t old = s;
    s = old + q[c];  // wraps like atomic_add
    if (old > 0xFFFFFFFFu - q[c]) sums.overflow[voxel] |= 1u << c;
  }
}

// ---- facing coverage (vx_add_facing, vx_add_facing_all) ----
constexpr float kFacingUnit = RP_VOXEL_FACING_UNIT;

// vx_add_facing: per axis i, round(a |n_i| / max|n| * UNIT) into the half of word 4 + i that
// matches the sign of n_i (low half n_i > 0, high half otherwise), wrapping like atomic_add.
// `exact`: false where n is the triangle normal (the kernel's comes from rsqrt): contributions
// whose rounding is within 1e-3 of a tie count as slack (VoxelSums::facing_slack).
void add_facing(VoxelSums& sums, uint32_t voxel, RefF3 n, float a, bool exact) {
  const RefF3 an = {std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)};
  const float scale = a * kFacingUnit / std::fmax(std::fmax(an.x, an.y), an.z);
  const float c[3] = {an.x * scale, an.y * scale, an.z * scale};
  const float s[3] = {n.x, n.y, n.z};
  for (int i = 0; i < 3; ++i) {
    const float v = std::fmin(c[i], kFacingUnit);
    const uint32_t q = uint32_t(v + 0.5f);
    const int half = s[i] > 0.0f ? 0 : 1;
    if (!exact && std::fabs((v - std::floor(v)) - 0.5f) <= 1e-3f)
      ++sums.facing_slack[6 * size_t(voxel) + 2 * i + half];
    if (q == 0u) continue;
    sums.accum[kAccumWords * size_t(voxel) + 4 + i] += half == 0 ? q : q << 16;
  }
}

void add_facing_all(VoxelSums& sums, uint32_t voxel, float a) {
  const uint32_t q = uint32_t(std::fmin(a, 1.0f) * kFacingUnit + 0.5f);
  if (q == 0u) return;
  for (int i = 0; i < 3; ++i) sums.accum[kAccumWords * size_t(voxel) + 4 + i] += q | (q << 16);
}

RefF3 voxel_centre_world(int x, int y, int z, uint32_t resolution) {
  const float s = 2.0f / float(resolution);
  return {(float(x) + 0.5f) * s - 1.0f, (float(y) + 0.5f) * s - 1.0f,
          (float(z) + 0.5f) * s - 1.0f};
}

// vx_axis_range
void axis_range(float lo, float hi, int resolution, int& first, int& last) {
  const float lim = float(resolution) + 1.0f;
  lo = std::fmin(std::fmax(lo, -1.0f), lim);
  hi = std::fmin(std::fmax(hi, -1.0f), lim);
  first = std::max(int(std::ceil(lo)) - 1, 0);
  last = std::min(int(std::floor(hi)), resolution - 1);
}

// chains: the mip chain of every texture of in.assets (built once per reference run).
void voxelize_triangle(const VoxelRefInput& in, const gpu::Instance& inst,
                       const scene::Mesh& mesh, size_t t,
                       const std::vector<render::MipChain>& chains,
                       const scene::AlphaMasks& masks, VoxelSums& sums) {
  const uint32_t R = sums.resolution;
  const glm::uvec3 idx = mesh.triangles[t];
  const scene::Vertex* v[3] = {&mesh.vertices[idx.x], &mesh.vertices[idx.y],
                               &mesh.vertices[idx.z]};
  const RefF3 w0 = transform(inst.model, f3(v[0]->position));
  const RefF3 w1 = transform(inst.model, f3(v[1]->position));
  const RefF3 w2 = transform(inst.model, f3(v[2]->position));
  const float half_r = 0.5f * float(R);
  const RefF3 a = add_scalar(w0, 1.0f) * half_r, b = add_scalar(w1, 1.0f) * half_r,
              c = add_scalar(w2, 1.0f) * half_r;
  // Every voxel of the triangle's voxel range (the kernel searches columns of it).
  const RefF3 lo = fmin3(fmin3(a, b), c), hi = fmax3(fmax3(a, b), c);
  int x0, x1, y0, y1, z0, z1;
  axis_range(lo.x, hi.x, int(R), x0, x1);
  axis_range(lo.y, hi.y, int(R), y0, y1);
  axis_range(lo.z, hi.z, int(R), z0, z1);
  if (x0 > x1 || y0 > y1 || z0 > z1) return;
  const RefF3 origin = {float(x0), float(y0), float(z0)};
  const TriangleAxes axes = triangle_axes(a - origin, b - origin, c - origin);
  if (axes.n.x == 0.0f && axes.n.y == 0.0f && axes.n.z == 0.0f) return;

  const RefF3 e01 = w1 - w0, e02 = w2 - w0;
  RefF3 nw = normalize(cross(e01, e02));
  const RefF3 nsum_obj = (f3(v[0]->normal) + f3(v[1]->normal)) + f3(v[2]->normal);
  const gpu::rp_mat4& nm = inst.normal_matrix;
  const RefF3 nsum = (f3(nm.c[0]) * nsum_obj.x + f3(nm.c[1]) * nsum_obj.y) +
                     f3(nm.c[2]) * nsum_obj.z;
  if (dot(nw, nsum) < 0.0f) nw = -nw;
  const float d00 = dot(e01, e01), d01 = dot(e01, e02), d11 = dot(e02, e02);
  const float inv_denom = 1.0f / (d00 * d11 - d01 * d01);
  const scene::Material& mat = in.assets->materials.at(mesh.materials[t]);
  static const render::MipChain kNoChain;
  const render::MipChain& chain = mat.texture >= 0 ? chains.at(size_t(mat.texture)) : kNoChain;
  float lod = 0.0f;
  if (mat.texture >= 0) {
    const scene::Texture& tex = in.assets->textures.at(size_t(mat.texture));
    lod = reference_texture_lod({w0, w1, w2},
                                {RefF3{v[0]->uv.x, v[0]->uv.y, 0.0f},
                                 RefF3{v[1]->uv.x, v[1]->uv.y, 0.0f},
                                 RefF3{v[2]->uv.x, v[2]->uv.y, 0.0f}},
                                uint32_t(tex.width), uint32_t(tex.height),
                                uint32_t(chain.levels.size()), R);
  }
  const float base_weight = shading::voxel_base_weight(shading::gloss_code(mat.specular),
                                                       shading::BrdfTables::get());
  // vx_shade at barycentrics (b0, b1, b2).
  auto shade = [&](float b0, float b1, float b2) {
    const RefF3 p = (w0 + e01 * b1) + e02 * b2;
    RefF3 albedo = f3(mat.albedo) * base_weight;  // the coat's base weight (GpuScene's albedo.w)
    if (mat.texture >= 0) {
      const float u = (v[0]->uv.x * b0 + v[1]->uv.x * b1) + v[2]->uv.x * b2;
      const float vv = (v[0]->uv.y * b0 + v[1]->uv.y * b1) + v[2]->uv.y * b2;
      albedo = albedo * texture_trilinear(chain, lod, u, vv);
    }
    return albedo * direct(in, p, nw) + f3(mat.emission);
  };
  // vx_alpha_keep: an alpha-masked material's surface exists where it is solid (uv as
  // kernels/common/alpha_mask.h interpolates it from b1, b2).
  const uint32_t material = mesh.materials[t];
  auto solid = [&](float b1, float b2) {
    if (!masks.masked(material)) return true;
    const float b0 = (1.0f - b1) - b2;
    const glm::vec2 uv((b0 * v[0]->uv.x + b1 * v[1]->uv.x) + b2 * v[2]->uv.x,
                       (b0 * v[0]->uv.y + b1 * v[1]->uv.y) + b2 * v[2]->uv.y);
    return masks.solid(material, uv);
  };
  const RefF3 extent = hi - lo;
  const bool small = std::fmax(std::fmax(extent.x, extent.y), extent.z) <= 2.0f;
  const float third = 1.0f / 3.0f;
  if (small && !solid(third, third)) return;  // a small triangle is cut or kept whole
  const RefF3 small_radiance = small ? shade(third, third, third) : RefF3{};

  for (int z = z0; z <= z1; ++z)
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        if (!axes_overlap(axes, {float(x - x0) + 0.5f, float(y - y0) + 0.5f,
                                 float(z - z0) + 0.5f}))
          continue;
        RefF3 radiance = small_radiance;
        if (!small) {
          const RefF3 centre = voxel_centre_world(x, y, z, R);
          const RefF3 q = centre - nw * dot(nw, centre - w0);
          const RefF3 rel = q - w0;
          const float d20 = dot(rel, e01), d21 = dot(rel, e02);
          float b1 = std::fmax((d11 * d20 - d01 * d21) * inv_denom, 0.0f);
          float b2 = std::fmax((d00 * d21 - d01 * d20) * inv_denom, 0.0f);
          float b0 = std::fmax(1.0f - b1 - b2, 0.0f);
          const float b_sum = b0 + b1 + b2;
          if (b_sum > 0.0f && b_sum < 1.0e30f) {
            b0 /= b_sum;
            b1 /= b_sum;
            b2 /= b_sum;
          } else {
            b0 = b1 = b2 = third;
          }
          if (!solid(b1, b2)) continue;
          radiance = shade(b0, b1, b2);
        }
        const uint32_t voxel = (uint32_t(z) * R + uint32_t(y)) * R + uint32_t(x);
        accumulate(sums, voxel, radiance, 1.0f);
        add_facing(sums, voxel, nw, 1.0f, false);
      }
}

void voxelize_sphere(const VoxelRefInput& in, const gpu::Sphere& s, VoxelSums& sums) {
  const uint32_t R = sums.resolution;
  const RefF3 cw = f3(s.center_radius);
  const float rw = s.center_radius.w;
  if (!(rw > 0.0f)) return;
  const float half_r = 0.5f * float(R);
  const RefF3 cg = add_scalar(cw, 1.0f) * half_r;
  const float rg = rw * half_r;
  const float r2 = rg * rg;
  const RefF3 lo = add_scalar(cg, -rg), hi = add_scalar(cg, rg);
  int x0, x1, y0, y1, z0, z1;
  axis_range(lo.x, hi.x, int(R), x0, x1);
  axis_range(lo.y, hi.y, int(R), y0, y1);
  axis_range(lo.z, hi.z, int(R), z0, z1);
  const float area = float(M_PI) * r2;
  const float inv_extent = 1.0f / std::fmin(2.0f * rg, 1.0f);
  const RefF3 albedo = f3(s.albedo) * s.albedo.w, emission = f3(s.emission);
  const bool small = rg < 0.5f;
  RefF3 small_radiance{};
  if (small) {
    const RefF3 l = normalize(f3(in.constants.light_pos) - cw);
    small_radiance = albedo * (direct(in, cw + l * rw, l) * 0.25f) + emission;
  }
  for (int k = z0; k <= z1; ++k) {
    const float fk = float(k);
    const float dz = std::fmax(std::fmax(fk - cg.z, cg.z - (fk + 1.0f)), 0.0f);
    const float fz = (std::fmin(hi.z, fk + 1.0f) - std::fmax(lo.z, fk)) * inv_extent;
    for (int j = y0; j <= y1; ++j) {
      const float fj = float(j);
      const float dy = std::fmax(std::fmax(fj - cg.y, cg.y - (fj + 1.0f)), 0.0f);
      const float fy = (std::fmin(hi.y, fj + 1.0f) - std::fmax(lo.y, fj)) * inv_extent;
      for (int i = x0; i <= x1; ++i) {
        const float fi = float(i);
        const float dx = std::fmax(std::fmax(fi - cg.x, cg.x - (fi + 1.0f)), 0.0f);
        if ((dx * dx + dy * dy) + dz * dz > r2) continue;
        const float fx = (std::fmin(hi.x, fi + 1.0f) - std::fmax(lo.x, fi)) * inv_extent;
        const float a = std::fmin(((area * fx) * fy) * fz, 1.0f);
        if (!(a > 0.0f)) continue;
        RefF3 radiance = small_radiance;
        if (!small) {
          const RefF3 to_voxel = voxel_centre_world(i, j, k, R) - cw;
          const float len2 = dot(to_voxel, to_voxel);
          const RefF3 nrm =
              len2 > 0.0f ? to_voxel * (1.0f / std::sqrt(len2)) : RefF3{0.0f, 1.0f, 0.0f};
          radiance = albedo * direct(in, cw + nrm * rw, nrm) + emission;
        }
        const uint32_t voxel = (uint32_t(k) * R + uint32_t(j)) * R + uint32_t(i);
        accumulate(sums, voxel, radiance, a);
        add_facing_all(sums, voxel, a);
      }
    }
  }
}

}  // namespace

float reference_texture_lod(const std::array<RefF3, 3>& world, const std::array<RefF3, 3>& uv,
                            uint32_t width, uint32_t height, uint32_t levels,
                            uint32_t resolution) {
  const RefF3 e1 = world[1] - world[0], e2 = world[2] - world[0];
  const float d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2);
  const float inv_den = 1.0f / (d00 * d11 - d01 * d01);
  const RefF3 gb1 = (e1 * d11 - e2 * d01) * inv_den, gb2 = (e2 * d00 - e1 * d01) * inv_den;
  const RefF3 gu = (gb1 * (uv[1].x - uv[0].x) + gb2 * (uv[2].x - uv[0].x)) * float(width);
  const RefF3 gv = (gb1 * (uv[1].y - uv[0].y) + gb2 * (uv[2].y - uv[0].y)) * float(height);
  const float a = dot(gu, gu), b = dot(gu, gv), c = dot(gv, gv);
  const float h = 0.5f * (a - c);
  const float stretch2 = 0.5f * (a + c) + std::sqrt(h * h + b * b);
  const float voxel = 2.0f / float(resolution);
  const float lod = 0.5f * std::log2(stretch2 * (voxel * voxel));
  return std::fmin(std::fmax(lod, 0.0f), float(levels - 1));
}

std::array<RefF3, 3> reference_grid_triangle(const gpu::rp_mat4& model,
                                             const std::array<RefF3, 3>& object,
                                             uint32_t resolution) {
  const float half_r = 0.5f * float(resolution);
  std::array<RefF3, 3> out;
  for (int i = 0; i < 3; ++i) out[i] = add_scalar(transform(model, object[i]), 1.0f) * half_r;
  return out;
}

bool reference_triangle_box(const std::array<RefF3, 3>& t, uint32_t resolution, int x, int y,
                            int z) {
  const RefF3 lo = fmin3(fmin3(t[0], t[1]), t[2]), hi = fmax3(fmax3(t[0], t[1]), t[2]);
  int x0, x1, y0, y1, z0, z1;
  axis_range(lo.x, hi.x, int(resolution), x0, x1);
  axis_range(lo.y, hi.y, int(resolution), y0, y1);
  axis_range(lo.z, hi.z, int(resolution), z0, z1);
  if (x < x0 || x > x1 || y < y0 || y > y1 || z < z0 || z > z1) return false;
  const RefF3 origin = {float(x0), float(y0), float(z0)};
  const TriangleAxes axes = triangle_axes(t[0] - origin, t[1] - origin, t[2] - origin);
  if (axes.n.x == 0.0f && axes.n.y == 0.0f && axes.n.z == 0.0f) return false;
  return axes_overlap(axes, {float(x - x0) + 0.5f, float(y - y0) + 0.5f, float(z - z0) + 0.5f});
}

VoxelSums reference_voxelize(const VoxelRefInput& in, uint32_t resolution) {
  if (in.assets == nullptr || in.frame == nullptr || in.instances.size() != in.frame->instances.size())
    throw std::invalid_argument("reference_voxelize: inconsistent input");
  VoxelSums sums;
  sums.resolution = resolution;
  const size_t voxels = size_t(resolution) * resolution * resolution;
  sums.accum.assign(voxels * kAccumWords, 0u);
  sums.overflow.assign(voxels, 0u);
  sums.facing_slack.assign(voxels * 6, 0u);
  std::vector<render::MipChain> chains;
  for (const scene::Texture& tex : in.assets->textures) chains.push_back(render::build_mip_chain(tex));
  const scene::AlphaMasks masks(*in.assets);
  for (size_t i = 0; i < in.instances.size(); ++i) {
    if (!in.frame->instances[i].voxelize) continue;  // the lamp cap: lit analytically
    // the mesh's voxel proxy at this resolution where it has one (scene::voxel_mesh)
    const scene::Mesh& mesh = in.assets->meshes.at(
        scene::voxel_mesh(in.assets->meshes, in.frame->instances[i].mesh, resolution));
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
      voxelize_triangle(in, in.instances[i], mesh, t, chains, masks, sums);
  }
  for (const gpu::Sphere& s : in.spheres) voxelize_sphere(in, s, sums);
  return sums;
}

std::vector<float> reference_resolve(const VoxelSums& sums) {
  const size_t voxels = sums.overflow.size();
  std::vector<float> out(voxels * 4);
  for (size_t v = 0; v < voxels; ++v) {
    float s[4];
    for (int c = 0; c < 4; ++c) {
      s[c] = float(sums.accum[kAccumWords * v + c]) * (1.0f / render::kVoxelFixedScale);
      if (sums.overflow[v] & (1u << c)) s[c] = render::kVoxelSaturatedSum;
    }
    const float inv = 1.0f / std::fmax(s[3], 1.0f);
    out[4 * v + 0] = s[0] * inv;
    out[4 * v + 1] = s[1] * inv;
    out[4 * v + 2] = s[2] * inv;
    out[4 * v + 3] = std::fmin(s[3], 1.0f);
  }
  return out;
}

size_t compare_sums(const VoxelSums& got, const VoxelSums& want, std::vector<std::string>* first,
                    size_t report) {
  const size_t voxels = want.overflow.size();
  if (got.accum.size() != voxels * kAccumWords || want.accum.size() != voxels * kAccumWords ||
      got.overflow.size() != voxels || want.facing_slack.size() != voxels * 6) {
    if (first) first->push_back("compare_sums: sizes differ");
    return voxels + 1;
  }
  size_t bad = 0;
  for (size_t v = 0; v < voxels; ++v) {
    std::string why;
    for (size_t w : {0, 1, 2, 3, 7})
      if (got.accum[kAccumWords * v + w] != want.accum[kAccumWords * v + w])
        why += " word " + std::to_string(w) + ": " +
               std::to_string(got.accum[kAccumWords * v + w]) + " vs " +
               std::to_string(want.accum[kAccumWords * v + w]);
    if (got.overflow[v] != want.overflow[v])
      why += " overflow: " + std::to_string(got.overflow[v]) + " vs " +
             std::to_string(want.overflow[v]);
    for (int axis = 0; axis < 3; ++axis)
      for (int half = 0; half < 2; ++half) {
        const int64_t g = facing_half(got, v, axis, half), r = facing_half(want, v, axis, half);
        const int64_t slack = want.facing_slack[6 * v + 2 * size_t(axis) + size_t(half)];
        if (g > r + slack || g < r - slack)
          why += " facing " + std::string(1, "xyz"[axis]) + (half == 0 ? "+" : "-") + ": " +
                 std::to_string(g) + " vs " + std::to_string(r) + " (slack " +
                 std::to_string(slack) + ")";
      }
    if (!why.empty() && bad++ < report && first)
      first->push_back("voxel " + std::to_string(v) + ":" + why);
  }
  return bad;
}

VoxelGpuOutput run_voxelize(render::GpuScene& gpu, const std::vector<float>& shadow, uint32_t r,
                            const ::cl::Buffer* bounce, uint32_t bounce_cells) {
  passes::VoxelizePass pass(context(), programs());
  render::VoxelVolume vol;
  return run_voxelize(pass, vol, gpu, shadow, r, bounce, bounce_cells);
}

VoxelGpuOutput run_voxelize(passes::VoxelizePass& pass, render::VoxelVolume& vol,
                            render::GpuScene& gpu, const std::vector<float>& shadow, uint32_t r,
                            const ::cl::Buffer* bounce, uint32_t bounce_cells,
                            render::ShadowMap* shadow_map) {
  rp::cl::Context& ctx = context();
  vol.resize(ctx.context, r);
  gpu.constants.voxel_resolution = vol.resolution;
  gpu.constants.voxel_levels = vol.levels;
  ctx.queue.enqueueWriteBuffer(gpu.frame, CL_TRUE, 0, sizeof(gpu.constants), &gpu.constants);

  const size_t voxels = size_t(r) * r * r;
  const std::vector<uint32_t> garbage(vol.chain_elements() * 4, 0x7F7F7F7Fu);
  ctx.queue.enqueueWriteBuffer(vol.chain, CL_TRUE, 0, vol.chain_elements() * 16, garbage.data());
  const std::vector<uint32_t> accum_garbage(voxels * kAccumWords, 0x7F7F7F7Fu);
  ctx.queue.enqueueWriteBuffer(vol.accum, CL_TRUE, 0, accum_garbage.size() * 4,
                               accum_garbage.data());
  ctx.queue.enqueueWriteBuffer(vol.overflow, CL_TRUE, 0, voxels * 4, garbage.data());

  render::ShadowMap own;
  render::ShadowMap& sm = shadow_map != nullptr ? *shadow_map : own;
  if (sm.size != gpu.constants.shadow_size) sm.resize(ctx.context, gpu.constants.shadow_size);
  if (shadow.size() != size_t(sm.size) * sm.size)
    throw std::invalid_argument("run_voxelize: shadow map size does not match the constants");
  ctx.queue.enqueueWriteBuffer(sm.depth, CL_TRUE, 0, shadow.size() * sizeof(float), shadow.data());

  rp::cl::Profiler profiler(ctx.queue);
  pass.run(profiler, gpu, sm, vol, bounce, bounce_cells);
  VoxelGpuOutput out;
  out.times = profiler.collect();
  out.sums.resolution = r;
  out.sums.accum.resize(voxels * kAccumWords);
  out.sums.overflow.resize(voxels);
  out.level0.resize(voxels * 4);
  ctx.queue.enqueueReadBuffer(vol.accum, CL_TRUE, 0, out.sums.accum.size() * 4,
                              out.sums.accum.data());
  ctx.queue.enqueueReadBuffer(vol.overflow, CL_TRUE, 0, voxels * 4, out.sums.overflow.data());
  ctx.queue.enqueueReadBuffer(vol.chain, CL_TRUE, 0, voxels * 16, out.level0.data());
  return out;
}

VoxelRefInput reference_input(const scene::SceneAssets& assets, const scene::FrameScene& frame,
                              const render::GpuScene& gpu, const std::vector<float>& shadow) {
  VoxelRefInput in;
  in.assets = &assets;
  in.frame = &frame;
  in.constants = gpu.constants;
  in.instances = gpu.host_instances;
  in.spheres = gpu.host_spheres;
  in.shadow = shadow;
  return in;
}

}  // namespace rp::test
