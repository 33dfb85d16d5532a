// The measures of `rolypoly bench --accuracy` (bench/src/accuracy_report.h): how a real-time frame's
// linear components differ from the path-traced truth of the same frame, over the image and per
// named region of the demo scene. Pure functions on host images (3 floats per pixel, RGB,
// row-major), so they are tested on synthetic images.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/frame_scene.h"
#include "truth/path_tracer.h"

namespace rp::bench {

// Named regions of the demo frame, from what the camera sees at each pixel centre (the path
// tracer's primary hits) and whether the lamp reaches that point. kImage is every covered pixel;
// the named ones keep only pixels whose four neighbours carry the same label, so a region's
// figures describe its surface, not its silhouette.
enum class Region : uint8_t {
  kImage,
  kCeiling,
  kFloorLit,
  kFloorShadow,     // floor the lamp does not reach: in a tumbler's (or marble's) shadow
  kBackWall,
  kLeftWall,        // orange, x = -1
  kRightWall,       // sky blue, x = +1
  kTumblerLit,      // tumbler surface facing the lamp and reached by it
  kTumblerShadowed, // tumbler surface turned away from the lamp or shadowed
  // Only in frames with marbles (the report's marble section, bench/src/accuracy_marbles.h):
  kMarble,          // a marble's surface (a sphere that does not emit)
  kFloorByMarbles,  // floor within kMarbleContactRadii marble radii of a resting marble's
                    // contact point, lit or not (taken out of kFloorLit / kFloorShadow): where
                    // a coarse volume leaks light under a marble or darkens the floor around it
  kCount
};
inline constexpr size_t kRegionCount = size_t(Region::kCount);
// The regions the plain demo frame has (the report's main section lists these only).
inline constexpr size_t kDemoRegionCount = size_t(Region::kMarble);
// Radius of the floor_by_marbles disc around a contact point, in marble radii: the marble's own
// footprint (1) plus 1.5 radii beside it (0.06 world units for the demo's r = 0.04 marbles: two
// voxels at 64^3, where a marble is under three voxels across).
inline constexpr float kMarbleContactRadii = 2.5f;
const char* region_name(Region r);

// Label per pixel: bit r set when the pixel belongs to region r (kImage for every covered
// pixel). Material indices are those of scene::make_demo_assets (scene::demo). `spheres` are
// the frame's (FrameScene::spheres, which PrimaryHit::sphere indexes): with none given, a
// sphere's pixel is in kImage only and no floor is kFloorByMarbles (the plain demo frame's and
// the direct section's labels). A marble "rests on the floor" when its lowest point is within
// 1 % of its radius of y = -1.
std::vector<uint16_t> classify_regions(const std::vector<truth::PrimaryHit>& hits, uint32_t width,
                                       uint32_t height,
                                       const std::vector<scene::Sphere>& spheres = {});

// sum |a - t| / sum t and sum a / sum t - 1 over the RGB channels of the pixels in `region`.
struct ErrorStats {
  double rel_l1 = 0.0;
  double bias = 0.0;
  double sum_truth = 0.0;  // over the region's pixels and channels
  uint64_t pixels = 0;
};
ErrorStats compare_region(const std::vector<float>& a, const std::vector<float>& truth,
                          const std::vector<uint16_t>& labels, Region region);

// Mean incoming indirect light on a surface (indirect radiance / albedo, per channel) over a
// region, and its hue R - B.
struct IncomingLight {
  std::array<double, 3> rgb{};
  double r_minus_b() const { return rgb[0] - rgb[2]; }
};
IncomingLight incoming_indirect(const std::vector<float>& indirect,
                                const std::vector<float>& albedo,
                                const std::vector<uint16_t>& labels, Region region);

// Pixels (covered) where a's indirect luminance exceeds 1.5 x the truth's + eps (leaks: light
// where the truth is dark) or falls below (truth - eps) / 1.5 (missing light); eps = 5 % of the
// truth's mean indirect luminance over the covered pixels. `in`: count only the pixels of that
// region (eps stays the whole image's; covered_pixels counts the region's pixels).
struct LeakStats {
  uint64_t leak_pixels = 0, missing_pixels = 0, covered_pixels = 0;
  double epsilon = 0.0;
};
LeakStats leaks_and_misses(const std::vector<float>& a, const std::vector<float>& truth,
                           const std::vector<uint16_t>& labels, Region in = Region::kImage);

// PSNR (dB, peak 1) of two radiance images after the renderer's tone map x / (1 + x) and the
// sRGB encode (no quantisation), over all pixels and channels; +inf when identical.
double tone_mapped_psnr(const std::vector<float>& a, const std::vector<float>& b);
// The same for a finished 8-bit frame (RGBA8, 4 bytes per pixel, alpha ignored; code / 255)
// against a radiance image (3 floats per pixel) through the same tone map and sRGB encode: the
// final image after TAA, which the renderer hands out only as RGBA8.
double rgba8_psnr(const std::vector<uint8_t>& rgba, const std::vector<float>& radiance);

// ---- The direct-light section ----

// PSNR (dB, peak 1) of `a` against `truth` after multiplying both by `scale`, over the RGB
// channels of the pixels where mask != 0 (1 byte per pixel); +inf when equal there, NaN when the
// mask is empty. The report takes it on the direct component with scale = 1 / (the truth's mean
// lit floor luminance), so 1 is the lit floor's level.
double masked_psnr(const std::vector<float>& a, const std::vector<float>& truth,
                   const std::vector<uint8_t>& mask, double scale);
// The same after the renderer's tone map x / (1 + x) and the exact sRGB encode (as
// tone_mapped_psnr), over the pixels where mask != 0.
double masked_tone_mapped_psnr(const std::vector<float>& a, const std::vector<float>& truth,
                               const std::vector<uint8_t>& mask);
// The tone-mapped error of `a` against `truth` (masked_tone_mapped_psnr's tone map and sRGB
// encode) over the pixels where mask != 0, sorted into `bins` equal bins of `key` (one value
// per pixel): bin b holds keys in [b / bins, (b + 1) / bins), keys below 0 fall into the first
// and keys from 1 on into the last. Per bin, over its pixels' RGB channels: the mean signed
// difference (a - truth), the RMS difference and the sum of squared differences (a bin's share
// of the masked MSE is its sum over the sum of all bins').
struct ErrorBin {
  uint64_t pixels = 0;
  double mean = 0.0, rms = 0.0, squared_sum = 0.0;
};
std::vector<ErrorBin> tone_mapped_error_by_key(const std::vector<float>& a,
                                               const std::vector<float>& truth,
                                               const std::vector<uint8_t>& mask,
                                               const std::vector<float>& key, int bins);
// PSNR (dB, peak 1) of two albedo images (linear, 3 floats per pixel) after the exact sRGB encode
// of each channel clamped to [0, 1] (the albedo view's encode without its quantisation), over
// the pixels where mask != 0.
double srgb_psnr(const std::vector<float>& a, const std::vector<float>& truth,
                 const std::vector<uint8_t>& mask);
// The mask grown by `radius` pixels (a (2 radius + 1)^2 square), width x height, 1 byte each.
std::vector<uint8_t> dilate(const std::vector<uint8_t>& mask, uint32_t width, uint32_t height,
                            int radius);
// One channel-plane value at fractional pixel coordinates (x right, y down, pixel centres at
// +0.5), bilinear between the four nearest centres (clamped to the image): `rgb` 3 floats per
// pixel, returns luminance (0.2126, 0.7152, 0.0722).
double bilinear_luma(const std::vector<float>& rgb, uint32_t width, uint32_t height, double x,
                     double y);

// A visibility profile across a shadow edge: s (world units along the line) ascending, v the
// lamp's visible fraction there (0 umbra, 1 lit).
struct ProfileSample {
  double s = 0.0, v = 0.0;
};
// 10-90 % transition width of a profile that rises from shadow to light: s90 = where v first
// reaches `hi` (interpolated linearly between samples), s10 = where v last rises through `lo`
// before s90; s90 - s10 (world units). NaN when the profile never reaches `hi` or does not start
// at or below `lo`.
double transition_width(const std::vector<ProfileSample>& profile, double lo = 0.1,
                        double hi = 0.9);

// Tiles of w x h RGBA8 images (4 bytes per pixel, top row first), `columns` per row, in the
// order given; missing tiles of the last row stay black. The report's side-by-side PNGs.
std::vector<uint8_t> tile_rgba8(const std::vector<std::vector<uint8_t>>& images, uint32_t w,
                                uint32_t h, uint32_t columns);

// Signed relative difference of indirect luminance, (a - t) / (t + eps), drawn as RGBA8: blue
// where a is too dark (-1 or less: full blue), white where equal, red where too bright (+1 or
// more); background black.
void signed_heat_map(const std::vector<float>& a, const std::vector<float>& truth,
                     const std::vector<uint16_t>& labels, double eps, std::vector<uint8_t>& rgba);

}  // namespace rp::bench
