// The material regions of a scene file's accuracy report (bench/src/accuracy_materials.h) on
// synthetic primary hits: the erosion at material edges, the labels the metrics read, the
// unique region names.
#include <gtest/gtest.h>

#include <vector>

#include "bench/src/accuracy_materials.h"

namespace rp::bench {
namespace {

// A 6x4 frame: the left half material 0, the right half material 1, the top row background,
// one pixel of material 7 (beyond the scene's two materials).
std::vector<truth::PrimaryHit> hits() {
  std::vector<truth::PrimaryHit> h(6 * 4);
  for (uint32_t y = 1; y < 4; ++y)
    for (uint32_t x = 0; x < 6; ++x) {
      truth::PrimaryHit& p = h[y * 6 + x];
      p.instance = 0;
      p.material = x < 3 ? 0 : 1;
    }
  h[3 * 6 + 5].material = 7;
  return h;
}

TEST(AccuracyMaterials, RegionsKeepPixelsInsideOneMaterial) {
  const MaterialPixels p = classify_materials(hits(), 6, 4, 2);
  ASSERT_EQ(p.counts.size(), 2u);
  // Interior pixels (all four neighbours inside the image and of the same material): row 2
  // only, x = 1 (material 0) and x = 4 (material 1); x = 2 and 3 touch the other material.
  EXPECT_EQ(p.counts[0], 1u);
  EXPECT_EQ(p.counts[1], 1u);
  EXPECT_EQ(p.material[2 * 6 + 1], 0u);
  EXPECT_EQ(p.material[2 * 6 + 4], 1u);
  EXPECT_EQ(p.material[2 * 6 + 2], kNoMaterial);
  uint32_t covered = 0;
  for (uint8_t c : p.covered) covered += c;
  EXPECT_EQ(covered, 18u) << "every hit, the unknown material's too";

  const std::vector<uint16_t> labels = material_labels(p, 1);
  const uint16_t image = 1u << unsigned(Region::kImage);
  const uint16_t own = 1u << unsigned(kMaterialRegion);
  EXPECT_EQ(labels[0], 0u) << "background";
  EXPECT_EQ(labels[2 * 6 + 1], image);
  EXPECT_EQ(labels[2 * 6 + 4], image | own);
  EXPECT_EQ(material_labels(p, kNoMaterial)[2 * 6 + 4], image);
  EXPECT_EQ(material_mask(p, 0)[2 * 6 + 1], 1u);
  EXPECT_EQ(material_mask(p, 0)[2 * 6 + 4], 0u);
  EXPECT_EQ(material_mask(p, kNoMaterial), p.covered);

  // The metrics of the demo's regions measure a material through its labels.
  std::vector<float> truth(6 * 4 * 3, 1.0f), rt(6 * 4 * 3, 1.0f);
  for (int c = 0; c < 3; ++c) rt[3 * (2 * 6 + 4) + c] = 1.5f;
  EXPECT_NEAR(compare_region(rt, truth, labels, kMaterialRegion).bias, 0.5, 1e-9);
  EXPECT_EQ(compare_region(rt, truth, labels, kMaterialRegion).pixels, 1u);
  EXPECT_EQ(compare_region(rt, truth, labels, Region::kImage).pixels, 18u);

  EXPECT_THROW(classify_materials(hits(), 5, 4, 2), std::invalid_argument);
}

TEST(AccuracyMaterials, RegionNamesAreUniqueAndNeverTheImage) {
  std::vector<scene::Material> m(6);
  m[0].name = "floor";
  m[1].name = "floor";
  m[2].name = "";
  m[3].name = "image";
  m[4].name = "material_2";
  m[5].name = "wall";
  EXPECT_EQ(material_region_names(m),
            (std::vector<std::string>{"floor", "floor#1", "material_2", "image#3",
                                      "material_2#4", "wall"}));
}

}  // namespace
}  // namespace rp::bench
