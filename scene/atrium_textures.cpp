// The atrium's procedural textures and materials (scene/atrium_build.h): 43 textures, each
// computed per texel from integer-hashed lattice noise, so they tile (every pattern's period
// divides the texture) and come out the same on every run. A material's albedo is sRGB bytes,
// its metallic-roughness map holds roughness in G and metallic in B (glTF), and its normal map
// is the central difference of a height field (tangent space, +y along the texture's v-up).
#include <algorithm>
#include <cmath>
#include <string>

#include "scene/atrium_build.h"

namespace rp::scene::atrium {
namespace {

// What a generator says about one texel; colours in sRGB [0, 1].
struct Texel {
  glm::vec3 colour{0.5f};
  float height = 0.5f;  // [0, 1], for the normal map
  float rough = 1.0f;
  float metal = 0.0f;
  float alpha = 1.0f;
};
using TexelFn = std::function<Texel(int x, int y)>;

float smooth(float t) { return t * t * (3.0f - 2.0f * t); }
float ramp(float a, float b, float x) { return smooth(std::clamp((x - a) / (b - a), 0.0f, 1.0f)); }

// Value noise on a lattice of `period` cells across the texture (u, v in [0, 1)), wrapping.
float noise(uint32_t seed, float u, float v, int period) {
  const float x = u * float(period), y = v * float(period);
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float fx = smooth(x - float(x0)), fy = smooth(y - float(y0));
  const auto at = [&](int i, int j) {
    return unit(hash(seed, uint32_t(((i % period) + period) % period),
                     uint32_t(((j % period) + period) % period)));
  };
  const float a = at(x0, y0) + (at(x0 + 1, y0) - at(x0, y0)) * fx;
  const float b = at(x0, y0 + 1) + (at(x0 + 1, y0 + 1) - at(x0, y0 + 1)) * fx;
  return a + (b - a) * fy;
}

// Octaves of noise from `period` cells up, each twice as fine and half as strong; [0, 1].
float fbm(uint32_t seed, float u, float v, int period, int octaves) {
  float sum = 0.0f, amp = 1.0f, total = 0.0f;
  for (int k = 0; k < octaves; ++k) {
    sum += amp * noise(seed + uint32_t(k) * 101u, u, v, period << k);
    total += amp;
    amp *= 0.5f;
  }
  return sum / total;
}

// A running bond of `cols` x `rows` blocks across the texture (odd rows shifted half a block):
// the texel's distance to the nearest joint in texels and the block's id.
struct Block {
  float edge;
  uint32_t id;
};
Block bond(int x, int y, int size, int cols, int rows) {
  const int bw = size / cols, bh = size / rows;
  const int row = y / bh;
  const int xs = (x + (row % 2 ? bw / 2 : 0)) % size;
  const int col = xs / bw;
  const int dx = std::min(xs % bw, bw - 1 - xs % bw), dy = std::min(y % bh, bh - 1 - y % bh);
  return {float(std::min(dx, dy)) + 0.5f, hash(uint32_t(row), uint32_t(col))};
}

glm::vec3 mix(glm::vec3 a, glm::vec3 b, float t) { return a + (b - a) * t; }

uint8_t byte(float x) { return uint8_t(std::lround(std::clamp(x, 0.0f, 1.0f) * 255.0f)); }

struct Maps {
  int albedo = -1, normal = -1, mr = -1;
};
// Which maps bake() makes: bit 0 albedo, bit 1 metallic-roughness, bit 2 normal.
enum MapSet { kAlbedoOnly = 1, kWithMr = 3, kDetailOnly = 6, kAll = 7 };

// Bakes `f` into an albedo (sRGB, alpha from Texel::alpha), a normal map (`bump`: height units
// per texel of slope) and a metallic-roughness map, as `which` asks.
Maps bake(SceneAssets& a, const std::string& name, int size, float bump, MapSet which,
          const TexelFn& f, TextureWrap wrap = TextureWrap::kRepeat) {
  std::vector<Texel> t(size_t(size * size));
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) t[size_t(y * size + x)] = f(x, y);
  const auto texture = [&](const char* kind, bool srgb) {
    Texture tex;
    tex.name = name + "_" + kind;
    tex.width = tex.height = size;
    tex.srgb = srgb;
    tex.wrap_u = tex.wrap_v = wrap;
    tex.rgba.assign(size_t(size * size * 4), 255);
    return tex;
  };
  Maps maps;
  if (which & 1) {
    Texture albedo = texture("albedo", true);
    for (size_t k = 0; k < t.size(); ++k)
      for (int c = 0; c < 4; ++c)
        albedo.rgba[k * 4 + size_t(c)] = byte(c < 3 ? t[k].colour[c] : t[k].alpha);
    maps.albedo = int(a.textures.size());
    a.textures.push_back(std::move(albedo));
  }
  if (which & 2) {
    Texture mr = texture("metallic_roughness", false);
    for (size_t k = 0; k < t.size(); ++k) {
      mr.rgba[k * 4 + 1] = byte(t[k].rough);
      mr.rgba[k * 4 + 2] = byte(t[k].metal);
    }
    maps.mr = int(a.textures.size());
    a.textures.push_back(std::move(mr));
  }
  if (which & 4) {
    Texture normal = texture("normal", false);
    const auto h = [&](int x, int y) {
      return t[size_t(((y + size) % size) * size + (x + size) % size)].height;
    };
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        // Rows run down the image and v up: the slope along +v is minus the slope along rows.
        const glm::vec3 n =
            glm::normalize(glm::vec3(-0.5f * bump * (h(x + 1, y) - h(x - 1, y)),
                                     0.5f * bump * (h(x, y + 1) - h(x, y - 1)), 1.0f));
        uint8_t* p = &normal.rgba[size_t(y * size + x) * 4];
        for (int c = 0; c < 3; ++c) p[c] = byte(n[c] * 0.5f + 0.5f);
      }
    maps.normal = int(a.textures.size());
    a.textures.push_back(std::move(normal));
  }
  return maps;
}

Material& material(SceneAssets& a, const char* name, const Maps& maps, float f0 = 0.04f) {
  Material m;
  m.name = name;
  m.albedo = glm::vec3(1.0f);
  m.texture = maps.albedo;
  m.normal_texture = maps.normal;
  m.metallic_roughness_texture = maps.mr;
  m.specular = {1.0f, f0, false};  // roughness from the map's G channel
  a.materials.push_back(m);
  return a.materials.back();
}

// A cloth banner's pattern: u across (0..1), up along it (0 bottom .. 1 top), `aspect` its
// length over its width; a notched hem cut out by alpha.
Texel banner_texel(int x, int y, int size, uint32_t kind) {
  const float u = (float(x) + 0.5f) / float(size), up = 1.0f - (float(y) + 0.5f) / float(size);
  const float aspect = 4.0f, du = std::abs(u - 0.5f);
  static const glm::vec3 grounds[3] = {
      {0.62f, 0.09f, 0.08f}, {0.10f, 0.18f, 0.52f}, {0.11f, 0.38f, 0.17f}};
  const glm::vec3 gold(0.86f, 0.66f, 0.24f), cream(0.88f, 0.85f, 0.76f);
  Texel t;
  t.colour = grounds[kind] * (0.9f + 0.2f * fbm(40 + kind, u, up, 8, 3));
  const bool border = du > 0.42f || up > 0.96f || (up < 0.12f && up > 0.09f);
  if (border) t.colour = kind == 1 ? cream : gold;
  const float dy = (up - 0.7f) * aspect;
  const float r = std::sqrt((u - 0.5f) * (u - 0.5f) + dy * dy);
  if (kind == 0 && r > 0.2f && r < 0.28f) t.colour = gold;                      // a ring
  if (kind == 0 && std::abs(u - 0.5f) + std::abs(dy) < 0.11f) t.colour = gold;  // a lozenge
  if (kind == 1 && du < 0.3f) {  // chevrons down the middle
    const float c = up * aspect * 1.5f + du * 2.0f;
    if (c - std::floor(c) < 0.22f && up > 0.15f && up < 0.9f) t.colour = cream;
  }
  if (kind == 2 && !border) {  // stripes and a diamond
    const float s = up * aspect * 2.0f;
    if (s - std::floor(s) < 0.08f && up > 0.15f) t.colour = gold;
    if (du + std::abs(dy) < 0.2f && du + std::abs(dy) > 0.13f) t.colour = gold;
  }
  t.alpha = up > 0.09f * (1.0f - 2.0f * du) ? 1.0f : 0.0f;  // a notched hem
  return t;
}

}  // namespace

void add_materials(SceneAssets& a) {
  // Floor tiles: an 8 x 8 checker of cream marble and terracotta in 2.5-texel grout, each tile
  // its own shade; tiles glossy, grout rough and sunk.
  const Maps tiles = bake(a, "floor_tiles", 512, 6.0f, kAll, [](int x, int y) {
    const int tx = x / 64, ty = y / 64;
    const float edge = float(std::min({x % 64, 63 - x % 64, y % 64, 63 - y % 64})) + 0.5f;
    const uint32_t id = hash(uint32_t(tx), uint32_t(ty), 7u);
    const float u = float(x) / 512.0f, v = float(y) / 512.0f;
    Texel t;
    const glm::vec3 cream(0.84f, 0.78f, 0.66f), red(0.60f, 0.31f, 0.21f);
    t.colour = ((tx + ty) % 2 ? red : cream) * (0.88f + 0.12f * unit(id)) *
               (0.9f + 0.2f * fbm(1, u, v, 16, 4));
    const float g = ramp(2.0f, 4.5f, edge);
    t.colour = mix(glm::vec3(0.42f, 0.40f, 0.36f), t.colour, g);
    t.height = 0.6f * g + 0.05f * fbm(2, u, v, 32, 3);
    t.rough = 0.95f - 0.55f * g + 0.15f * fbm(3, u, v, 16, 3);
    return t;
  });
  // Flagstones: four rows of slabs of uneven length, grey-beige, worn.
  const Maps flags = bake(a, "flagstone", 512, 4.0f, kAll, [](int x, int y) {
    const int row = y / 128;
    const uint32_t rh = hash(uint32_t(row), 11u);
    const int n = 2 + int(rh % 3), offset = int(hash(rh) % 512u);
    const int xs = (x - offset + 512) % 512;
    int lo = 0, hi = 512, slab = n - 1;
    for (int k = 1; k < n; ++k) {
      const int cut = k * 512 / n + int(hash(rh, uint32_t(k)) % 41u) - 20;
      if (xs < cut) {
        hi = cut;
        slab = k - 1;
        break;
      }
      lo = cut;
    }
    const float edge = float(std::min({xs - lo, hi - 1 - xs, y % 128, 127 - y % 128})) + 0.5f;
    const uint32_t id = hash(rh, uint32_t(slab), 5u);
    const float u = float(x) / 512.0f, v = float(y) / 512.0f;
    Texel t;
    t.colour = glm::vec3(0.62f, 0.58f, 0.52f) * (0.85f + 0.2f * unit(id)) *
               (0.85f + 0.3f * fbm(12, u, v, 8, 5));
    const float g = ramp(1.5f, 5.0f, edge);
    t.colour *= 0.55f + 0.45f * g;
    t.height = 0.5f * g + 0.15f * fbm(13, u, v, 16, 4);
    t.rough = 0.9f - 0.25f * fbm(14, u, v, 8, 3) * g;
    return t;
  });
  // Sandstone: fine grain and faint bedding lines (columns, arches, trim).
  const Maps stone = bake(a, "stone", 512, 3.0f, kAll, [](int x, int y) {
    const float u = float(x) / 512.0f, v = float(y) / 512.0f;
    const float grain = fbm(21, u, v, 32, 4), bed = fbm(22, u, v, 4, 3);
    const float s = std::sin(6.2831853f * (v * 12.0f + 0.6f * bed));
    Texel t;
    t.colour = glm::vec3(0.80f, 0.71f, 0.57f) * (0.86f + 0.18f * grain + 0.04f * s);
    t.height = 0.4f * grain + 0.05f * s;
    t.rough = 0.8f + 0.15f * grain;
    return t;
  });
  // Ashlar: 1 x 0.5 m blocks (two per row, four rows per 2 m repeat) in thin mortar joints.
  const Maps ashlar = bake(a, "ashlar", 512, 5.0f, kAll, [](int x, int y) {
    const Block b = bond(x, y, 512, 2, 4);
    const float u = float(x) / 512.0f, v = float(y) / 512.0f;
    Texel t;
    t.colour = glm::vec3(0.78f, 0.70f, 0.58f) * (0.88f + 0.14f * unit(b.id)) *
               (0.88f + 0.24f * fbm(31, u, v, 16, 4));
    const float g = ramp(1.0f, 4.0f, b.edge);
    t.colour = mix(glm::vec3(0.55f, 0.52f, 0.47f), t.colour, g);
    t.height = 0.5f * g + 0.2f * fbm(32, u, v, 32, 3);
    t.rough = 0.85f;
    return t;
  });
  // Lime plaster: warm off-white, broad stains, fine trowel bumps (vaults, aisle walls).
  const Maps plaster = bake(a, "plaster", 512, 2.0f, kAll, [](int x, int y) {
    const float u = float(x) / 512.0f, v = float(y) / 512.0f;
    const float stain = fbm(41, u, v, 4, 4);
    Texel t;
    t.colour = glm::vec3(0.90f, 0.84f, 0.71f) * (0.8f + 0.2f * stain);
    t.height = 0.5f * fbm(42, u, v, 32, 4);
    t.rough = 0.92f;
    return t;
  });
  // Brick: 16 courses of 4 bricks per 1 m repeat, running bond, recessed mortar.
  const Maps brick = bake(a, "brick", 512, 6.0f, kAll, [](int x, int y) {
    const Block b = bond(x, y, 512, 4, 16);
    const float u = float(x) / 512.0f, v = float(y) / 512.0f;
    Texel t;
    const glm::vec3 dark(0.45f, 0.20f, 0.13f), light(0.70f, 0.38f, 0.25f);
    t.colour = mix(dark, light, unit(b.id)) * (0.85f + 0.3f * fbm(51, u, v, 32, 3));
    const float g = ramp(1.5f, 3.5f, b.edge);
    t.colour = mix(glm::vec3(0.62f, 0.60f, 0.55f), t.colour, g);
    t.height = 0.6f * g + 0.15f * fbm(52, u, v, 64, 2);
    t.rough = 0.88f;
    return t;
  });
  // Wood: four planks along u, growth rings warped by noise, dark seams.
  const Maps wood = bake(a, "wood", 256, 4.0f, kAll, [](int x, int y) {
    const float u = float(x) / 256.0f, v = float(y) / 256.0f;
    const int plank = y / 64;
    const float w = fbm(61 + uint32_t(plank), u, v, 4, 4);
    const float ring = float(y % 64) * 0.35f + 9.0f * w;
    const float stripe = 0.5f + 0.5f * std::sin(6.2831853f * (ring - std::floor(ring)));
    Texel t;
    t.colour = glm::vec3(0.52f, 0.34f, 0.19f) * (0.78f + 0.22f * stripe) *
               (0.9f + 0.2f * unit(hash(uint32_t(plank), 62u)));
    const float seam = ramp(0.5f, 2.0f, float(std::min(y % 64, 63 - y % 64)) + 0.5f);
    t.colour *= 0.5f + 0.5f * seam;
    t.height = 0.5f * seam + 0.08f * stripe;
    t.rough = 0.6f - 0.1f * stripe;
    return t;
  });
  // Marble: white with grey veins (balustrade, fountain), polished.
  const Maps marble = bake(a, "marble", 256, 1.0f, kAll, [](int x, int y) {
    const float u = float(x) / 256.0f, v = float(y) / 256.0f;
    const float s = std::abs(std::sin(6.2831853f * (2.0f * u + v + 0.8f * fbm(71, u, v, 4, 5))));
    float vein = 1.0f - s;
    vein *= vein;
    vein *= vein;
    Texel t;
    t.colour = mix(glm::vec3(0.93f, 0.92f, 0.89f), glm::vec3(0.45f, 0.46f, 0.48f), vein);
    t.height = 0.5f - 0.3f * vein;
    t.rough = 0.22f + 0.1f * fbm(72, u, v, 16, 2);
    return t;
  });
  // Terracotta: orange-red clay with throwing rings (pots).
  const Maps clay = bake(a, "terracotta", 256, 3.0f, kAll, [](int x, int y) {
    const float u = float(x) / 256.0f, v = float(y) / 256.0f;
    const float ring = 0.5f + 0.5f * std::sin(6.2831853f * 24.0f * v);
    Texel t;
    t.colour = glm::vec3(0.74f, 0.42f, 0.27f) * (0.85f + 0.25f * fbm(81, u, v, 8, 4));
    t.height = 0.2f * ring + 0.3f * fbm(82, u, v, 32, 3);
    t.rough = 0.82f;
    return t;
  });
  // Cloth: a plain weave of 4-texel threads (normal and roughness shared by all cloth).
  const Maps weave = bake(a, "weave", 256, 1.5f, kDetailOnly, [](int x, int y) {
    const bool warp = ((x / 4) + (y / 4)) % 2 == 0;
    const float across = float(warp ? x % 4 : y % 4) + 0.5f;
    Texel t;
    t.height = std::sin(3.1415927f * across / 4.0f);
    t.rough = 0.95f;
    return t;
  });
  Maps banners[3];
  for (uint32_t k = 0; k < 3; ++k) {
    static const char* const names[3] = {"banner_red", "banner_blue", "banner_green"};
    banners[k] = bake(
        a, names[k], 256, 0.0f, kAlbedoOnly,
        [k](int x, int y) { return banner_texel(x, y, 256, k); }, TextureWrap::kClampToEdge);
  }
  // Curtain: ochre damask, lozenges on a 4 x 4 lattice per repeat.
  const Maps curtain = bake(a, "curtain", 256, 0.0f, kAlbedoOnly, [](int x, int y) {
    const float u = float(x) / 256.0f, v = float(y) / 256.0f;
    const float d = std::abs(u * 4.0f - std::floor(u * 4.0f) - 0.5f) +
                    std::abs(v * 4.0f - std::floor(v * 4.0f) - 0.5f);
    Texel t;
    t.colour = glm::vec3(0.72f, 0.52f, 0.18f) * (0.9f + 0.15f * fbm(91, u, v, 16, 3));
    if ((d > 0.28f && d < 0.36f) || d < 0.08f) t.colour *= 0.62f;
    return t;
  });
  // Tapestry: a dark red border around a lattice of blue, green and cream lozenges.
  const Maps tapestry = bake(
      a, "tapestry", 256, 0.0f, kAlbedoOnly,
      [](int x, int y) {
        const float u = float(x) / 256.0f, v = float(y) / 256.0f;
        Texel t;
        const float border = std::min({u, 1.0f - u, v, 1.0f - v});
        const int cx = int(u * 6.0f), cy = int(v * 6.0f);
        const float d =
            std::abs(u * 6.0f - float(cx) - 0.5f) + std::abs(v * 6.0f - float(cy) - 0.5f);
        static const glm::vec3 palette[3] = {
            {0.16f, 0.24f, 0.52f}, {0.18f, 0.40f, 0.22f}, {0.85f, 0.78f, 0.60f}};
        t.colour = d < 0.45f ? palette[uint32_t(cx + 2 * cy) % 3u] : glm::vec3(0.55f, 0.12f, 0.10f);
        if (d > 0.38f && d < 0.45f) t.colour = glm::vec3(0.86f, 0.66f, 0.24f);
        if (border < 0.06f) t.colour = glm::vec3(0.45f, 0.08f, 0.07f);
        if (border > 0.035f && border < 0.045f) t.colour = glm::vec3(0.86f, 0.66f, 0.24f);
        t.colour *= 0.9f + 0.15f * fbm(95, u, v, 16, 3);
        return t;
      },
      TextureWrap::kClampToEdge);
  // Leaves, cut out by alpha: a fern frond (a stem and slanted leaflets) and a broad leaf
  // (midrib, lateral veins); u across, up from the stalk (0) to the tip (1).
  const Maps fern = bake(
      a, "fern", 256, 0.0f, kAlbedoOnly,
      [](int x, int y) {
        const float u = (float(x) + 0.5f) / 256.0f, up = 1.0f - (float(y) + 0.5f) / 256.0f;
        const float du = std::abs(u - 0.5f);
        const float w = 0.47f * (1.0f - up) * std::min(1.0f, up * 6.0f);
        const float p = (up - 0.6f * du) * 16.0f;
        const float leaflet = std::abs(p - std::floor(p) - 0.5f);
        const bool in =
            du < 0.012f ? up < 0.98f : (du < w && leaflet < 0.34f * (1.0f - du / w) + 0.04f);
        Texel t;
        t.colour = glm::vec3(0.25f, 0.46f, 0.13f) * (0.75f + 0.35f * du / 0.47f) *
                   (0.9f + 0.2f * fbm(101, u, up, 8, 3));
        t.alpha = in ? 1.0f : 0.0f;
        return t;
      },
      TextureWrap::kClampToEdge);
  const Maps broad = bake(
      a, "broad_leaf", 256, 0.0f, kAlbedoOnly,
      [](int x, int y) {
        const float u = (float(x) + 0.5f) / 256.0f, up = 1.0f - (float(y) + 0.5f) / 256.0f;
        const float du = std::abs(u - 0.5f);
        const float s = std::sin(3.1415927f * std::clamp((up - 0.12f) / 0.88f, 0.0f, 1.0f));
        const bool in = up < 0.12f ? du < 0.015f : du < 0.46f * std::sqrt(s);
        const float vein = (up - 0.7f * du) * 9.0f;
        const bool lateral = vein - std::floor(vein) < 0.06f;
        Texel t;
        t.colour = glm::vec3(0.17f, 0.38f, 0.11f) * (0.85f + 0.25f * fbm(111, u, up, 8, 3));
        if (du < 0.012f || lateral) t.colour = glm::vec3(0.36f, 0.52f, 0.20f);
        t.alpha = in ? 1.0f : 0.0f;
        return t;
      },
      TextureWrap::kClampToEdge);
  const Maps leaf = bake(a, "leaf", 256, 2.0f, kDetailOnly, [](int x, int y) {
    const float u = float(x) / 256.0f, v = float(y) / 256.0f;
    Texel t;
    t.height = fbm(121, u, v, 32, 2);
    t.rough = 0.5f + 0.1f * t.height;
    return t;
  });
  // Iron (lamps, railings): dark metal with rust blotches that are rough and not metallic.
  const Maps iron = bake(a, "iron", 256, 0.0f, kWithMr, [](int x, int y) {
    const float u = float(x) / 256.0f, v = float(y) / 256.0f;
    const float rust = ramp(0.58f, 0.68f, fbm(131, u, v, 8, 4));
    Texel t;
    t.colour = mix(glm::vec3(0.36f, 0.35f, 0.34f), glm::vec3(0.45f, 0.24f, 0.12f), rust);
    t.rough = 0.45f + 0.45f * rust;
    t.metal = 1.0f - rust;
    return t;
  });
  // Brass (lamp caps, fountain spout): polished, lightly tarnished.
  const Maps brass = bake(a, "brass", 256, 0.0f, kWithMr, [](int x, int y) {
    const float u = float(x) / 256.0f, v = float(y) / 256.0f;
    const float tarnish = fbm(141, u, v, 8, 4);
    Texel t;
    t.colour = glm::vec3(0.88f, 0.72f, 0.42f) * (0.85f + 0.15f * tarnish);
    t.rough = 0.25f + 0.2f * tarnish;
    t.metal = 1.0f;
    return t;
  });
  const Maps soil = bake(a, "soil", 256, 0.0f, kAlbedoOnly, [](int x, int y) {
    const float u = float(x) / 256.0f, v = float(y) / 256.0f;
    Texel t;
    t.colour = glm::vec3(0.27f, 0.19f, 0.13f) * (0.6f + 0.6f * fbm(151, u, v, 32, 3));
    return t;
  });

  // Materials, in the order of Mat.
  material(a, "floor_tiles", tiles);
  material(a, "flagstone", flags);
  material(a, "stone", stone);
  material(a, "ashlar", ashlar);
  material(a, "plaster", plaster);
  material(a, "brick", brick);
  material(a, "wood", wood);
  material(a, "marble", marble);
  material(a, "terracotta", clay);
  for (int k = 0; k < 3; ++k) {
    static const char* const names[3] = {"banner_red", "banner_blue", "banner_green"};
    Material& m = material(a, names[k], {banners[k].albedo, weave.normal, weave.mr});
    m.alpha_mode = AlphaMode::kMask;
    m.double_sided = true;
  }
  material(a, "curtain", {curtain.albedo, weave.normal, weave.mr}).double_sided = true;
  material(a, "tapestry", {tapestry.albedo, weave.normal, weave.mr}).double_sided = true;
  for (const Maps* m : {&fern, &broad}) {
    Material& leaves =
        material(a, m == &fern ? "fern" : "broad_leaf", {m->albedo, leaf.normal, leaf.mr});
    leaves.alpha_mode = AlphaMode::kMask;
    leaves.double_sided = true;
  }
  for (const Maps* m : {&iron, &brass}) {
    Material& metal = material(a, m == &iron ? "iron" : "brass", *m);
    metal.metallic = 1.0f;
    metal.specular.metal = true;
  }
  material(a, "soil", soil);
  Material& water = material(a, "water", Maps{}, 0.02f);  // n = 1.33
  water.albedo = glm::vec3(0.04f, 0.07f, 0.08f);
  water.specular.roughness = 0.05f;
}

}  // namespace rp::scene::atrium
