// Names of render::ShadowMode (--shadows, key H, the window title).
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

}  // namespace rp::render
