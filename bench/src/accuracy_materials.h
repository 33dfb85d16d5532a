// The regions of `bench --accuracy --scene FILE` (bench/src/accuracy_file.h): the whole image
// and one region per material of the scene, from the surface the path tracer's camera ray
// meets at each pixel centre (truth::PrimaryHit::material). A file has no named surfaces the
// way the demo's box has (accuracy_metrics.h Region), but every material is a surface someone
// chose, so its figures say where the light is wrong. As with the demo's regions, a material's
// region keeps only pixels whose four neighbours show the same material: its figures describe
// the surface, not its silhouette, where the real-time and the truth's pixel footprints differ.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bench/src/accuracy_metrics.h"
#include "scene/frame_scene.h"
#include "truth/path_tracer.h"

namespace rp::bench {

inline constexpr uint32_t kNoMaterial = truth::PrimaryHit::kNone;

// The label bit of the pixels of one material in material_labels, next to Region::kImage's
// (bit 0, every covered pixel): the measures of accuracy_metrics.h then take the material's
// pixels with this region, and the whole image where they need it (leaks_and_misses' epsilon).
inline constexpr Region kMaterialRegion = Region(1);

struct MaterialPixels {
  uint32_t width = 0, height = 0;
  std::vector<uint32_t> material;  // per pixel: the material (eroded), or kNoMaterial
  std::vector<uint8_t> covered;    // per pixel: 1 where the camera sees a surface
  std::vector<uint64_t> counts;    // per material of the scene: its region's pixels
};

// From the primary hits (width * height, row-major) of a frame whose assets have
// `material_count` materials (a hit on a material index beyond is counted as covered only).
MaterialPixels classify_materials(const std::vector<truth::PrimaryHit>& hits, uint32_t width,
                                  uint32_t height, size_t material_count);

// Labels for the measures: Region::kImage on every covered pixel, kMaterialRegion on those of
// `material` (none when it is kNoMaterial: the whole image alone).
std::vector<uint16_t> material_labels(const MaterialPixels& pixels, uint32_t material);

// 1 byte per pixel: 1 on the pixels of `material`, or on every covered pixel for kNoMaterial
// (the masks of masked_tone_mapped_psnr and srgb_psnr).
std::vector<uint8_t> material_mask(const MaterialPixels& pixels, uint32_t material);

// A region name per material, unique and never "image" (the whole image's): the material's
// name, "material_<i>" for an unnamed one, "<name>#<i>" for a name already taken.
std::vector<std::string> material_region_names(const std::vector<scene::Material>& materials);

}  // namespace rp::bench
