// The voxel radiance volume on the device: the whole mip chain in one float4 buffer (layout in
// kernels/shared/voxel_layout.h, conventions in kernels/common/voxel.h) plus the voxelizer's
// fixed-point accumulation buffers. Reallocated only when the resolution changes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <CL/opencl.hpp>

#include "cl/buffer.h"
#include "cl/error.h"
#include "kernels/shared/voxel_layout.h"

namespace rp::render {

// Fixed-point format of the voxelizer's sums (passed to kernels/voxelize.cl as -D options, so
// this is the one definition): every contribution is stored as round(value * 2^16) in a uint
// (value = radiance * opacity per colour channel, or opacity), clamped to
// [0, kVoxelMaxContribution] first. A voxel's per-channel sum wraps past 2^32 - 1 units, i.e.
// 65535.99 (radiance * opacity, or opacity); the add that wraps sets the voxel's overflow bit
// for that channel and the resolve saturates the channel to kVoxelSaturatedSum. Whether a
// wrap happens depends only on the total, so the result stays order independent.
inline constexpr uint32_t kVoxelFixedBits = 16;
inline constexpr float kVoxelFixedScale = float(1u << kVoxelFixedBits);  // units per 1.0
inline constexpr float kVoxelMaxContribution = 65535.0f;  // largest value one contribution adds
inline constexpr float kVoxelSaturatedSum = 65536.0f;     // a channel whose sum overflowed

struct VoxelVolume {
  uint32_t resolution = 0;  // R: level-0 voxels per side over [-1,1]^3 (a power of two)
  uint32_t levels = 0;      // log2(R) + 1: level 0 (R^3, isotropic) down to level log2(R) (1^3)
  ::cl::Buffer chain;       // float4[gpu::rp_voxel_total(R, levels)]: level 0, then six
                            // directional volumes per level (rgb premultiplied radiance, a opacity)
  ::cl::Buffer accum;       // uint[8 R^3] voxelizer scratch per voxel: fixed-point sums (r*a,
                            // g*a, b*a, a), facing coverage x, y, z, unused (voxel_layout.h);
                            // the mip builder reads the facing coverage for level 1
  ::cl::Buffer overflow;    // uint[R^3] voxelizer scratch: bit c set = channel c of accum wrapped

  // Resolutions the passes accept: powers of two from 2 to 256 (the app uses 32, 64 or 128).
  static bool valid_resolution(uint32_t r) { return r >= 2 && r <= 256 && (r & (r - 1)) == 0; }

  // log2(r) + 1.
  static uint32_t levels_for(uint32_t r) {
    uint32_t levels = 1;
    while ((r >> (levels - 1)) > 1) ++levels;
    return levels;
  }

  // float4 elements in the chain.
  size_t chain_elements() const { return gpu::rp_voxel_total(resolution, levels); }

  // Allocates the buffers for resolution r (nothing happens when r is the current one). The
  // contents are undefined until the voxelize and voxel_mips passes have run.
  void resize(const ::cl::Context& context, uint32_t r) {
    if (!valid_resolution(r))
      throw rp::cl::Error("voxel resolution " + std::to_string(r) +
                          " is not supported: use a power of two from 2 to 256 (32, 64 or 128)");
    if (r == resolution && chain() != nullptr) return;
    resolution = r;
    levels = levels_for(r);
    const size_t voxels = size_t(r) * r * r;
    const std::string at = " at " + std::to_string(r) + "^3";
    const std::string advice = "a smaller --voxels needs less (the volume grows as its cube)";
    chain = rp::cl::make_buffer(context, CL_MEM_READ_WRITE, chain_elements() * 4 * sizeof(float),
                                "the dense GI volume's mip chain" + at, advice);
    accum = rp::cl::make_buffer(context, CL_MEM_READ_WRITE,
                                voxels * RP_VOXEL_ACCUM_WORDS * sizeof(uint32_t),
                                "the voxelizer's sums" + at, advice);
    overflow = rp::cl::make_buffer(context, CL_MEM_READ_WRITE, voxels * sizeof(uint32_t),
                                   "the voxelizer's overflow bits" + at, advice);
  }
};

}  // namespace rp::render
