// Filtered textures against straightforward C++ references:
//   - the mip chain (render/texture_mips.h): level sizes, counts and offsets; every level of
//     odd-sized textures against an explicit 2D area box filter of the previous level (in
//     double, linear light); alpha linear; a hand-computed 2x1 case;
//   - the GBuffer's per-pixel footprint: a textured quad at a known distance, facing the camera
//     (the closed-form level of detail) and tilted away (numerical derivatives of the exact
//     ray-plane texel mapping in double, with TAA jitter), read from the kernel's
//     -DRP_GBUFFER_LOD_OUT variant;
//   - trilinear and anisotropic albedo against a C++ sampler over the same tilted quad, at the
//     GPU layout (one pixel a work-item) and the CPU layout (8-pixel spans).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "passes/gbuffer.h"
#include "render/gpu_scene.h"
#include "render/texture_mips.h"
#include "support/cl_fixture.h"

namespace {

using rp::render::MipChain;

double decode(int code) {
  const double c = code / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
int encode(double l) {
  l = std::clamp(l, 0.0, 1.0);
  return int(std::lround(255.0 * (l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1 / 2.4) - 0.055)));
}

// Deterministic texture of pseudo-random codes (alpha too).
rp::scene::Texture random_texture(int w, int h, uint32_t seed) {
  rp::scene::Texture t{"random", w, h, {}};
  uint32_t s = seed;
  for (int i = 0; i < w * h * 4; ++i) {
    s = s * 1664525u + 1013904223u;
    t.rgba.push_back(uint8_t(s >> 24));
  }
  return t;
}

// ---- mip chain ----

TEST(MipChain, LevelSizesCountsAndOffsets) {
  EXPECT_EQ(rp::render::mip_level_count(1, 1), 1u);
  EXPECT_EQ(rp::render::mip_level_count(5, 3), 3u);
  EXPECT_EQ(rp::render::mip_level_count(512, 256), 10u);
  EXPECT_EQ(rp::render::mip_level_count(512, 512), 10u);
  EXPECT_EQ(rp::render::mip_level_count(7, 1), 3u);
  const MipChain c = rp::render::build_mip_chain(random_texture(5, 3, 1));
  ASSERT_EQ(c.levels.size(), 3u);
  const uint32_t want[3][3] = {{5, 3, 0}, {2, 1, 15}, {1, 1, 17}};  // width, height, offset
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(c.levels[k].width, want[k][0]) << "level " << k;
    EXPECT_EQ(c.levels[k].height, want[k][1]) << "level " << k;
    EXPECT_EQ(c.levels[k].offset, want[k][2]) << "level " << k;
  }
  EXPECT_EQ(c.texels.size(), 18u);
  const MipChain wide = rp::render::build_mip_chain(random_texture(512, 256, 2));
  ASSERT_EQ(wide.levels.size(), 10u);
  EXPECT_EQ(wide.levels[9].width, 1u);
  EXPECT_EQ(wide.levels[9].height, 1u);
  EXPECT_EQ(wide.levels[8].width, 2u);
  EXPECT_EQ(wide.levels[8].height, 1u);
  EXPECT_EQ(wide.texels.size(), 174763u);  // 512*256 + 256*128 + ... + 2*1 + 1*1
}

// Level 0 is the texture's own bytes; rgb is averaged in linear light, alpha linearly.
TEST(MipChain, Level0UnchangedRgbLinearAlphaLinear) {
  rp::scene::Texture t{"two", 2, 1, {0, 0, 0, 0, 255, 255, 255, 255}};
  const MipChain c = rp::render::build_mip_chain(t);
  ASSERT_EQ(c.texels.size(), 3u);
  EXPECT_EQ(c.texels[0], 0x00000000u);
  EXPECT_EQ(c.texels[1], 0xFFFFFFFFu);
  // Linear 0.5 is sRGB code 188 (187.5 before rounding); the alpha mean 127.5 rounds to 128.
  EXPECT_EQ(c.texels[2], 188u | 188u << 8 | 188u << 16 | 128u << 24);
}

// A data map (normals, roughness: Texture::srgb false) stands for code / 255, so its levels
// average the codes: the same two texels give 128 in every channel, not sRGB's 188; a 4x2 map's
// level 1 holds the means of its 2x2 blocks (rounded to nearest), level 2 the mean of all.
TEST(MipChain, DataMapsAverageTheirCodes) {
  rp::scene::Texture t{"two", 2, 1, {0, 0, 0, 0, 255, 255, 255, 255}};
  t.srgb = false;
  const MipChain c = rp::render::build_mip_chain(t);
  ASSERT_EQ(c.texels.size(), 3u);
  EXPECT_EQ(c.texels[0], 0x00000000u);
  EXPECT_EQ(c.texels[1], 0xFFFFFFFFu);
  EXPECT_EQ(c.texels[2], 128u | 128u << 8 | 128u << 16 | 128u << 24);

  rp::scene::Texture n{"normals", 4, 2, {}};
  n.srgb = false;
  const uint8_t codes[8] = {10, 20, 200, 210, 30, 41, 220, 231};  // row 0 then row 1, red
  for (uint8_t code : codes) n.rgba.insert(n.rgba.end(), {code, uint8_t(255 - code), 128, 255});
  const MipChain m = rp::render::build_mip_chain(n);
  ASSERT_EQ(m.levels.size(), 3u);
  const auto red = [&m](int level, int i) { return int(m.texels[m.levels[level].offset + i] & 0xFF); };
  const auto green = [&m](int level, int i) {
    return int((m.texels[m.levels[level].offset + i] >> 8) & 0xFF);
  };
  EXPECT_EQ(red(1, 0), 25);   // (10 + 20 + 30 + 41) / 4 = 25.25
  EXPECT_EQ(red(1, 1), 215);  // (200 + 210 + 220 + 231) / 4 = 215.25
  EXPECT_EQ(green(1, 0), 230);  // 255 - 25.25 = 229.75
  EXPECT_EQ(red(2, 0), 120);    // 962 / 8 = 120.25
  EXPECT_EQ(green(2, 0), 135);  // 255 - 120.25 = 134.75
}

// Each level against an explicit 2D area box filter of the previous level (the reference keeps
// linear doubles like the chain does): output texel (i, j) of an m x n level covers the input
// rectangle [i W / m, (i + 1) W / m] x [j H / n, (j + 1) H / n]; every input texel counts with
// its overlap area.
void check_chain_against_box_filter(int w0, int h0, uint32_t seed) {
  const rp::scene::Texture t = random_texture(w0, h0, seed);
  const MipChain c = rp::render::build_mip_chain(t);
  std::vector<double> prev(t.rgba.size());
  for (size_t i = 0; i < t.rgba.size(); i += 4) {
    for (int ch = 0; ch < 3; ++ch) prev[i + ch] = decode(t.rgba[i + ch]);
    prev[i + 3] = t.rgba[i + 3] / 255.0;
  }
  int w = w0, h = h0;
  for (size_t k = 1; k < c.levels.size(); ++k) {
    const int m = std::max(1, w / 2), n = std::max(1, h / 2);
    ASSERT_EQ(c.levels[k].width, uint32_t(m));
    ASSERT_EQ(c.levels[k].height, uint32_t(n));
    std::vector<double> next(size_t(m) * n * 4, 0.0);
    const double sx = double(w) / m, sy = double(h) / n;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < m; ++i)
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const double ox = std::min(x + 1.0, (i + 1) * sx) - std::max(double(x), i * sx);
            const double oy = std::min(y + 1.0, (j + 1) * sy) - std::max(double(y), j * sy);
            if (ox <= 0.0 || oy <= 0.0) continue;
            for (int ch = 0; ch < 4; ++ch)
              next[(size_t(j) * m + i) * 4 + ch] +=
                  ox * oy / (sx * sy) * prev[(size_t(y) * w + x) * 4 + ch];
          }
    for (int p = 0; p < m * n; ++p) {
      const uint32_t texel = c.texels[c.levels[k].offset + p];
      for (int ch = 0; ch < 4; ++ch) {
        const int got = int((texel >> (8 * ch)) & 0xFF);
        const double v = next[size_t(p) * 4 + ch];
        const int want = ch < 3 ? encode(v) : int(std::lround(v * 255.0));
        EXPECT_LE(std::abs(got - want), 0)
            << w0 << "x" << h0 << " level " << k << " texel " << p << " channel " << ch;
      }
    }
    prev = next;
    w = m;
    h = n;
  }
}

TEST(MipChain, OddSizedLevelsAreAreaBoxFilters) {
  check_chain_against_box_filter(5, 3, 7);
  check_chain_against_box_filter(7, 5, 8);
  check_chain_against_box_filter(11, 1, 9);
  check_chain_against_box_filter(6, 9, 10);
}

// ---- footprint and filtered samples in the GBuffer ----

constexpr int kTex = 64;  // texture side (7 levels)

// A 2 x 2 quad (uv 0..1 over it) turned by `tilt` about x (its top away from the camera at
// tilt > 0), in front of a camera at z = 3 looking at the origin; a W x W frame.
struct QuadScene {
  uint32_t size = 24;
  rp::scene::SceneAssets assets;
  rp::scene::FrameScene frame;
  glm::dmat4 model;
  uint32_t jitter_frames = 0;

  QuadScene(double tilt_deg, uint32_t frame_size, uint32_t jitter) : size(frame_size) {
    assets.textures.push_back(random_texture(kTex, kTex, 42));
    assets.materials = {{"wood", {1.0f, 1.0f, 1.0f}, {0.0f, 0.0f, 0.0f}, 0}};
    rp::scene::Mesh quad;
    quad.name = "quad";
    quad.vertices = {{{-1, -1, 0}, {0, 0, 1}, {0, 0}},
                     {{1, -1, 0}, {0, 0, 1}, {1, 0}},
                     {{1, 1, 0}, {0, 0, 1}, {1, 1}},
                     {{-1, 1, 0}, {0, 0, 1}, {0, 1}}};
    quad.triangles = {{0, 1, 2}, {0, 2, 3}};
    quad.materials = {0, 0};
    assets.meshes.push_back(quad);
    frame.camera.position = {0.0f, 0.0f, 3.0f};
    frame.camera.target = {0.0f, 0.0f, 0.0f};
    frame.camera.far_plane = 10.0f;
    frame.prev_camera = frame.camera;
    frame.frame_index = 5;
    const glm::mat4 m = glm::rotate(glm::mat4(1.0f), glm::radians(float(-tilt_deg)),
                                    glm::vec3(1, 0, 0));
    rp::scene::MeshInstance inst;
    inst.mesh = 0;
    inst.model = inst.prev_model = m;
    frame.instances.push_back(inst);
    model = glm::dmat4(m);
    jitter_frames = jitter;
  }

  glm::dvec3 world(int i) const {
    return glm::dvec3(model * glm::dvec4(glm::dvec3(assets.meshes[0].vertices[i].position), 1));
  }

  // Camera ray through screen point (sx, sy) (pixels; TAA jitter added by the caller).
  void ray(double sx, double sy, glm::dvec3& o, glm::dvec3& d) const {
    const glm::dmat4 vp = glm::dmat4(frame.camera.projection(1.0f)) * glm::dmat4(frame.camera.view());
    const glm::dmat4 inv = glm::inverse(vp);
    const double nx = sx / size * 2 - 1, ny = 1 - sy / size * 2;
    glm::dvec4 a = inv * glm::dvec4(nx, ny, -1, 1), b = inv * glm::dvec4(nx, ny, 1, 1);
    o = glm::dvec3(a) / a.w;
    d = glm::normalize(glm::dvec3(b) / b.w - o);
  }

  // The quad's uv where the ray through screen point (sx, sy) meets its plane (the mapping is
  // affine on the plane: u along v1 - v0, v along v3 - v0, perpendicular edges).
  glm::dvec2 uv_at(double sx, double sy) const {
    glm::dvec3 o, d;
    ray(sx, sy, o, d);
    const glm::dvec3 p0 = world(0), eu = world(1) - p0, ev = world(3) - p0;
    const glm::dvec3 n = glm::cross(eu, ev);
    const glm::dvec3 p = o + d * (glm::dot(n, p0 - o) / glm::dot(n, d));
    return {glm::dot(p - p0, eu) / glm::dot(eu, eu), glm::dot(p - p0, ev) / glm::dot(ev, ev)};
  }

  glm::dvec2 jitter() const {
    return glm::dvec2(rp::render::taa_jitter_px(frame.frame_index, jitter_frames));
  }
};

struct Footprint {
  bool hit = false;
  glm::dvec2 uv{0.0};
  glm::dvec2 ddx{0.0}, ddy{0.0};  // level-0 texel derivatives per pixel
};

// Reference footprint of pixel (x, y): central differences (h = 1/64 pixel) of the exact
// texel mapping around the jittered pixel centre (the jitter moves projected points by +j
// pixels, so the pixel centre sees the surface at unjittered screen point centre - j).
Footprint reference_footprint(const QuadScene& s, uint32_t x, uint32_t y) {
  const glm::dvec2 c = glm::dvec2(x + 0.5, y + 0.5) - s.jitter();
  Footprint f;
  f.uv = s.uv_at(c.x, c.y);
  f.hit = f.uv.x > 0 && f.uv.x < 1 && f.uv.y > 0 && f.uv.y < 1;
  const double h = 1.0 / 64;
  f.ddx = (s.uv_at(c.x + h, c.y) - s.uv_at(c.x - h, c.y)) * (double(kTex) / (2 * h));
  f.ddy = (s.uv_at(c.x, c.y + h) - s.uv_at(c.x, c.y - h)) * (double(kTex) / (2 * h));
  return f;
}

struct GBufferOut {
  std::vector<float> albedo, position, emission, velocity;
  std::vector<Footprint> ref;
};

// Hand-written visibility buffer of the quad (ray cast at the jittered pixel centres in double)
// resolved by the pass with `filter`; extra_options picks the kernel variant.
GBufferOut resolve(const QuadScene& s, uint32_t filter, const std::string& extra_options,
                   bool stochastic_levels = false) {
  auto& ctx = rp::test::context();
  rp::render::GpuScene scene(ctx.context, ctx.queue, s.assets);
  scene.update(s.frame, s.size, s.size, 64, 64, s.jitter_frames);
  const size_t n = size_t(s.size) * s.size;
  std::vector<uint32_t> ids(n * 2, RP_ID_NONE);
  std::vector<float> bary(n * 2, 0.0f);
  GBufferOut out;
  out.ref.resize(n);
  for (uint32_t y = 0; y < s.size; ++y)
    for (uint32_t x = 0; x < s.size; ++x) {
      const size_t i = size_t(y) * s.size + x;
      out.ref[i] = reference_footprint(s, x, y);
      if (!out.ref[i].hit) continue;
      const glm::dvec2 uv = out.ref[i].uv;
      // Barycentrics of the hit in the triangle that holds it.
      ids[i * 2] = 0;
      if (uv.x >= uv.y) {  // (v0, v1, v2): uv = b1 (1, 0) + b2 (1, 1)
        ids[i * 2 + 1] = 0;
        bary[i * 2] = float(uv.x - uv.y);
        bary[i * 2 + 1] = float(uv.y);
      } else {  // (v0, v2, v3): uv = b1 (1, 1) + b2 (0, 1)
        ids[i * 2 + 1] = 1;
        bary[i * 2] = float(uv.x);
        bary[i * 2 + 1] = float(uv.y - uv.x);
      }
    }
  rp::render::VisibilityBuffer vis;
  vis.resize(ctx.context, s.size, s.size);
  ctx.queue.enqueueWriteBuffer(vis.ids, CL_TRUE, 0, n * 8, ids.data());
  ctx.queue.enqueueWriteBuffer(vis.bary, CL_TRUE, 0, n * 8, bary.data());
  rp::render::GBuffer gb;
  gb.resize(ctx.context, s.size, s.size);
  rp::cl::Profiler profiler(ctx.queue);
  rp::passes::GBufferPass pass(ctx, rp::test::programs(), extra_options);
  pass.run(profiler, scene, vis, gb, filter, 0.0f, stochastic_levels);
  auto read = [&](const ::cl::Buffer& b, size_t count) {
    std::vector<float> v(count);
    ctx.queue.enqueueReadBuffer(b, CL_TRUE, 0, count * 4, v.data());
    return v;
  };
  out.albedo = read(gb.albedo, n * 4);
  out.position = read(gb.position, n * 4);
  out.emission = read(gb.emission, n * 4);
  out.velocity = read(gb.velocity, n * 2);
  return out;
}

int count_hits(const GBufferOut& g) {
  return int(std::count_if(g.ref.begin(), g.ref.end(), [](const Footprint& f) { return f.hit; }));
}

// Facing the camera at distance 3: the footprint is the same everywhere, closed form:
// texels per pixel = 32 texels per unit * (2 * 3 * tan(30 deg) / 32 units per pixel).
TEST(TextureFootprint, FacingQuadHasTheClosedFormLevel) {
  QuadScene s(0.0, 32, 0);
  const GBufferOut g = resolve(s, RP_TEXTURE_FILTER_TRILINEAR, "-DRP_GBUFFER_LOD_OUT");
  const double want = std::log2(32.0 * 2.0 * 3.0 * std::tan(glm::radians(30.0)) / 32.0);
  ASSERT_GT(count_hits(g), 100);
  for (size_t i = 0; i < g.ref.size(); ++i) {
    if (!g.ref[i].hit) continue;
    EXPECT_NEAR(g.emission[i * 4 + 3], want, 1e-3) << "lod at pixel " << i;
    EXPECT_NEAR(g.position[i * 4 + 3], want, 1e-3) << "log2 |dT/dx| at pixel " << i;
    EXPECT_NEAR(g.velocity[i * 2], want, 1e-3) << "log2 |dT/dy| at pixel " << i;
  }
}

// Tilted 60 degrees away, with TAA jitter: per pixel both footprint axes match the numerical
// derivatives of the exact mapping; the y axis (along the tilt) is the longer one, and the
// level of detail rises with distance (towards the top of the image).
TEST(TextureFootprint, TiltedQuadMatchesNumericalDerivatives) {
  for (const char* span : {"1", "8", "16"}) {
    setenv("ROLYPOLY_GBUFFER_SPAN", span, 1);
    QuadScene s(60.0, 32, 16);
    ASSERT_NE(s.jitter(), glm::dvec2(0.0));
    const GBufferOut g = resolve(s, RP_TEXTURE_FILTER_TRILINEAR, "-DRP_GBUFFER_LOD_OUT");
    unsetenv("ROLYPOLY_GBUFFER_SPAN");
    ASSERT_GT(count_hits(g), 60);
    // Mean level of detail of the quad's first and last rows.
    uint32_t first_row = s.size, last_row = 0;
    for (size_t i = 0; i < g.ref.size(); ++i)
      if (g.ref[i].hit) {
        first_row = std::min(first_row, uint32_t(i / s.size));
        last_row = std::max(last_row, uint32_t(i / s.size));
      }
    double top_lod = 0.0, bottom_lod = 0.0;
    int top_n = 0, bottom_n = 0;
    for (size_t i = 0; i < g.ref.size(); ++i) {
      const Footprint& f = g.ref[i];
      if (!f.hit) continue;
      const double lx = std::log2(glm::length(f.ddx)), ly = std::log2(glm::length(f.ddy));
      EXPECT_NEAR(g.position[i * 4 + 3], lx, 2e-3) << "span " << span << " pixel " << i;
      EXPECT_NEAR(g.velocity[i * 2], ly, 2e-3) << "span " << span << " pixel " << i;
      EXPECT_NEAR(g.emission[i * 4 + 3], std::max(lx, ly), 2e-3) << "lod, pixel " << i;
      EXPECT_GT(ly, lx + 0.5) << "the tilt stretches the footprint along y, pixel " << i;
      const uint32_t y = uint32_t(i / s.size);
      if (y == first_row) top_lod += g.emission[i * 4 + 3], ++top_n;
      if (y == last_row) bottom_lod += g.emission[i * 4 + 3], ++bottom_n;
    }
    ASSERT_GT(last_row, first_row + 4);
    EXPECT_GT(top_lod / top_n, bottom_lod / bottom_n + 0.2) << "farther rows take coarser levels";
  }
}

// ---- reference sampler ----

struct LinearLevels {
  std::vector<rp::render::MipLevel> levels;
  std::vector<glm::dvec3> texels;
};

LinearLevels linear_levels(const rp::scene::Texture& t) {
  const MipChain c = rp::render::build_mip_chain(t);
  LinearLevels out{c.levels, {}};
  for (uint32_t texel : c.texels)
    out.texels.push_back({decode(texel & 0xFF), decode((texel >> 8) & 0xFF),
                          decode((texel >> 16) & 0xFF)});
  return out;
}

// Bilinear, wrap, texel row = (1 - v) * height, in level k.
glm::dvec3 bilinear(const LinearLevels& t, int k, glm::dvec2 uv) {
  const rp::render::MipLevel& l = t.levels[size_t(k)];
  const int w = int(l.width), h = int(l.height);
  const double x = uv.x * w - 0.5, y = (1.0 - uv.y) * h - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
  auto at = [&](double xi, double yi) {
    const int tx = ((int(xi) % w) + w) % w, ty = ((int(yi) % h) + h) % h;
    return t.texels[l.offset + size_t(ty) * w + tx];
  };
  return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx),
                  glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
}

glm::dvec3 trilinear(const LinearLevels& t, double lod, glm::dvec2 uv) {
  lod = std::clamp(lod, 0.0, double(t.levels.size() - 1));
  const int l0 = int(std::floor(lod));
  const double f = lod - l0;
  if (f == 0.0) return bilinear(t, l0, uv);
  return glm::mix(bilinear(t, l0, uv), bilinear(t, l0 + 1, uv), f);
}

constexpr int kMaxAniso = 4;  // gbuffer.cl RP_TEXTURE_MAX_ANISO

void check_filtered(uint32_t filter, const char* span, double tilt, uint32_t size) {
  setenv("ROLYPOLY_GBUFFER_SPAN", span, 1);
  QuadScene s(tilt, size, 16);
  const GBufferOut g = resolve(s, filter, "");
  unsetenv("ROLYPOLY_GBUFFER_SPAN");
  const LinearLevels tex = linear_levels(s.assets.textures[0]);
  const int lanes = std::stoi(span);
  size_t bad = 0, checked = 0, differs_from_level0 = 0;
  for (uint32_t y = 0; y < s.size; ++y)
    for (uint32_t x0 = 0; x0 < s.size; x0 += uint32_t(lanes)) {
      // Taps per lane: the span's largest ceil(major / minor), capped (gbuffer.cl); a ratio
      // within 1e-3 of a whole number could round either way: skip that span.
      int taps = 1;
      bool ambiguous = false;
      for (uint32_t x = x0; x < x0 + uint32_t(lanes) && x < s.size; ++x) {
        const Footprint& f = g.ref[size_t(y) * s.size + x];
        if (!f.hit) continue;
        const double a = glm::length(f.ddx), b = glm::length(f.ddy);
        const double ratio = std::min(std::max(a, b) / std::min(a, b), double(kMaxAniso));
        ambiguous |= std::fabs(ratio - std::round(ratio)) < 1e-3 && ratio < kMaxAniso;
        taps = std::max(taps, int(std::ceil(ratio)));
      }
      if (ambiguous) continue;
      for (uint32_t x = x0; x < x0 + uint32_t(lanes) && x < s.size; ++x) {
        const size_t i = size_t(y) * s.size + x;
        const Footprint& f = g.ref[i];
        if (!f.hit) continue;
        const double lx = glm::length(f.ddx), ly = glm::length(f.ddy);
        glm::dvec3 want(0.0);
        if (filter == RP_TEXTURE_FILTER_TRILINEAR) {
          want = trilinear(tex, std::log2(std::max(lx, ly)), f.uv);
        } else {
          const double major = std::max(lx, ly), minor = std::min(lx, ly);
          const glm::dvec2 axis = (ly > lx ? f.ddy : f.ddx) / double(kTex);  // uv units
          const double lod = std::log2(std::max(minor, major / taps));
          for (int k = 0; k < taps; ++k)
            want += trilinear(tex, lod, f.uv + axis * ((k + 0.5) / taps - 0.5));
          want /= double(taps);
        }
        ++checked;
        const glm::dvec3 level0 = bilinear(tex, 0, f.uv);
        differs_from_level0 += glm::length(want - level0) > 0.05;
        for (int c = 0; c < 3; ++c)
          if (!(std::fabs(g.albedo[i * 4 + c] - want[c]) <= 4e-3) && bad++ < 8)
            ADD_FAILURE() << "span " << span << " pixel " << x << "," << y << " channel " << c
                          << ": " << g.albedo[i * 4 + c] << " vs reference " << want[c];
      }
    }
  EXPECT_EQ(bad, 0u);
  EXPECT_GT(checked, 60u);
  EXPECT_GT(differs_from_level0, checked / 2) << "the filter must matter in this scene";
}

TEST(TextureFilter, TrilinearMatchesReferenceSampler) {
  check_filtered(RP_TEXTURE_FILTER_TRILINEAR, "1", 60.0, 32);
  check_filtered(RP_TEXTURE_FILTER_TRILINEAR, "8", 60.0, 32);
  check_filtered(RP_TEXTURE_FILTER_TRILINEAR, "16", 60.0, 32);  // the CPU layout
}

TEST(TextureFilter, AnisotropicMatchesReferenceSampler) {
  check_filtered(RP_TEXTURE_FILTER_ANISOTROPIC, "1", 60.0, 32);
  check_filtered(RP_TEXTURE_FILTER_ANISOTROPIC, "8", 60.0, 32);
  check_filtered(RP_TEXTURE_FILTER_ANISOTROPIC, "8", 80.0, 48);  // ratios past the cap
  check_filtered(RP_TEXTURE_FILTER_ANISOTROPIC, "16", 80.0, 48);
}

// Stochastic trilinear (the renderer's mode under TAA): every pixel holds ONE of the two
// levels' bilinear samples, the upper one about as often as the blend weights say (the same
// mean as trilinear), at the GPU layout and 8-pixel spans.
TEST(TextureFilter, StochasticTrilinearPicksOneLevelWithTheBlendWeight) {
  for (const char* span : {"1", "8", "16"}) {
    setenv("ROLYPOLY_GBUFFER_SPAN", span, 1);
    QuadScene s(60.0, 48, 16);
    const GBufferOut g = resolve(s, RP_TEXTURE_FILTER_TRILINEAR, "", true);
    unsetenv("ROLYPOLY_GBUFFER_SPAN");
    const LinearLevels tex = linear_levels(s.assets.textures[0]);
    size_t bad = 0, told_apart = 0, upper = 0;
    double expected = 0.0, variance = 0.0;
    for (size_t i = 0; i < g.ref.size(); ++i) {
      const Footprint& f = g.ref[i];
      if (!f.hit) continue;
      const double lod = std::clamp(std::log2(std::max(glm::length(f.ddx), glm::length(f.ddy))),
                                    0.0, double(tex.levels.size() - 1));
      const int l0 = int(std::floor(lod));
      const double frac = lod - l0;
      const glm::dvec3 lo = bilinear(tex, l0, f.uv);
      const glm::dvec3 hi = l0 + 1 < int(tex.levels.size()) ? bilinear(tex, l0 + 1, f.uv) : lo;
      const glm::dvec3 got(g.albedo[i * 4], g.albedo[i * 4 + 1], g.albedo[i * 4 + 2]);
      const double d_lo = glm::length(got - lo), d_hi = glm::length(got - hi);
      if (!(std::min(d_lo, d_hi) <= 7e-3) && bad++ < 8)
        ADD_FAILURE() << "span " << span << " pixel " << i << ": neither level";
      if (glm::length(hi - lo) > 0.05) {  // the two levels can be told apart
        ++told_apart;
        upper += d_hi < d_lo;
        expected += frac;
        variance += frac * (1.0 - frac);
      }
    }
    EXPECT_EQ(bad, 0u) << span;
    ASSERT_GT(told_apart, 200u) << span;
    EXPECT_LE(std::fabs(double(upper) - expected), 4.0 * std::sqrt(variance) + 1.0)
        << "span " << span << ": " << upper << " upper picks, " << expected << " expected";
  }
}

}  // namespace
