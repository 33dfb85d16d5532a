// glTF materials as scene::Material, and their textures. Materials are converted when a drawn
// primitive first uses one, so images no drawn surface needs are never decoded. One
// scene::Texture per (glTF texture, colour or data use): the same image read as base colour
// (sRGB) and as a normal map (linear) becomes two textures with the right `srgb` flag.
#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <new>

#include <stb/stb_image.h>
#include <tiny_gltf.h>

#include "scene/gltf_internal.h"

namespace rp::scene::gltf {
namespace {

float clamp01(const Context& ctx, double v, const std::string& where) {
  return to_float(ctx, std::clamp(v, 0.0, 1.0), where);
}

TextureWrap wrap_mode(const Context& ctx, int mode, const std::string& where) {
  switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return TextureWrap::kRepeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::kClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::kMirroredRepeat;
    default: ctx.fail(where + ": wrap mode " + std::to_string(mode) + " is not a glTF wrap mode");
  }
}

bool is_png(const std::vector<unsigned char>& b) {
  static const unsigned char kMagic[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  return b.size() >= 8 && std::memcmp(b.data(), kMagic, 8) == 0;
}

bool is_jpeg(const std::vector<unsigned char>& b) {
  return b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF;
}

// The emissiveStrength of KHR_materials_emissive_strength, or 1.
double emissive_strength(const Context& ctx, const tinygltf::Material& g, const std::string& at) {
  const auto ext = g.extensions.find("KHR_materials_emissive_strength");
  if (ext == g.extensions.end() || !ext->second.Has("emissiveStrength")) return 1.0;
  const tinygltf::Value& v = ext->second.Get("emissiveStrength");
  if (!v.IsNumber() || !(v.GetNumberAsDouble() >= 0.0))
    ctx.fail(at + ": emissiveStrength must be a number >= 0");
  return v.GetNumberAsDouble();
}

// The coat's reflectance at normal incidence from KHR_materials_ior's index n:
// ((n - 1) / (n + 1))^2; glTF's default n = 1.5 gives 0.04. n = 1 is no coat.
float ior_f0(const Context& ctx, const tinygltf::Material& g, const std::string& at) {
  const auto ext = g.extensions.find("KHR_materials_ior");
  if (ext == g.extensions.end() || !ext->second.Has("ior")) return 0.04f;
  const tinygltf::Value& v = ext->second.Get("ior");
  const double n = v.IsNumber() ? v.GetNumberAsDouble() : 0.0;
  if (!(n >= 1.0) || !std::isfinite(n))
    ctx.fail(at + ": KHR_materials_ior ior must be a number >= 1");
  const double r = (n - 1.0) / (n + 1.0);
  return static_cast<float>(r * r);
}

}  // namespace

bool MaterialTable::has_normal_map(int index) const {
  const auto& materials = ctx_.model->materials;
  return index >= 0 && static_cast<size_t>(index) < materials.size() &&
         materials[static_cast<size_t>(index)].normalTexture.index >= 0;
}

uint32_t MaterialTable::material(int index, const std::string& where) {
  if (const auto it = materials_.find(index); it != materials_.end()) return it->second;
  const auto& materials = ctx_.model->materials;
  Material m;
  if (index == -1) {
    // glTF's default material: white, fully metallic, fully rough (glTF 2.0, 3.9.6).
    m.name = "default";
    m.albedo = glm::vec3(1.0f);
    m.metallic = 1.0f;
    m.specular = {1.0f, 0.04f, true};
  } else {
    if (index < 0 || static_cast<size_t>(index) >= materials.size())
      ctx_.fail(where + ": material " + std::to_string(index) + " does not exist (" +
                std::to_string(materials.size()) + " materials)");
    const tinygltf::Material& g = materials[static_cast<size_t>(index)];
    const std::string at = "material " + std::to_string(index);
    const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
    m.name = g.name.empty() ? at : g.name;
    if (pbr.baseColorFactor.size() != 4) ctx_.fail(at + ": baseColorFactor must have 4 numbers");
    m.albedo = {clamp01(ctx_, pbr.baseColorFactor[0], at),
                clamp01(ctx_, pbr.baseColorFactor[1], at),
                clamp01(ctx_, pbr.baseColorFactor[2], at)};
    m.opacity = clamp01(ctx_, pbr.baseColorFactor[3], at);
    m.metallic = clamp01(ctx_, pbr.metallicFactor, at);
    // The renderer's coat (frame_scene.h): metal or dielectric as a whole, the texture's B
    // channel scaling metallic per texel; f0 from the index of refraction (default 1.5: 0.04).
    m.specular = {clamp01(ctx_, pbr.roughnessFactor, at), ior_f0(ctx_, g, at), m.metallic >= 0.5f};
    if (pbr.baseColorTexture.index >= 0)
      m.texture = texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, true,
                          at + " baseColorTexture");
    if (pbr.metallicRoughnessTexture.index >= 0)
      m.metallic_roughness_texture =
          texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord, false,
                  at + " metallicRoughnessTexture");
    if (g.normalTexture.index >= 0) {
      m.normal_texture =
          texture(g.normalTexture.index, g.normalTexture.texCoord, false, at + " normalTexture");
      m.normal_scale = to_float(ctx_, g.normalTexture.scale, at + " normalTexture.scale");
    }
    if (g.emissiveFactor.size() != 3) ctx_.fail(at + ": emissiveFactor must have 3 numbers");
    const double strength = emissive_strength(ctx_, g, at);
    for (int c = 0; c < 3; ++c)
      m.emission[c] =
          to_float(ctx_, std::clamp(g.emissiveFactor[static_cast<size_t>(c)], 0.0, 1.0) * strength,
                   at + " emission");
    if (g.emissiveTexture.index >= 0)
      m.emission_texture = texture(g.emissiveTexture.index, g.emissiveTexture.texCoord, true,
                                   at + " emissiveTexture");
    if (g.alphaMode == "MASK") {
      m.alpha_mode = AlphaMode::kMask;
      m.alpha_cutoff = clamp01(ctx_, g.alphaCutoff, at + " alphaCutoff");
    } else if (g.alphaMode == "BLEND") {
      // No blending in the renderer; a cutout keeps leaves and decals recognisable.
      m.alpha_mode = AlphaMode::kMask;
      m.alpha_cutoff = 0.5f;
      ctx_.warnings.add("BLEND materials are drawn as MASK with alpha cutoff 0.5", at);
    } else if (g.alphaMode != "OPAQUE") {
      ctx_.fail(at + ": alphaMode \"" + g.alphaMode.substr(0, 20) +
                "\" is not OPAQUE, MASK or BLEND");
    }
    m.double_sided = g.doubleSided;
    // occlusionTexture is left out on purpose: the GI computes the occlusion it stands for.
  }
  const uint32_t slot = static_cast<uint32_t>(assets_.materials.size());
  assets_.materials.push_back(std::move(m));
  materials_[index] = slot;
  return slot;
}

int MaterialTable::texture(int index, int tex_coord, bool srgb, const std::string& where) {
  const tinygltf::Model& model = *ctx_.model;
  if (index < 0 || static_cast<size_t>(index) >= model.textures.size())
    ctx_.fail(where + ": texture " + std::to_string(index) + " does not exist (" +
              std::to_string(model.textures.size()) + " textures)");
  if (tex_coord != 0)
    ctx_.warnings.add(
        "textures on TEXCOORD_1 or higher are read with TEXCOORD_0 (the only set "
        "loaded)",
        where);
  if (const auto it = textures_.find({index, srgb}); it != textures_.end()) return it->second;
  const tinygltf::Texture& t = model.textures[static_cast<size_t>(index)];
  const std::string at = where + ": texture " + std::to_string(index);
  if (t.source < 0) {
    // Only an extension's image (KTX2, WebP) and no PNG/JPEG fallback.
    ctx_.warnings.add("textures without a PNG or JPEG image are left out", at);
    textures_[{index, srgb}] = -1;
    return -1;
  }
  Texture tex;
  if (t.sampler >= 0) {
    if (static_cast<size_t>(t.sampler) >= model.samplers.size())
      ctx_.fail(at + ": sampler " + std::to_string(t.sampler) + " does not exist (" +
                std::to_string(model.samplers.size()) + " samplers)");
    const tinygltf::Sampler& s = model.samplers[static_cast<size_t>(t.sampler)];
    const std::string sat = "sampler " + std::to_string(t.sampler);
    tex.wrap_u = wrap_mode(ctx_, s.wrapS, sat + " wrapS");
    tex.wrap_v = wrap_mode(ctx_, s.wrapT, sat + " wrapT");
  }
  // Decoded straight into the texture: an image used twice (colour and data) is decoded twice
  // rather than kept decoded alongside its copies.
  tex.rgba = decoded_image(t.source, &tex.width, &tex.height, at);
  const uint64_t texels = static_cast<uint64_t>(tex.width) * static_cast<uint64_t>(tex.height);
  if (ctx_.texels + texels > ctx_.limits.max_texels)
    ctx_.fail(at + ": the scene's textures need more than " +
              std::to_string(ctx_.limits.max_texels) + " texels");
  ctx_.texels += texels;
  tex.srgb = srgb;
  const std::string& image_name = model.images[static_cast<size_t>(t.source)].name;
  tex.name = !t.name.empty()       ? t.name
             : !image_name.empty() ? image_name
                                   : "texture " + std::to_string(index);
  const int slot = static_cast<int>(assets_.textures.size());
  assets_.textures.push_back(std::move(tex));
  textures_[{index, srgb}] = slot;
  return slot;
}

std::vector<uint8_t> MaterialTable::decoded_image(int index, int* width, int* height,
                                                  const std::string& where) {
  const tinygltf::Model& model = *ctx_.model;
  if (static_cast<size_t>(index) >= model.images.size())
    ctx_.fail(where + ": image " + std::to_string(index) + " does not exist (" +
              std::to_string(model.images.size()) + " images)");
  const tinygltf::Image& im = model.images[static_cast<size_t>(index)];
  const bool external = !im.uri.empty() && im.uri.rfind("data:", 0) != 0;
  const std::string at = where + ": image " + std::to_string(index) +
                         (external ? " ('" + im.uri.substr(0, 200) + "')" : std::string());
  const std::vector<unsigned char>& bytes = im.image;
  if (bytes.empty()) {
    std::string why = "it has no data";
    if (external) {
      // The reason tinygltf only warned about (missing, a directory, a FIFO, empty), asked of
      // the file system without opening the file.
      const std::string path = join_path(base_dir_of(ctx_.file), uri_decode(im.uri));
      uint64_t size = 0;
      if (!regular_file_size(path, &size, &why))
        why = path + ": " + why;
      else
        why = path + (size == 0 ? ": is empty" : ": could not be read");
    }
    ctx_.fail(at + " is missing: " + why);
  }
  const bool png = is_png(bytes);
  if (!png && !is_jpeg(bytes)) ctx_.fail(at + " is neither PNG nor JPEG");
  if (bytes.size() > static_cast<size_t>(INT32_MAX)) ctx_.fail(at + " is larger than 2 GiB");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int length = static_cast<int>(bytes.size());
  int w = 0, h = 0, channels = 0;
  // The header's size is checked before decoding: stb_image allocates for it first.
  if (!stbi_info_from_memory(data, length, &w, &h, &channels) || w <= 0 || h <= 0) {
    const char* reason = stbi_failure_reason();
    ctx_.fail(at + " cannot be decoded: " + (reason ? reason : "bad header"));
  }
  const int side = ctx_.limits.max_image_side;
  if (w > side || h > side)
    ctx_.fail(at + " is " + std::to_string(w) + "x" + std::to_string(h) + " texels, more than " +
              std::to_string(side) + " a side");
  const uint64_t texels = static_cast<uint64_t>(w) * static_cast<uint64_t>(h);
  if (ctx_.texels + texels > ctx_.limits.max_texels)
    ctx_.fail(at + ": the scene's textures need more than " +
              std::to_string(ctx_.limits.max_texels) + " texels");
  // Deflate compresses at most ~1032:1: a PNG whose data is shorter than that allows for its
  // size is cut short, and is refused before its pixels are allocated.
  const uint64_t raw = texels * static_cast<uint64_t>(std::max(channels, 1)) *
                       (stbi_is_16_bit_from_memory(data, length) ? 2u : 1u);
  if (png && bytes.size() < raw / 1032)
    ctx_.fail(at + ": its " + std::to_string(bytes.size()) + " bytes cannot hold " +
              std::to_string(w) + "x" + std::to_string(h) + " texels");
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> pixels(
      stbi_load_from_memory(data, length, &w, &h, &channels, 4), &stbi_image_free);
  ctx_.decode_ms +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (!pixels) {
    const char* reason = stbi_failure_reason();
    // stb_image's malloc failed: the host's memory, not the file, is at fault (the app says so
    // and names the scene; a SceneFileError would call the file bad).
    if (reason != nullptr && std::strcmp(reason, "outofmem") == 0) throw std::bad_alloc();
    ctx_.fail(at + " cannot be decoded: " + (reason ? reason : "unknown error"));
  }
  *width = w;
  *height = h;
  return std::vector<uint8_t>(pixels.get(), pixels.get() + texels * 4);
}

}  // namespace rp::scene::gltf
