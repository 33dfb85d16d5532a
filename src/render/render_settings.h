// What the renderer is asked to do: the settings of render::Renderer and the enums that choose
// its modes, each with its one name table (util/named_enum.h), which the command line
// (app/cli_options.cpp), the window title, the bench's JSON and the tests print and parse. The
// command line's options embed RenderSettings (app::CommonOptions::render).
#pragma once

#include <cstdint>
#include <iterator>
#include <span>

#include "util/named_enum.h"

namespace rp::render {

// Post-processing after the light pass, in this order (SPEC 6.6-6.9): TAA on tone-mapped values
// (its output is inverse tone mapped back to HDR), bloom mixed into that HDR, motion blur, then
// tone map + sRGB + dither. Each can be switched off; the others keep their place.
struct Effects {
  bool taa = true;            // 16-sample Halton jitter + history (key T, --no-taa)
  bool bloom = true;          // (key B, --no-bloom)
  bool motion_blur = true;    // (key M, --no-motion-blur)
  float bloom_strength = 0.1f;  // f in colour * (1 - f) + bloom * f
  // Fraction of the frame interval the virtual shutter is open (a 180 degree shutter): the blur
  // streak is velocity * shutter, where velocity is the screen motion since the previous frame.
  float shutter = 0.5f;
  bool operator==(const Effects&) const = default;
};

// Where the visibility buffer comes from: the compute rasterizer on the OpenCL device, or Embree
// primary rays traced on the host and uploaded (passes/embree_visibility.h). Same buffer format;
// the shadow map is rasterized with either.
enum class VisibilityBackend { kRaster, kEmbree };
constexpr NamedValue<VisibilityBackend> kVisibilityBackendNames[] = {
    {VisibilityBackend::kRaster, "raster"}, {VisibilityBackend::kEmbree, "embree"}};
constexpr std::span<const NamedValue<VisibilityBackend>> names(VisibilityBackend) {
  return kVisibilityBackendNames;
}

// How indirect (cone traced) light is computed:
//   kFast:      the real-time default: cones traced at reduced resolution with interleaved
//               directions, filtered spatially and accumulated over frames, upsampled with
//               depth- and normal-aware weights.
//   kReference: per-pixel cones at full resolution, 16 cones and twice the steps, no temporal
//               reuse of indirect light (--quality reference): the yardstick the fast mode is
//               measured against.
enum class Quality { kFast, kReference };
constexpr NamedValue<Quality> kQualityNames[] = {{Quality::kFast, "fast"},
                                                 {Quality::kReference, "reference"}};
constexpr std::span<const NamedValue<Quality>> names(Quality) { return kQualityNames; }

// Which volume holds the voxels the cones trace (--gi-volume):
//   kDense: the dense anisotropic mip chain (render/voxel_volume.h), 32^3 .. 128^3;
//   kSvo:   the sparse voxel octree of seed 001 (render/svo_volume.h, passes/svo.h), 256^3 or
//           512^3: the same values where it has nodes, memory for the surfaces only.
// Both are traced by the same cone functions (kernels/common/cone_trace.h, RP_GI_SVO).
enum class GiVolume { kDense, kSvo };
constexpr NamedValue<GiVolume> kGiVolumeNames[] = {{GiVolume::kDense, "dense"},
                                                   {GiVolume::kSvo, "svo"}};
constexpr std::span<const NamedValue<GiVolume>> names(GiVolume) { return kGiVolumeNames; }
// Resolutions each volume takes: dense powers of two 2..256 (the app: 32, 64, 128), svo powers of
// two 2..1024 (the app: 256, 512; tests smaller).
bool gi_resolution_supported(GiVolume volume, uint32_t resolution);

// How the lamp's shadow is filtered (--shadows). The lamp is a half sphere of radius
// 0.35, so real shadows are soft: their penumbra widens with the blocker-receiver distance.
//   kHard: one shadow-map tap per pixel (a point lamp's hard shadow);
//   kPcf:  percentage-closer filtering over a fixed radius (soft edges of one width);
//   kPcss: percentage-closer soft shadows: blocker search, then PCF over the penumbra width
//          the blocker and receiver depths and the lamp size imply;
//   kVssm: variance soft shadow maps: filtered depth moments, Chebyshev bound.
enum class ShadowMode { kHard, kPcf, kPcss, kVssm };
constexpr NamedValue<ShadowMode> kShadowModeNames[] = {{ShadowMode::kHard, "hard"},
                                                       {ShadowMode::kPcf, "pcf"},
                                                       {ShadowMode::kPcss, "pcss"},
                                                       {ShadowMode::kVssm, "vssm"}};
constexpr std::span<const NamedValue<ShadowMode>> names(ShadowMode) { return kShadowModeNames; }
// The next mode in the table's order, wrapping (key H).
constexpr ShadowMode next_shadow_mode(ShadowMode mode) {
  return ShadowMode((int(mode) + 1) % int(std::size(kShadowModeNames)));
}
// The shadow-map mip planes a mode filters from (passes/shadow_filter.h): PCSS's min-depth
// chain (1), VSSM's depth moments (3), none for the others.
constexpr uint32_t shadow_mip_planes(ShadowMode mode) {
  return mode == ShadowMode::kPcss ? 1u : mode == ShadowMode::kVssm ? 3u : 0u;
}

// How surface textures are sampled (--texture-filter; default kTrilinear: kAnisotropic
// is closer to the path tracer's pixel-averaged albedo but costs 1.2 ms more at 720 busy, past
// the 33 ms budget): kBilinear: the base level only
// (aliases when minified); kTrilinear: mipmaps, level from the pixel's UV footprint;
// kAnisotropic: several trilinear taps along the footprint's major axis.
enum class TextureFilter { kBilinear, kTrilinear, kAnisotropic };
constexpr NamedValue<TextureFilter> kTextureFilterNames[] = {
    {TextureFilter::kBilinear, "bilinear"},
    {TextureFilter::kTrilinear, "trilinear"},
    {TextureFilter::kAnisotropic, "anisotropic"}};
constexpr std::span<const NamedValue<TextureFilter>> names(TextureFilter) {
  return kTextureFilterNames;
}

struct RenderSettings {
  uint32_t width = 720, height = 720;
  uint32_t shadow_size = 1024;  // shadow map texels per side
  // GI volume: voxels per side over the scene's cube (dense: 32, 64 or 128; svo: 256 or 512).
  // The command line sets kDefaultSvoResolution for --gi-volume svo without --voxels.
  uint32_t voxel_resolution = 64;
  static constexpr uint32_t kDefaultSvoResolution = 256;
  GiVolume gi_volume = GiVolume::kDense;  // --gi-volume dense|svo
  Effects effects;
  VisibilityBackend visibility = VisibilityBackend::kRaster;  // --visibility raster|embree
  Quality quality = Quality::kFast;  // --quality fast|reference
  // --bounces: 1 = single-bounce indirect light (cones gather the voxels' direct light and
  // emission); >= 2 = multi-bounce: the voxels' radiance also carries the indirect light they
  // receive (passes/bounce.h), which converges to all bounces (the truth at 64).
  uint32_t bounces = kDefaultBounces;
  static constexpr uint32_t kDefaultBounces = 64;
  ShadowMode shadows = ShadowMode::kPcss;                  // --shadows
  TextureFilter texture_filter = TextureFilter::kTrilinear;  // --texture-filter
  // --render-scale: render pixels per output pixel along each axis, in [kMinRenderScale, 1].
  // Below 1 the final view renders visibility, GBuffer, light and the screen-space passes at
  // the scaled size and temporal upsampling (passes/taa_upsample.h) reconstructs the output
  // size; bloom, motion blur and tone map run at the output size. Debug views render at the
  // output size.
  float render_scale = 1.0f;
  // Resolve with temporal upsampling even at scale 1 (the scale follows the frame time, so
  // the history survives its changes).
  bool scale_follows_time = false;
  static constexpr float kMinRenderScale = 0.5f;
};

// The render size for an output size at a scale: each side scaled and rounded, at least 1.
uint32_t scaled_side(uint32_t output_side, float scale);

}  // namespace rp::render
