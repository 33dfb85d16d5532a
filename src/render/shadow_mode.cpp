// Names of render::ShadowMode (--shadows, key H, the window title) and render::GiVolume
// (--gi-volume).
#include "render/renderer.h"

namespace rp::render {

const char* shadow_mode_name(ShadowMode mode) {
  switch (mode) {
    case ShadowMode::kHard: return "hard";
    case ShadowMode::kPcf: return "pcf";
    case ShadowMode::kPcss: return "pcss";
    case ShadowMode::kVssm: return "vssm";
  }
  return "pcss";
}

std::optional<ShadowMode> parse_shadow_mode(std::string_view name) {
  for (ShadowMode m : {ShadowMode::kHard, ShadowMode::kPcf, ShadowMode::kPcss, ShadowMode::kVssm})
    if (name == shadow_mode_name(m)) return m;
  return std::nullopt;
}

ShadowMode next_shadow_mode(ShadowMode mode) {
  return ShadowMode((int(mode) + 1) % 4);
}

const char* gi_volume_name(GiVolume volume) {
  return volume == GiVolume::kSvo ? "svo" : "dense";
}

std::optional<GiVolume> parse_gi_volume(std::string_view name) {
  if (name == "dense") return GiVolume::kDense;
  if (name == "svo") return GiVolume::kSvo;
  return std::nullopt;
}

bool gi_resolution_supported(GiVolume volume, uint32_t resolution) {
  if (volume == GiVolume::kSvo)
    return resolution >= 2 && resolution <= 1024 && (resolution & (resolution - 1)) == 0;
  return VoxelVolume::valid_resolution(resolution);
}

}  // namespace rp::render
