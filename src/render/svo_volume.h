// The sparse voxel octree on the device: one buffer with header, node pool, brick
// table and sample pool (kernels/shared/svo_layout.h), handed to the cone tracer in place of the
// dense chain, plus what the last build measured. Built by passes::SvoPass.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <CL/opencl.hpp>

#include "kernels/shared/svo_layout.h"

namespace rp::render {

struct SvoVolume {
  uint32_t resolution = 0;  // R: level-0 voxels per side (a power of two, 2 .. 1024)
  uint32_t depths = 0;      // D = log2 R node depths; the cone tracer's levels = D + 1
  ::cl::Buffer buffer;      // header + node pool + brick table + sample pool (svo_layout.h)
  size_t node_capacity = 0;    // nodes the buffer holds
  size_t brick_capacity = 0;   // brick-table entries the buffer holds
  size_t sample_capacity = 0;  // samples the sample pool holds
  uint32_t sample_bytes = 5;   // 5: packed (RGB9E5 uint + opacity byte), 16: float4

  // The last build: fragments; per depth the nodes, the existing nodes (bricks) and the
  // occupied own voxels (samples stored per direction); the samples stored.
  uint32_t fragments = 0;
  std::vector<uint32_t> nodes_per_depth, bricks_per_depth, own_per_depth;
  uint64_t samples = 0;
  // Device memory of the octree path after the last build, from the runtime (CL_MEM_SIZE):
  // the builder's scratch (fragment list, flags, owners / list links, coordinates, sums), that
  // plus this buffer, and the most that sum has been after any build so far.
  uint64_t scratch_bytes = 0;
  uint64_t fragment_bytes = 0;  // of which the fragment list (its capacity)
  uint64_t device_bytes = 0;
  uint64_t peak_device_bytes = 0;
  // The fragment voxelizer's own buffers (its static surface cache: 80 bytes a cached
  // sample), set by SvoPass::run.
  uint64_t voxelizer_bytes = 0;

  // Levels as the dense chain counts them (log2 R + 1), what the cone tracer is given.
  uint32_t levels() const { return depths + 1; }
  uint64_t nodes() const {
    uint64_t n = 0;
    for (uint32_t c : nodes_per_depth) n += c;
    return n;
  }
  uint64_t bricks() const {
    uint64_t n = 0;
    for (uint32_t c : bricks_per_depth) n += c;
    return n;
  }
  // Bytes in use after the last build: the node pool, the brick table, the sample pool, and
  // the brick pool (table + samples).
  uint64_t node_bytes() const { return nodes() * 8; }
  uint64_t table_bytes() const { return bricks() * RP_SVO_TABLE_WORDS * 4; }
  uint64_t sample_pool_bytes() const { return samples * sample_bytes; }
  uint64_t brick_bytes() const { return table_bytes() + sample_pool_bytes(); }
  // First uint of the brick table: after the node pool, 16-byte aligned.
  size_t table_offset() const {
    return 4 * RP_SVO_HEADER_FLOAT4S + (node_capacity * 2 + 3) / 4 * 4;
  }
  // First float4 of the sample pool (the brick table is a whole number of float4s).
  size_t brick_offset() const {
    return (table_offset() + brick_capacity * RP_SVO_TABLE_WORDS) / 4;
  }
  // The dense chain (level 0 + six directional volumes per level) at the same resolution, in
  // float4: what the octree replaces.
  static uint64_t dense_bytes(uint32_t r) {
    uint64_t total = uint64_t(r) * r * r, n = r;
    while (n > 1) {
      n /= 2;
      total += 6 * n * n * n;
    }
    return total * 16;
  }
  // Bytes of the solid grid held behind the brick pool (0: none; passes/svo_solid.h).
  size_t solid_capacity = 0;
  double solid_host_ms = 0.0;  // the last frame's grid: host computation (the device builds)
  // Byte offset of the solid grid: after the sample pool, 16-byte aligned.
  size_t solid_offset() const {
    return ((brick_offset() * 16) + sample_capacity * sample_bytes + 15) / 16 * 16;
  }
  size_t buffer_bytes() const {
    return solid_capacity > 0 ? solid_offset() + solid_capacity
                              : (brick_offset() * 16) + sample_capacity * sample_bytes;
  }
  // Byte offset of the opacity plane (packed samples): after the rgb plane's uints.
  size_t alpha_offset() const {
    return sample_bytes == 16 ? 0 : brick_offset() * 16 + sample_capacity * 4;
  }
};

}  // namespace rp::render
