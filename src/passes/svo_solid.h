// Solid occupancy of the closed objects for the octree's coarse cone samples.
//
// The voxelizer writes surfaces: at 256^3 and 512^3 a tumbler (51 / 102 voxels across) is a
// hollow shell one voxel thick, and from level 2 on a cone's trilinear samples mix that shell
// with the empty inside, so the cones see through the tumblers: their contact shadows on the
// floor got 38-50 % more indirect light than the path tracer's. Filling the inside voxels at
// level 0 would add a fragment per inside voxel (4 M at 512^3 on the demo: over the 256 MB
// budget), so the inside is described once per frame at the coarse levels only: the fraction of
// each level-l cell (l >= kSvoSolidFirstLevel) that lies inside a tumbler or a sphere, from their
// analytic shapes (scene/tumbler_shape.h's signed distance, the spheres' centres and radii), as
// bytes (0..255) behind the brick pool (layout: kernels/shared/svo_layout.h). The cone tracer
// raises a coarse sample's opacity to RP_SVO_SOLID_WEIGHT (0.6) x that fraction
// (kernels/common/svo.h rp_svo_solid_apply says why not the whole fraction).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/tumbler_shape.h"

namespace rp::passes {

// First level with solid fractions: level 2 (cells of 4 level-0 voxels). Levels 0 and 1 resolve
// the shell themselves (a cone there is at most 2 voxels wide); the grid at level 2 costs
// (R/4)^3 bytes (2 MiB at 512^3, 8/7 of it with the coarser levels).
inline constexpr uint32_t kSvoSolidFirstLevel = 2;

struct SolidObjects {
  scene::TumblerShape tumbler;                  // the shape every tumbler instance has
  std::vector<glm::mat4> tumbler_world_to_local;  // one per tumbler instance
  std::vector<glm::vec4> spheres;               // xyz centre, w radius (world)
};

// Bytes of the solid grid for a resolution-R octree (levels kSvoSolidFirstLevel .. log2 R - 1,
// (R >> l)^3 bytes each, back to back); 0 when R is too small to have such a level.
size_t svo_solid_bytes(uint32_t resolution);

// Byte offset of level l's first cell inside the grid.
size_t svo_solid_level_offset(uint32_t resolution, uint32_t level);

// The grid: cell (x, y, z) of level l at svo_solid_level_offset(R, l) + (z n + y) n + x,
// n = R >> l, holds round(255 * the fraction of the cell inside some object). Level
// kSvoSolidFirstLevel: from the signed distance d at the cell's centre, clamp(1/2 - d / cell,
// 0, 1) (exact for a plane across an axis; 4^3 sub-samples took 130 ms a frame at 512^3 on the
// 2-core CPU, this one distance a cell in the objects' boxes 10); coarser levels: the mean of
// their 8 children (from the unrounded fractions).
std::vector<uint8_t> svo_solid_grid(uint32_t resolution, const SolidObjects& objects);

}  // namespace rp::passes
