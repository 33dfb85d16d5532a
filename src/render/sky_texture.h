// The environment light's map as the real-time modes read it (kernels/common/sky.h): the
// equirectangular map and its mip chain, each level the solid-angle weighted 2x2 mean of the one
// below, as float4 texels (rgb, w 0) in one buffer with the diffuse cones' table after it
// (render/sky_cells.h), and the SkyGpu record that places both and carries the turn and
// strength (kernels/shared/types.h).
#pragma once

#include <cstdint>
#include <vector>

#include "render/gpu_types.h"
#include "scene/environment.h"

namespace rp::render {

// Maps wider than this are box-filtered down to it for level 0 (halving, so a 2:1 map keeps 2:1):
// 2048 x 1024 float4 texels = 32 MiB, finer than a 720-pixel view with a 60-degree field needs.
inline constexpr int kSkyMaxWidth = 2048;
// The diffuse cones' table (render/sky_cells.h) integrates the first level at most this tall:
// 128 x 64 texels of 2.8 degrees for a 2:1 map, against cells 29 to 52 degrees across
// (about 0.1 s to build for 33 x 33 normals).
inline constexpr int kSkyCellMapHeight = 64;

// The kernel build option for frames whose diffuse cones carry no sky (kernels/common/sky.h:
// RP_SKY_DIFFUSE_CONES): the passes that trace diffuse cones build that variant first and the
// one without it when a frame has a sky (SkyGpu.diffuse_cones).
inline constexpr const char* kNoDiffuseSkyOption = "-DRP_SKY_DIFFUSE_CONES=0";

struct SkyTexture {
  std::vector<gpu::rp_float4> texels;
  gpu::SkyGpu info{};  // levels and offsets; turn = (1, 0, 1) (no turn, strength 1)
};

// The chain of `map` (a positive width and height, rgb of width x height x 3 floats): level 0
// the map (or its halvings down to kSkyMaxWidth), then halvings until one row is left or
// RP_SKY_MAX_LEVELS levels are made, then the diffuse cones' table (render/sky_cells.h) at
// info.cell_offset. Level l is max(width >> l, 1) x max(height >> l, 1); its
// texel (x, y) is the mean of texels (2x .. 2x + 1, 2y .. 2y + 1) of level l - 1 (clamped at an
// odd edge), each row weighted by its solid angle (cos theta0 - cos theta1).
SkyTexture build_sky_texture(const scene::EnvironmentMap& map);

// Level 0 of that chain alone (what the device shows of a map whose suns were taken out of the
// chain the cones read: GpuScene::sky_seen), without the coarser levels and the cones' table.
std::vector<gpu::rp_float4> build_sky_level0(const scene::EnvironmentMap& map);

// The texels build_sky_texture makes of a width x height map (what the device holds): the chain
// and the cones' table.
uint64_t sky_texel_count(int width, int height);
// The texels of its level 0 alone (what the device holds besides, to show a map whose suns
// were taken out of the chain: GpuScene::sky_seen).
uint64_t sky_level0_texel_count(int width, int height);

// `levels` (a SkyTexture's info) with the environment's turn and strength (the path tracer's
// convention: truth::EnvironmentSampler), or all zero (no sky) when `environment` is disabled.
gpu::SkyGpu sky_record(const gpu::SkyGpu& levels, const scene::Environment& environment);

}  // namespace rp::render
