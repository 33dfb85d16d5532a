// Material regions of a scene file's accuracy report (see accuracy_materials.h).
#include "bench/src/accuracy_materials.h"

#include <set>
#include <stdexcept>

namespace rp::bench {

MaterialPixels classify_materials(const std::vector<truth::PrimaryHit>& hits, uint32_t width,
                                  uint32_t height, size_t material_count) {
  if (hits.size() != size_t(width) * height)
    throw std::invalid_argument("accuracy: primary hits do not match the image size");
  MaterialPixels p;
  p.width = width;
  p.height = height;
  p.covered.assign(hits.size(), 0);
  p.material.assign(hits.size(), kNoMaterial);
  p.counts.assign(material_count, 0);
  std::vector<uint32_t> raw(hits.size(), kNoMaterial);
  for (size_t i = 0; i < hits.size(); ++i) {
    if (!hits[i].hit()) continue;
    p.covered[i] = 1;
    if (hits[i].material < material_count) raw[i] = hits[i].material;
  }
  for (uint32_t y = 1; y + 1 < height; ++y)
    for (uint32_t x = 1; x + 1 < width; ++x) {
      const size_t i = size_t(y) * width + x;
      const uint32_t m = raw[i];
      if (m == kNoMaterial) continue;
      if (raw[i - 1] == m && raw[i + 1] == m && raw[i - width] == m && raw[i + width] == m) {
        p.material[i] = m;
        ++p.counts[m];
      }
    }
  return p;
}

std::vector<uint16_t> material_labels(const MaterialPixels& pixels, uint32_t material) {
  const uint16_t image = uint16_t(1u << unsigned(Region::kImage));
  const uint16_t own = uint16_t(1u << unsigned(kMaterialRegion));
  std::vector<uint16_t> labels(pixels.covered.size(), 0);
  for (size_t i = 0; i < labels.size(); ++i) {
    if (pixels.covered[i]) labels[i] = image;
    if (material != kNoMaterial && pixels.material[i] == material) labels[i] |= own;
  }
  return labels;
}

std::vector<uint8_t> material_mask(const MaterialPixels& pixels, uint32_t material) {
  if (material == kNoMaterial) return pixels.covered;
  std::vector<uint8_t> mask(pixels.material.size(), 0);
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = pixels.material[i] == material ? 1 : 0;
  return mask;
}

std::vector<std::string> material_region_names(const std::vector<scene::Material>& materials) {
  std::vector<std::string> names;
  std::set<std::string> taken = {region_name(Region::kImage)};
  for (size_t i = 0; i < materials.size(); ++i) {
    // Appends only: `"literal" + std::string` trips GCC 12's -Wrestrict false positive.
    const std::string index = std::to_string(i);
    std::string name = materials[i].name;
    if (name.empty()) name.append("material_").append(index);
    // "material_3" may itself be a file's name for another material: the index makes it unique.
    while (taken.count(name)) name.append("#").append(index);
    taken.insert(name);
    names.push_back(name);
  }
  return names;
}

}  // namespace rp::bench
