// The name tables of the renderer's enums (render/render_settings.h) and of the PRT transfer
// kinds: every value has one name, names are distinct, and printing then parsing gives the
// value back. The command line, the window title and the bench's JSON all go through them.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "render/render_settings.h"
#include "truth/prt_transfer.h"

namespace rp::render {
namespace {

// Each table lists the enum's values in declaration order, 0 to N-1, once each (so a new
// enumerator without a row fails here), with distinct non-empty names that parse back.
template <typename E>
void expect_complete_table(size_t enumerators) {
  const auto table = names(E{});
  ASSERT_EQ(table.size(), enumerators);
  std::set<std::string_view> seen;
  for (size_t i = 0; i < table.size(); ++i) {
    EXPECT_EQ(static_cast<size_t>(table[i].value), i) << table[i].name;
    EXPECT_FALSE(table[i].name.empty());
    EXPECT_TRUE(seen.insert(table[i].name).second) << "duplicate name " << table[i].name;
    EXPECT_EQ(name_of(table[i].value), table[i].name);
    EXPECT_EQ(parse_name<E>(table[i].name), table[i].value);
    EXPECT_EQ(name_list<E>().at(i), std::string(table[i].name));
  }
  EXPECT_FALSE(parse_name<E>("").has_value());
  EXPECT_FALSE(parse_name<E>("no-such-name").has_value());
}

TEST(RenderSettingsNames, EveryEnumHasACompleteTable) {
  expect_complete_table<VisibilityBackend>(2);
  expect_complete_table<Quality>(2);
  expect_complete_table<GiVolume>(2);
  expect_complete_table<ShadowMode>(4);
  expect_complete_table<TextureFilter>(3);
  expect_complete_table<truth::PrtKind>(3);
}

TEST(RenderSettingsNames, NamesAreTheCommandLineWords) {
  EXPECT_EQ(name_of(ShadowMode::kPcss), "pcss");
  EXPECT_EQ(name_of(GiVolume::kSvo), "svo");
  EXPECT_EQ(name_of(Quality::kReference), "reference");
  EXPECT_EQ(name_of(VisibilityBackend::kEmbree), "embree");
  EXPECT_EQ(name_of(TextureFilter::kAnisotropic), "anisotropic");
  EXPECT_EQ(name_of(truth::PrtKind::kInterreflected), "interreflected");
  EXPECT_FALSE(parse_name<ShadowMode>("PCSS").has_value());  // case-sensitive, as typed
}

TEST(RenderSettingsNames, KeyHCyclesEveryShadowModeInTableOrder) {
  ShadowMode m = ShadowMode::kHard;
  for (const NamedValue<ShadowMode>& entry : names(ShadowMode{})) {
    EXPECT_EQ(m, entry.value);
    m = next_shadow_mode(m);
  }
  EXPECT_EQ(m, ShadowMode::kHard);
}

TEST(RenderSettingsNames, ShadowMipPlanesPerMode) {
  EXPECT_EQ(shadow_mip_planes(ShadowMode::kHard), 0u);
  EXPECT_EQ(shadow_mip_planes(ShadowMode::kPcf), 0u);
  EXPECT_EQ(shadow_mip_planes(ShadowMode::kPcss), 1u);  // the min-depth chain
  EXPECT_EQ(shadow_mip_planes(ShadowMode::kVssm), 3u);  // depth moments
}

}  // namespace
}  // namespace rp::render
