// Bytes and flops per frame of the hot passes, from the kernels' structure. Conventions in
// pass_work.h; every constant below names the kernel lines it stands for. Symbols:
//   N = width * height pixels, S = shadow_size^2 texels, R = voxel_resolution,
//   T = instance_triangles (drawn by the camera; voxel_triangles for the voxelizer,
//   shadow_triangles for the shadow map), P = spheres, items = T + P (rasterizer draw items).
#include "bench/src/pass_work.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "passes/pass_names.h"

namespace rp::bench {
namespace {

namespace pass_name = passes::pass_name;

constexpr double kFloat = 4, kFloat2 = 8, kFloat4 = 16;

// ---- visibility / shadow_map (kernels/visibility.cl, one rasterizer for both views) --------
constexpr double kTile = 16;  // RP_RASTER_TILE
// Tiles a draw item is binned into: assumed 1 for the many small tumbler triangles and
// spheres, plus kCoverLayers screen-covering layers of large triangles (the box walls around
// the camera) in every tile. A typical case, not a bound: tile lists are data dependent.
constexpr double kCoverLayers = 2;
// The Instance record (kernels/shared/types.h; gpu_types.h checks its size).
constexpr double kInstanceBytes = 224;
// setup and bin (one work-item per item, each walks the same transform): Triangle (16 B),
// three Vertex (3 x 32 B), the Instance record; setup writes a RasterTriangle (64 B)
// and bounds (16 B); both do an atomic per touched tile (8 B); bin writes a 4 B list entry.
constexpr double kItemReadBytes = 16 + 3 * 32 + kInstanceBytes;
constexpr double kSetupWriteBytes = 64 + 16;
// Transform: model then view_proj per vertex (2 x 28 flops x 3), edge/bounds setup ~30.
constexpr double kItemFlops = 3 * 2 * 28 + 30;
// raster: per (tile, item) pair the group loads the list entry, RasterTriangle and bounds once
// (4 + 64 + 16 B); every pixel of the tile then evaluates 3 edges + depth (4 mads) + compare.
constexpr double kPairBytes = 4 + 64 + 16;
constexpr double kPixelTestFlops = 4 * 2 + 2;

PassWork raster_view(double pixels, double tiles, double items, double out_bytes_per_pixel,
                     double resolve_flops_per_pixel) {
  const double pairs = items + kCoverLayers * tiles;
  PassWork w;
  w.bytes = tiles * 2 * kFloat                                           // clear counts
            + items * (kItemReadBytes + kSetupWriteBytes + 8)            // setup
            + items * (kItemReadBytes + 4 + 8)                           // bin
            + pairs * kPairBytes + pixels * out_bytes_per_pixel;         // raster
  w.flops = 2 * items * kItemFlops + pairs * kTile * kTile * kPixelTestFlops +
            pixels * resolve_flops_per_pixel;
  // Tile counts, the setup records and bounds, one list entry per pair, the output planes.
  w.footprint = tiles * 2 * kFloat + items * kSetupWriteBytes + pairs * 4 +
                pixels * out_bytes_per_pixel;
  return w;
}

PassWork visibility(const WorkParams& p) {
  const double tiles = std::ceil(p.width / kTile) * std::ceil(p.height / kTile);
  // Writes depth (4 B), ids (uint2) and barycentrics (float2); resolving the winner's
  // barycentrics ~10 flops.
  return raster_view(double(p.width) * p.height, tiles, double(p.instance_triangles) + p.spheres,
                     kFloat + 2 * kFloat2, 10);
}

PassWork shadow_map(const WorkParams& p) {
  const double tiles = std::pow(std::ceil(p.shadow_size / kTile), 2);
  // RP_DEPTH_ONLY: writes depth only.
  return raster_view(double(p.shadow_size) * p.shadow_size, tiles,
                     double(p.shadow_triangles) + p.spheres, kFloat, 0);
}

// ---- gbuffer (kernels/gbuffer.cl): upper bound, every pixel covered by a textured triangle --
// Reads ids (8) + bary (8) + Instance (224) + Triangle (16) + 3 Vertex (96) + Material (48) +
// TextureInfo (16) + 4 bilinear texels (16); writes albedo, normal_depth, position, emission
// (4 x 16) and velocity (8).
constexpr double kGBufferBytes = 8 + 8 + kInstanceBytes + 16 + 96 + 48 + 16 + 16 + 4 * 16 + 8;
// Interpolation of position/normal/uv (3 vertices x 8 floats, mads ~50), model transforms of
// position and normal (~60), current and previous screen positions (2 x 28 + divides ~60),
// normalise (~10), bilinear texture with sRGB table decode (~40).
constexpr double kGBufferFlops = 220;

PassWork gbuffer(const WorkParams& p) {
  const double n = double(p.width) * p.height;
  // Footprint: ids and barycentrics read, the five planes written (the gathered mesh records
  // and texels are shared by many pixels).
  return {n * kGBufferBytes, n * kGBufferFlops, n * (8 + 8 + 4 * 16 + 8)};
}

// ---- voxelize (kernels/voxelize.cl) ---------------------------------------------------------
// clear: per voxel 4 uint sums + 1 overflow word written (20 B); resolve: those read (20 B), the
// float4 written (16 B), ~8 flops (scale, divide, clamp).
constexpr double kVoxelClearResolveBytes = 20 + 20 + 16;
constexpr double kVoxelResolveFlops = 8;
// Per triangle (one work-item each): Triangle 16 + 3 Vertex 96 + Instance 224 + Material 48 +
// TextureInfo 16 + 4 texels 16 + 1 shadow tap 4 (shaded once at the centroid: small triangles).
constexpr double kVoxelTriangleBytes = 16 + 96 + kInstanceBytes + 48 + 16 + 16 + 4;
// Vertex transforms to world and grid (3 x 28 + 18), normal (9), shading: texture, direct
// light, shadow projection (~150).
constexpr double kVoxelTriangleFlops = 3 * 28 + 18 + 9 + 150;
// Candidate voxels of a small triangle (bounding box <= RP_VOXEL_SMALL_TRIANGLE = 2 voxels per
// axis): at most 3 x 3 columns x 2 voxels = 18 (upper bound); each gets the exact SAT test
// (13 axes, ~10 flops each) and, touched, 4 atomic adds (4 x 8 B).
constexpr double kVoxelCandidates = 18;
constexpr double kSatFlops = 130;
constexpr double kVoxelAtomicBytes = 4 * 8;
// Large triangles (the box's walls, floor and ceiling: 5 faces) touch about R^2 voxels each and
// are shaded per voxel: texels 16 + shadow 4 B + atomics, SAT + shading flops.
constexpr double kWallFaces = 5;
// Spheres: Sphere record 64 B + shadow tap 4 B, ~100 flops; up to 3^3 voxels each (particles
// and marbles are at most a few voxels wide at R <= 128: upper bound for those), per voxel
// ~40 flops (overlap, opacity, shading) and 4 atomics.
constexpr double kSphereVoxels = 27;

PassWork voxelize(const WorkParams& p) {
  const double r = p.voxel_resolution;
  const double v = r * r * r, t = p.voxel_triangles, s = p.spheres;
  const double walls = kWallFaces * r * r;
  PassWork w;
  w.bytes = v * kVoxelClearResolveBytes +
            t * (kVoxelTriangleBytes + kVoxelCandidates * kVoxelAtomicBytes) +
            walls * (16 + 4 + kVoxelAtomicBytes) +
            s * (64 + 4 + kSphereVoxels * kVoxelAtomicBytes);
  w.flops = v * kVoxelResolveFlops + t * (kVoxelTriangleFlops + kVoxelCandidates * kSatFlops) +
            walls * (kSatFlops + 150) + s * (100 + kSphereVoxels * 40);
  // The sums and overflow word (20 B) and the resolved float4 (16 B) per voxel, each triangle
  // and sphere record once.
  w.footprint = v * (20 + 16) + t * 16 + s * 64;
  return w;
}

// ---- voxel_mips (kernels/voxel_mips.cl): exact, no data dependence ----------------------------
// Level 1 voxel: 8 children read once from level 0 (128 B), 6 directions written (96 B).
// Level l >= 2 voxel: per direction 8 children (128 B) read and 1 written (16 B).
// Flops per direction: 4 columns x (1 sub + float4 mad 8) + 3 float4 adds + 1 float4 mul = 52.
PassWork voxel_mips(const WorkParams& p) {
  PassWork w;
  const uint32_t r = p.voxel_resolution;
  for (uint32_t level = 1; (r >> level) > 0; ++level) {
    const double n = r >> level, voxels = n * n * n;
    w.bytes += voxels * (level == 1 ? 8 * kFloat4 + 6 * kFloat4 : 6 * (8 * kFloat4 + kFloat4));
    w.flops += voxels * 6 * 52;
  }
  w.footprint = w.bytes;  // every child is read by exactly one parent per direction
  return w;
}

// ---- light (kernels/light.cl) --------------------------------------------------------------------
// Fast mode (light_compose): per pixel position, normal_depth, albedo, emission (4 x 16 B), one
// shadow tap (4 B), hdr written (16 B), and the joint-bilateral upsample's 2 x 2 low-resolution
// taps of geometry (4 floats) and accumulated irradiance (3 floats), counted per pixel (an upper
// bound: neighbouring pixels share them in cache). ~150 flops: direct term and shadow projection
// (~80), four geometry weights (~50), weighted sum and compose (~20).
// Reference mode (light_shade, 16 cones per pixel with data-dependent step counts) and the fast
// mode's indirect_trace / indirect_filter are not modelled (their bytes and flops show as 0).
PassWork light(const WorkParams& p) {
  if (p.reference_quality) return {};
  const double n = double(p.width) * p.height;
  // Footprint: the four GBuffer planes and hdr once, the low-resolution taps once per
  // low-resolution pixel (a quarter of N).
  return {n * (4 * kFloat4 + kFloat + kFloat4 + 4 * 7 * kFloat), n * 150,
          n * (4 * kFloat4 + kFloat4) + n / 4 * 7 * kFloat};
}

// ---- taa (kernels/taa.cl): exact per pixel -----------------------------------------------------
// Reads hdr_in 5-tap cross (5 x 16), depth of the cross (normal_depth .w, 5 x 4), the chosen
// velocity (8), bilinear history (4 x 16); writes history_out and hdr_out (2 x 16).
// Flops: tone map + YCoCg of 5 taps (70), mean / variance / sqrt (55), bilinear (32), clip and
// back to RGB (45), blend and inverse tone map (15).
PassWork taa(const WorkParams& p) {
  if (!p.taa) return {};
  const double n = double(p.width) * p.height;
  // Footprint: hdr_in, depths, velocity and history once each, the two outputs.
  return {n * (5 * kFloat4 + 5 * kFloat + kFloat2 + 4 * kFloat4 + 2 * kFloat4), n * 217,
          n * (kFloat4 + kFloat + kFloat2 + kFloat4 + 2 * kFloat4)};
}

// ---- bloom (kernels/bloom.cl, src/passes/bloom.cpp): exact -------------------------------------
// Levels: halve (rounding up) up to 6 times while the smaller side stays >= 8 (BloomPass).
// Karis downsample to level 1, per texel: 13 taps x 4 float4 (832 B) read, 16 B written;
//   13 boxes x 4 channels x 4 + 5 Karis weights (~7) + weighted sum and divide ~ 290 flops.
// Downsample to level k >= 2, per float: 52 floats read + 1 written (212 B), 78 flops.
// Upsample-add into level k < N, per float: 9 coarse + 1 level read, 1 written (44 B), 21 flops.
// Mix at full size, per float: input + 9 coarse read, 1 written (44 B), 23 flops.
PassWork bloom(const WorkParams& p) {
  if (!p.bloom) return {};
  std::vector<double> texels;  // per level 1..N
  uint32_t w = p.width, h = p.height;
  for (int k = 1; k <= 6; ++k) {
    w = (w + 1) / 2;
    h = (h + 1) / 2;
    if (k > 1 && std::min(w, h) < 8) break;
    texels.push_back(double(w) * h);
  }
  PassWork out;
  for (size_t k = 0; k < texels.size(); ++k) {
    if (k == 0) {
      out.bytes += texels[k] * (52 * kFloat4 + kFloat4);
      out.flops += texels[k] * 290;
    } else {
      out.bytes += texels[k] * 4 * (52 * kFloat + kFloat);
      out.flops += texels[k] * 4 * 78;
    }
    if (k + 1 < texels.size()) {  // U(k) = D(k) + up(U(k+1)) for every level but the last
      out.bytes += texels[k] * 4 * 11 * kFloat;
      out.flops += texels[k] * 4 * 21;
    }
  }
  const double floats = 4.0 * p.width * p.height;
  out.bytes += floats * 11 * kFloat;
  out.flops += floats * 23;
  // Footprint: the input and the mixed output once, each level's downsample and upsample
  // planes once.
  out.footprint = 2 * floats * kFloat;
  for (double t : texels) out.footprint += 2 * t * kFloat4;
  return out;
}

// ---- motion_blur (kernels/motion_blur.cl): upper bound, every tile moving ----------------------
// tile_max: velocity read per pixel (8 B, ~4 flops), one float2 per 20x20 tile written;
// neighbour_max: per tile 25 flags + 9 maxima read, max + flag written (~300 B).
// depth_speed (only in flagged tiles; bound: all): flag 4 + depth 4 + velocity 8 read, half2 4
//   written, ~8 flops.
// reconstruct: neighbour max 8 + depth_speed 4 + hdr 16, RP_MB_SAMPLES - 1 = 14 samples of
//   depth_speed (4) + hdr (16), hdr_out 16 written; ~50 flops per sample + ~25 per pixel.
//   (A still tile only copies: 32 B, 0 flops.)
PassWork motion_blur(const WorkParams& p) {
  if (!p.motion_blur) return {};
  const double n = double(p.width) * p.height;
  const double tiles = std::ceil(p.width / 20.0) * std::ceil(p.height / 20.0);
  PassWork w;
  w.bytes = n * kFloat2 + tiles * (kFloat2 + 300) + n * (4 + 4 + 8 + 4) +
            n * (8 + 4 + 16 + 14 * (4 + 16) + 16);
  w.flops = n * 4 + n * 8 + n * (25 + 14 * 50);
  // Footprint: velocity, depth, hdr read once, depth_speed written, hdr_out written.
  w.footprint = n * (kFloat2 + kFloat + kFloat4 + 4 + kFloat4);
  return w;
}

// ---- tone_map (kernels/tone_map.cl): exact --------------------------------------------------
// One work-item per output byte: reads one float (4 B), writes one byte; a pixel = 16 B read +
// 4 B written. Per item: exposure mul 1, x / (1 + x) 2, sRGB encode 2 sqrt + 5 mad = 12,
// v * 255 + d 2: 17 flops (the alpha item computes and discards it too): 68 per pixel.
PassWork tone_map(const WorkParams& p) {
  const double n = double(p.width) * p.height;
  return {n * (4 * kFloat + 4), n * 4 * 17, n * (4 * kFloat + 4)};
}

using Model = std::function<PassWork(const WorkParams&)>;

const std::vector<std::pair<std::string, Model>>& models() {
  static const std::vector<std::pair<std::string, Model>> all = {
      {pass_name::kVisibility, visibility}, {pass_name::kShadowMap, shadow_map},
      {pass_name::kGBuffer, gbuffer},       {pass_name::kVoxelize, voxelize},
      {pass_name::kVoxelMips, voxel_mips},  {pass_name::kLight, light},
      {pass_name::kTaa, taa},               {pass_name::kBloom, bloom},
      {pass_name::kMotionBlur, motion_blur}, {pass_name::kToneMap, tone_map}};
  return all;
}

}  // namespace

double bandwidth_ceiling_gbps(const std::vector<BandwidthLevel>& levels, double bytes,
                              double footprint) {
  if (levels.empty() || bytes <= 0) return 0;
  double fastest = 0, holding = 0;
  for (const BandwidthLevel& l : levels) {
    fastest = std::max(fastest, l.gbps);
    if (l.working_set_bytes >= footprint) holding = std::max(holding, l.gbps);
  }
  if (holding <= 0) holding = levels.back().gbps;
  if (fastest <= 0 || holding <= 0) return 0;
  const double seconds = std::max(bytes / fastest, std::max(footprint, 0.0) / holding);
  return bytes / seconds;
}

PassEfficiency pass_efficiency(const PassWork& work, double median_ms,
                               const std::vector<BandwidthLevel>& levels, double peak_gflops) {
  PassEfficiency e;
  e.bytes = work.bytes;
  e.flops = work.flops;
  e.footprint = work.footprint;
  const double seconds = median_ms * 1e-3;
  if (!(seconds > 0.0)) return e;
  e.gbytes_per_s = work.bytes / seconds * 1e-9;
  e.gflops_per_s = work.flops / seconds * 1e-9;
  e.ceiling_gbps = bandwidth_ceiling_gbps(levels, work.bytes, work.footprint);
  // A fraction above 1 cannot be true: the model (a bound, or bytes served from a closer cache
  // than its footprint says) is wrong for this pass here, so it shows nothing (NaN).
  auto fraction = [](double achieved, double ceiling) {
    if (!(ceiling > 0.0) || !(achieved > 0.0)) return 0.0;
    const double f = achieved / ceiling;
    return f <= 1.0 ? f : std::nan("");
  };
  e.bandwidth_fraction = fraction(e.gbytes_per_s, e.ceiling_gbps);
  e.compute_fraction = fraction(e.gflops_per_s, peak_gflops);
  return e;
}

PassWork pass_work(const std::string& pass, const WorkParams& p) {
  for (const auto& [name, model] : models())
    if (name == pass) return model(p);
  return {};
}

const std::vector<std::string>& modelled_passes() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const auto& entry : models()) out.push_back(entry.first);
    return out;
  }();
  return names;
}

}  // namespace rp::bench
